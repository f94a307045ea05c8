//! Opaque, unmasked spans of Gouraud-shaded or textured triangles, eight pixels at a time
//! (docs/hardware/gpu.md §3.6, §6): the pixel pipeline of [`super::shade_pixel`] for
//! primitives without semi-transparency or mask check, where a pixel's value depends only on
//! its own attributes and texel. Colour maths runs on eight 16-bit lanes, attribute stepping
//! on eight 32-bit lanes (SSE2 on x86-64, NEON on AArch64, plain arrays elsewhere); texels
//! are fetched one by one.
//!
//! Why this shape: eight lanes cut the Gouraud class from 6,754 to 4,806 instructions a
//! triangle (with the group rows of `triangle.rs`), and a 4-bit page the window leaves alone
//! computes its eight texel addresses in the lanes, a read, a shift and a CLUT read per texel
//! instead of about 22 instructions (docs/performance.md, "GPU primitive classes").

use super::PixelEnv;
use crate::VRAM_LEN;
use crate::color::DITHER_MATRIX;
use crate::texture::texture_halfword;
use crate::texture_cache::{SlowReads, TextureCache, mode, steps_slowly};
use wide::bytemuck::cast;
use wide::{i16x8, i32x8, u16x8, u32x8};

/// Pixels per group.
const LANES: usize = 8;

/// Each lane's index.
pub(super) const LANE_INDEX: u32x8 = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);

/// The dither offsets of eight consecutive pixels starting at a pixel with `x & 3 == c` on a
/// line with `y & 3 == r`, indexed `[r][c]` (docs/hardware/gpu.md §6).
static DITHER_LANES: [[[i16; LANES]; 4]; 4] = dither_lanes();

const fn dither_lanes() -> [[[i16; LANES]; 4]; 4] {
    let mut t = [[[0i16; LANES]; 4]; 4];
    let mut r = 0;
    while r < 4 {
        let mut c = 0;
        while c < 4 {
            let mut k = 0;
            while k < LANES {
                t[r][c][k] = DITHER_MATRIX[r][(c + k) & 3] as i16;
                k += 1;
            }
            c += 1;
        }
        r += 1;
    }
    t
}

/// The dither offsets of [`DITHER_LANES`] split by sign for [`gouraud`], each in the high byte
/// of a 16-bit lane: `[r][c][0]` holds `max(d, 0) << 8`, `[r][c][1]` holds `max(-d, 0) << 8`
/// (docs/hardware/gpu.md §6).
static DITHER_SIGNED: [[[[u16; LANES]; 2]; 4]; 4] = dither_signed();

const fn dither_signed() -> [[[[u16; LANES]; 2]; 4]; 4] {
    let mut t = [[[[0u16; LANES]; 2]; 4]; 4];
    // Every lane of every cell of DITHER_LANES, by one index.
    let mut i = 0;
    while i < 4 * 4 * LANES {
        let (r, c, k) = (i / (4 * LANES), i / LANES % 4, i % LANES);
        let d = DITHER_LANES[r][c][k];
        if d > 0 {
            t[r][c][0][k] = (d as u16) << 8;
        } else {
            t[r][c][1][k] = (d.unsigned_abs()) << 8;
        }
        i += 1;
    }
    t
}

/// A triangle's per-pixel attribute steps (0-2 colour, 3-4 UV; 8.24, wrapping like the
/// console's 32-bit adders) spread over the lanes of a group: lane `k` of attribute `i` is
/// `k * step[i]`, and a group advances every lane by `8 * step[i]`.
#[derive(Clone, Copy)]
pub(super) struct LaneSteps {
    offset: [u32x8; 5],
    group: [u32x8; 5],
    /// Every lane of U and V one pixel's step: a pixel's less these are the pixel before it.
    pixel_uv: (u32x8, u32x8),
    /// The texels step slowly ([`steps_slowly`]).
    slow: bool,
}

