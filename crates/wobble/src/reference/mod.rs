//! The reference renderer: the same scene drawn the way the artist meant it, in f64, for
//! measuring what the PS1's shortcuts cost. Exact trigonometry and division, sub-pixel
//! vertex positions, perspective-correct texture coordinates and colours, polygons clipped
//! (not dropped) at a near plane, a z-buffer instead of painter's order, no dithering,
//! nearest texel; fog, where the scene has it, computed per pixel from the exact depth with
//! the GTE's depth-cue curve (linear in 1/Z, docs/hardware/gte.md §5 step 7). Not hardware behaviour: the `gpu` crate stays hardware-faithful.
//!
//! An independent calculation: the geometry is computed here from the scene's own numbers
//! (mesh positions, normals and texture coordinates as f64, the object's scale, rotation and
//! position), sharing no code with the pipeline it measures: no 16-bit vertices, 1.3.12
//! normals or matrices, 8.8 texels, or 1/4096-turn angles.
//!
//! Sampling convention, shared with the GPU so face-on views agree exactly: pixel (x, y)
//! samples the scene at its integer coordinate, and the texel chosen is the nearest,
//! `floor(u + 0.5)` (the GPU's +0.5 bias then truncation).

use crate::scene::mesh::MeshVertex;
use crate::scene::{Object, Scene};

/// One reference frame.
#[derive(Clone, Debug)]
pub struct ReferenceFrame {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// RGB, row-major.
    pub rgb: Vec<[u8; 3]>,
    /// The texel sampled at each pixel, where the nearest surface is textured.
    pub texel: Vec<Option<(i32, i32)>>,
    /// The size of the texture sampled at each pixel.
    pub texture_size: Vec<Option<(i32, i32)>>,
}

impl ReferenceFrame {
    /// As an image.
    pub fn image(&self) -> image::RgbImage {
        image::RgbImage::from_fn(self.width as u32, self.height as u32, |x, y| {
            image::Rgb(self.rgb[y as usize * self.width + x as usize])
        })
    }
}

/// Rz * Ry * Rx for angles in degrees (the convention of `gte::typed::Matrix::rotation`).
pub fn rotation(deg: [f64; 3]) -> [[f64; 3]; 3] {
    let [x, y, z] = deg.map(f64::to_radians);
    let (sx, cx, sy, cy, sz, cz) = (x.sin(), x.cos(), y.sin(), y.cos(), z.sin(), z.cos());
    [
        [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
        [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
        [-sy, cy * sx, cy * cx],
    ]
}

fn mul(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// A vertex in camera space with the attributes the rasterizer interpolates.
#[derive(Clone, Copy, Debug)]
struct CamVertex {
    p: [f64; 3],
    /// u, v (texels), r, g, b (0..255 light-modulated material colour).
    attr: [f64; 5],
}

fn lerp(a: &CamVertex, b: &CamVertex, t: f64) -> CamVertex {
    CamVertex {
        p: std::array::from_fn(|i| a.p[i] + (b.p[i] - a.p[i]) * t),
        attr: std::array::from_fn(|i| a.attr[i] + (b.attr[i] - a.attr[i]) * t),
    }
}

/// Clip a convex polygon against z >= near (Sutherland-Hodgman).
fn clip_near(poly: &[CamVertex], near: f64) -> Vec<CamVertex> {
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let a = &poly[i];
        let b = &poly[(i + 1) % poly.len()];
        let (ina, inb) = (a.p[2] >= near, b.p[2] >= near);
        if ina {
            out.push(*a);
        }
        if ina != inb {
            let t = (near - a.p[2]) / (b.p[2] - a.p[2]);
            out.push(lerp(a, b, t));
        }
    }
    out
}

/// Fog as the reference applies it: 1/near, 1/far and the far colour.
#[derive(Clone, Copy, Debug)]
struct FogCurve {
    inv_near: f64,
    inv_far: f64,
    color: [f64; 3],
}

impl FogCurve {
    /// The fraction of fog colour at 1/z = `inv_z`: 0 at `near`, 1 at `far` and beyond,
    /// linear in 1/z between (the shape of the GTE's IR0, docs/hardware/gte.md §5 step 7).
    fn apply(&self, inv_z: f64, c: [f64; 3]) -> [f64; 3] {
        let f = ((self.inv_near - inv_z) / (self.inv_near - self.inv_far)).clamp(0.0, 1.0);
        std::array::from_fn(|k| c[k] + (self.color[k] - c[k]) * f)
    }
}

/// What a triangle is drawn with besides its vertices.
#[derive(Clone, Copy)]
struct Surface<'a> {
    texture: Option<&'a crate::scene::texture::Texture>,
    fog: Option<FogCurve>,
}

/// The directional light as the reference applies it: the unit vector towards the light,
/// the light colour and the ambient colour, 0..1.
type Lamp = ([f64; 3], [f64; 3], [f64; 3]);

fn lamp(scene: &Scene) -> Option<Lamp> {
    scene.light.map(|l| {
        let d = l.direction;
        let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-12);
        (
            d.map(|c| -c / len),
            l.color.map(|c| c as f64 / 255.0),
            l.ambient.map(|c| c as f64 / 255.0),
        )
    })
}

