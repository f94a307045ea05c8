//! The scene pipeline on hand-made cases whose outcome is known independently, the affine
//! texture warp measured against a perspective-correct reference computed here in f64, and
//! the default scene's determinism and golden image.

use gpu::Gpu;
use gpu::TextureDepth;
use wobble::pipeline::{PipelineOptions, Renderer};
use wobble::scene::mesh::{Mesh, MeshFace, MeshVertex};
use wobble::scene::texture::Texture;
use wobble::scene::{Camera, MeshAsset, Object, Scene, Screen, TextureAsset};

/// A unit square in the XY plane facing -Z (towards a camera at the origin looking +Z),
/// as one GP0-ordered quad: TL, TR, BL, BR with UVs (0,0), (1,0), (0,1), (1,1).
fn square() -> Mesh {
    let v = |x: f64, y: f64, u: f64, w: f64| MeshVertex {
        position: [x, y, 0.0],
        normal: [0.0, 0.0, -1.0],
        uv: [u, w],
    };
    Mesh {
        vertices: vec![
            v(-1.0, -1.0, 0.0, 0.0),
            v(1.0, -1.0, 1.0, 0.0),
            v(-1.0, 1.0, 0.0, 1.0),
            v(1.0, 1.0, 1.0, 1.0),
        ],
        faces: vec![MeshFace {
            indices: [0, 1, 2, 3],
            quad: true,
        }],
    }
}

fn object(mesh: usize, position: [f64; 3], rotation: [f64; 3], scale: f64) -> Object {
    Object {
        mesh,
        texture: None,
        position,
        rotation,
        spin: [0.0; 3],
        scale,
        color: [128, 128, 128],
        blend: None,
        tessellation: 0,
        split_extent: wobble::scene::DEFAULT_SPLIT_EXTENT,
    }
}

fn scene(meshes: Vec<Mesh>, objects: Vec<Object>) -> Scene {
    Scene {
        screen: Screen {
            width: 320,
            height: 240,
            dither: false,
            background: [0, 0, 0],
        },
        accuracy: Default::default(),
        camera: Camera {
            position: [0.0; 3],
            rotation: [0.0; 3],
            h: 256,
        },
        light: None,
        fog: None,
        textures: Vec::new(),
        meshes: meshes
            .into_iter()
            .enumerate()
            .map(|(i, mesh)| MeshAsset {
                name: format!("m{i}"),
                mesh,
            })
            .collect(),
        objects,
    }
}

fn pixel(gpu: &Gpu, x: usize, y: usize) -> u16 {
    gpu.vram().pixel(x, y) & 0x7FFF
}

/// A quad seen from behind (turned half a turn about Y) runs anticlockwise on screen:
/// NCLIP <= 0, culled. The same quad facing the camera is drawn.
#[test]
fn back_facing_quad_is_culled() {
    let s = scene(
        vec![square()],
        vec![object(0, [0.0, 0.0, 500.0], [0.0, 180.0, 0.0], 50.0)],
    );
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.culled, stats.drawn), (1, 0));
    let s = scene(
        vec![square()],
        vec![object(0, [0.0, 0.0, 500.0], [0.0; 3], 50.0)],
    );
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.culled, stats.drawn), (0, 1));
    assert_ne!(pixel(r.gpu(), 160, 120), 0);
}

/// A triangle with one vertex behind the camera (z < 0) is dropped whole: nothing of it is
/// drawn, not even the part in front of the near plane.
#[test]
fn triangle_crossing_near_plane_is_dropped_whole() {
    let v = |p: [f64; 3]| MeshVertex {
        position: p,
        normal: [0.0, 0.0, -1.0],
        uv: [0.0, 0.0],
    };
    // Clockwise on screen (NCLIP > 0) as seen from the camera; the third vertex at z = -200.
    let tri = Mesh {
        vertices: vec![
            v([-100.0, -50.0, 600.0]),
            v([100.0, -50.0, 600.0]),
            v([0.0, 80.0, -200.0]),
        ],
        faces: vec![MeshFace {
            indices: [0, 1, 2, 0],
            quad: false,
        }],
    };
    let s = scene(vec![tri], vec![object(0, [0.0; 3], [0.0; 3], 1.0)]);
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.dropped, stats.drawn), (1, 0));
    let img = r.image();
    assert!(img.pixels().all(|p| p.0 == [0, 0, 0]), "nothing drawn");
}