impl LaneSteps {
    /// Lane offsets for the per-pixel steps `step`, over a texture of kind `TEX`.
    #[inline(always)]
    pub(super) fn new<const TEX: u8>(step: [u32; 5]) -> Self {
        Self {
            offset: step.map(|s| u32x8::new(core::array::from_fn(|k| s.wrapping_mul(k as u32)))),
            group: step.map(|s| u32x8::splat(s.wrapping_mul(LANES as u32))),
            pixel_uv: (u32x8::splat(step[3]), u32x8::splat(step[4])),
            slow: TEX != super::TEX_NONE && steps_slowly::<TEX>((step[3], step[4])),
        }
    }
}

/// The 8-bit integer parts of eight 8.24 attribute lanes.
#[inline(always)]
fn integer(lanes: u32x8) -> i16x8 {
    i16x8::from_i32x8_saturate(cast::<u32x8, i32x8>(lanes >> 24))
}

/// One channel to 5 bits: `clamp(c + d, 0, 255) >> 3` per lane (docs/hardware/gpu.md §6).
#[inline(always)]
fn to5(c: i16x8, d: i16x8) -> i16x8 {
    (c + d).max(i16x8::ZERO).min(i16x8::splat(255)) >> 3
}

/// The 16-bit top halves of eight 8.24 attribute lanes: the 8-bit integer part in the high
/// byte, the fraction's top byte in the low one.
#[inline(always)]
fn top_halves(lanes: u32x8) -> u16x8 {
    // An arithmetic shift keeps every lane in i16's range, so the signed pack is exact.
    cast::<i16x8, u16x8>(i16x8::from_i32x8_saturate(
        cast::<u32x8, i32x8>(lanes) >> 16,
    ))
}

/// Eight untextured Gouraud pixels (docs/hardware/gpu.md §6): channel `i` of pixel `k` is the
/// integer part of lane `k` of `lanes[i]`, `c`, written as `clamp(c + d, 0, 255) >> 3`, `d`
/// the pixel's dither offset, given as its sign's two parts ([`DITHER_SIGNED`]) `raise` and
/// `lower`. With `c` in the high byte of a 16-bit lane, the clamp is a saturating add of
/// `raise` then a saturating subtraction of `lower` (one of them 0): a sum past 255 saturates
/// to FFFFh, whose high byte is 255, and one under 0 to 0, while the low byte (the fraction)
/// never carries into the high one.
#[inline(always)]
fn gouraud(lanes: &[u32x8; 3], (raise, lower): (u16x8, u16x8), mask_or: u16x8) -> u16x8 {
    let channel = |l: u32x8| top_halves(l).saturating_add(raise).saturating_sub(lower);
    let (r, g, b) = (channel(lanes[0]), channel(lanes[1]), channel(lanes[2]));
    (r >> 11) | ((g >> 11) << 5) | ((b >> 11) << 10) | mask_or
}

/// Draw `[x_start, x_end)` of line `y` (VRAM row offset `row`), not empty, for an opaque
/// primitive without mask check whose texture, if any, is modulated. `acc` holds the five
/// 8.24 attributes at `x_start` (0-2 colour, 3-4 UV); `flat` is the colour when not
/// `GOURAUD`. A texel of value 0000h leaves its pixel as it is; others keep their bit 15
/// (docs/hardware/gpu.md §6, §7). The last group of a span stores only the pixels left: an
/// untextured one its first and last four, two or one ([`gouraud_span`]), a textured one
/// pixel by pixel.
/// `PLAIN`: the texture window is the identity and the page lies inside VRAM without
/// wrapping ([`plain_page`]), so the eight texel addresses are computed together. `CACHE`:
/// texels are read through the texture cache (docs/hardware/gpu.md §10), the reads of a span
/// whose texels step slowly ([`steps_slowly`]) looked up only where they leave an entry.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn draw<
    const TEX: u8,
    const GOURAUD: bool,
    const DITHER: bool,
    const PLAIN: bool,
    const CACHE: u8,