/// An object's polygons in camera space, computed here in f64 from the scene's own numbers
/// (nothing of the pipeline's fixed-point preparation): mesh positions times the object's
/// scale, turned by its exact rotation at `frame` and the camera's, moved by its position
/// relative to the camera; texture coordinates in texels by the scene's rule (a face's
/// coordinates shifted by whole repeats to start in the first repeat, 0..1 spanning texels
/// 0..size-1, docs/formats.md), with no rounding or clamping; colours lit per vertex from
/// the mesh's normal. Quads come in polygon order (GP0's v0 v1 v2 v3 is v0 v1 v3 v2 around
/// the edge); a face naming a vertex the mesh lacks is skipped.
fn camera_polygons(scene: &Scene, object: &Object, frame: u32) -> Vec<Vec<CamVertex>> {
    let Some(mesh) = scene.meshes.get(object.mesh).map(|m| &m.mesh) else {
        return Vec::new();
    };
    let view = rotation(scene.camera.rotation);
    let rot = rotation(object.rotation_at(frame));
    let m: [[f64; 3]; 3] = std::array::from_fn(|r| {
        std::array::from_fn(|c| (0..3).map(|k| view[r][k] * rot[k][c]).sum())
    });
    let rel: [f64; 3] = std::array::from_fn(|i| object.position[i] - scene.camera.position[i]);
    let t = mul(&view, rel);
    let span = object
        .texture
        .and_then(|i| scene.textures.get(i))
        .map_or([1.0, 1.0], |t| {
            [
                f64::from(t.texture.width) - 1.0,
                f64::from(t.texture.height) - 1.0,
            ]
        });
    let light = lamp(scene);
    let base = object.color.map(f64::from);
    let shade = |v: &MeshVertex| -> [f64; 3] {
        match light {
            None => base,
            Some((to_light, color, ambient)) => {
                let n = mul(&rot, v.normal);
                let i = (n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2]).max(0.0);
                std::array::from_fn(|k| (base[k] * (ambient[k] + color[k] * i)).min(255.0))
            }
        }
    };
    let mut polygons = Vec::with_capacity(mesh.faces.len());
    for face in &mesh.faces {
        let order: &[usize] = if face.quad { &[0, 1, 3, 2] } else { &[0, 1, 2] };
        let corners: Option<Vec<&MeshVertex>> = order
            .iter()
            .map(|&k| mesh.vertices.get(face.indices[k] as usize))
            .collect();
        let Some(corners) = corners else {
            continue;
        };
        let first_repeat = |axis: usize| {
            corners
                .iter()
                .map(|v| v.uv[axis])
                .fold(f64::INFINITY, f64::min)
                .floor()
        };
        let start = [first_repeat(0), first_repeat(1)];
        polygons.push(
            corners
                .iter()
                .map(|v| {
                    let p = mul(&m, v.position.map(|c| c * object.scale));
                    let c = shade(v);
                    CamVertex {
                        p: [p[0] + t[0], p[1] + t[1], p[2] + t[2]],
                        attr: [
                            (v.uv[0] - start[0]) * span[0],
                            (v.uv[1] - start[1]) * span[1],
                            c[0],
                            c[1],
                            c[2],
                        ],
                    }
                })
                .collect(),
        );
    }
    polygons
}

/// Screen-space vertex: position, 1/z, attributes divided by z.
#[derive(Clone, Copy)]
struct ScreenVertex {
    x: f64,
    y: f64,
    w: f64,
    attr_w: [f64; 5],
}

/// Render frame `frame` of a scene.
pub fn render(scene: &Scene, frame: u32) -> ReferenceFrame {
    let (width, height) = (scene.screen.width as usize, scene.screen.height as usize);
    let h = scene.camera.h as f64;
    let (cx, cy) = ((width / 2) as f64, (height / 2) as f64);
    let near = 1.0;
    let bg = scene.screen.background;
    let mut rgb = vec![bg; width * height];
    let mut texel = vec![None; width * height];
    let mut texture_size = vec![None; width * height];
    let mut depth = vec![0.0f64; width * height];
    let fog = scene
        .fog
        .filter(|f| f.near > 0.0 && f.far > f.near)
        .map(|f| FogCurve {
            inv_near: 1.0 / f.near,
            inv_far: 1.0 / f.far,
            color: f.color.map(f64::from),
        });
    for object in &scene.objects {
        let texture = object
            .texture
            .and_then(|i| scene.textures.get(i))
            .map(|t| &t.texture);
        for poly in camera_polygons(scene, object, frame) {
            let clipped = clip_near(&poly, near);
            if clipped.len() < 3 {
                continue;
            }
            let sv: Vec<ScreenVertex> = clipped
                .iter()
                .map(|v| {
                    let w = 1.0 / v.p[2];
                    ScreenVertex {
                        x: cx + h * v.p[0] * w,
                        y: cy + h * v.p[1] * w,
                        w,
                        attr_w: v.attr.map(|a| a * w),
                    }
                })
                .collect();
            // Back-face test on the whole polygon (same sign as NCLIP).
            let area: f64 = (0..sv.len())
                .map(|i| {
                    let (a, b) = (&sv[i], &sv[(i + 1) % sv.len()]);
                    a.x * b.y - b.x * a.y
                })
                .sum();
            if area <= 0.0 {
                continue;
            }
            for k in 1..sv.len() - 1 {
                raster(
                    [&sv[0], &sv[k], &sv[k + 1]],
                    (width, height),
                    Surface { texture, fog },
                    &mut rgb,
                    &mut texel,
                    &mut texture_size,
                    &mut depth,
                );
            }
        }
    }
    ReferenceFrame {
        width,
        height,
        rgb,
        texel,
        texture_size,
    }
}

