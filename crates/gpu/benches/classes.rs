//! The GPU primitive classes of the throughput comparison (issue 9): 1,000 primitives per
//! iteration, command words built up front from a seeded generator, only `Gpu::gp0_words`
//! timed. Criterion reports primitives per second; each class also prints Mpix/s from the
//! pixel count its geometry gives.
//!
//! Triangles: right triangles with 24-pixel legs (about 288 pixels) at random positions in a
//! 640x490 drawing area, random colours. Textured classes sample random UVs inside a 256x256
//! page; the 4-bit page holds random texels 1-15 and its 16-entry CLUT random non-zero
//! colours, the 15-bit page random non-zero texels. All classes but the last draw one shape
//! of triangle; the last draws it in four orientations with its vertices in any order. Lines: flat, 24 pixels along the major
//! axis (25 drawn). Quads: 320x240, inside the area.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use gpu::encode::{
    self, Line, Polygon, PolygonTexture, Rectangle, RectangleTexture, SpriteSize, Vertex,
};
use gpu::{BlendMode, ClutAttr, DrawMode, Gpu, Texpage, TextureDepth};
use std::hint::black_box;
use std::time::Instant;

const PRIMITIVES: usize = 1000;
const AREA_W: u32 = 640;
const AREA_H: u32 = 490;
const LEG: u32 = 24;
/// The 4-bit page at VRAM (640, 0).
const PAGE4: Texpage = page(640, 0, TextureDepth::Clut4);
/// The 15-bit page at VRAM (768, 256).
const PAGE15: Texpage = page(768, 256, TextureDepth::Direct15);
/// The CLUT at VRAM (0, 500).
const CLUT: ClutAttr = ClutAttr { x: 0, y: 500 };

const fn page(page_x: u16, page_y: u16, depth: TextureDepth) -> Texpage {
    Texpage {
        page_x,
        page_y,
        blend: BlendMode::Average,
        depth,
        depth_reserved: false,
        texture_disable: false,
    }
}

/// The draw mode word set before a class: its page, dithering on or off.
fn draw_mode(page: Texpage, dither: bool) -> u32 {
    encode::draw_mode(DrawMode {
        page_x: page.page_x,
        page_y: page.page_y,
        depth: page.depth,
        dither,
        ..DrawMode::default()
    })
}

/// xorshift32, seeded: the same words every run.
struct Rng(u32);

impl Rng {
    fn next(&mut self) -> u32 {
        let mut x = self.0;
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        self.0 = x;
        x
    }
    fn below(&mut self, n: u32) -> u32 {
        self.next() % n
    }
    fn color(&mut self) -> [u8; 3] {
        let [r, g, b, _] = self.next().to_le_bytes();
        [r, g, b]
    }
    /// A texel (U, V) inside the 256x256 page.
    fn uv(&mut self) -> (u8, u8) {
        let [u, v, ..] = self.next().to_le_bytes();
        (u, v)
    }
}

/// A vertex at (x, y) of colour `color` and texel `uv`.
fn vertex(x: u32, y: u32, color: [u8; 3], (u, v): (u8, u8)) -> Vertex {
    Vertex {
        x: x as i16,
        y: y as i16,
        color,
        u,
        v,
    }
}

/// The three corners of a right triangle with 24-pixel legs inside the area.
fn right_triangle(rng: &mut Rng) -> [(u32, u32); 3] {
    let x = rng.below(AREA_W - LEG);
    let y = rng.below(AREA_H - LEG);
    [(x, y), (x + LEG, y), (x, y + LEG)]
}

/// A textured polygon's texture: `clut`, `page`, modulated or raw.
fn texture(clut: ClutAttr, page: Texpage, raw: bool) -> Option<PolygonTexture> {
    Some(PolygonTexture { clut, page, raw })
}