/// Two overlapping quads: the near one red, the far one green, submitted near-first. The
/// ordering table puts the far one first (painter's algorithm), so the overlap is red.
#[test]
fn overlapping_quads_drawn_far_first() {
    let mut near = object(0, [0.0, 0.0, 400.0], [0.0; 3], 40.0);
    near.color = [255, 0, 0];
    let mut far = object(0, [20.0, 20.0, 800.0], [0.0; 3], 80.0);
    far.color = [0, 255, 0];
    let s = scene(vec![square()], vec![near, far]);
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!(stats.drawn, 2);
    // The centre (160,120) is inside both quads; the near one covers 160 +- 25.6.
    assert_eq!(pixel(r.gpu(), 160, 120), 0x001F, "red on top");
    // (190,150) is outside the near quad but inside the far one (centre 166.4,126.4, +-25.6).
    assert_eq!(
        pixel(r.gpu(), 190, 150),
        0x03E0,
        "green where only the far quad is"
    );
}

/// A 16-colour image (channels multiples of 8, so exact in 5 bits) quantised to 4 bits,
/// uploaded by the renderer, and read back through its CLUT from VRAM reproduces the PNG.
#[test]
fn four_bit_texture_round_trips_through_vram() {
    let palette: Vec<[u8; 4]> = (0..16u8)
        .map(|i| [i * 16, 248 - i * 8, (i % 4) * 64 + 8, 255])
        .collect();
    let img = image::RgbaImage::from_fn(32, 16, |x, y| {
        image::Rgba(palette[((x / 2 + y) % 16) as usize])
    });
    let scratch = wobble_suite::Scratch::new("four_bit_texture_round_trips_through_vram");
    let path = scratch.join("16c.png");
    img.save(&path).unwrap();
    let texture = Texture::load_png(&path, TextureDepth::Clut4).unwrap();
    let mut s = scene(vec![square()], vec![]);
    s.textures.push(TextureAsset {
        name: "t".into(),
        texture,
    });
    let r = Renderer::new(s, PipelineOptions::default()).unwrap();
    // The allocator puts the first texture at page (320, 0) and its CLUT at (0, 480).
    let page = wobble::vram_image::texture_page_image(
        r.gpu().vram().as_slice(),
        320,
        0,
        gpu::TextureDepth::Clut4,
        (0, 480),
        wobble::vram_image::Expand::Shift,
    );
    for (x, y, p) in img.enumerate_pixels() {
        assert_eq!(page.get_pixel(x, y).0, p.0, "texel ({x},{y})");
    }
}

/// A 64x64 15-bit texture whose texel (u, v) encodes u and v: R = u & 31, G = v & 31,
/// B = u >> 5 | (v >> 5) << 1 (black (0,0) becomes 8000h, still decoding to (0,0)).
fn uv_texture() -> Texture {
    let pixels: Vec<[u8; 4]> = (0..64 * 64)
        .map(|i| {
            let (u, v) = ((i % 64) as u8, (i / 64) as u8);
            [
                (u & 31) << 3,
                (v & 31) << 3,
                ((u >> 5) | ((v >> 5) << 1)) << 3,
                255,
            ]
        })
        .collect();
    Texture::from_rgba(64, 64, &pixels, TextureDepth::Direct15).unwrap()
}

fn decode(p: u16) -> (i32, i32) {
    let (r, g, b) = (p & 31, (p >> 5) & 31, (p >> 10) & 31);
    ((r | (b & 1) << 5) as i32, (g | ((b >> 1) & 1) << 5) as i32)
}

