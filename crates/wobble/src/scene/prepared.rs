//! Objects prepared for the GTE: an object's mesh in the units the GTE reads, once per
//! scene. Positions scaled and rounded to 16-bit vertices (V0-V2), normals in 1.3.12,
//! per-face texture coordinates in 8.8 texels; the distinct vertices each face indexes
//! (projected once a frame) and the distinct normals (lit once a frame).

use super::Scene;
use gte::typed::Vector3;
use std::collections::HashMap;

/// Fraction bits of the texture coordinates carried through splits: 8.8 texels.
pub const UV_FRACTION_BITS: u32 = 8;

/// A polygon vertex ready for the GTE: position in GTE units (V0-V2), 1.3.12 normal and
/// texture coordinate in 8.8 texels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PreparedVertex {
    /// Position, a 16-bit GTE vertex.
    pub position: Vector3,
    /// Normal, 1.3.12 (4096 = 1.0).
    pub normal: Vector3,
    /// Texture coordinate in 1/256 texels (0..=255 texels).
    pub uv: [u16; 2],
}

impl PreparedVertex {
    /// The texture coordinate rounded to whole texels, as a GP0 UV byte pair.
    pub fn texel(&self) -> (u8, u8) {
        let round = |c: u16| {
            let t = (u32::from(c) + (1 << (UV_FRACTION_BITS - 1))) >> UV_FRACTION_BITS;
            t.min(255) as u8
        };
        (round(self.uv[0]), round(self.uv[1]))
    }
}

/// A polygon with its own vertices: quads in GP0 order (v3 opposite v0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PreparedFace {
    /// Vertices; the fourth is unused for triangles.
    pub v: [PreparedVertex; 4],
    /// Quad or triangle.
    pub quad: bool,
}

/// What the GTE reads of a vertex shared by faces: the 16-bit position (RTPS) and the
/// 1.3.12 normal (NCCS/NCDS). Texture coordinates stay with each face ([`PreparedFace`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct SharedVertex {
    /// Position, a 16-bit GTE vertex.
    pub position: Vector3,
    /// Normal, 1.3.12.
    pub normal: Vector3,
}

/// An object's mesh in GTE units: its faces, and the distinct vertices and normals they
/// share. Mesh faces with a vertex index past the mesh's vertices are left out.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PreparedMesh {
    /// The faces, each with its own copy of its vertices.
    pub faces: Vec<PreparedFace>,
    /// The distinct vertices (position and normal): mesh vertices that come out with the
    /// same position and normal are one.
    pub vertices: Vec<SharedVertex>,
    /// For each of `faces`, its vertices' indices into `vertices` (the fourth 0 for a
    /// triangle).
    pub indices: Vec<[u32; 4]>,
    /// For each of `faces`, its vertices' texture coordinates rounded to whole texels.
    pub texels: Vec<[(u8, u8); 4]>,
    /// The distinct normals of `vertices`. NCCS/NCDS depend on a vertex through its normal
    /// alone (the material colour, light matrices, BK, FC and IR0 are the object's), so
    /// vertices with one normal share one colour.
    pub normals: Vec<Vector3>,
    /// For each of `vertices`, its normal's index into `normals`.
    pub normal_of: Vec<u32>,
}

/// A real number as 1.3.12 fixed point (4096 = 1.0), saturated to 16 bits.
pub fn to_fixed(v: f64) -> i16 {
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

/// Prepare object `index` of `scene` for the GTE: positions scaled by the object's scale
/// and rounded to 16-bit vertices, normals in 1.3.12, per-face texel coordinates (each
/// face's texture coordinates shifted by whole texture repeats to start in the first
/// repeat, then scaled to 0..size-1 texels and clamped to 255) in 8.8 fixed point. An
/// object index or mesh index past the scene's lists gives an empty mesh.
pub fn prepare(scene: &Scene, index: usize) -> PreparedMesh {
    let mut out = PreparedMesh::default();
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
        out.texels.push(face.v.map(|v| v.texel()));
        out.faces.push(face);
        out.indices.push(indices);
    }
    (out.normals, out.normal_of) = normal_table(&out.vertices);
    out
}

/// The distinct normals of `vertices`, and each vertex's index into them.
pub(crate) fn normal_table(vertices: &[SharedVertex]) -> (Vec<Vector3>, Vec<u32>) {
    let mut index = HashMap::new();
    let mut normals = Vec::new();
    let of = vertices
        .iter()
        .map(|v| {
            *index.entry(v.normal).or_insert_with(|| {
                normals.push(v.normal);
                (normals.len() - 1) as u32
            })
        })
        .collect();
    (normals, of)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texel_rounds_half_up_and_saturates() {
        let v = |u: u16| PreparedVertex {
            uv: [u, 0],
            ..Default::default()
        };
        assert_eq!(v(0x0280).texel().0, 3);
        assert_eq!(v(0x027F).texel().0, 2);
        assert_eq!(v(0xFFFF).texel().0, 255);
    }
}