/// Drawing area 640x490 at the origin, no offset, textures and CLUT uploaded.
fn setup(rng: &mut Rng) -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[
        encode::area_top_left(0, 0),
        encode::area_bottom_right(AREA_W as u16 - 1, AREA_H as u16 - 1),
        encode::drawing_offset(0, 0),
    ]);
    // 4-bit page: 64 halfwords x 256 lines of nibbles 1-15.
    g.gp0_words(&encode::cpu_to_vram(640, 0, 64, 256));
    for _ in 0..64 * 256 / 2 {
        let mut w = 0u32;
        for n in 0..8 {
            w |= (1 + rng.below(15)) << (4 * n);
        }
        g.gp0(w);
    }
    // CLUT: 16 non-zero colours.
    g.gp0_words(&encode::cpu_to_vram(0, 500, 16, 1));
    for _ in 0..8 {
        g.gp0((1 + rng.below(0xFFFF)) << 16 | (1 + rng.below(0xFFFF)));
    }
    // 15-bit page: 256x256 non-zero texels.
    g.gp0_words(&encode::cpu_to_vram(768, 256, 256, 256));
    for _ in 0..256 * 256 / 2 {
        g.gp0((1 + rng.below(0xFFFF)) << 16 | (1 + rng.below(0xFFFF)));
    }
    g
}

/// One class: its name, the E1 word set before it, its words, pixels per primitive.
struct Class {
    name: &'static str,
    e1: u32,
    words: Vec<u32>,
    pixels: u64,
}

