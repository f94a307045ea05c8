//! Rectangle (sprite) rasterization (docs/hardware/gpu.md §5): no dithering, U/V counted per pixel and
//! wrapped at 256 (decremented when flipped, starting from `u0 | 1` under the X flip), clipped
//! to the drawing area.
//!
//! Why this shape: one routine per feature set, as for triangles, with a 4-bit texture's CLUT
//! shaded once per rectangle; a row whose texels run left to right unwindowed reads each
//! texture halfword once for the texels it holds, and at 4-bit each cache entry once for
//! sixteen pixels at a time: 16x16 4-bit sprites take about 4,600 instructions each, 3.9x
//! fewer than Mednafen's (docs/performance.md, "Sprite rows sixteen texels at a time").

use super::{
    DrawCount, PixelEnv, TEX_NONE, put_shaded, shade_pixel, wrap11, write_shaded, write_texel,
};
use crate::color::PLAIN_TABLE;
use crate::primitive::Rectangle;
use crate::rows::Rows;
use crate::state::{DrawState, DrawingArea};
use crate::texture::clut_index;
use crate::texture_cache::{TextureCache, mode};
use crate::{VRAM_LEN, VRAM_WIDTH};

/// The drawn columns `[x_start, x_end)` and rows `[y_start, y_end)`: the rectangle at its
/// wrapped origin clipped to the drawing area (docs/hardware/gpu.md §5); `None` when nothing is left.
#[inline(always)]
pub(super) fn clip(rect: &Rectangle, area: &DrawingArea) -> Option<(i32, i32, i32, i32)> {
    let (x0, y0) = (wrap11(rect.origin.x), wrap11(rect.origin.y));
    let x_start = x0.max(area.left as i32);
    let x_end = (x0 + rect.width as i32).min(area.right as i32 + 1);
    let y_start = y0.max(area.top as i32);
    let y_end = (y0 + rect.height as i32).min(area.bottom as i32 + 1);
    (x_start < x_end && y_start < y_end).then_some((x_start, x_end, y_start, y_end))
}

