//! Rasterization of decoded primitives into VRAM (gpu.md §3-§6).

use crate::Vram;
use crate::primitive::{Line, Rectangle, Triangle};
use crate::state::DrawState;
use crate::texture::ClutCache;

/// Draw one triangle (gpu.md §3): size drop, fill rule, attribute stepping, texture,
/// blending, dithering, mask.
pub fn draw_triangle(vram: &mut Vram, state: &DrawState, clut: &mut ClutCache, tri: &Triangle) {
    let _ = (vram, state, clut, tri);
}

/// Draw one line segment, both endpoints included (gpu.md §4).
pub fn draw_line(vram: &mut Vram, state: &DrawState, line: &Line) {
    let _ = (vram, state, line);
}

/// Draw one rectangle (gpu.md §5).
pub fn draw_rectangle(vram: &mut Vram, state: &DrawState, clut: &mut ClutCache, rect: &Rectangle) {
    let _ = (vram, state, clut, rect);
}