/// The perspective-correct texel at pixel (x, y) for the square at (0, 0, 512), half-size
/// 126, turned `yaw` 1/4096-turn units about Y: the ray through the pixel's integer screen
/// coordinate (X/Z = (x - 160)/256, Y/Z = (y - 120)/256) meets the square's plane at
/// (p, q); u = 63 (p/126 + 1)/2, rounded to the nearest texel (the GPU's +0.5 bias).
fn reference_texel(x: f64, y: f64, yaw: i32) -> (i32, i32) {
    let (s, c) = (
        gte::typed::sin(yaw) as f64 / 4096.0,
        gte::typed::cos(yaw) as f64 / 4096.0,
    );
    // Columns of Ry: r0 = (c, 0, -s), r1 = (0, 1, 0); centre (0, 0, 512).
    let (a, b) = ((x - 160.0) / 256.0, (y - 120.0) / 256.0);
    let (r0, r1, cz) = ([c, 0.0, -s], [0.0, 1.0, 0.0], 512.0);
    // (r0x - a r0z) p + (r1x - a r1z) q = a cz;  (r0y - b r0z) p + (r1y - b r1z) q = b cz.
    let (m00, m01, m10, m11) = (
        r0[0] - a * r0[2],
        r1[0] - a * r1[2],
        r0[1] - b * r0[2],
        r1[1] - b * r1[2],
    );
    let det = m00 * m11 - m01 * m10;
    let p = (a * cz * m11 - m01 * b * cz) / det;
    let q = (m00 * b * cz - a * cz * m10) / det;
    let u = 63.0 * (p / 126.0 + 1.0) / 2.0;
    let v = 63.0 * (q / 126.0 + 1.0) / 2.0;
    // Ties round up, as the GPU's +0.5 then truncation does; 1e-9 absorbs f64 error at
    // exact half texels.
    (
        (u + 0.5 + 1e-9).floor() as i32,
        (v + 0.5 + 1e-9).floor() as i32,
    )
}

/// Largest texel error (in u or v) along the quad's split diagonal (v1 = TR to v2 = BL on
/// screen), over pixels well inside the quad.
fn diagonal_error(yaw_degrees: f64) -> i32 {
    diagonal_error_tessellated(yaw_degrees, 0)
}

/// [`diagonal_error`] with the quad split uniformly `level` times before projection.
fn diagonal_error_tessellated(yaw_degrees: f64, level: u8) -> i32 {
    let mut obj = object(0, [0.0, 0.0, 512.0], [0.0, yaw_degrees, 0.0], 126.0);
    obj.texture = Some(0);
    obj.tessellation = level;
    let mut s = scene(vec![square()], vec![obj]);
    s.textures.push(TextureAsset {
        name: "uv".into(),
        texture: uv_texture(),
    });
    let options = PipelineOptions {
        split_extent: Some(0),
        ..PipelineOptions::default()
    };
    let mut r = Renderer::new(s, options).unwrap();
    assert_eq!(r.render_frame(0).drawn, 1 << (2 * level));
    let yaw = (yaw_degrees * 4096.0 / 360.0).round() as i32;
    // Screen positions of TR and BL from the same geometry.
    let project = |p: [f64; 3]| {
        let (s, c) = (
            gte::typed::sin(yaw) as f64 / 4096.0,
            gte::typed::cos(yaw) as f64 / 4096.0,
        );
        let (x, y, z) = (c * p[0], p[1], 512.0 - s * p[0]);
        (160.0 + 256.0 * x / z, 120.0 + 256.0 * y / z)
    };
    let tr = project([126.0, -126.0, 0.0]);
    let bl = project([-126.0, 126.0, 0.0]);
    let mut worst = 0;
    let steps = 200;
    for i in 20..=steps - 20 {
        let t = i as f64 / steps as f64;
        let x = (tr.0 + (bl.0 - tr.0) * t).round();
        let y = (tr.1 + (bl.1 - tr.1) * t).round();
        let (u, v) = decode(pixel(r.gpu(), x as usize, y as usize));
        let (ru, rv) = reference_texel(x, y, yaw);
        worst = worst.max((u - ru).abs()).max((v - rv).abs());
    }
    worst
}

