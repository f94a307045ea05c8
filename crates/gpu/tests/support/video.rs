//! GPUs in a chosen video mode for the video timing tests (`beam.rs`, `timing.rs`), and the
//! deterministic sequence they slice time with.

#![allow(dead_code)]

use gpu::{Gpu, VideoStandard};

/// GP1(08h) mode bits (psx-spx "GP1(08h) - Display mode"): PAL, vertical interlace, 480 lines.
pub const PAL: u32 = 0x08;
pub const INTERLACE: u32 = 0x20;
pub const LINES480: u32 = 0x04;

/// A GPU of `standard` in GP1(08h) display mode `mode`.
pub fn gpu(standard: VideoStandard, mode: u32) -> Gpu {
    let mut g = Gpu::with_standard(standard);
    g.gp1(0x0800_0000 | mode);
    g
}

/// [`gpu`], then the horizontal display range X1..X2 (GP1(06h)) and the vertical range
/// Y1..Y2 (GP1(07h)).
pub fn ranged(
    standard: VideoStandard,
    mode: u32,
    (x1, x2): (u32, u32),
    (y1, y2): (u32, u32),
) -> Gpu {
    let mut g = gpu(standard, mode);
    g.gp1(0x0600_0000 | x2 << 12 | x1);
    g.gp1(0x0700_0000 | y2 << 10 | y1);
    g
}

/// A deterministic pseudo-random sequence from `seed`: the top 31 bits of a 64-bit linear
/// congruential generator's state after each step (Knuth's MMIX multiplier and increment).
pub fn sequence(seed: u64) -> impl Iterator<Item = u64> {
    let mut x = seed;
    std::iter::repeat_with(move || {
        x = x
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        x >> 33
    })
}