>(
    vram: &mut [u16; VRAM_LEN],
    row: usize,
    y: i32,
    x_start: i32,
    x_end: i32,
    acc: [u32; 5],
    steps: &LaneSteps,
    flat: [i32; 3],
    env: &PixelEnv,
    cache: &mut TextureCache,
) {
    let span = (row, y, x_start, x_end);
    if TEX == super::TEX_NONE {
        gouraud_span::<DITHER>(vram, span, acc, steps, env.mask_or);
    } else if PLAIN && CACHE == mode::TAGS && steps.slow {
        groups::<TEX, GOURAUD, DITHER, PLAIN, CACHE, true>(
            vram, span, acc, steps, flat, env, cache,
        );
    } else {
        groups::<TEX, GOURAUD, DITHER, PLAIN, CACHE, false>(
            vram, span, acc, steps, flat, env, cache,
        );
    }
}

/// [`draw`] for a textured span, with the reads of a span whose texels step slowly tracked as
/// such when `SLOW`.
#[inline(always)]
fn groups<
    const TEX: u8,
    const GOURAUD: bool,
    const DITHER: bool,
    const PLAIN: bool,
    const CACHE: u8,
    const SLOW: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    (row, y, x_start, x_end): (usize, i32, i32, i32),
    acc: [u32; 5],
    steps: &LaneSteps,
    flat: [i32; 3],
    env: &PixelEnv,
    cache: &mut TextureCache,
) {
    let mask_or = i16x8::splat(env.mask_or as i16);
    let flat = flat.map(|c| i16x8::splat(c as i16));
    let dither_row = &DITHER_LANES[(y & 3) as usize];
    // A span's groups start a multiple of eight pixels apart: the same dither offsets.
    let dither = if DITHER {
        i16x8::new(dither_row[(x_start & 3) as usize])
    } else {
        i16x8::ZERO
    };
    let mut reads = SlowReads::new();
    let mut group = |vram: &[u16; VRAM_LEN], lanes: &[u32x8; 5], n: usize| {
        Group::<TEX, GOURAUD, PLAIN, CACHE, SLOW>::shade(
            vram,
            (&mut *cache, &mut reads, steps.pixel_uv),
            env,
            (flat, mask_or, dither),
            lanes,
            n,
        )
    };
    let put = put::<TEX>;
    // Attribute `i` of pixel `x + k` in lane `k`.
    let mut lanes: [u32x8; 5] = core::array::from_fn(|i| u32x8::splat(acc[i]) + steps.offset[i]);
    let mut x = x_start;
    while x_end - x > LANES as i32 {
        let (out, t, _) = group(vram, &lanes, LANES);
        put(vram, row + x as usize, out, t);
        for (l, s) in lanes.iter_mut().zip(&steps.group) {
            *l += *s;
        }
        x += LANES as i32;
    }
    // The last 1 to 8 pixels.
    let n = (x_end - x) as usize;
    let (out, t, texel) = group(vram, &lanes, n);
    let start = row + x as usize;
    if n == LANES {
        put(vram, start, out, t);
    } else if let Some(dst) = vram.get_mut(start..).and_then(|d| d.get_mut(..n)) {
        let out = out.to_array();
        for (k, d) in dst.iter_mut().enumerate() {
            if texel[k] != 0 {
                *d = out[k];
            }
        }
    }
}