/// Face-on, affine and perspective-correct mapping agree exactly: the square projects to
/// (97,57)-(223,183), 2 pixels a texel, with no rounding anywhere.
#[test]
fn no_warp_face_on() {
    assert_eq!(diagonal_error(0.0), 0);
}

/// Turned 60 degrees, the affine interpolation along the split diagonal misses the
/// perspective-correct texel by more than 3 texels (the PS1 wobble).
#[test]
fn affine_warp_at_an_angle() {
    let e = diagonal_error(60.0);
    eprintln!("max texel error along the split diagonal at 60 degrees: {e}");
    assert!(e > 3, "max texel error along the diagonal: {e}");
}

/// The default scene renders the same bytes twice, and matches its golden image
/// (fixtures/golden/default-scene.png; regenerate on purpose with
/// `cargo run --release -- render -o fixtures/golden/default-scene.png`).
#[test]
fn default_scene_deterministic_and_golden() {
    let render = || {
        let mut r = Renderer::new(Scene::default_scene(), PipelineOptions::default()).unwrap();
        r.render_frame(0);
        r.image()
    };
    let a = render();
    let b = render();
    assert!(a == b, "two renders differ");
    let golden = image::open(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/golden/default-scene.png"
    ))
    .expect("golden image")
    .to_rgb8();
    let differing = a
        .pixels()
        .zip(golden.pixels())
        .filter(|(x, y)| x != y)
        .count();
    assert_eq!(a.dimensions(), golden.dimensions());
    assert_eq!(
        differing, 0,
        "{differing} pixels differ from the golden image"
    );
}

/// Tessellation is the cure: split three times (8x8 quads of 8x8 texels) the same quad at 60
/// degrees misses the perspective-correct texel by at most 2 texels. Each piece spans an
/// eighth of the depth range, so its own affine error is a fraction of a texel; what is left
/// is integer vertex snapping (half a pixel, a texel at 2 pixels per texel or less) and the
/// rounding of the reference.
#[test]
fn tessellation_reduces_the_warp() {
    let flat = diagonal_error_tessellated(60.0, 0);
    let split = diagonal_error_tessellated(60.0, 3);
    eprintln!("max texel error at 60 degrees: {flat} whole, {split} split three levels");
    assert!(split <= 2, "max texel error with 3 levels: {split}");
    assert!(split < flat, "tessellated {split} vs whole {flat}");
}

/// Small polygons are not split: the face-on quad of half-size 50 at Z = 500 with H = 256
/// spans 2 * 50 * 256 / 500 = 51.2 pixels, under the 64-pixel default, so level 2 leaves
/// it whole; with a split extent of 0 it becomes 4^2 = 16 quads.
#[test]
fn split_by_projected_size() {
    let mut obj = object(0, [0.0, 0.0, 500.0], [0.0; 3], 50.0);
    obj.tessellation = 2;
    let s = scene(vec![square()], vec![obj]);
    let mut r = Renderer::new(s.clone(), PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.polygons, stats.drawn), (1, 1));
    let options = PipelineOptions {
        split_extent: Some(0),
        ..PipelineOptions::default()
    };
    let mut r = Renderer::new(s.clone(), options).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.polygons, stats.drawn), (16, 16));
    // Twice as near (Z = 250) it spans 102.4 pixels: split once into 51.2-pixel quads.
    let mut near = s;
    near.objects[0].position[2] = 250.0;
    let mut r = Renderer::new(near, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.polygons, stats.drawn), (4, 4));
}

