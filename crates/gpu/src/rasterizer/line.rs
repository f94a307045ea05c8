//! Line rasterization (docs/hardware/gpu.md §4): both endpoints drawn, 32.32 positions with a half-pixel
//! bias, colour stepped in 12-bit fixed point, every pixel tested against the drawing area.

use super::{
    Coverage, DrawCount, DropReason, PixelEnv, TEX_NONE, line_coverage, shade_pixel, wrap11,
};
use crate::color::{DITHER_TABLES, PLAIN_TABLE};
use crate::primitive::Line;
use crate::state::DrawState;
use crate::{VRAM_LEN, VRAM_WIDTH};

/// Per-point step of a 32.32 coordinate over `k` steps, rounded away from zero.
fn step(delta: i32, k: i32) -> i64 {
    super::step_away_from_zero(delta, k)
}

/// Draw with the pixel pipeline fixed by the const parameters.
pub(super) fn draw<
    const GOURAUD: bool,
    const BLEND: bool,
    const DITHER: bool,
    const MASK_CHECK: bool,
    const FILTERED: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    env_ref: &PixelEnv,
    line: &Line,
    rows: super::Rows,
) -> DrawCount {
    // A local copy, so the pixel loop keeps it in registers.
    let env = *env_ref;
    let [mut p0, mut p1] = line.vertices;
    p0.x = wrap11(p0.x);
    p0.y = wrap11(p0.y);
    p1.x = wrap11(p1.x);
    p1.y = wrap11(p1.y);
    // Size drop (docs/hardware/gpu.md §4). A line clipped away still walks its points (their cost is
    // counted); each is rejected by the per-point area test below.
    let coverage = line_coverage([(p0.x, p0.y), (p1.x, p1.y)], &state.area);
    if coverage == Coverage::Dropped(DropReason::SizeLimit) {
        return DrawCount::default();
    }
    if !GOURAUD {
        // A flat line has the command colour: the first vertex's, before any swap.
        p1.color = p0.color;
    }
    if p0.x > p1.x {
        core::mem::swap(&mut p0, &mut p1);
    }
    let (dx, dy) = (p1.x - p0.x, p1.y - p0.y);
    let k = dx.abs().max(dy.abs());
    let (x_step, y_step) = if k == 0 {
        (0, 0)
    } else {
        (step(dx, k), step(dy, k))
    };
    let mut x = (((p0.x as i64) << 32) | (1 << 31)) - 1024;
    let mut y = ((p0.y as i64) << 32) | (1 << 31);
    if dy < 0 {
        y -= 1024;
    }
    let mut color = [0i32; 3];
    let mut color_step = [0i32; 3];
    for i in 0..3 {
        color[i] = ((p0.color[i] as i32) << 12) | (1 << 11);
        if k != 0 {
            color_step[i] = ((p1.color[i] as i32 - p0.color[i] as i32) << 12) / k;
        }
    }
    let area = state.area;
    for _ in 0..=k {
        let px = ((x >> 32) & 2047) as i32;
        let py = ((y >> 32) & 2047) as i32;
        if px >= area.left as i32
            && px <= area.right as i32
            && py >= area.top as i32
            && py <= area.bottom as i32
            && (!FILTERED || rows.keeps(py))
        {
            let rgb = [color[0] >> 12, color[1] >> 12, color[2] >> 12];
            let shade = if DITHER {
                &DITHER_TABLES[(py & 3) as usize][(px & 3) as usize]
            } else {
                &PLAIN_TABLE
            };
            shade_pixel::<TEX_NONE, false, BLEND, MASK_CHECK>(
                vram,
                ((py & 511) as usize) * VRAM_WIDTH + (px & 1023) as usize,
                rgb,
                0,
                0,
                shade,
                &env,
                None,
            );
        }
        x = x.wrapping_add(x_step);
        y = y.wrapping_add(y_step);
        if GOURAUD {
            for i in 0..3 {
                color[i] = color[i].wrapping_add(color_step[i]);
            }
        }
    }
    DrawCount {
        pixels: k as u32 + 1,
        pairs: 0,
    }
}
