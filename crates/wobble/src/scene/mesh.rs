//! Meshes: Wavefront OBJ loading (through `tobj`), built-in shapes, and scaling into the
//! GTE's signed 16-bit vertex range.

use std::fmt;
use std::path::{Path, PathBuf};

/// One mesh vertex: position in mesh units, unit normal, texture coordinate in 0..1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshVertex {
    /// Position.
    pub position: [f64; 3],
    /// Unit normal.
    pub normal: [f64; 3],
    /// Texture coordinate, (0,0) top-left, (1,1) bottom-right of the texture.
    pub uv: [f64; 2],
}

/// A polygon: three or four vertex indices, counter-clockwise seen from the front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MeshFace {
    /// Vertex indices; the fourth is unused for triangles.
    pub indices: [u32; 4],
    /// Four vertices (a quad, drawn as one GP0 quad) or three.
    pub quad: bool,
}

/// A polygon mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertices.
    pub vertices: Vec<MeshVertex>,
    /// Faces.
    pub faces: Vec<MeshFace>,
}

/// Why a mesh could not be loaded or placed.
#[derive(Debug)]
pub enum MeshError {
    /// The OBJ file could not be read (missing, unreadable, not text).
    Io {
        /// The file, as resolved against the scene file's directory.
        file: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The OBJ reader refused the file; `line` is the offending line when it can be found.
    Obj {
        /// The file.
        file: PathBuf,
        /// 1-based line of the error, when located.
        line: Option<usize>,
        /// The reader's error.
        source: tobj::LoadError,
    },
    /// A vertex position is not a finite number.
    NotFinite {
        /// The file.
        file: PathBuf,
        /// 1-based vertex number.
        vertex: usize,
    },
    /// A `v`, `vt` or `vn` line holds a number that is NaN or infinite, or too large for
    /// the reader's 32-bit floats.
    NotFiniteLine {
        /// The file.
        file: PathBuf,
        /// 1-based line in the file.
        line: usize,
        /// The line's keyword: `v`, `vt` or `vn`.
        keyword: String,
    },
    /// A face's indices run past the index list.
    IndicesPastEnd {
        /// The file.
        file: PathBuf,
    },
    /// A face refers to a vertex that does not exist.
    MissingVertex {
        /// The file.
        file: PathBuf,
    },
    /// The file has no faces.
    NoFaces {
        /// The file.
        file: PathBuf,
    },
    /// A scale that is not a positive number.
    BadScale {
        /// Who asked for the scale (object and mesh).
        name: String,
        /// The scale.
        scale: f64,
    },
    /// The scaled coordinates exceed the GTE's signed 16-bit vertices.
    TooLarge {
        /// Who asked for the scale (object and mesh).
        name: String,
        /// Largest absolute coordinate of the mesh.
        extent: f64,
        /// The scale.
        scale: f64,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Io { file, source } => write!(
                f,
                "mesh file {}: cannot read it: {source}",
                super::file_shown(file)
            ),
            MeshError::Obj {
                file,
                line: Some(n),
                source,
            } => write!(f, "{}: line {n}: {source}", file.display()),
            MeshError::Obj {
                file,
                line: None,
                source,
            } => write!(f, "{}: {source}", file.display()),
            MeshError::NotFinite { file, vertex } => {
                write!(f, "{}: vertex {vertex} is not finite", file.display())
            }
            MeshError::NotFiniteLine {
                file,
                line,
                keyword,
            } => write!(
                f,
                "{}: line {line}: `{keyword}` has a number that is not finite (NaN, infinity, or \
                 beyond 3.4e38)",
                file.display()
            ),
            MeshError::IndicesPastEnd { file } => write!(
                f,
                "{}: face indices run past the index list",
                file.display()
            ),
            MeshError::MissingVertex { file } => {
                write!(f, "{}: face refers to a missing vertex", file.display())
            }
            MeshError::NoFaces { file } => write!(f, "{}: no faces", file.display()),
            MeshError::BadScale { name, scale } => {
                write!(f, "{name}: scale must be a positive number, got {scale}")
            }
            MeshError::TooLarge {
                name,
                extent,
                scale,
            } => {
                let limit = MAX_COORDINATE / extent;
                if limit >= MIN_SUGGESTED_SCALE {
                    write!(
                        f,
                        "{name}: coordinates up to {} times scale {} exceed the GTE's 16-bit \
                         range (32767); use scale <= {}",
                        plain(*extent),
                        plain(*scale),
                        at_most(limit)
                    )
                } else {
                    write!(
                        f,
                        "{name}: the mesh's coordinates are far too large (up to {}); the GTE \
                         takes vertices within +-32767 after scaling, which would need a scale \
                         below {}: rescale the model itself",
                        plain(*extent),
                        plain(limit)
                    )
                }
            }
        }
    }
}