/// The near-plane cure: the triangle that crossed the near plane, split three times,
/// keeps the pieces wholly in front of the camera (they are drawn) and still drops the
/// pieces that touch the vertex behind it, whole.
#[test]
fn tessellation_recovers_part_of_a_near_plane_polygon() {
    let v = |p: [f64; 3]| MeshVertex {
        position: p,
        normal: [0.0, 0.0, -1.0],
        uv: [0.0, 0.0],
    };
    let tri = Mesh {
        vertices: vec![
            v([-100.0, -50.0, 600.0]),
            v([100.0, -50.0, 600.0]),
            v([0.0, 80.0, -200.0]),
        ],
        faces: vec![MeshFace {
            indices: [0, 1, 2, 0],
            quad: false,
        }],
    };
    let mut obj = object(0, [0.0; 3], [0.0; 3], 1.0);
    obj.tessellation = 3;
    let s = scene(vec![tri], vec![obj]);
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert!(stats.drawn > 0 && stats.dropped > 0, "{stats:?}");
    assert_eq!(
        stats.polygons,
        stats.drawn + stats.culled + stats.offscreen + stats.dropped
    );
    // The pieces at the first two vertices project around y = 120 - 50 * 256 / 600 = 98.7,
    // x = 160 -+ 42.7: the row just below the top edge is drawn there.
    assert_ne!(pixel(r.gpu(), 160, 100), 0);
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Any placement of a textured, lit cube and any tessellation set-up: every polygon
        /// the GTE stage examined ends in exactly one of drawn, culled, off screen or dropped,
        /// and nothing panics. A closed cube has at most three faces towards the camera, so
        /// without splitting at most three of its six quads are drawn.
        #[test]
        fn every_polygon_is_accounted_for(
            pos in prop::array::uniform3(-3000.0f64..3000.0),
            rot in prop::array::uniform3(-360.0f64..360.0),
            scale in 1.0f64..3000.0,
            level in 0u8..=3,
            split_extent in 0u16..200,
            frame in 0u32..1000,
        ) {
            let mut s = Scene::default_scene();
            s.objects.truncate(1);
            s.objects[0].position = pos;
            s.objects[0].rotation = rot;
            s.objects[0].scale = scale;
            s.objects[0].tessellation = level;
            let options = PipelineOptions { split_extent: Some(split_extent), ..PipelineOptions::default() };
            let mut r = Renderer::new(s, options).unwrap();
            let st = r.render_frame(frame);
            prop_assert_eq!(st.polygons, st.drawn + st.culled + st.offscreen + st.dropped);
            prop_assert!(st.polygons <= 6 << (2 * level));
            if level == 0 {
                prop_assert_eq!(st.polygons, 6);
                prop_assert!(st.drawn <= 3);
            }
        }

        /// Any image of at most 16 (resp. 256) 15-bit-exact colours goes through a 4-bit
        /// (8-bit) CLUT unchanged: the CLUT entry of every texel is the pixel's own colour.
        #[test]
        fn few_colours_are_kept_exactly(
            colours in prop::collection::vec(prop::array::uniform3(0u8..32), 1..=16),
            picks in prop::collection::vec(any::<prop::sample::Index>(), 1..=200),
            eight in any::<bool>(),
        ) {
            let pixels: Vec<[u8; 4]> = picks
                .iter()
                .map(|i| {
                    let c = colours[i.index(colours.len())];
                    [c[0] << 3, c[1] << 3, c[2] << 3, 255]
                })
                .collect();
            let depth = if eight { TextureDepth::Clut8 } else { TextureDepth::Clut4 };
            let t = Texture::from_rgba(pixels.len() as u16, 1, &pixels, depth).unwrap();
            prop_assert_eq!(t.clut.len(), if eight { 256 } else { 16 });
            for (p, &index) in pixels.iter().zip(&t.texels) {
                let want = u16::from(p[0] >> 3) | u16::from(p[1] >> 3) << 5 | u16::from(p[2] >> 3) << 10;
                let want = if want == 0 { 0x8000 } else { want };
                prop_assert_eq!(t.clut[index as usize], want);
            }
        }

        /// Textures and CLUTs placed by the allocator never overlap each other or the two
        /// display buffers, and stay inside VRAM; CLUTs sit at x multiples of 16.
        #[test]
        fn vram_placements_are_disjoint(
            width in prop::sample::select(vec![256u16, 320, 368, 512, 640]),
            height in prop_oneof![1u16..=256, Just(256u16)],
            textures in prop::collection::vec((0u8..3, 1u16..=256, 1u16..=256), 1..24),
        ) {
            let widest_clut = textures
                .iter()
                .map(|&(d, _, _)| [16usize, 256, 0][d as usize])
                .max()
                .unwrap_or(0);
            let mut alloc =
                wobble::pipeline::vram_alloc::VramAllocator::new(width, height, widest_clut);
            // Rectangles (x, y, w, h) in halfwords.
            let mut used = vec![(0u32, 0u32, u32::from(width), 2 * u32::from(height))];
            for (i, &(d, w, h)) in textures.iter().enumerate() {
                let depth = [TextureDepth::Clut4, TextureDepth::Clut8, TextureDepth::Direct15][d as usize];
                let t = Texture {
                    width: w,
                    height: h,
                    depth,
                    texels: vec![0; w as usize * h as usize],
                    clut: vec![0; depth.clut_len()],
                };
                let Ok(p) = alloc.place(&format!("t{i}"), &t) else { break };
                let per = [4u32, 2, 1][d as usize];
                used.push((
                    u32::from(p.page_x),
                    u32::from(p.page_y),
                    u32::from(w).div_ceil(per),
                    u32::from(h),
                ));
                if let Some((x, y)) = p.clut {
                    prop_assert_eq!(x % 16, 0);
                    used.push((u32::from(x), u32::from(y), depth.clut_len() as u32, 1));
                }
            }
            for (i, a) in used.iter().enumerate() {
                prop_assert!(a.0 + a.2 <= 1024 && a.1 + a.3 <= 512, "{a:?} outside VRAM");
                for b in &used[..i] {
                    let apart = a.0 + a.2 <= b.0 || b.0 + b.2 <= a.0
                        || a.1 + a.3 <= b.1 || b.1 + b.3 <= a.1;
                    prop_assert!(apart, "{a:?} overlaps {b:?}");
                }
            }
        }
    }
}