/// [`draw`] for an untextured (Gouraud) span: the groups but the last written whole, the
/// last (1 to 8 pixels) as its first and last four, two or one ([`copy_ends`]).
#[inline(always)]
fn gouraud_span<const DITHER: bool>(
    vram: &mut [u16; VRAM_LEN],
    (row, y, x_start, x_end): (usize, i32, i32, i32),
    acc: [u32; 5],
    steps: &LaneSteps,
    mask_or: u16,
) {
    let mask_or = u16x8::splat(mask_or);
    let dither = if DITHER {
        let [raise, lower] = &DITHER_SIGNED[(y & 3) as usize][(x_start & 3) as usize];
        (u16x8::new(*raise), u16x8::new(*lower))
    } else {
        (u16x8::ZERO, u16x8::ZERO)
    };
    // Colour `i` of pixel `x + k` in lane `k`.
    let mut lanes: [u32x8; 3] = core::array::from_fn(|i| u32x8::splat(acc[i]) + steps.offset[i]);
    let mut x = x_start;
    while x_end - x > LANES as i32 {
        let out = gouraud(&lanes, dither, mask_or);
        if let Some(dst) = vram
            .get_mut(row + x as usize..)
            .and_then(|d| d.first_chunk_mut::<LANES>())
        {
            *dst = out.to_array();
        }
        for (l, s) in lanes.iter_mut().zip(&steps.group) {
            *l += *s;
        }
        x += LANES as i32;
    }
    let out = gouraud(&lanes, dither, mask_or);
    let n = (x_end - x) as usize;
    if let Some(dst) = vram
        .get_mut(row + x as usize..)
        .and_then(|d| d.get_mut(..n))
    {
        copy_ends(dst, &out.to_array());
    }
}

/// One group of eight pixels of a textured span; `PLAIN` and `CACHE` as for [`draw`], `SLOW`
/// as for [`groups`].
struct Group<
    const TEX: u8,
    const GOURAUD: bool,
    const PLAIN: bool,
    const CACHE: u8,
    const SLOW: bool,
>;

impl<const TEX: u8, const GOURAUD: bool, const PLAIN: bool, const CACHE: u8, const SLOW: bool>
    Group<TEX, GOURAUD, PLAIN, CACHE, SLOW>
{
    /// Eight pixels with attribute `i` of pixel `k` in lane `k` and dither offsets `dither`:
    /// their values and their texels (0 past the first `n`, which are not fetched).
    /// The reads of a span whose texels step slowly tracked through `reads` when `SLOW`, the
    /// read one pixel before each from U and V less `back`, their steps per pixel.
    #[inline(always)]
    fn shade(
        vram: &[u16; VRAM_LEN],
        (cache, reads, back): (&mut TextureCache, &mut SlowReads, (u32x8, u32x8)),
        env: &PixelEnv,
        (flat, mask_or, dither): ([i16x8; 3], i16x8, i16x8),
        lanes: &[u32x8; 5],
        n: usize,
    ) -> (u16x8, i16x8, [u16; LANES]) {
        let [r, g, b] = if GOURAUD {
            [integer(lanes[0]), integer(lanes[1]), integer(lanes[2])]
        } else {
            flat
        };
        let mut texel = [0u16; LANES];
        if PLAIN {
            // The halfword holding texel (u, v) is `page + v * 1024 + u / 4` (4-bit),
            // `u / 2` (8-bit) or `u` (15-bit), the texel at bit `(u % 4) * 4` or
            // `(u % 2) * 8` of it (docs/hardware/gpu.md §7).
            let s = &env.sampler;
            let page = u32x8::splat((s.page_y * crate::VRAM_WIDTH + s.page_x) as u32);
            let u = lanes[3] >> 24;
            let address = halfword_lanes::<TEX>(page, (u, lanes[4] >> 24));
            let shift = match TEX {
                1 => (u & u32x8::splat(3)) << 2,
                2 => (u & u32x8::splat(1)) << 3,
                _ => u32x8::ZERO,
            };
            // With the tags tracked, the reads' entries and tags are worked out in the lanes
            // too (docs/hardware/gpu.md §10).
            let tags = CACHE == mode::TAGS;
            if tags {
                if SLOW {
                    // The reads one pixel back: U and V less one step.
                    let uv_back = ((lanes[3] - back.0) >> 24, (lanes[4] - back.1) >> 24);
                    let before = halfword_lanes::<TEX>(page, uv_back);
                    cache.track_slow_lanes::<TEX>(address, before, n, reads);
                } else {
                    cache.track_lanes::<TEX>(address, n);
                }
            }
            let (address, shift) = (address.to_array(), shift.to_array());
            for (k, t) in texel.iter_mut().enumerate().take(n) {
                let word = if tags {
                    vram[address[k] as usize & (VRAM_LEN - 1)]
                } else {
                    texture_halfword::<TEX, CACHE>(vram, cache, address[k] as usize)
                };
                *t = match TEX {
                    1 => s.clut[usize::from((word >> shift[k]) & 0xF)],
                    2 => s.clut[usize::from((word >> shift[k]) & 0xFF)],
                    _ => word,
                };
            }
        } else {
            let (u, v) = (integer(lanes[3]).to_array(), integer(lanes[4]).to_array());
            for (k, t) in texel.iter_mut().enumerate().take(n) {
                *t = env
                    .sampler
                    .fetch::<TEX, CACHE>(vram, cache, u[k] as u8, v[k] as u8);
            }
        }
        let t = i16x8::new(texel.map(|t| t as i16));
        // Modulation (docs/hardware/gpu.md §6): (t5 * c8) >> 4, then the dither.
        let five = i16x8::splat(0x1F);
        let (cr, cg, cb) = (
            ((t & five) * r) >> 4,
            (((t >> 5) & five) * g) >> 4,
            (((t >> 10) & five) * b) >> 4,
        );
        let out = to5(cr, dither)
            | to5(cg, dither) << 5
            | to5(cb, dither) << 10
            | (t & i16x8::splat(i16::MIN))
            | mask_or;
        (cast::<i16x8, u16x8>(out), t, texel)
    }
}

