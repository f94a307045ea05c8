//! The GPU primitive classes of the throughput comparison (issue 9): 1,000 primitives per
//! iteration, command words built up front from a seeded generator, only `Gpu::gp0_words`
//! timed. Criterion reports primitives per second; each class also prints Mpix/s from the
//! pixel count its geometry gives.
//!
//! Triangles: right triangles with 24-pixel legs (about 288 pixels) at random positions in a
//! 640x490 drawing area, random colours. Textured classes sample random UVs inside a 256x256
//! page; the 4-bit page holds random texels 1-15 and its 16-entry CLUT random non-zero
//! colours, the 15-bit page random non-zero texels. Lines: flat, 24 pixels along the major
//! axis (25 drawn). Quads: 320x240, inside the area.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use gpu::Gpu;
use std::hint::black_box;
use std::time::Instant;

const PRIMITIVES: usize = 1000;
const AREA_W: u32 = 640;
const AREA_H: u32 = 490;
const LEG: u32 = 24;
/// 4-bit page at VRAM (640, 0): texpage attribute bits 0-3 = 10, depth 0.
const PAGE4: u32 = 10;
/// 15-bit page at VRAM (768, 256): bits 0-3 = 12, bit 4 = 1, depth 2 (bits 7-8).
const PAGE15: u32 = 12 | 1 << 4 | 2 << 7;
/// CLUT at VRAM (0, 500): attribute X / 16 in bits 0-5, Y in bits 6-14.
const CLUT: u32 = 500 << 6;

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
    fn color(&mut self) -> u32 {
        self.next() & 0xFF_FFFF
    }
    /// A UV word inside the 256x256 page, `attr` in the high half.
    fn uv(&mut self, attr: u32) -> u32 {
        attr << 16 | (self.next() & 0xFFFF)
    }
}

fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// The three corners of a right triangle with 24-pixel legs inside the area.
fn right_triangle(rng: &mut Rng) -> [u32; 3] {
    let x = rng.below(AREA_W - LEG);
    let y = rng.below(AREA_H - LEG);
    [xy(x, y), xy(x + LEG, y), xy(x, y + LEG)]
}

/// Drawing area 640x490 at the origin, no offset, textures and CLUT uploaded.
fn setup(rng: &mut Rng) -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[
        0xE300_0000,
        0xE400_0000 | (AREA_H - 1) << 10 | (AREA_W - 1),
        0xE500_0000,
    ]);
    // 4-bit page: 64 halfwords x 256 lines of nibbles 1-15.
    g.gp0_words(&[0xA000_0000, xy(640, 0), 256 << 16 | 64]);
    for _ in 0..64 * 256 / 2 {
        let mut w = 0u32;
        for n in 0..8 {
            w |= (1 + rng.below(15)) << (4 * n);
        }
        g.gp0(w);
    }
    // CLUT: 16 non-zero colours.
    g.gp0_words(&[0xA000_0000, xy(0, 500), 1 << 16 | 16]);
    for _ in 0..8 {
        g.gp0((1 + rng.below(0xFFFF)) << 16 | (1 + rng.below(0xFFFF)));
    }
    // 15-bit page: 256x256 non-zero texels.
    g.gp0_words(&[0xA000_0000, xy(768, 256), 256 << 16 | 256]);
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
    class("flat_triangles", 0xE100_0000, tri_pixels, &mut |r, w| {
        let [a, b, c] = right_triangle(r);
        w.extend([0x2000_0000 | r.color(), a, b, c]);
    });
    class(
        "gouraud_triangles_dithered",
        0xE100_0200,
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            w.extend([0x3000_0000 | r.color(), a, r.color(), b, r.color(), c]);
        },
    );
    class(
        "clut4_textured_gouraud_dithered",
        0xE100_0200 | PAGE4,
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            w.extend([0x3400_0000 | r.color(), a, r.uv(CLUT)]);
            w.extend([r.color(), b, r.uv(PAGE4 | 1 << 9)]);
            w.extend([r.color(), c, r.uv(0)]);
        },
    );
    class(
        "raw15_textured_triangles",
        0xE100_0000 | PAGE15,
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            w.extend([0x2500_0000, a, r.uv(0), b, r.uv(PAGE15), c, r.uv(0)]);
        },
    );
    class(
        "clut4_sprites_16x16",
        0xE100_0000 | PAGE4,
        256,
        &mut |r, w| {
            let x = r.below(AREA_W - 16);
            let y = r.below(AREA_H - 16);
            w.extend([0x7C00_0000 | r.color(), xy(x, y), r.uv(CLUT)]);
        },
    );
    class("flat_lines", 0xE100_0000, LEG as u64 + 1, &mut |r, w| {
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
        w.extend([
            0x4000_0000 | r.color(),
            xy(x, y),
            xy(x + dx - LEG, y + dy - LEG),
        ]);
    });
    class("flat_quads_320x240", 0xE100_0000, 320 * 240, &mut |r, w| {
        let x = r.below(AREA_W - 320 + 1);
        let y = r.below(AREA_H - 240 + 1);
        w.extend([
            0x2800_0000 | r.color(),
            xy(x, y),
            xy(x + 320, y),
            xy(x, y + 240),
            xy(x + 320, y + 240),
        ]);
    });
    class(
        "semi_transparent_clut4_triangles",
        0xE100_0000 | PAGE4,
        tri_pixels,
        &mut |r, w| {
            let [a, b, c] = right_triangle(r);
            w.extend([
                0x2600_0000 | r.color(),
                a,
                r.uv(CLUT),
                b,
                r.uv(PAGE4),
                c,
                r.uv(0),
            ]);
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

criterion_group!(benches, bench, floor);
criterion_main!(benches);
