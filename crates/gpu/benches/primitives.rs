//! Cost of drawing each primitive kind, at three sizes, with the pixel-pipeline features each
//! one uses: through `Gpu::gp0_words` (decoding included) and through the rasterizer
//! functions directly. Textures and CLUTs are uploaded once up front.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use gpu::Gpu;
use gpu::primitive::{Line, Rectangle, Texture, Triangle, Vertex};
use gpu::rasterizer::{draw_line, draw_rectangle, draw_triangle};
use gpu::state::{BlendMode, TextureDepth};
use gpu::texture::ClutCache;
use std::hint::black_box;

fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

fn setup() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
    // A 4-bit 64x256 checker texture at page (640, 0) and a 16-entry CLUT at (0, 480).
    g.gp0_words(&[0xA000_0000, xy(640, 0), 256 << 16 | 64]);
    for i in 0..(64 * 256 / 2) {
        g.gp0(if (i / 64) % 2 == 0 {
            0x1010_1010
        } else {
            0x0101_0101
        });
    }
    g.gp0_words(&[0xA000_0000, xy(0, 480), 1 << 16 | 16]);
    for i in 0..8u32 {
        g.gp0((0x7FFF - i * 0x421) << 16 | (0x1234 + i));
    }
    g
}

fn triangles(c: &mut Criterion) {
    let mut group = c.benchmark_group("triangle");
    for size in [16u32, 64, 256] {
        let (a, b, cc) = (xy(10, 10), xy(10 + size, 10), xy(10, 10 + size));
        let flat = [0x2000_8040, a, b, cc];
        let gouraud = [0x3000_00FF, a, 0x0000_FF00, b, 0x00FF_0000, cc];
        // 4-bit CLUT texture, page x = 640 (E1 bits 0-3 = 10), CLUT at (0, 480).
        let clut = (480 << 6) << 16;
        let tpage = 10 << 16;
        let textured = [0x2480_8080, a, clut, b, tpage | 0x3F, cc, 0x3F00];
        let gouraud_textured_blend = [
            0x3680_8080,
            a,
            clut,
            0x0040_8080,
            b,
            tpage | 0x20 << 16 | 0x3F,
            0x0080_4080,
            cc,
            0x3F00,
        ];
        let cases: [(&str, &[u32]); 4] = [
            ("flat", &flat),
            ("gouraud_dither", &gouraud),
            ("textured_4bit", &textured),
            ("gouraud_textured_blend_dither", &gouraud_textured_blend),
        ];
        for (name, packet) in cases {
            let mut g = setup();
            g.gp0(0xE100_020A);
            group.bench_with_input(BenchmarkId::new(name, size), &packet, |bch, p| {
                bch.iter(|| g.gp0_words(black_box(p)))
            });
        }
    }
    group.finish();
}

fn rectangles_and_lines(c: &mut Criterion) {
    let mut group = c.benchmark_group("other");
    let mut g = setup();
    group.bench_function("rectangle_flat_64x64", |b| {
        b.iter(|| g.gp0_words(black_box(&[0x6000_8040, xy(10, 10), 64 << 16 | 64])))
    });
    group.bench_function("rectangle_textured_64x64", |b| {
        g.gp0(0xE100_000A);
        b.iter(|| {
            g.gp0_words(black_box(&[
                0x6480_8080,
                xy(10, 10),
                (480 << 6) << 16,
                64 << 16 | 64,
            ]))
        })
    });
    group.bench_function("line_gouraud_200px", |b| {
        b.iter(|| {
            g.gp0_words(black_box(&[
                0x5000_00FF,
                xy(10, 10),
                0x00FF_0000,
                xy(210, 90),
            ]))
        })
    });
    group.bench_function("fill_320x240", |b| {
        b.iter(|| g.gp0_words(black_box(&[0x0200_0000, 0, 240 << 16 | 320])))
    });
    group.finish();
}

/// A right triangle with legs of `size` at (10, 10), U/V spanning 0..63.
fn right_triangle(size: i32, colors: [[u8; 3]; 3]) -> Triangle {
    let uv = [(0, 0), (63, 0), (0, 63)];
    let pos = [(10, 10), (10 + size, 10), (10, 10 + size)];
    let mut vertices = [Vertex::default(); 3];
    for i in 0..3 {
        vertices[i] = Vertex {
            x: pos[i].0,
            y: pos[i].1,
            color: colors[i],
            u: uv[i].0,
            v: uv[i].1,
        };
    }
    Triangle {
        vertices,
        ..Triangle::default()
    }
}

fn direct(c: &mut Criterion) {
    let g = setup();
    let mut vram = g.vram().clone();
    let mut state = *g.draw_state();
    state.mode.dither = true;
    let mut clut = ClutCache::default();
    let texture = Texture {
        page_x: 640,
        page_y: 0,
        depth: TextureDepth::Clut4,
        clut_x: 0,
        clut_y: 480,
        raw: false,
    };
    let mut group = c.benchmark_group("direct_triangle");
    for size in [16, 64, 256] {
        let flat = right_triangle(size, [[0x40, 0x80, 0x20]; 3]);
        let mut gouraud = right_triangle(size, [[0xFF, 0, 0], [0, 0xFF, 0], [0, 0, 0xFF]]);
        gouraud.gouraud = true;
        gouraud.dither = true;
        let mut textured = flat;
        textured.texture = Some(texture);
        textured.dither = true;
        let mut all = gouraud;
        all.texture = Some(texture);
        all.blend = Some(BlendMode::Average);
        let cases = [
            ("flat", flat),
            ("gouraud_dither", gouraud),
            ("textured_4bit_dither", textured),
            ("gouraud_textured_blend_dither", all),
        ];
        for (name, tri) in cases {
            group.bench_with_input(BenchmarkId::new(name, size), &tri, |b, t| {
                b.iter(|| draw_triangle(&mut vram, &state, &mut clut, black_box(t)))
            });
        }
    }
    group.finish();

    let mut group = c.benchmark_group("direct_other");
    let line = |gouraud: bool, blend: Option<BlendMode>| Line {
        vertices: [
            Vertex {
                x: 10,
                y: 10,
                color: [0xFF, 0, 0],
                ..Vertex::default()
            },
            Vertex {
                x: 210,
                y: 90,
                color: [0, 0, 0xFF],
                ..Vertex::default()
            },
        ],
        gouraud,
        blend,
        dither: true,
    };
    for (name, l) in [
        ("line_flat_200px", line(false, None)),
        ("line_gouraud_blend_200px", line(true, Some(BlendMode::Add))),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| draw_line(&mut vram, &state, black_box(&l)))
        });
    }
    let rect = |texture: Option<Texture>, blend: Option<BlendMode>| Rectangle {
        origin: Vertex {
            x: 10,
            y: 10,
            color: [0x80, 0x80, 0x80],
            ..Vertex::default()
        },
        width: 64,
        height: 64,
        texture,
        blend,
        ..Rectangle::default()
    };
    for (name, r) in [
        ("rectangle_flat_64x64", rect(None, None)),
        ("rectangle_textured_64x64", rect(Some(texture), None)),
        (
            "rectangle_textured_blend_64x64",
            rect(Some(texture), Some(BlendMode::Average)),
        ),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| draw_rectangle(&mut vram, &state, &mut clut, black_box(&r)))
        });
    }
    group.finish();
}

criterion_group!(benches, triangles, rectangles_and_lines, direct);
criterion_main!(benches);