/// The VRAM index of the halfword holding texel `(u, v)` of lane `k`, in a page at index `page`
/// that lies inside VRAM under the identity window ([`plain_page`]): `page + v * 1024 + u / 4`
/// (4-bit, `TEX` 1), `u / 2` (8-bit) or `u` (15-bit) (docs/hardware/gpu.md §7).
#[inline(always)]
pub(super) fn halfword_lanes<const TEX: u8>(page: u32x8, (u, v): (u32x8, u32x8)) -> u32x8 {
    let base = page + (v << 10u32);
    match TEX {
        1 => base + (u >> 2u32),
        2 => base + (u >> 1u32),
        _ => base + u,
    }
}

/// The texel reads of up to eight consecutive pixels of a span over a page of kind `TEX` (1 =
/// 4-bit, 3 = 15-bit) that lies inside VRAM under the identity window ([`plain_page`], its
/// index `page`): the halfwords' addresses `page + v * 1024 + u / 4` (4-bit) or `+ u`
/// (15-bit) in lanes and as an array, and the texel's bit position in it (docs/hardware/gpu.md
/// §7). U and V start at `uv` and step by `duv` (8.24).
pub(super) struct PlainReads {
    pub(super) lanes: u32x8,
    pub(super) address: [u32; LANES],
    pub(super) shift: [u32; LANES],
}

impl PlainReads {
    /// The reads of the eight pixels from (`u`, `v`), the lanes' offsets `steps` (`k * du`,
    /// `k * dv`) made by [`PlainReads::steps`].
    #[inline(always)]
    pub(super) fn new<const TEX: u8>(
        page: usize,
        (u, v): (u32, u32),
        steps: &(u32x8, u32x8),
    ) -> Self {
        let (u, v) = (
            (u32x8::splat(u) + steps.0) >> 24u32,
            (u32x8::splat(v) + steps.1) >> 24u32,
        );
        let address = halfword_lanes::<TEX>(u32x8::splat(page as u32), (u, v));
        let shift = if TEX == 1 {
            (u & u32x8::splat(3)) << 2u32
        } else {
            u32x8::ZERO
        };
        Self {
            lanes: address,
            address: address.to_array(),
            shift: shift.to_array(),
        }
    }

    /// The lanes' offsets from the per-pixel steps `(du, dv)`.
    #[inline(always)]
    pub(super) fn steps((du, dv): (u32, u32)) -> (u32x8, u32x8) {
        (LANE_INDEX * u32x8::splat(du), LANE_INDEX * u32x8::splat(dv))
    }
}

