//! Objects as the pipeline draws them: each one's mesh in GTE units, tessellation level and
//! texture attributes, prepared once; per frame, what the GTE stage loads for it: RT and TR,
//! and with a light LLM, LCM and BK (docs/pipeline.md step 1).

use super::tessellate::MAX_LEVEL;
use super::vram_alloc::Placement;
use crate::scene::prepared::{PreparedMesh, prepare, to_fixed};
use crate::scene::{Object, Scene};
use gte::typed::{Matrix, Translation};

/// An object ready to draw.
#[derive(Clone, Debug)]
pub(super) struct PreparedObject {
    /// Its mesh in GTE units.
    pub(super) mesh: PreparedMesh,
    /// How many times a polygon may be split (0..=[`MAX_LEVEL`]).
    pub(super) level: u8,
    /// A polygon wider or taller than this many pixels on screen is split while the level
    /// allows.
    pub(super) split_extent: i32,
    /// The CLUT and texpage attributes of its polygons (docs/hardware/gpu.md §7), when it
    /// is textured; the texpage carries the blend mode.
    pub(super) texture: Option<(gpu::ClutAttr, gpu::Texpage)>,
    /// Its semi-transparency mode, when semi-transparent.
    pub(super) blend: Option<u8>,
}

impl PreparedObject {
    /// Object `index` of `scene`, its texture placed at `placements[object.texture]`, split
    /// up to `tessellation` levels when larger than `split_extent` pixels (the object's own
    /// level and extent when `None`).
    pub(super) fn new(
        scene: &Scene,
        index: usize,
        placements: &[Placement],
        (tessellation, split_extent): (Option<u8>, Option<u16>),
    ) -> Option<Self> {
        let object = scene.objects.get(index)?;
        let level = tessellation.unwrap_or(object.tessellation).min(MAX_LEVEL);
        let split_extent = i32::from(split_extent.unwrap_or(object.split_extent));
        let blend = object.blend;
        let texture = object.texture.and_then(|t| {
            let depth = scene.textures.get(t)?.texture.depth;
            let p = placements.get(t)?;
            let mode = gpu::BlendMode::from_bits(u32::from(blend.unwrap_or(0)));
            Some((p.clut_attr(), p.texpage(depth, mode)))
        });
        Some(Self {
            mesh: prepare(scene, index),
            level,
            split_extent,
            texture,
            blend,
        })
    }

    /// The most polygons a frame can draw of it: each face split into 4^level pieces.
    pub(super) fn most_polygons(&self) -> usize {
        self.mesh.faces.len().saturating_mul(1 << (2 * self.level))
    }
}

/// What the GTE's lighting registers hold for an object: LLM, LCM and BK.
pub(super) struct ObjectLight {
    /// LLM: row 0 the direction towards the light in object space.
    pub(super) directions: Matrix,
    /// LCM: column 0 the light's colour.
    pub(super) colors: Matrix,
    /// BK: the ambient colour.
    pub(super) background: [i32; 3],
}

/// The lighting registers for `object` at `frame` under the scene's light (none without
/// one): the direction towards the light, -(light direction), turned into object space by
/// the transpose of the object's rotation (R^T (-d)), and the colours in 1.3.12.
pub(super) fn object_light(scene: &Scene, object: &Object, frame: u32) -> Option<ObjectLight> {
    let light = scene.light.as_ref()?;
    let r = object.rotation_at(frame);
    let rot = Matrix::rotation(angle(r[0]), angle(r[1]), angle(r[2]));
    let d = light.direction;
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
    let to_light = [-d[0] / len, -d[1] / len, -d[2] / len];
    let rb = rot.to_bits();
    let obj: [f64; 3] = std::array::from_fn(|c| {
        (0..3).map(|r| rb[r][c] as f64 * to_light[r]).sum::<f64>() / 4096.0
    });
    let zero = [0i16; 3];
    let col = light.color.map(|c| to_fixed(c as f64 / 255.0));
    Some(ObjectLight {
        directions: Matrix::from_bits([obj.map(to_fixed), zero, zero]),
        colors: Matrix::from_bits([[col[0], 0, 0], [col[1], 0, 0], [col[2], 0, 0]]),
        background: light.ambient.map(|c| (c as i32 * 4096) / 255),
    })
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
