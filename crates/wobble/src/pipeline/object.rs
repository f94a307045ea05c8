//! Objects as the pipeline draws them (their mesh in GTE units, tessellation level and
//! texture placement), and the per-frame rotation and translation loaded into RT and TR.

use super::vram_alloc::Placement;
use crate::scene::prepared::PreparedMesh;
use crate::scene::{Object, Scene};
use gte::typed::{Matrix, Translation};

/// An object ready to draw: its mesh in GTE units, tessellation level and texture
/// placement.
#[derive(Clone, Debug)]
pub(super) struct PreparedObject {
    pub(super) mesh: PreparedMesh,
    pub(super) level: u8,
    pub(super) texture: Option<(Placement, gpu::TextureDepth)>,
}

/// Degrees to 1/4096 turn.
pub fn angle(deg: f64) -> i32 {
    (deg.rem_euclid(360.0) * 4096.0 / 360.0).round() as i32
}

/// Apply a 1.3.12 matrix to a vector in f64 (CPU-side set-up only).
fn apply(m: &Matrix, v: [f64; 3]) -> [f64; 3] {
    let b = m.to_bits();
    let row = |r: usize| (0..3).map(|c| b[r][c] as f64 * v[c]).sum::<f64>() / 4096.0;
    [row(0), row(1), row(2)]
}

/// RT and TR for an object at `frame`: the camera rotation times the object rotation, and
/// the object's position in camera space (what the pipeline loads into the GTE).
pub fn object_transform(scene: &Scene, object: &Object, frame: u32) -> (Matrix, Translation) {
    let cam = &scene.camera;
    let view = Matrix::rotation(
        angle(cam.rotation[0]),
        angle(cam.rotation[1]),
        angle(cam.rotation[2]),
    );
    let r = object.rotation_at(frame);
    let rot = Matrix::rotation(angle(r[0]), angle(r[1]), angle(r[2]));
    let relative = [
        object.position[0] - cam.position[0],
        object.position[1] - cam.position[1],
        object.position[2] - cam.position[2],
    ];
    let t = apply(&view, relative);
    let clamp32 = |v: f64| v.round().clamp(i32::MIN as f64, i32::MAX as f64) as i32;
    (
        view.multiply(&rot),
        Translation {
            x: clamp32(t[0]),
            y: clamp32(t[1]),
            z: clamp32(t[2]),
        },
    )
}
