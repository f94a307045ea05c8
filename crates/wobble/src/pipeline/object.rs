//! Objects prepared for the GTE: faces scaled into 16-bit vertices with 1.3.12 normals and
//! 8.8 texel coordinates, and the per-frame rotation and translation loaded into RT and TR.

use super::tessellate::{PreparedFace, PreparedVertex, UV_FRACTION_BITS};
use crate::scene::vram_alloc::Placement;
use crate::scene::{Object, Scene};
use gte::typed::{Matrix, Translation, Vector3};
use std::collections::HashMap;

/// An object ready to draw: faces in GTE units with texel coordinates.
#[derive(Clone, Debug)]
pub(super) struct PreparedObject {
    pub(super) faces: Vec<PreparedFace>,
    /// The object's distinct vertices (position and normal), each projected once a frame.
    pub(super) vertices: Vec<SharedVertex>,
    /// For each of `faces`, its vertices' indices into `vertices` (the fourth 0 for a
    /// triangle).
    pub(super) indices: Vec<[u32; 4]>,
    /// For each of `faces`, its vertices' texture coordinates rounded to whole texels.
    pub(super) texels: Vec<[(u8, u8); 4]>,
    /// The distinct normals of `vertices`, each lit once a frame.
    pub(super) normals: Vec<Vector3>,
    /// For each of `vertices`, its normal's index into `normals`.
    pub(super) normal_of: Vec<u32>,
    pub(super) level: u8,
    pub(super) texture: Option<(Placement, gpu::TextureDepth)>,
}

/// What the GTE reads of a vertex shared by faces: the 16-bit position (RTPS) and the
/// 1.3.12 normal (NCCS/NCDS). Texture coordinates stay with each face ([`PreparedFace`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub(super) struct SharedVertex {
    pub(super) position: Vector3,
    pub(super) normal: Vector3,
}

/// An object's faces with their shared vertices (see [`PreparedObject`]).
pub(super) struct PreparedMesh {
    pub(super) faces: Vec<PreparedFace>,
    pub(super) vertices: Vec<SharedVertex>,
    pub(super) indices: Vec<[u32; 4]>,
}

/// Degrees to 1/4096 turn.
pub fn angle(deg: f64) -> i32 {
    (deg.rem_euclid(360.0) * 4096.0 / 360.0).round() as i32
}

pub(super) fn to_fixed(v: f64) -> i16 {
    (v * 4096.0).round().clamp(-32768.0, 32767.0) as i16
}

fn to_i16(v: f64) -> i16 {
    v.round().clamp(-32768.0, 32767.0) as i16
}

fn vector(p: [f64; 3]) -> Vector3 {
    Vector3 {
        x: to_i16(p[0]),
        y: to_i16(p[1]),
        z: to_i16(p[2]),
    }
}

fn normal(n: [f64; 3]) -> Vector3 {
    Vector3 {
        x: to_fixed(n[0]),
        y: to_fixed(n[1]),
        z: to_fixed(n[2]),
    }
}

/// Apply a 1.3.12 matrix to a vector in f64 (CPU-side set-up only).
fn apply(m: &Matrix, v: [f64; 3]) -> [f64; 3] {
    let b = m.to_bits();
    let row = |r: usize| (0..3).map(|c| b[r][c] as f64 * v[c]).sum::<f64>() / 4096.0;
    [row(0), row(1), row(2)]
}

/// Prepare an object's faces for the GTE: positions scaled and rounded to 16-bit vertices,
/// normals in 1.3.12, per-face texel coordinates (each face's texture coordinates shifted by
/// whole texture repeats to start in the first repeat, then scaled to 0..size-1 texels and
/// clamped to 255) in 8.8 fixed point.
pub fn prepare(scene: &Scene, index: usize) -> Vec<PreparedFace> {
    prepare_indexed(scene, index).faces
}

/// [`prepare`], and the object's distinct vertices with each face's indices into them:
/// mesh vertices that come out with the same position and normal are one vertex.
pub(super) fn prepare_indexed(scene: &Scene, index: usize) -> PreparedMesh {
    let mut out = PreparedMesh {
        faces: Vec::new(),
        vertices: Vec::new(),
        indices: Vec::new(),
    };
    let Some(o) = scene.objects.get(index) else {
        return out;
    };
    let Some(mesh) = scene.meshes.get(o.mesh).map(|m| &m.mesh) else {
        return out;
    };
    let mut shared: HashMap<SharedVertex, u32> = HashMap::new();
    let size = o
        .texture
        .and_then(|t| scene.textures.get(t))
        .map_or((1.0, 1.0), |t| {
            (t.texture.width as f64 - 1.0, t.texture.height as f64 - 1.0)
        });
    let uv_scale = f64::from(1u32 << UV_FRACTION_BITS);
    out.faces.reserve(mesh.faces.len());
    out.indices.reserve(mesh.faces.len());
    for f in &mesh.faces {
        let count = if f.quad { 4 } else { 3 };
        let mut vs = [None; 4];
        for (slot, &i) in vs.iter_mut().zip(&f.indices).take(count) {
            *slot = mesh.vertices.get(i as usize);
        }
        if vs.iter().take(count).any(Option::is_none) {
            continue;
        }
        let vs = vs.iter().take(count).flatten();
        let min_u = vs
            .clone()
            .map(|v| v.uv[0])
            .fold(f64::INFINITY, f64::min)
            .floor();
        let min_v = vs
            .clone()
            .map(|v| v.uv[1])
            .fold(f64::INFINITY, f64::min)
            .floor();
        let mut face = PreparedFace {
            quad: f.quad,
            ..Default::default()
        };
        let mut indices = [0u32; 4];
        for ((slot, v), index) in face.v.iter_mut().zip(vs).zip(&mut indices) {
            let texel = |c: f64, min: f64, size: f64| {
                (((c - min) * size).clamp(0.0, 255.0) * uv_scale).round() as u16
            };
            *slot = PreparedVertex {
                position: vector(v.position.map(|c| c * o.scale)),
                normal: normal(v.normal),
                uv: [texel(v.uv[0], min_u, size.0), texel(v.uv[1], min_v, size.1)],
            };
            let key = SharedVertex {
                position: slot.position,
                normal: slot.normal,
            };
            *index = *shared.entry(key).or_insert_with(|| {
                out.vertices.push(key);
                (out.vertices.len() - 1) as u32
            });
        }
        out.faces.push(face);
        out.indices.push(indices);
    }
    out
}

/// The object's rotation in degrees at `frame`.
pub fn object_rotation(object: &Object, frame: u32) -> [f64; 3] {
    let f = frame as f64;
    [
        object.rotation[0] + object.spin[0] * f,
        object.rotation[1] + object.spin[1] * f,
        object.rotation[2] + object.spin[2] * f,
    ]
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
    let r = object_rotation(object, frame);
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
