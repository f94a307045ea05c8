//! Line rasterization (docs/hardware/gpu.md §4): both endpoints drawn, 32.32 positions with a half-pixel
//! bias, colour stepped in 12-bit fixed point, every pixel tested against the drawing area.
//!
//! Why this shape: a flat opaque undithered line inside the drawing area has a loop of its
//! own, one store per point straight from the packet's positions: 681 to 593 instructions a
//! line, and with the whole-packet path of `gp0.rs` 91 to 38 µs per 1,000 lines
//! (docs/performance.md, "What each change bought").

use super::coverage::exceeds_size_limit;
use super::{DrawCount, PixelEnv, TEX_NONE, shade_pixel, step_away_from_zero, wrap11};
use crate::color::{DITHER_TABLES, PLAIN_TABLE};
use crate::primitive::{Line, Vertex};
use crate::rows::Rows;
use crate::state::{DrawState, DrawingArea};
use crate::{VRAM_LEN, VRAM_WIDTH};

/// The endpoints with 11-bit coordinates, the left one first, and a flat line's colour (the
/// first vertex's in command order) on both; `None` when the size limit drops the line
/// (docs/hardware/gpu.md §4). A line clipped away still walks its points (their cost is
/// counted); each is rejected by the per-point area test.
#[inline(always)]
fn endpoints(line: &Line) -> Option<[Vertex; 2]> {
    let [mut p0, mut p1] = line.vertices;
    p0.x = wrap11(p0.x);
    p0.y = wrap11(p0.y);
    p1.x = wrap11(p1.x);
    p1.y = wrap11(p1.y);
    if exceeds_size_limit((p0.x, p0.y), (p1.x, p1.y)) {
        return None;
    }
    if !line.gouraud {
        p1.color = p0.color;
    }
    if p0.x > p1.x {
        core::mem::swap(&mut p0, &mut p1);
    }
    Some([p0, p1])
}

/// The points of a segment (docs/hardware/gpu.md §4): `k + 1` of them, from a 32.32 start
/// with a half-pixel bias, one step apart.
struct Walk {
    x: i64,
    y: i64,
    x_step: i64,
    y_step: i64,
    k: i32,
}

impl Walk {
    /// The walk from `p0` to `p1` (wrapped positions), `p0` the left endpoint.
    #[inline(always)]
    fn new(p0: (i32, i32), p1: (i32, i32)) -> Walk {
        let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
        let k = dx.abs().max(dy.abs());
        let (x_step, y_step) = if k == 0 {
            (0, 0)
        } else {
            (step_away_from_zero(dx, k), step_away_from_zero(dy, k))
        };
        let x = (((p0.0 as i64) << 32) | (1 << 31)) - 1024;
        let mut y = ((p0.1 as i64) << 32) | (1 << 31);
        if dy < 0 {
            y -= 1024;
        }
        Walk {
            x,
            y,
            x_step,
            y_step,
            k,
        }
    }

    /// What stepping the points costs: every point, drawn or not.
    fn count(&self) -> DrawCount {
        DrawCount {
            rows: 0,
            pixels: self.k as u32 + 1,
            pairs: 0,
        }
    }
}

/// A flat, opaque, undithered line without the mask test, on every row, from `p0` to `p1`
/// (offset applied, not yet wrapped), pixel value `value`: every point is one store when all
/// lie inside the drawing area, which they do when both endpoints do (each point lies in the
/// box of the two endpoints: over the whole segment the steps fall short of the endpoint by
/// less than 2^-21 of a pixel, too little to change a pixel). `None` when an endpoint lies
/// outside (the general [`draw`] then tests each point); a line the size limit drops
/// (docs/hardware/gpu.md §4) draws and steps nothing.
#[inline(always)]
pub(super) fn draw_flat_inside(
    vram: &mut [u16; VRAM_LEN],
    area: &DrawingArea,
    [p0, p1]: [(i32, i32); 2],
    value: u16,
) -> Option<DrawCount> {
    let (mut p0, mut p1) = ((wrap11(p0.0), wrap11(p0.1)), (wrap11(p1.0), wrap11(p1.1)));
    if exceeds_size_limit(p0, p1) {
        return Some(DrawCount::default());
    }
    if p0.0 > p1.0 {
        core::mem::swap(&mut p0, &mut p1);
    }
    if p0.0 < area.left as i32
        || p1.0 > area.right as i32
        || p0.1.min(p1.1) < area.top as i32
        || p0.1.max(p1.1) > area.bottom as i32
    {
        return None;
    }
    let walk = Walk::new(p0, p1);
    let (mut x, mut y) = (walk.x, walk.y);
    for _ in 0..walk.k + 1 {
        let (px, py) = ((x >> 32) as usize, (y >> 32) as usize);
        vram[(py * VRAM_WIDTH + px) & (VRAM_LEN - 1)] = value;
        x = x.wrapping_add(walk.x_step);
        y = y.wrapping_add(walk.y_step);
    }
    Some(walk.count())
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
    rows: Rows,
    cache: &mut crate::texture_cache::TextureCache,
) -> DrawCount {
    // A local copy, so the pixel loop keeps it in registers.
    let env = *env_ref;
    let Some([p0, p1]) = endpoints(line) else {
        return DrawCount::default();
    };
    let walk = Walk::new((p0.x, p0.y), (p1.x, p1.y));
    let (mut x, mut y, k) = (walk.x, walk.y, walk.k);
    let mut color = [0i32; 3];
    let mut color_step = [0i32; 3];
    for i in 0..3 {
        color[i] = ((p0.color[i] as i32) << 12) | (1 << 11);
        if GOURAUD && k != 0 {
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
            shade_pixel::<TEX_NONE, false, BLEND, MASK_CHECK, { crate::texture_cache::mode::OFF }>(
                vram,
                ((py & 511) as usize) * VRAM_WIDTH + (px & 1023) as usize,
                rgb,
                0,
                0,
                shade,
                &env,
                None,
                cache,
            );
        }
        x = x.wrapping_add(walk.x_step);
        y = y.wrapping_add(walk.y_step);
        if GOURAUD {
            for i in 0..3 {
                color[i] = color[i].wrapping_add(color_step[i]);
            }
        }
    }
    walk.count()
}
