//! The drawing-cost table of docs/emulator.md ("Drawing time"), written out again for the
//! tests in CPU cycles as the table gives them, and the conversion to the time a test sees.

#![allow(dead_code)]

/// Triangle, or first triangle of a quad: set-up.
pub const TRIANGLE_SETUP: f64 = 41.0;
/// Second triangle of a quad: set-up.
pub const QUAD_SECOND_SETUP: f64 = 23.0;
/// Extra set-up per triangle, Gouraud only.
pub const GOURAUD_SETUP: f64 = 144.0;
/// Extra set-up per triangle, textured only.
pub const TEXTURED_SETUP: f64 = 90.0;
/// Each row a triangle or rectangle walks inside the drawing area.
pub const ROW: f64 = 615.0 / 256.0;
/// Each pixel a triangle or rectangle writes.
pub const PIXEL: f64 = 136.0 / 256.0;
/// Each even-aligned pixel pair a blending or mask-checking span reads back.
pub const PAIR: f64 = 140.0 / 256.0;
/// Extra per Gouraud-shaded or textured pixel.
pub const SHADED_PIXEL: f64 = 0.5;
/// Rectangle set-up.
pub const RECTANGLE_SETUP: f64 = 8.0;
/// Each texture cache miss (textured triangles and rectangles).
pub const TEXTURE_MISS: f64 = 2255.0 / 256.0;
/// Line set-up and cost per major-axis step.
pub const LINE_SETUP: f64 = 8.0;
pub const LINE_STEP: f64 = 1.0;
/// Fill: set-up, per 16 pixels of a row, per row.
pub const FILL_SETUP: f64 = 23.0;
pub const FILL_16_PIXELS: f64 = 1.0;
pub const FILL_ROW: f64 = 1870.0 / 256.0;
/// VRAM-to-VRAM copy, per pixel.
pub const COPY_PIXEL: f64 = 347.0 / 256.0;
/// CPU-to-VRAM, per data word.
pub const WRITE_WORD: f64 = 2.0 * PIXEL;
/// VRAM-to-CPU, per word fetched.
pub const READ_WORD: f64 = 570.0 / 256.0;

/// A fill of `w` (rounded to 16) x `h`.
pub fn fill(w: u32, h: u32) -> f64 {
    FILL_SETUP + h as f64 * ((w / 16) as f64 * FILL_16_PIXELS + FILL_ROW)
}

/// GPU cycles of a cost in CPU cycles on a fresh NTSC GPU: 11/7 of it, the fraction of a
/// cycle carried (rounded down).
pub fn gpu_cycles(cpu: f64) -> u64 {
    (cpu * 11.0 / 7.0 + 1e-9).floor() as u64
}

/// CPU cycles that hold `gpu` GPU cycles, rounded up (7/11).
pub fn cpu_cycles(gpu: u64) -> u32 {
    (gpu as f64 * 7.0 / 11.0 - 1e-9).ceil() as u32
}

/// CPU cycles until a fresh NTSC GPU has finished work costing `cpu` CPU cycles.
pub fn cycles_to_idle(cpu: f64) -> u32 {
    cpu_cycles(gpu_cycles(cpu))
}
