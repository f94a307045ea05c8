//! Cost of drawing each primitive kind, at three sizes, with the pixel-pipeline features each
//! one uses, through the port an emulator writes (`Gpu::gp0_words`: decoding, drawing and the
//! drawing-time accounting included). Textures and CLUTs are uploaded once up front.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use gpu::Gpu;
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
    group.bench_function("rectangle_textured_blend_64x64", |b| {
        g.gp0(0xE100_000A);
        b.iter(|| {
            g.gp0_words(black_box(&[
                0x6680_8080,
                xy(10, 10),
                (480 << 6) << 16,
                64 << 16 | 64,
            ]))
        })
    });
    group.bench_function("line_flat_200px", |b| {
        b.iter(|| g.gp0_words(black_box(&[0x4000_00FF, xy(10, 10), xy(210, 90)])))
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

criterion_group!(benches, triangles, rectangles_and_lines);
criterion_main!(benches);