fn classes() -> Vec<Class> {
    let mut rng = Rng(0x2545_F491);
    let tri_pixels = (LEG * LEG / 2) as u64;
    let mut out = Vec::new();
    let mut class = |name, e1, pixels, f: &mut dyn FnMut(&mut Rng, &mut Vec<u32>)| {
        let mut words = Vec::new();
        for _ in 0..PRIMITIVES {
            f(&mut rng, &mut words);
        }
        out.push(Class {
            name,
            e1,
            words,
            pixels,
        });
    };
    let none = page(0, 0, TextureDepth::Clut4);
    class(
        "flat_triangles",
        draw_mode(none, false),
        tri_pixels,
        &mut |r, w| {
            let corners = right_triangle(r);
            let color = r.color();
            let p = Polygon::triangle(corners.map(|(x, y)| vertex(x, y, color, (0, 0))));
            w.extend_from_slice(&p.packet());
        },
    );
    class(
        "gouraud_triangles_dithered",
        draw_mode(none, true),
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            let mut corner = |(x, y)| vertex(x, y, r.color(), (0, 0));
            let p = Polygon {
                vertices: [corner(a), corner(b), corner(c), Vertex::default()],
                gouraud: true,
                ..Polygon::default()
            };
            w.extend_from_slice(&p.packet());
        },
    );
    class(
        "clut4_textured_gouraud_dithered",
        draw_mode(PAGE4, true),
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            let mut corner = |(x, y)| {
                let color = r.color();
                vertex(x, y, color, r.uv())
            };
            let p = Polygon {
                vertices: [corner(a), corner(b), corner(c), Vertex::default()],
                gouraud: true,
                texture: texture(CLUT, PAGE4, false),
                ..Polygon::default()
            };
            w.extend_from_slice(&p.packet());
        },
    );
    class(
        "raw15_textured_triangles",
        draw_mode(PAGE15, false),
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            let mut corner = |(x, y)| vertex(x, y, [0; 3], r.uv());
            let p = Polygon {
                vertices: [corner(a), corner(b), corner(c), Vertex::default()],
                texture: texture(ClutAttr::default(), PAGE15, true),
                ..Polygon::default()
            };
            w.extend_from_slice(&p.packet());
        },
    );
    class(
        "clut4_sprites_16x16",
        draw_mode(PAGE4, false),
        256,
        &mut |r, w| {
            let x = r.below(AREA_W - 16);
            let y = r.below(AREA_H - 16);
            let color = r.color();
            let (u, v) = r.uv();
            let sprite = Rectangle {
                x: x as i16,
                y: y as i16,
                color,
                size: SpriteSize::Sixteen,
                texture: Some(RectangleTexture {
                    clut: CLUT,
                    u,
                    v,
                    raw: false,
                }),
                ..Rectangle::default()
            };
            w.extend_from_slice(&sprite.packet());
        },
    );
    class(
        "flat_lines",
        draw_mode(none, false),
        LEG as u64 + 1,
        &mut |r, w| {
            let x = LEG + r.below(AREA_W - 2 * LEG);
            let y = LEG + r.below(AREA_H - 2 * LEG);
            // 24 pixels along the major axis, any direction.
            let minor = r.below(2 * LEG + 1);
            let (dx, dy) = match r.below(4) {
                0 => (2 * LEG, minor),
                1 => (0, minor),
                2 => (minor, 2 * LEG),
                _ => (minor, 0),
            };
            let color = r.color();
            let line = Line {
                vertices: [
                    vertex(x, y, color, (0, 0)),
                    vertex(x + dx - LEG, y + dy - LEG, color, (0, 0)),
                ],
                ..Line::default()
            };
            w.extend_from_slice(&line.packet());
        },
    );
    class(
        "flat_quads_320x240",
        draw_mode(none, false),
        320 * 240,
        &mut |r, w| {
            let x = r.below(AREA_W - 320 + 1);
            let y = r.below(AREA_H - 240 + 1);
            let color = r.color();
            let corners = [(x, y), (x + 320, y), (x, y + 240), (x + 320, y + 240)];
            let p = Polygon::quad(corners.map(|(x, y)| vertex(x, y, color, (0, 0))));
            w.extend_from_slice(&p.packet());
        },
    );
    class(
        "semi_transparent_clut4_triangles",
        draw_mode(PAGE4, false),
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            let color = r.color();
            let mut corner = |(x, y)| vertex(x, y, color, r.uv());
            let p = Polygon {
                vertices: [corner(a), corner(b), corner(c), Vertex::default()],
                semi_transparent: true,
                texture: texture(CLUT, PAGE4, false),
                ..Polygon::default()
            };
            w.extend_from_slice(&p.packet());
        },
    );
    // Last, so that the classes above keep their words. The same triangles as the Gouraud
    // class but for their shape: the right angle at any of the box's four corners and the
    // vertices in any order, so that the set-up's and the rows' branches (which vertex is the
    // middle one, which side is long, spans growing or shrinking) change from one triangle to
    // the next as in a game's mesh, where the classes above repeat one shape.
    class(
        "gouraud_triangles_mixed_shapes",
        draw_mode(none, true),
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            let (x0, y0) = a;
            let flip = |(x, y): (u32, u32), fx: bool, fy: bool| {
                (
                    if fx { 2 * x0 + LEG - x } else { x },
                    if fy { 2 * y0 + LEG - y } else { y },
                )
            };
            let turn = r.below(4);
            let (fx, fy) = (turn & 1 != 0, turn & 2 != 0);
            let mut v = [flip(a, fx, fy), flip(b, fx, fy), flip(c, fx, fy)];
            // One of the six orders of the three vertices.
            let order = r.below(6) as usize;
            v.swap(0, order % 3);
            if order >= 3 {
                v.swap(1, 2);
            }
            let mut corner = |(x, y)| vertex(x, y, r.color(), (0, 0));
            let p = Polygon {
                vertices: [corner(v[0]), corner(v[1]), corner(v[2]), Vertex::default()],
                gouraud: true,
                ..Polygon::default()
            };
            w.extend_from_slice(&p.packet());
        },
    );
    out
}