/// An upper bound for a message, with four significant digits (at least every digit before
/// the point) rounded down and no trailing zeros, so that the number printed still
/// satisfies the bound: 32767, 0.3276, 1.234, 0.000001.
fn at_most(v: f64) -> String {
    if !v.is_finite() || v <= 0.0 {
        return plain(v);
    }
    let digits = v.log10().floor() as i32 + 1;
    let decimals = (4 - digits).clamp(0, 12);
    let scale = 10f64.powi(decimals);
    let down = (v * scale).floor() / scale;
    let text = format!("{down:.*}", decimals as usize);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

/// Below this, a suggested scale would print as zeros: the mesh is reported as far too large.
const MIN_SUGGESTED_SCALE: f64 = 1e-6;

/// A number for a message: as is when of ordinary size, in exponent form (`1.0e30`) when
/// it would print with many digits.
fn plain(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e9 || v.abs() < 1e-4) {
        format!("{v:.1e}")
    } else {
        format!("{v}")
    }
}

impl std::error::Error for MeshError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            MeshError::Obj { source, .. } => Some(source),
            MeshError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// Largest coordinate a scaled vertex may have: the GTE takes signed 16-bit vertices.
pub const MAX_COORDINATE: f64 = 32767.0;

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len > 0.0 {
        [v[0] / len, v[1] / len, v[2] / len]
    } else {
        [0.0, 0.0, -1.0]
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The 1-based line of an OBJ file that `tobj` refused with `error` (tobj reports the kind
/// of error only): the first `v`/`vn`/`vt` line whose numbers do not parse, or the first `f`
/// line with a malformed or out-of-range index or fewer than three vertices.
pub fn locate_obj_error(text: &str, error: tobj::LoadError) -> Option<usize> {
    use tobj::LoadError as E;
    let floats = |rest: &[&str], n: usize| {
        rest.len() >= n && rest.iter().take(n).all(|t| t.parse::<f32>().is_ok())
    };
    let (mut positions, mut texcoords, mut normals) = (0i64, 0i64, 0i64);
    for (number, line) in text.lines().enumerate() {
        let mut tokens = line.split_whitespace();
        let Some(keyword) = tokens.next() else {
            continue;
        };
        let rest: Vec<&str> = tokens.collect();
        let bad = match keyword {
            "v" => {
                positions += 1;
                matches!(error, E::PositionParseError | E::ScalingByZeroError)
                    && (!floats(&rest, 3) || rest.get(3).is_some_and(|w| w.parse() == Ok(0.0f32)))
            }
            "vt" => {
                texcoords += 1;
                matches!(error, E::TexcoordParseError) && !floats(&rest, 2)
            }
            "vn" => {
                normals += 1;
                matches!(error, E::NormalParseError) && !floats(&rest, 3)
            }
            "f" => {
                let index_ok = |t: Option<&str>, count: i64, required: bool| match t {
                    None | Some("") => !required,
                    Some(t) => t
                        .parse::<i64>()
                        .is_ok_and(|i| (i > 0 && i <= count) || (i < 0 && -i <= count)),
                };
                matches!(
                    error,
                    E::FaceParseError
                        | E::InvalidPolygon
                        | E::FaceVertexOutOfBounds
                        | E::FaceTexCoordOutOfBounds
                        | E::FaceNormalOutOfBounds
                ) && (rest.len() < 3
                    || rest.iter().any(|v| {
                        let mut parts = v.split('/');
                        !(index_ok(parts.next(), positions, true)
                            && index_ok(parts.next(), texcoords, false)
                            && index_ok(parts.next(), normals, false))
                    }))
            }
            _ => false,
        };
        if bad {
            return Some(number + 1);
        }
    }
    None
}

/// The 1-based line and keyword of the first `v`, `vt` or `vn` line of an OBJ file with a
/// number that reads as NaN or infinite in the reader's 32-bit floats (`tobj` accepts them).
pub fn locate_non_finite(text: &str) -> Option<(usize, &str)> {
    text.lines().enumerate().find_map(|(number, line)| {
        let mut tokens = line.split_whitespace();
        let keyword = tokens.next()?;
        let vertex_data = matches!(keyword, "v" | "vt" | "vn");
        (vertex_data && tokens.any(|t| t.parse::<f32>().is_ok_and(|v| !v.is_finite())))
            .then_some((number + 1, keyword))
    })
}

impl Mesh {
    /// Number of triangles (a quad counts two).
    pub fn triangle_count(&self) -> usize {
        self.faces.iter().map(|f| if f.quad { 2 } else { 1 }).sum()
    }

    /// Largest absolute coordinate.
    pub fn extent(&self) -> f64 {
        self.vertices
            .iter()
            .flat_map(|v| v.position)
            .fold(0.0, |m, c| m.max(c.abs()))
    }

    /// Check that positions times `scale` fit the GTE's 16-bit vertices; the error names the
    /// largest scale that would.
    pub fn check_scale(&self, name: &str, scale: f64) -> Result<(), MeshError> {
        let extent = self.extent();
        if !scale.is_finite() || scale <= 0.0 {
            return Err(MeshError::BadScale {
                name: name.into(),
                scale,
            });
        }
        if extent * scale > MAX_COORDINATE {
            return Err(MeshError::TooLarge {
                name: name.into(),
                extent,
                scale,
            });
        }
        Ok(())
    }

    /// Load a Wavefront OBJ (all models in the file; faces with 3 or 4 vertices; larger
    /// polygons are fanned into triangles). Missing normals are computed per face; missing
    /// texture coordinates are 0.
    pub fn load_obj(path: &Path) -> Result<Mesh, MeshError> {
        let file = || path.to_path_buf();
        let text = std::fs::read_to_string(path).map_err(|source| MeshError::Io {
            file: file(),
            source,
        })?;
        if let Some((line, keyword)) = locate_non_finite(&text) {
            return Err(MeshError::NotFiniteLine {
                file: file(),
                line,
                keyword: keyword.to_string(),
            });
        }
        let options = tobj::LoadOptions {
            single_index: true,
            triangulate: false,
            ignore_points: true,
            ignore_lines: true,
        };
        let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| {
            let line = locate_obj_error(&text, e);
            MeshError::Obj {
                file: file(),
                line,
                source: e,
            }
        })?;
        let mut mesh = Mesh::default();
        for model in models {
            let m = &model.mesh;
            let base = mesh.vertices.len() as u32;
            let count = m.positions.len() / 3;
            for i in 0..count {
                // OBJ is Y-up looking down -Z; the GTE's camera space is Y-down looking down
                // +Z: a half turn about X maps one onto the other.
                let p = [
                    m.positions[3 * i] as f64,
                    -(m.positions[3 * i + 1] as f64),
                    -(m.positions[3 * i + 2] as f64),
                ];
                if p.iter().any(|c| !c.is_finite()) {
                    return Err(MeshError::NotFinite {
                        file: file(),
                        vertex: i + 1,
                    });
                }
                let normal = if m.normals.len() >= 3 * (i + 1) {
                    normalize([
                        m.normals[3 * i] as f64,
                        -(m.normals[3 * i + 1] as f64),
                        -(m.normals[3 * i + 2] as f64),
                    ])
                } else {
                    [0.0; 3]
                };
                let uv = if m.texcoords.len() >= 2 * (i + 1) {
                    // OBJ V runs up; texture rows run down.
                    [
                        m.texcoords[2 * i] as f64,
                        1.0 - m.texcoords[2 * i + 1] as f64,
                    ]
                } else {
                    [0.0, 0.0]
                };
                mesh.vertices.push(MeshVertex {
                    position: p,
                    normal,
                    uv,
                });
            }
            let arities: Vec<u32> = if m.face_arities.is_empty() {
                vec![3; m.indices.len() / 3]
            } else {
                m.face_arities.clone()
            };
            let mut at = 0usize;
            for n in arities {
                let n = n as usize;
                let Some(idx) = m.indices.get(at..at + n) else {
                    return Err(MeshError::IndicesPastEnd { file: file() });
                };
                at += n;
                if idx.iter().any(|&i| i as usize >= count) {
                    return Err(MeshError::MissingVertex { file: file() });
                }
                // OBJ front faces run counter-clockwise as seen; on the PS1 screen (Y down)
                // a front face's first three vertices run clockwise as seen (NCLIP > 0), and a
                // GP0 quad is ordered v0 v1 v2 v3 with v3 opposite v0.
                let g = |k: usize| base + idx[k];
                match n {
                    0..=2 => {}
                    3 => mesh.faces.push(MeshFace {
                        indices: [g(0), g(2), g(1), 0],
                        quad: false,
                    }),
                    4 => mesh.faces.push(MeshFace {
                        indices: [g(0), g(3), g(1), g(2)],
                        quad: true,
                    }),
                    _ => {
                        for k in 1..n - 1 {
                            mesh.faces.push(MeshFace {
                                indices: [g(0), g(k + 1), g(k), 0],
                                quad: false,
                            });
                        }
                    }
                }
            }
        }
        if mesh.faces.is_empty() {
            return Err(MeshError::NoFaces { file: file() });
        }
        mesh.fill_missing_normals();
        Ok(mesh)
    }

    /// Give vertices without a normal the normal of a face that uses them.
    fn fill_missing_normals(&mut self) {
        for f in self.faces.clone() {
            let p = |k: usize| self.vertices[f.indices[k] as usize].position;
            let n = normalize(cross(sub(p(1), p(0)), sub(p(2), p(0))));
            let count = if f.quad { 4 } else { 3 };
            for k in 0..count {
                let v = &mut self.vertices[f.indices[k] as usize];
                if v.normal == [0.0; 3] {
                    v.normal = n;
                }
            }
        }
    }

    /// An axis-aligned cube of half-size `half`, each face a quad with the whole texture.
    /// Faces are stored in GP0 quad order (v0 v1 v2 v3 = top-left, top-right, bottom-left,
    /// bottom-right as seen from outside).
    pub fn cube(half: f64) -> Mesh {
        let mut mesh = Mesh::default();
        // (normal, right, down) for each face.
        let faces: [([f64; 3], [f64; 3], [f64; 3]); 6] = [
            ([0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([0.0, 0.0, 1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
            ([-1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
            ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
            ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ];
        for (n, r, d) in faces {
            let base = mesh.vertices.len() as u32;
            for (su, sv) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                let a = 2.0 * su - 1.0;
                let b = 2.0 * sv - 1.0;
                let position = [
                    half * (n[0] + a * r[0] + b * d[0]),
                    half * (n[1] + a * r[1] + b * d[1]),
                    half * (n[2] + a * r[2] + b * d[2]),
                ];
                mesh.vertices.push(MeshVertex {
                    position,
                    normal: n,
                    uv: [su, sv],
                });
            }
            mesh.faces.push(MeshFace {
                indices: [base, base + 1, base + 2, base + 3],
                quad: true,
            });
        }
        mesh
    }

    /// A flat square grid in the XZ plane facing -Y (up, with Y pointing down as on screen),
    /// `cells` x `cells` quads over `size` units, the texture repeated `repeat` times across.
    pub fn grid(size: f64, cells: u32, repeat: f64) -> Mesh {
        let cells = cells.clamp(1, 256);
        let mut mesh = Mesh::default();
        let n = cells + 1;
        for j in 0..n {
            for i in 0..n {
                let s = i as f64 / cells as f64;
                let t = j as f64 / cells as f64;
                mesh.vertices.push(MeshVertex {
                    position: [size * (s - 0.5), 0.0, size * (0.5 - t)],
                    normal: [0.0, -1.0, 0.0],
                    uv: [s * repeat, t * repeat],
                });
            }
        }
        for j in 0..cells {
            for i in 0..cells {
                let a = j * n + i;
                mesh.faces.push(MeshFace {
                    indices: [a, a + 1, a + n, a + n + 1],
                    quad: true,
                });
            }
        }
        mesh
    }

    /// A UV sphere with `rings` x `segments` quads (triangles at the poles).
    pub fn sphere(radius: f64, rings: u32, segments: u32) -> Mesh {
        let (rings, segments) = (rings.clamp(2, 128), segments.clamp(3, 256));
        let mut mesh = Mesh::default();
        for r in 0..=rings {
            let theta = std::f64::consts::PI * r as f64 / rings as f64;
            for s in 0..=segments {
                let phi = 2.0 * std::f64::consts::PI * s as f64 / segments as f64;
                let n = [
                    theta.sin() * phi.cos(),
                    -theta.cos(),
                    theta.sin() * phi.sin(),
                ];
                mesh.vertices.push(MeshVertex {
                    position: [radius * n[0], radius * n[1], radius * n[2]],
                    normal: n,
                    uv: [s as f64 / segments as f64, r as f64 / rings as f64],
                });
            }
        }
        let w = segments + 1;
        for r in 0..rings {
            for s in 0..segments {
                let a = r * w + s;
                let (tl, tr, bl, br) = (a, a + 1, a + w, a + w + 1);
                if r == 0 {
                    mesh.faces.push(MeshFace {
                        indices: [tl, br, bl, 0],
                        quad: false,
                    });
                } else if r == rings - 1 {
                    mesh.faces.push(MeshFace {
                        indices: [tl, tr, bl, 0],
                        quad: false,
                    });
                } else {
                    mesh.faces.push(MeshFace {
                        indices: [tl, tr, bl, br],
                        quad: true,
                    });
                }
            }
        }
        mesh
    }
}

#[cfg(test)]
mod tests {
    use super::at_most;

    /// Bounds print with four significant digits, rounded down, without trailing zeros.
    #[test]
    fn bounds_print_rounded_down() {
        assert_eq!(at_most(32767.0), "32767");
        assert_eq!(at_most(32767.0 / 3.0), "10922");
        assert_eq!(at_most(0.32767), "0.3276");
        assert_eq!(at_most(1.5), "1.5");
        assert_eq!(at_most(0.00012345), "0.0001234");
    }
}