/// A quad 1,120 pixels wide (X -400..720 on screen, no coordinate saturated) is one the GPU
/// would drop (|dx| >= 1024), so it is dropped whole; split once, its 560-pixel pieces are
/// drawn and cover the screen centre.
#[test]
fn polygon_wider_than_the_gpu_draws_is_dropped_then_split() {
    let v = |x: f64, y: f64| MeshVertex {
        position: [x, y, 0.0],
        normal: [0.0, 0.0, -1.0],
        uv: [0.0, 0.0],
    };
    // At Z = 256 with H = 256 a unit of X is a pixel: screen X = 160 + X.
    let wide = Mesh {
        vertices: vec![
            v(-560.0, -50.0),
            v(560.0, -50.0),
            v(-560.0, 50.0),
            v(560.0, 50.0),
        ],
        faces: vec![MeshFace {
            indices: [0, 1, 2, 3],
            quad: true,
        }],
    };
    let mut obj = object(0, [0.0, 0.0, 256.0], [0.0; 3], 1.0);
    let s = scene(vec![wide.clone()], vec![obj.clone()]);
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.dropped, stats.drawn), (1, 0));
    assert!(
        r.image().pixels().all(|p| p.0 == [0, 0, 0]),
        "nothing drawn"
    );
    obj.tessellation = 1;
    let s = scene(vec![wide], vec![obj]);
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.dropped, stats.drawn), (0, 4));
    assert_ne!(pixel(r.gpu(), 160, 120), 0);
}