fn bench(c: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9);
    let base = setup(&mut rng);
    let mut group = c.benchmark_group("class");
    group.throughput(Throughput::Elements(PRIMITIVES as u64));
    for class in classes() {
        let mut g = base.clone();
        g.gp0(class.e1);
        group.bench_function(class.name, |b| {
            b.iter(|| g.gp0_words(black_box(&class.words)))
        });
        // Mpix/s from the best of a few timed iterations.
        let best = (0..10)
            .map(|_| {
                let t = Instant::now();
                g.gp0_words(black_box(&class.words));
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        let pixels = class.pixels * PRIMITIVES as u64;
        println!(
            "{}: {pixels} px per iteration, {:.1} Mpix/s, {:.0} µs (best of 10)",
            class.name,
            pixels as f64 / best / 1e6,
            best * 1e6
        );
    }
    group.finish();
}

/// The triangle classes whose spans have an AVX2 build (`Gpu::set_avx2`).
const BUILT_FOR_AVX2: [&str; 2] = [
    "clut4_textured_gouraud_dithered",
    "raw15_textured_triangles",
];

/// Those classes in the two builds of their span loops, side by side: the baseline build,
/// then the AVX2 one, which runs only on an x86-64 host with AVX2 and the `std` feature
/// (`cargo bench -p gpu --features std --bench classes -- build`).
fn builds(c: &mut Criterion) {
    let mut rng = Rng(0x9E37_79B9);
    let base = setup(&mut rng);
    if !base.clone().set_avx2(true) {
        println!("build: the AVX2 build cannot run here (no AVX2, or no `std` feature)");
        return;
    }
    let mut group = c.benchmark_group("build");
    group.throughput(Throughput::Elements(PRIMITIVES as u64));
    for class in classes()
        .into_iter()
        .filter(|c| BUILT_FOR_AVX2.contains(&c.name))
    {
        // One GPU for both builds: two GPUs drawing with the same build have measured up to
        // 8% apart, one after the other: more than some builds differ by.
        let mut g = base.clone();
        g.gp0(class.e1);
        for avx2 in [false, true] {
            assert_eq!(g.set_avx2(avx2), avx2);
            let name = format!("{}/{}", class.name, if avx2 { "avx2" } else { "baseline" });
            group.bench_function(name, |b| b.iter(|| g.gp0_words(black_box(&class.words))));
        }
    }
    group.finish();
}

/// The store floor of the two classes bound by writing pixels: the same quads and flat
/// triangles (positions and colours from the class's own words) written into a 1024x512
/// halfword array as plain row fills, with no GPU: no decode, no edge walk, no clip, no
/// drawing-time count. 15-bit colour conversion is done once per primitive.
fn floor(c: &mut Criterion) {
    let all = classes();
    let mut vram = vec![0u16; 1024 * 512];
    let mut group = c.benchmark_group("floor");
    group.throughput(Throughput::Elements(PRIMITIVES as u64));
    let pixel = |w: u32| ((w >> 3) & 0x1F | (w >> 6) & 0x3E0 | (w >> 9) & 0x7C00) as u16;
    let origin = |w: u32| ((w & 0xFFFF) as usize, (w >> 16) as usize);
    let quads = &all
        .iter()
        .find(|c| c.name == "flat_quads_320x240")
        .unwrap()
        .words;
    group.bench_function("flat_quads_320x240_row_fills", |b| {
        b.iter(|| {
            for q in black_box(quads).chunks_exact(5) {
                let (x, y) = origin(q[1]);
                let p = pixel(q[0]);
                for row in y..y + 240 {
                    vram[row * 1024 + x..row * 1024 + x + 320].fill(p);
                }
            }
        })
    });
    let tris = &all
        .iter()
        .find(|c| c.name == "flat_triangles")
        .unwrap()
        .words;
    group.bench_function("flat_triangles_row_fills", |b| {
        b.iter(|| {
            for t in black_box(tris).chunks_exact(4) {
                let (x, y) = origin(t[1]);
                let p = pixel(t[0]);
                for k in 0..LEG as usize {
                    let row = (y + k) * 1024 + x;
                    vram[row..row + LEG as usize - k].fill(p);
                }
            }
        })
    });
    group.finish();
    black_box(&vram);
}

criterion_group!(benches, bench, builds, floor);
criterion_main!(benches);