/// Textured spans shorter than this stay pixel by pixel: a group's fixed work, its texel
/// fetches included, costs more than a few pixels one at a time.
pub(super) const MIN_TEXTURED_PIXELS: i32 = 4;

/// Copy the first `dst.len()` (0 to 8) entries of `out` to `dst` as two copies of its first
/// and last four, two or one entries, which may overlap.
#[inline(always)]
fn copy_ends(dst: &mut [u16], out: &[u16; LANES]) {
    let n = dst.len();
    if n >= 4 {
        if let (Some(d), Some(s)) = (dst.first_chunk_mut::<4>(), out.first_chunk::<4>()) {
            *d = *s;
        }
        if let (Some(d), Some(s)) = (
            dst.last_chunk_mut::<4>(),
            out.get(n - 4..).and_then(|s| s.first_chunk::<4>()),
        ) {
            *d = *s;
        }
    } else if n >= 2 {
        if let (Some(d), Some(s)) = (dst.first_chunk_mut::<2>(), out.first_chunk::<2>()) {
            *d = *s;
        }
        if let (Some(d), Some(s)) = (
            dst.last_chunk_mut::<2>(),
            out.get(n - 2..).and_then(|s| s.first_chunk::<2>()),
        ) {
            *d = *s;
        }
    } else if let (Some(d), Some(&s)) = (dst.first_mut(), out.first()) {
        *d = s;
    }
}

/// Write the eight pixels `out` at `start`; a texel `t` of 0000h is transparent: the pixel
/// keeps its value.
#[inline(always)]
fn put<const TEX: u8>(vram: &mut [u16; VRAM_LEN], start: usize, out: u16x8, t: i16x8) {
    if let Some(dst) = vram
        .get_mut(start..)
        .and_then(|d| d.first_chunk_mut::<LANES>())
    {
        *dst = if TEX != super::TEX_NONE {
            let old = u16x8::new(*dst);
            cast::<i16x8, u16x8>(t.simd_eq(i16x8::ZERO))
                .select(old, out)
                .to_array()
        } else {
            out.to_array()
        };
    }
}

/// The halfwords a texture page of kind `tex` (1 = 4-bit, 2 = 8-bit, 3 = 15-bit) spans from
/// its left edge: 64, 128 or 256 (docs/hardware/gpu.md §7).
fn page_width(tex: u8) -> usize {
    match tex {
        1 => 64,
        2 => 128,
        _ => 256,
    }
}

/// The page of kind `tex` (1 = 4-bit, 2 = 8-bit, 3 = 15-bit) as a VRAM index when neither
/// the window nor a wrap changes a texel's address: the window is the identity, and the
/// page's 64, 128 or 256 halfwords and 256 lines lie inside VRAM (docs/hardware/gpu.md §7).
/// Texel (u, v) is then in the halfword at this index plus `v * 1024 + u / 4` (4-bit),
/// `u / 2` (8-bit) or `u` (15-bit).
#[inline(always)]
pub(super) fn plain_page(sampler: &crate::texture::Sampler, tex: u8) -> Option<usize> {
    (sampler.window_is_identity()
        && sampler.page_x + page_width(tex) <= crate::VRAM_WIDTH
        && sampler.page_y + 256 <= 512)
        .then_some(sampler.page_y * crate::VRAM_WIDTH + sampler.page_x)
}

