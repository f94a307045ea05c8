//! Tessellation: splitting polygons before projection, the PS1 games' cure for affine
//! texture warp and near-plane drops (the SDK's DivPolyFT4-style subdivision). A split cuts
//! a quad into four quads and a triangle into four triangles at its edge midpoints, in object
//! space, with normals and texture coordinates interpolated linearly; the new vertices go
//! through the GTE like any other. All arithmetic is integer, as on the console.
//!
//! The renderer decides per polygon and per frame whether to split (`pipeline/gte_stage.rs`): up to
//! the object's level, a polygon is split while its projected size (object size / depth) is
//! large or while a vertex lies behind the near plane.

use crate::scene::prepared::{PreparedFace, PreparedVertex};
use gte::typed::Vector3;

/// Midpoint of two 16-bit values (floor of the mean; never overflows).
fn mid16(a: i16, b: i16) -> i16 {
    ((i32::from(a) + i32::from(b)) >> 1) as i16
}

fn mid_vector(a: Vector3, b: Vector3) -> Vector3 {
    Vector3 {
        x: mid16(a.x, b.x),
        y: mid16(a.y, b.y),
        z: mid16(a.z, b.z),
    }
}

fn mid(a: &PreparedVertex, b: &PreparedVertex) -> PreparedVertex {
    let avg = |x: u16, y: u16| ((u32::from(x) + u32::from(y)) >> 1) as u16;
    PreparedVertex {
        position: mid_vector(a.position, b.position),
        normal: mid_vector(a.normal, b.normal),
        uv: [avg(a.uv[0], b.uv[0]), avg(a.uv[1], b.uv[1])],
    }
}

/// Split one face into four with the winding (and so the NCLIP sign) of the parent.
pub fn split(face: &PreparedFace) -> [PreparedFace; 4] {
    let [v0, v1, v2, v3] = &face.v;
    if face.quad {
        // Midpoints of the four edges (v0v1, v0v2, v1v3, v2v3) and the centre (the midpoint
        // of the two opposite edge midpoints).
        let (m01, m02, m13, m23) = (mid(v0, v1), mid(v0, v2), mid(v1, v3), mid(v2, v3));
        let c = mid(&m01, &m23);
        let q = |a, b, c, d| PreparedFace {
            v: [a, b, c, d],
            quad: true,
        };
        [
            q(*v0, m01, m02, c),
            q(m01, *v1, c, m13),
            q(m02, c, *v2, m23),
            q(c, m13, m23, *v3),
        ]
    } else {
        let (m01, m12, m02) = (mid(v0, v1), mid(v1, v2), mid(v0, v2));
        let t = |a, b, c| PreparedFace {
            v: [a, b, c, PreparedVertex::default()],
            quad: false,
        };
        [
            t(*v0, m01, m02),
            t(m01, *v1, m12),
            t(m02, m12, *v2),
            t(m01, m12, m02),
        ]
    }
}

/// Largest tessellation level.
pub const MAX_LEVEL: u8 = 4;

/// Pending faces of one depth-first subdivision: at most three siblings wait at each of
/// [`MAX_LEVEL`] levels, plus the face being examined.
pub const STACK_DEPTH: usize = 3 * MAX_LEVEL as usize + 1;

/// A fixed-capacity stack of faces and their levels for depth-first subdivision without
/// allocation.
#[derive(Clone, Debug)]
pub struct SplitStack {
    items: [(PreparedFace, u8); STACK_DEPTH + 3],
    len: usize,
}

impl Default for SplitStack {
    fn default() -> Self {
        Self {
            items: [(PreparedFace::default(), 0); STACK_DEPTH + 3],
            len: 0,
        }
    }
}

impl SplitStack {
    /// Push a face at a level; returns false (and drops it) when full, which cannot happen
    /// while levels stay within [`MAX_LEVEL`].
    pub fn push(&mut self, face: PreparedFace, level: u8) -> bool {
        match self.items.get_mut(self.len) {
            Some(slot) => {
                *slot = (face, level);
                self.len += 1;
                true
            }
            None => false,
        }
    }

    /// Push the four children of `face`, in reverse so the first child is examined first.
    pub fn push_split(&mut self, face: &PreparedFace, level: u8) -> bool {
        let children = split(face);
        children.iter().rev().all(|c| self.push(*c, level))
    }

    /// Take the most recently pushed face.
    pub fn pop(&mut self) -> Option<(PreparedFace, u8)> {
        self.len = self.len.checked_sub(1)?;
        self.items.get(self.len).copied()
    }
}

/// Split every face `level` times (uniform tessellation: 4^level faces per face).
pub fn tessellate(faces: &[PreparedFace], level: u8) -> Vec<PreparedFace> {
    let mut faces = faces.to_vec();
    for _ in 0..level.min(MAX_LEVEL) {
        faces = faces.iter().flat_map(split).collect();
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: i16, y: i16) -> PreparedVertex {
        PreparedVertex {
            position: Vector3 { x, y, z: 0 },
            normal: Vector3 {
                x: 0,
                y: 0,
                z: -4096,
            },
            uv: [x as u16 * 256, y as u16 * 256],
        }
    }

    #[test]
    fn quad_split_covers_the_quad() {
        let q = PreparedFace {
            v: [vertex(0, 0), vertex(4, 0), vertex(0, 4), vertex(4, 4)],
            quad: true,
        };
        let parts = tessellate(&[q], 2);
        assert_eq!(parts.len(), 16);
        // Each level-2 quad is 1x1 and keeps the Z order (v3 opposite v0).
        for p in &parts {
            assert_eq!(p.v[1].position.x - p.v[0].position.x, 1);
            assert_eq!(p.v[2].position.y - p.v[0].position.y, 1);
            assert_eq!(p.v[3].position.x, p.v[1].position.x);
            assert_eq!(p.v[3].position.y, p.v[2].position.y);
            // Texture coordinates follow positions (uv = 256 * position here).
            assert_eq!(
                p.v[3].uv,
                [
                    p.v[3].position.x as u16 * 256,
                    p.v[3].position.y as u16 * 256
                ]
            );
        }
    }

    #[test]
    fn triangle_split_keeps_winding() {
        let t = PreparedFace {
            v: [vertex(0, 0), vertex(4, 0), vertex(0, 4), vertex(0, 0)],
            quad: false,
        };
        for p in split(&t) {
            let [a, b, c, _] = p.v.map(|v| (v.position.x as i32, v.position.y as i32));
            let area = (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1);
            assert_eq!(area, 4, "each child has a quarter of the area, same sign");
        }
    }

    #[test]
    fn stack_holds_a_full_depth_first_descent() {
        let q = PreparedFace {
            v: [vertex(0, 0), vertex(16, 0), vertex(0, 16), vertex(16, 16)],
            quad: true,
        };
        let mut s = SplitStack::default();
        assert!(s.push(q, 0));
        let mut leaves = 0;
        while let Some((f, level)) = s.pop() {
            if level < MAX_LEVEL {
                assert!(s.push_split(&f, level + 1));
            } else {
                leaves += 1;
            }
        }
        assert_eq!(leaves, 256);
    }
}