fn expand(c: u16) -> f64 {
    let c = c & 31;
    ((c << 3) | (c >> 2)) as f64
}

/// Rasterize one clockwise (front-facing) triangle with a top-left rule at integer sample
/// points, perspective-correct attributes and a 1/z depth test.
fn raster(
    t: [&ScreenVertex; 3],
    (width, height): (usize, usize),
    Surface { texture, fog }: Surface<'_>,
    rgb: &mut [[u8; 3]],
    texel: &mut [Option<(i32, i32)>],
    texture_size: &mut [Option<(i32, i32)>],
    depth: &mut [f64],
) {
    let [a, b, c] = t;
    let area = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if area <= 0.0 || !area.is_finite() {
        return;
    }
    let min_x = a.x.min(b.x).min(c.x).floor().max(0.0) as usize;
    let max_x = (a.x.max(b.x).max(c.x).ceil().min(width as f64 - 1.0)).max(0.0) as usize;
    let min_y = a.y.min(b.y).min(c.y).floor().max(0.0) as usize;
    let max_y = (a.y.max(b.y).max(c.y).ceil().min(height as f64 - 1.0)).max(0.0) as usize;
    // Edge function of edge p->q at (x, y); inside is positive for clockwise-on-screen
    // triangles (Y down). Top-left rule: a pixel exactly on an edge belongs to it when the
    // edge is a top or left edge.
    let edge = |p: &ScreenVertex, q: &ScreenVertex, x: f64, y: f64| {
        (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x)
    };
    let top_left = |p: &ScreenVertex, q: &ScreenVertex| (q.y == p.y && q.x > p.x) || q.y < p.y;
    let edges = [(a, b, c), (b, c, a), (c, a, b)];
    for y in min_y..=max_y {
        for x in min_x..=max_x {
            let (fx, fy) = (x as f64, y as f64);
            let mut w = [0.0; 3];
            let mut inside = true;
            for (i, (p, q, _)) in edges.iter().enumerate() {
                let e = edge(p, q, fx, fy);
                if e < 0.0 || (e == 0.0 && !top_left(p, q)) {
                    inside = false;
                    break;
                }
                w[i] = e / area;
            }
            if !inside {
                continue;
            }
            // w[0] weights c (opposite a->b), w[1] weights a, w[2] weights b.
            let interp = |f: &dyn Fn(&ScreenVertex) -> f64| w[1] * f(a) + w[2] * f(b) + w[0] * f(c);
            let inv_z = interp(&|v| v.w);
            let idx = y * width + x;
            if inv_z <= depth[idx] {
                continue;
            }
            let attr: [f64; 5] = std::array::from_fn(|k| interp(&|v| v.attr_w[k]) / inv_z);
            let shade = [attr[2], attr[3], attr[4]];
            let (color, coord) = match texture {
                None => (shade, None),
                Some(tex) => {
                    // Nearest texel, ties up; 1e-9 absorbs f64 error at exact half texels.
                    let u = (attr[0] + 0.5 + 1e-9).floor() as i32;
                    let v = (attr[1] + 0.5 + 1e-9).floor() as i32;
                    let (tw, th) = (tex.width as i32, tex.height as i32);
                    let index = (v.rem_euclid(th) * tw + u.rem_euclid(tw)) as usize;
                    let t = tex.texels.get(index).copied().unwrap_or(0);
                    let c = if tex.clut.is_empty() {
                        t
                    } else {
                        tex.clut.get(t as usize).copied().unwrap_or(0)
                    };
                    if c == 0 {
                        continue;
                    }
                    let tc = [expand(c), expand(c >> 5), expand(c >> 10)];
                    (
                        std::array::from_fn(|k| tc[k] * shade[k] / 128.0),
                        Some((u, v)),
                    )
                }
            };
            let color = match fog {
                Some(f) => f.apply(inv_z, color),
                None => color,
            };
            depth[idx] = inv_z;
            rgb[idx] = color.map(|v| v.round().clamp(0.0, 255.0) as u8);
            texel[idx] = coord;
            texture_size[idx] = texture.map(|t| (t.width as i32, t.height as i32));
        }
    }
}