/// Draw with the pixel pipeline fixed by the const parameters, texels read in the texture
/// cache mode `CACHE` (docs/hardware/gpu.md §10).
pub(super) fn draw<
    const TEX: u8,
    const CACHE: u8,
    const RAW: bool,
    const BLEND: bool,
    const MASK_CHECK: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    env_ref: &PixelEnv,
    rect: &Rectangle,
    filter: Rows,
    cache: &mut TextureCache,
) -> DrawCount {
    // A local copy, so the pixel loop keeps it in registers.
    let env = *env_ref;
    let o = rect.origin;
    let (x0, y0) = (wrap11(o.x), wrap11(o.y));
    let Some((x_start, x_end, y_start, y_end)) = clip(rect, &state.area) else {
        return DrawCount::default();
    };
    let mut row_count = DrawCount::default();
    row_count.span(x_start, x_end, BLEND || MASK_CHECK);
    let rows = filter.count(y_start, y_end);
    let drawn = DrawCount {
        rows,
        pixels: row_count.pixels * rows,
        pairs: row_count.pairs * rows,
    };
    let flat = o.color.map(|c| c as i32);
    // Per-pixel texel steps: +1, or -1 (255 in 8-bit wrapping arithmetic) when flipped.
    let du: u8 = if rect.flip_x { 255 } else { 1 };
    let dv: u8 = if rect.flip_y { 255 } else { 1 };
    // With the X flip the origin column samples u0 | 1, not u0 (docs/hardware/gpu.md §5).
    let u0 = if rect.flip_x { o.u | 1 } else { o.u };
    // Texel at the first drawn column: u0 + (x_start - x0) steps.
    let u_start = u0.wrapping_add(du.wrapping_mul((x_start - x0) as u8));
    // Texels that run left to right along one VRAM line, read a halfword at a time.
    let forward = TEX != TEX_NONE && !rect.flip_x && env.sampler.window_is_identity();
    // A 4-bit texture's shaded CLUT with the mask bit set in it, when no blend reads the
    // texel's own bit 15 after it.
    let (lut, mask_or) = if TEX == 1 && !BLEND {
        let set = u32::from(env.mask_or);
        (env.lut.map(|e| if e == 0 { 0 } else { e | set }), 0)
    } else {
        (env.lut, env.mask_or)
    };
    filter.each(y_start, y_end, |y| {
        let row = ((y & 511) as usize) * VRAM_WIDTH;
        if TEX == TEX_NONE && !BLEND && !MASK_CHECK {
            super::fill_span(
                vram,
                row,
                x_start,
                x_end,
                super::flat_color(flat, env.mask_or),
                env.line,
            );
            return;
        }
        let v = o.v.wrapping_add(dv.wrapping_mul((y - y0) as u8));
        if forward {
            let texels = ((env.sampler.page_y + v as usize) & 511) * VRAM_WIDTH;
            // With the cache off, texels come straight from VRAM: a row drawn over its own
            // texels must see each pixel written before the next texel is read.
            if CACHE != mode::OFF || texels != row {
                // Sixteen texels are read before their pixels are written: not on the
                // line the row draws, where a pixel may land on an entry read after it.
                if TEX == 1 && texels != row {
                    clut4_row::<CACHE, BLEND, MASK_CHECK>(
                        vram, cache, &env, &lut, mask_or, texels, u_start, row, x_start, x_end,
                    );
                } else {
                    forward_row::<TEX, CACHE, RAW, BLEND, MASK_CHECK>(
                        vram, cache, &env, flat, texels, u_start, row, x_start, x_end,
                    );
                }
                return;
            }
        }
        let mut u = u_start;
        for x in x_start..x_end {
            shade_pixel::<TEX, RAW, BLEND, MASK_CHECK, CACHE>(
                vram,
                row + x as usize,
                flat,
                u,
                v,
                &PLAIN_TABLE,
                &env,
                (TEX == 1).then_some(&env.lut),
                cache,
            );
            u = u.wrapping_add(du);
        }
    });
    drawn
}

/// One row of a textured rectangle drawn left to right with the texture window off
/// (docs/hardware/gpu.md §5, §7): its texels lie one after the other along the VRAM line
/// starting at `texels`, U wrapping at 256 within the page, so each halfword is read once
/// for the 4, 2 or 1 texels it holds. The pixels are those [`shade_pixel`] writes.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn forward_row<
    const TEX: u8,
    const CACHE: u8,
    const RAW: bool,
    const BLEND: bool,
    const MASK_CHECK: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    cache: &mut TextureCache,
    env: &PixelEnv,
    flat: [i32; 3],
    texels: usize,
    u_start: u8,
    row: usize,
    x_start: i32,
    x_end: i32,
) {
    let shift = match TEX {
        1 => 2,
        2 => 1,
        _ => 0,
    };
    let per = 1usize << shift;
    // Halfwords along a page line: U wraps at 256 texels.
    let line_halfwords = 256 >> shift;
    let page_x = env.sampler.page_x;
    let address = |h: usize| texels + ((page_x + h) & (VRAM_WIDTH - 1));
    let (mut h, mut x, end) = (
        usize::from(u_start) >> shift,
        row + x_start as usize,
        row + x_end as usize,
    );
    // The halfword the row starts inside, then whole halfwords, then the one it ends inside.
    let first = usize::from(u_start) & (per - 1);
    if first != 0 {
        let word = cache.halfword::<TEX, CACHE>(vram, address(h));
        let n = (per - first).min(end - x);
        for j in 0..n {
            pixel::<TEX, RAW, BLEND, MASK_CHECK>(vram, x + j, word, first + j, env, flat);
        }
        x += n;
        h = (h + 1) & (line_halfwords - 1);
    }
    for _ in 0..(end - x) >> shift {
        let word = cache.halfword::<TEX, CACHE>(vram, address(h));
        for j in 0..per {
            pixel::<TEX, RAW, BLEND, MASK_CHECK>(vram, x + j, word, j, env, flat);
        }
        x += per;
        h = (h + 1) & (line_halfwords - 1);
    }
    if x < end {
        let word = cache.halfword::<TEX, CACHE>(vram, address(h));
        for j in 0..end - x {
            pixel::<TEX, RAW, BLEND, MASK_CHECK>(vram, x + j, word, j, env, flat);
        }
    }
}

