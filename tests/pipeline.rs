//! The scene pipeline on hand-made cases whose outcome is known independently, the affine
//! texture warp measured against a perspective-correct reference computed here in f64, and
//! the default scene's determinism and golden image.

use gpu::Gpu;
use wobble::mesh::{Mesh, MeshFace, MeshVertex};
use wobble::pipeline::{PipelineOptions, Renderer};
use wobble::quantize::{Depth, Texture};
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
        camera: Camera {
            position: [0.0; 3],
            rotation: [0.0; 3],
            h: 256,
        },
        light: None,
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
    let path = std::env::temp_dir().join(format!("wobble-16c-{}.png", std::process::id()));
    img.save(&path).unwrap();
    let texture = Texture::load_png(&path, Depth::Clut4).unwrap();
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
        wobble::vram_image::PageDepth::Clut4,
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
    Texture::from_rgba(64, 64, &pixels, Depth::Direct15).unwrap()
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
    let mut obj = object(0, [0.0, 0.0, 512.0], [0.0, yaw_degrees, 0.0], 126.0);
    obj.texture = Some(0);
    let mut s = scene(vec![square()], vec![obj]);
    s.textures.push(TextureAsset {
        name: "uv".into(),
        texture: uv_texture(),
    });
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    assert_eq!(r.render_frame(0).drawn, 1);
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