/// TextureDepth cueing: with fog from Z = 500 to Z = 2000, a quad beyond the far depth gets
/// IR0 = 1.0 (clamped) and the GTE's interpolation gives exactly the far colour (docs/hardware/gte.md §8:
/// MAC = (FC - in) * IR0 / 4096 + in = FC); a quad nearer than `near` gets IR0 = 0 and keeps
/// its own colour. Lit (NCDT/NCDS) or unlit (DPCS), the result is the same.
#[test]
fn fog_fades_to_the_far_colour() {
    for light in [false, true] {
        let mut near = object(0, [-60.0, 0.0, 400.0], [0.0; 3], 20.0);
        near.color = [255, 0, 0];
        let mut far = object(0, [1500.0, 0.0, 5000.0], [0.0; 3], 500.0);
        far.color = [255, 0, 0];
        let mut s = scene(vec![square()], vec![near, far]);
        s.fog = Some(wobble::scene::Fog {
            color: [0, 248, 0],
            near: 500.0,
            far: 2000.0,
        });
        if light {
            // Straight at the quads, white, no ambient: the lit colour is the material's.
            s.light = Some(wobble::scene::Light {
                direction: [0.0, 0.0, 1.0],
                color: [255, 255, 255],
                ambient: [0, 0, 0],
            });
        }
        let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
        assert_eq!(r.render_frame(0).drawn, 2);
        // Near quad centre: 160 - 60 * 256 / 400 = 121.6; far: 160 + 1500 * 256 / 5000 = 236.8.
        assert_eq!(pixel(r.gpu(), 237, 120), 0x03E0, "far quad, light {light}");
        if !light {
            assert_eq!(pixel(r.gpu(), 122, 120), 0x001F, "near quad");
        } else {
            // Lit: red only, faded by nothing (the exact level depends on the light maths).
            let p = pixel(r.gpu(), 122, 120);
            assert!(p & 0x1F > 0 && p >> 5 == 0, "near quad lit: {p:04x}");
        }
    }
}

/// A fog range too narrow for the 16-bit DQA is refused, not wrapped.
#[test]
fn narrow_fog_is_refused() {
    let mut s = scene(vec![square()], vec![]);
    s.fog = Some(wobble::scene::Fog {
        color: [0; 3],
        near: 30000.0,
        far: 30001.0,
    });
    let e = Renderer::new(s, PipelineOptions::default())
        .err()
        .expect("refused")
        .to_string();
    assert!(e.contains("fog"), "{e}");
}

/// Semi-transparency mode 2 (B - F) on an untextured quad: over a white background
/// (31, 31, 31 in 5 bits) a quad of colour (128, 0, 0) (16, 0, 0 in 5 bits) leaves
/// (15, 31, 31) = 7FEFh. The default mode 0 would give ((31 + 16) / 2, 15, 15) instead.
#[test]
fn untextured_semi_transparency_uses_its_own_mode() {
    let mut quad = object(0, [0.0, 0.0, 500.0], [0.0; 3], 50.0);
    quad.color = [128, 0, 0];
    quad.blend = Some(2);
    let mut s = scene(vec![square()], vec![quad]);
    s.screen.background = [255, 255, 255];
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    assert_eq!(r.render_frame(0).drawn, 1);
    assert_eq!(pixel(r.gpu(), 160, 120), 0x7FEF);
    assert_eq!(pixel(r.gpu(), 10, 10), 0x7FFF, "background");
}

/// Textured semi-transparency: texels only blend with bit 15 set, so a semi-transparent
/// material's texture is uploaded with it. A texture of one colour (128, 0, 0) (16, 0, 0 in
/// 5 bits), unmodulated (colour 128), in mode 2 (B - F) over white leaves (15, 31, 31) =
/// 7FEFh; drawn opaque it would be 0010h.
#[test]
fn textured_semi_transparency_blends() {
    let pixels = vec![[128u8, 0, 0, 255]; 16 * 16];
    let texture = Texture::from_rgba(16, 16, &pixels, TextureDepth::Clut4).unwrap();
    let mut quad = object(0, [0.0, 0.0, 500.0], [0.0; 3], 50.0);
    quad.texture = Some(0);
    quad.blend = Some(2);
    let mut s = scene(vec![square()], vec![quad]);
    s.screen.background = [255, 255, 255];
    s.textures.push(TextureAsset {
        name: "red".into(),
        texture,
    });
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    assert_eq!(r.render_frame(0).drawn, 1);
    assert_eq!(pixel(r.gpu(), 160, 120), 0x7FEF);
}