/// One row of a 4-bit textured rectangle drawn left to right with the texture window off
/// (docs/hardware/gpu.md §5, §7): up to sixteen pixels at a time, whose texels lie in one or
/// two cache entries of sixteen texels each (§10), each entry read once for all the texels
/// of it the row takes. `lut` is the primitive's shaded CLUT ([`crate::color::shaded_clut4`]),
/// `mask_or` what is set in each written pixel besides. The pixels are those
/// [`shade_pixel`] writes.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn clut4_row<const CACHE: u8, const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    cache: &mut TextureCache,
    env: &PixelEnv,
    lut: &[u32; 16],
    mask_or: u16,
    texels: usize,
    u_start: u8,
    row: usize,
    x_start: i32,
    x_end: i32,
) {
    let page_x = env.sampler.page_x;
    // The entry holding texels 16e to 16e + 15 of the line, the lowest in the low bits: four
    // halfwords from column page_x + 4e, e wrapping at 16 as U wraps at 256.
    let read = |cache: &mut TextureCache, vram: &[u16; VRAM_LEN], e: usize| {
        let column = (page_x + 4 * (e & 15)) & (VRAM_WIDTH - 1);
        let h = cache
            .entry_halfwords::<1, CACHE>(vram, texels + column)
            .map(u64::from);
        h[0] | h[1] << 16 | h[2] << 32 | h[3] << 48
    };
    let (mut u, mut x, end) = (
        usize::from(u_start),
        row + x_start as usize,
        row + x_end as usize,
    );
    while x < end {
        let n = (end - x).min(16);
        let (e, first) = (u >> 4, u & 15);
        let low = read(cache, vram, e);
        // The texels from U on, the next entry's read only when the pixels reach it.
        let texel_bits = if first + n > 16 {
            let high = read(cache, vram, e + 1);
            ((u128::from(high) << 64 | u128::from(low)) >> (4 * first)) as u64
        } else {
            low >> (4 * first)
        };
        let Some(pixels) = vram.get_mut(x..x + n) else {
            return;
        };
        let put = |(j, dst): (usize, &mut u16)| {
            let e = lut[(texel_bits >> (4 * j)) as usize & 15];
            put_shaded::<BLEND, MASK_CHECK>(dst, e, mask_or, env.blend);
        };
        // Sixteen pixels, the row of a 16-wide sprite, unrolled.
        match <&mut [u16; 16]>::try_from(&mut *pixels) {
            Ok(sixteen) => sixteen.iter_mut().enumerate().for_each(put),
            Err(_) => pixels.iter_mut().enumerate().for_each(put),
        }
        x += n;
        u = (u + n) & 255;
    }
}

/// Write the pixel at `index` from texel `j` of the texture halfword `word` (docs/hardware/gpu.md
/// §6, §7).
#[inline(always)]
fn pixel<const TEX: u8, const RAW: bool, const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    index: usize,
    word: u16,
    j: usize,
    env: &PixelEnv,
    flat: [i32; 3],
) {
    match TEX {
        1 => {
            let e = env.lut[clut_index::<1>(word, j)];
            write_shaded::<BLEND, MASK_CHECK>(vram, index, e, env.mask_or, env.blend);
        }
        2 => {
            let t = env.sampler.clut[clut_index::<2>(word, j)];
            write_texel::<RAW, BLEND, MASK_CHECK>(vram, index, t, flat, &PLAIN_TABLE, env);
        }
        _ => write_texel::<RAW, BLEND, MASK_CHECK>(vram, index, word, flat, &PLAIN_TABLE, env),
    }
}
