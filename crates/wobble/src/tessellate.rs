//! Tessellation: splitting polygons before projection, the PS1 games' cure for affine
//! texture warp and near-plane drops. Each level splits every quad into four quads and every
//! triangle into four triangles at edge midpoints (object space, texture coordinates
//! interpolated linearly), so level n multiplies the polygon count by 4^n.

/// A polygon vertex prepared for the GTE: position in GTE units, unit normal, texture
/// coordinate in texels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PreparedVertex {
    /// Position (fits signed 16 bits).
    pub position: [f64; 3],
    /// Unit normal.
    pub normal: [f64; 3],
    /// Texture coordinate in texels.
    pub uv: [f64; 2],
}

/// A polygon with its own vertices: quads in GP0 order (v3 opposite v0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PreparedFace {
    /// Vertices; the fourth is unused for triangles.
    pub v: [PreparedVertex; 4],
    /// Quad or triangle.
    pub quad: bool,
}

fn mid(a: &PreparedVertex, b: &PreparedVertex) -> PreparedVertex {
    let avg = |x: f64, y: f64| (x + y) / 2.0;
    PreparedVertex {
        position: [
            avg(a.position[0], b.position[0]),
            avg(a.position[1], b.position[1]),
            avg(a.position[2], b.position[2]),
        ],
        normal: [
            avg(a.normal[0], b.normal[0]),
            avg(a.normal[1], b.normal[1]),
            avg(a.normal[2], b.normal[2]),
        ],
        uv: [avg(a.uv[0], b.uv[0]), avg(a.uv[1], b.uv[1])],
    }
}

/// Split one face into four.
pub fn split(face: &PreparedFace) -> [PreparedFace; 4] {
    let [v0, v1, v2, v3] = &face.v;
    if face.quad {
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

/// Tessellate faces `level` times.
pub fn tessellate(faces: Vec<PreparedFace>, level: u8) -> Vec<PreparedFace> {
    let mut faces = faces;
    for _ in 0..level {
        faces = faces.iter().flat_map(split).collect();
    }
    faces
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: f64, y: f64) -> PreparedVertex {
        PreparedVertex {
            position: [x, y, 0.0],
            normal: [0.0, 0.0, -1.0],
            uv: [x, y],
        }
    }

    #[test]
    fn quad_split_covers_the_quad() {
        let q = PreparedFace {
            v: [
                vertex(0.0, 0.0),
                vertex(4.0, 0.0),
                vertex(0.0, 4.0),
                vertex(4.0, 4.0),
            ],
            quad: true,
        };
        let parts = tessellate(vec![q], 2);
        assert_eq!(parts.len(), 16);
        // Each level-2 quad is 1x1 and keeps the Z order (v3 opposite v0).
        for p in &parts {
            assert_eq!(p.v[1].position[0] - p.v[0].position[0], 1.0);
            assert_eq!(p.v[2].position[1] - p.v[0].position[1], 1.0);
            assert_eq!(
                p.v[3].position,
                [p.v[1].position[0], p.v[2].position[1], 0.0]
            );
        }
    }

    #[test]
    fn triangle_split_keeps_winding() {
        let t = PreparedFace {
            v: [
                vertex(0.0, 0.0),
                vertex(4.0, 0.0),
                vertex(0.0, 4.0),
                vertex(0.0, 0.0),
            ],
            quad: false,
        };
        for p in split(&t) {
            let [a, b, c, _] = p.v;
            let area = (b.position[0] - a.position[0]) * (c.position[1] - a.position[1])
                - (c.position[0] - a.position[0]) * (b.position[1] - a.position[1]);
            assert_eq!(area, 4.0, "each child has a quarter of the area, same sign");
        }
    }
}
