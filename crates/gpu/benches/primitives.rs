//! Cost of drawing each primitive kind, at three sizes, with the pixel-pipeline features each
//! one uses, through the port an emulator writes (`Gpu::gp0_words`: decoding, drawing and the
//! drawing-time accounting included). Textures and CLUTs are uploaded once up front.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use gpu::encode::{
    self, Line, Packet, Polygon, PolygonTexture, Rectangle, RectangleTexture, Vertex,
};
use gpu::{BlendMode, ClutAttr, DrawMode, Gpu, Texpage};
use std::hint::black_box;

/// The 4-bit texture page at (640, 0).
const PAGE: Texpage = Texpage {
    page_x: 640,
    page_y: 0,
    blend: BlendMode::Average,
    depth: gpu::TextureDepth::Clut4,
    depth_reserved: false,
    texture_disable: false,
};
/// The 16-entry CLUT at (0, 480).
const CLUT: ClutAttr = ClutAttr { x: 0, y: 480 };

fn setup() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[
        encode::area_top_left(0, 0),
        encode::area_bottom_right(1023, 511),
        encode::drawing_offset(0, 0),
    ]);
    // A 4-bit 64x256 checker texture at the page and a 16-entry CLUT.
    g.gp0_words(&encode::cpu_to_vram(640, 0, 64, 256));
    for i in 0..(64 * 256 / 2) {
        g.gp0(if (i / 64) % 2 == 0 {
            0x1010_1010
        } else {
            0x0101_0101
        });
    }
    g.gp0_words(&encode::cpu_to_vram(0, 480, 16, 1));
    for i in 0..8u32 {
        g.gp0((0x7FFF - i * 0x421) << 16 | (0x1234 + i));
    }
    g
}

/// The draw mode of the benches: the page, dithering on when `dither`.
fn draw_mode(dither: bool) -> u32 {
    encode::draw_mode(DrawMode {
        page_x: PAGE.page_x,
        dither,
        ..DrawMode::default()
    })
}

fn vertex(x: i16, y: i16, color: [u8; 3], (u, v): (u8, u8)) -> Vertex {
    Vertex { x, y, color, u, v }
}

fn triangles(c: &mut Criterion) {
    let mut group = c.benchmark_group("triangle");
    for size in [16i16, 64, 256] {
        let (a, b, cc) = ((10, 10), (10 + size, 10), (10, 10 + size));
        let at = |(x, y), color, uv| vertex(x, y, color, uv);
        let grey = [0x80, 0x80, 0x80];
        let flat = Polygon::triangle([a, b, cc].map(|p| at(p, [0x40, 0x80, 0], (0, 0))));
        let gouraud = Polygon {
            vertices: [
                at(a, [0xFF, 0, 0], (0, 0)),
                at(b, [0, 0xFF, 0], (0, 0)),
                at(cc, [0, 0, 0xFF], (0, 0)),
                Vertex::default(),
            ],
            gouraud: true,
            ..Polygon::default()
        };
        let textured = Polygon {
            vertices: [
                at(a, grey, (0, 0)),
                at(b, grey, (0x3F, 0)),
                at(cc, grey, (0, 0x3F)),
                Vertex::default(),
            ],
            texture: Some(PolygonTexture {
                clut: CLUT,
                page: PAGE,
                raw: false,
            }),
            ..Polygon::default()
        };
        let gouraud_textured_blend = Polygon {
            vertices: [
                at(a, grey, (0, 0)),
                at(b, [0x80, 0x80, 0x40], (0x3F, 0)),
                at(cc, [0x80, 0x40, 0x80], (0, 0x3F)),
                Vertex::default(),
            ],
            gouraud: true,
            semi_transparent: true,
            texture: Some(PolygonTexture {
                clut: CLUT,
                page: Texpage {
                    blend: BlendMode::Add,
                    ..PAGE
                },
                raw: false,
            }),
            ..Polygon::default()
        };
        let cases: [(&str, Packet); 4] = [
            ("flat", flat.packet()),
            ("gouraud_dither", gouraud.packet()),
            ("textured_4bit", textured.packet()),
            (
                "gouraud_textured_blend_dither",
                gouraud_textured_blend.packet(),
            ),
        ];
        for (name, packet) in cases {
            let mut g = setup();
            g.gp0(draw_mode(true));
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
    let rectangle = Rectangle {
        x: 10,
        y: 10,
        color: [0x40, 0x80, 0],
        width: 64,
        height: 64,
        ..Rectangle::default()
    };
    let flat = rectangle.packet();
    group.bench_function("rectangle_flat_64x64", |b| {
        b.iter(|| g.gp0_words(black_box(&flat)))
    });
    let textured = Rectangle {
        color: [0x80, 0x80, 0x80],
        texture: Some(RectangleTexture {
            clut: CLUT,
            ..RectangleTexture::default()
        }),
        ..rectangle
    };
    let packet = textured.packet();
    group.bench_function("rectangle_textured_64x64", |b| {
        g.gp0(draw_mode(false));
        b.iter(|| g.gp0_words(black_box(&packet)))
    });
    let blended = Rectangle {
        semi_transparent: true,
        ..textured
    }
    .packet();
    group.bench_function("rectangle_textured_blend_64x64", |b| {
        g.gp0(draw_mode(false));
        b.iter(|| g.gp0_words(black_box(&blended)))
    });
    let red = [0xFF, 0, 0];
    let line = Line {
        vertices: [
            vertex(10, 10, red, (0, 0)),
            vertex(210, 90, [0, 0, 0xFF], (0, 0)),
        ],
        ..Line::default()
    };
    let flat_line = line.packet();
    group.bench_function("line_flat_200px", |b| {
        b.iter(|| g.gp0_words(black_box(&flat_line)))
    });
    let gouraud_line = Line {
        gouraud: true,
        ..line
    }
    .packet();
    group.bench_function("line_gouraud_200px", |b| {
        b.iter(|| g.gp0_words(black_box(&gouraud_line)))
    });
    let fill = encode::fill([0, 0, 0], 0, 0, 320, 240);
    group.bench_function("fill_320x240", |b| b.iter(|| g.gp0_words(black_box(&fill))));
    group.finish();
}

criterion_group!(benches, triangles, rectangles_and_lines);
criterion_main!(benches);