/// Whether the VRAM a texture page of kind `tex` (1 = 4-bit, 2 = 8-bit, 3 = 15-bit) can be
/// read from lies clear of the columns `[x0, x1)` and lines `[y0, y1)` a primitive writes.
/// A group reads its eight texels before it writes its eight pixels, while the console reads
/// and writes pixel by pixel; the two agree unless the primitive draws over its own texture.
/// The page spans 64, 128 or 256 halfwords from its left edge (wrapping at 1024) and 256
/// lines (wrapping at 512) (docs/hardware/gpu.md §7).
pub(super) fn texture_clear_of(
    sampler: &crate::texture::Sampler,
    tex: u8,
    (x0, x1): (i32, i32),
    (y0, y1): (i32, i32),
) -> bool {
    let width = page_width(tex);
    let overlaps = |start: usize, len: usize, modulus: usize, lo: i32, hi: i32| {
        let (lo, hi) = (lo.max(0) as usize, hi.max(0) as usize);
        let s = start % modulus;
        let e = s + len;
        (s < hi && lo < e) || (e > modulus && lo < e - modulus)
    };
    !(overlaps(sampler.page_x, width, 1024, x0, x1) && overlaps(sampler.page_y, 256, 512, y0, y1))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::TextureWindow;
    use crate::texture::Sampler;

    /// Every integer part and fraction top byte of each channel under each dither offset and
    /// mask bit, against the formula of docs/hardware/gpu.md §6 worked in i32.
    #[test]
    fn gouraud_lanes_match_the_dither_formula() {
        let expect = |c: i32, d: i32| ((c + d).clamp(0, 255) >> 3) as u16;
        for r in 0..4 {
            for col in 0..4 {
                let [raise, lower] = DITHER_SIGNED[r][col];
                let dither = (u16x8::new(raise), u16x8::new(lower));
                for top in 0..=u16::MAX {
                    // Lane k of channel ch has the top half `top + (k + ch) * 2301h`
                    // (wrapping), with the fraction's low bits set in every third lane.
                    let half = |k: u32, ch: u32| {
                        u32::from(top.wrapping_add(((k + ch) as u16).wrapping_mul(0x2301)))
                    };
                    let lanes: [u32x8; 3] = core::array::from_fn(|ch| {
                        u32x8::new(core::array::from_fn(|k| {
                            (half(k as u32, ch as u32) << 16) | if k % 3 == 0 { 0xFFFF } else { 0 }
                        }))
                    });
                    let mask = if top & 1 == 0 { 0 } else { 0x8000 };
                    let out = gouraud(&lanes, dither, u16x8::splat(mask)).to_array();
                    for (k, &px) in out.iter().enumerate() {
                        let d = DITHER_MATRIX[r][(col + k) & 3];
                        let c = |ch: u32| (half(k as u32, ch) >> 8) as i32;
                        let want =
                            expect(c(0), d) | expect(c(1), d) << 5 | expect(c(2), d) << 10 | mask;
                        assert_eq!(px, want, "row {r} column {col} lane {k} top {top:04x}");
                    }
                }
            }
        }
    }

    #[test]
    fn texture_page_footprints() {
        let clut = [0u16; 256];
        let at = |x, y| Sampler::new(&clut, x, y, TextureWindow::default());
        // A 4-bit page at (64, 0) covers columns 64..128 and lines 0..256.
        assert!(texture_clear_of(&at(64, 0), 1, (0, 64), (0, 10)));
        assert!(texture_clear_of(&at(64, 0), 1, (128, 200), (0, 10)));
        assert!(!texture_clear_of(&at(64, 0), 1, (127, 200), (255, 300)));
        assert!(texture_clear_of(&at(64, 0), 1, (100, 110), (256, 300)));
        // An 8-bit page is 128 halfwords wide, a 15-bit one 256.
        assert!(!texture_clear_of(&at(64, 0), 2, (191, 200), (0, 1)));
        assert!(!texture_clear_of(&at(64, 0), 3, (319, 320), (0, 1)));
        assert!(texture_clear_of(&at(64, 0), 3, (320, 400), (0, 1)));
        // Pages wrap at column 1024 and line 512.
        assert!(!texture_clear_of(&at(960, 0), 3, (10, 20), (0, 1)));
        assert!(texture_clear_of(&at(960, 0), 3, (192, 960), (0, 1)));
        assert!(!texture_clear_of(&at(0, 384), 3, (0, 1), (100, 110)));
        assert!(texture_clear_of(&at(0, 384), 3, (0, 1), (128, 384)));
    }
}
