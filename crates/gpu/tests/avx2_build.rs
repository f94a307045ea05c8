//! The AVX2 build of the textured triangles' span loops (`Gpu::set_avx2`) draws what the
//! baseline build draws: the same VRAM, texture cache misses and entries, and drawing time,
//! on random streams of textured triangles and quads of every texture depth, blend, dither,
//! mask and window setting, with the cache on and off and VRAM written under sampled pages.

use gpu::Gpu;

/// xorshift32, seeded.
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
    fn chance(&mut self, in_n: u32) -> bool {
        self.below(in_n) == 0
    }
}

/// A vertex word: signed 11-bit X and Y.
fn xy(x: i32, y: i32) -> u32 {
    (((y as u32) & 0x7FF) << 16) | ((x as u32) & 0x7FF)
}

/// One random stream: set-up words, then textured polygons, fills and uploads.
fn stream(rng: &mut Rng, primitives: usize) -> Vec<u32> {
    let mut w = vec![
        0xE300_0000,
        0xE400_0000 | (479 << 10) | 639,
        0xE500_0000,
        // A random 256x256 block of texels and CLUTs at (512, 0).
        0xA000_0000,
        xy(512, 0),
        (256 << 16) | 256,
    ];
    for _ in 0..256 * 256 / 2 {
        w.push(rng.next());
    }
    for _ in 0..primitives {
        match rng.below(24) {
            0 => w.push(0xE100_0000 | rng.below(1 << 11)),
            1 => w.push(0xE200_0000 | if rng.chance(2) { 0 } else { rng.below(1 << 20) }),
            2 => w.push(0xE600_0000 | rng.below(4)),
            3 => {
                // A fill under the sampled block.
                w.extend([
                    0x0200_0000 | (rng.next() & 0xFF_FFFF),
                    xy(512 + 16 * rng.below(16) as i32, rng.below(256) as i32),
                    ((1 + rng.below(32)) << 16) | (16 * (1 + rng.below(4))),
                ]);
            }
            4 => {
                // A small upload under the sampled block.
                let (width, height) = (1 + rng.below(8), 1 + rng.below(8));
                w.extend([
                    0xA000_0000,
                    xy(512 + rng.below(256) as i32, rng.below(256) as i32),
                    (height << 16) | width,
                ]);
                for _ in 0..(width * height).div_ceil(2) {
                    w.push(rng.next());
                }
            }
            _ => polygon(rng, &mut w),
        }
    }
    w
}

/// A textured triangle or quad, flat or Gouraud, raw or modulated, opaque or blended, of
/// a random page and CLUT in the block at (512, 0), its texels stepping fast or slowly.
fn polygon(rng: &mut Rng, w: &mut Vec<u32>) {
    let gouraud = rng.chance(2);
    let quad = rng.chance(3);
    let op = 0x24 | (rng.below(4)) | if quad { 8 } else { 0 } | if gouraud { 0x10 } else { 0 };
    let depth = rng.below(3);
    let page = (8 + rng.below(4)) | depth << 7 | rng.below(4) << 5;
    let clut = (32 + rng.below(16)) | rng.below(256) << 6;
    let size = [8, 24, 64, 200][rng.below(4) as usize];
    let (x0, y0) = (rng.below(680) as i32 - 20, rng.below(520) as i32 - 20);
    // Texels near 1:1 (slow steps) or anywhere in the page.
    let slow = rng.chance(2);
    let (u0, v0) = (rng.below(256), rng.below(256));
    let n = if quad { 4 } else { 3 };
    for k in 0..n {
        let (x, y) = (
            x0 + rng.below(size) as i32 - size as i32 / 2,
            y0 + rng.below(size) as i32 - size as i32 / 2,
        );
        let (u, v) = if slow {
            (
                (u0 as i32 + x - x0) as u32 & 0xFF,
                (v0 as i32 + y - y0) as u32 & 0xFF,
            )
        } else {
            (rng.below(256), rng.below(256))
        };
        let color = rng.next() & 0xFF_FFFF;
        if k == 0 {
            w.push(op << 24 | color);
        } else if gouraud {
            w.push(color);
        }
        let attr = match k {
            0 => clut,
            1 => page,
            _ => 0,
        };
        w.extend([xy(x, y), attr << 16 | v << 8 | u]);
    }
}

/// What a stream leaves that either build could change.
fn drawn(
    words: &[u32],
    cache: bool,
    avx2: bool,
) -> (Vec<u16>, u64, u64, Vec<Option<gpu::TextureCacheEntry>>) {
    let mut gpu = Gpu::new();
    gpu.set_texture_cache(cache);
    assert_eq!(gpu.set_avx2(avx2), avx2);
    gpu.gp0_words(words);
    let entries = (0..=255).map(|i| gpu.texture_cache_entry(i)).collect();
    (
        gpu.vram().as_slice().to_vec(),
        gpu.texture_cache_misses(),
        gpu.work_cycles(),
        entries,
    )
}

/// Whether this host runs the AVX2 build: exactly where the standard library finds the
/// instruction sets it is built for, with the `std` feature on x86-64.
fn avx2_runs() -> bool {
    let runs = Gpu::new().set_avx2(true);
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    assert_eq!(
        runs,
        std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("lzcnt")
            && std::is_x86_feature_detected!("popcnt")
    );
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    assert!(!runs);
    runs
}

#[test]
fn a_new_gpu_takes_the_avx2_build_where_it_runs() {
    let runs = avx2_runs();
    assert_eq!(Gpu::new().avx2(), runs);
    let mut gpu = Gpu::new();
    assert!(!gpu.set_avx2(false));
    assert!(!gpu.avx2());
    assert_eq!(gpu.set_avx2(true), runs);
}

#[test]
fn both_builds_draw_the_same() {
    if !avx2_runs() {
        // Only the baseline build can run here: nothing to compare it with.
        return;
    }
    let streams: u32 = if cfg!(debug_assertions) { 4 } else { 24 };
    for seed in 1..=streams {
        let mut rng = Rng(0x2545_F491 ^ seed.wrapping_mul(0x9E37_79B9));
        let words = stream(&mut rng, 400);
        for cache in [true, false] {
            let (a, b) = (drawn(&words, cache, false), drawn(&words, cache, true));
            assert!(a.0 == b.0, "VRAM differs: seed {seed}, cache {cache}");
            assert_eq!(a.1, b.1, "misses: seed {seed}, cache {cache}");
            assert_eq!(a.2, b.2, "drawing time: seed {seed}, cache {cache}");
            assert_eq!(a.3, b.3, "cache entries: seed {seed}, cache {cache}");
        }
        // The streams draw: not all of VRAM outside the texel block is still black.
        let (vram, ..) = drawn(&words, true, true);
        assert!(
            vram.chunks(1024)
                .any(|line| line[..512].iter().any(|&p| p != 0))
        );
    }
}
