//! Rasterization of decoded primitives into VRAM (docs/hardware/gpu.md §3-§6).
//!
//! Each primitive picks, once, a span routine monomorphised for exactly the features it uses
//! (Gouraud, texture depth, raw texture, blending, dithering, mask check): a flat untextured
//! opaque triangle runs a loop with no texture, blend, dither or mask code in it.
//!
//! Why this shape: per-pixel choices cost more than the pixels. A 4-bit texture under one
//! colour has its 16 CLUT entries shaded once per primitive and each pixel becomes a table
//! read; with the four blend modes on packed channels, sprites and semi-transparent triangles
//! ran about 2x faster (510ba65). The other measurements are in docs/performance.md ("What
//! each change bought").

mod coverage;
mod line;
#[cfg(feature = "precise")]
pub(crate) mod precise;
mod rectangle;
mod span;
mod triangle;

use crate::color::{DitheredCells, ShadeTable, blend, blend_lanes, pack555, shaded_clut4};
use crate::host_cpu::HostCpu;
use crate::primitive::{Line, Rectangle, Texture, Triangle};
use crate::rows::Rows;
use crate::state::{BlendMode, DrawState, TextureDepth};
use crate::texture::{ClutCache, Sampler};
use crate::texture_cache::{TextureCache, mode};
use crate::{VRAM_LEN, Vram};
pub use coverage::{
    Coverage, DropReason, PixelBounds, classify_line, classify_rectangle, classify_triangle,
};

/// What a primitive drew after clipping, counted once per span (never per pixel), for the
/// drawing-time model (docs/emulator.md, "Drawing time, FIFO and DMA").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DrawCount {
    /// Rows walked inside the drawing area: for a triangle the rows between its top and
    /// bottom vertex, for a rectangle its rows, each counted whether or not its span is
    /// empty after the horizontal clip (lines: 0).
    pub rows: u32,
    /// Pixels drawn (lines: points stepped through, drawn or clipped).
    pub pixels: u32,
    /// Pixel pairs the spans touch, counted on even-aligned pairs: what a read-modify-write
    /// span (blending or mask check) reads from VRAM. Counted only for such spans (the model
    /// charges nothing for them otherwise); 0 for others.
    pub pairs: u32,
}

impl DrawCount {
    /// Count one span `[x_start, x_end)`, `x_start < x_end`, that reads VRAM back when
    /// `read_back` (a constant in every caller).
    #[inline(always)]
    pub(crate) fn span(&mut self, x_start: i32, x_end: i32, read_back: bool) {
        self.pixels += (x_end - x_start) as u32;
        if read_back {
            self.pairs += ((((x_end + 1) & !1) - (x_start & !1)) >> 1) as u32;
        }
    }
}

/// Texture kind as a const parameter: none, 4-bit, 8-bit or 15-bit.
pub(crate) const TEX_NONE: u8 = 0;

/// The const texture-kind code of a primitive's texture.
fn texture_kind(texture: Option<&Texture>) -> u8 {
    match texture.map(|t| t.depth) {
        None => TEX_NONE,
        Some(TextureDepth::Clut4) => 1,
        Some(TextureDepth::Clut8) => 2,
        Some(TextureDepth::Direct15) => 3,
    }
}

/// Whether a primitive's span routine shades texels through [`PixelEnv::lut`]: a 4-bit
/// texture under one colour and no dithering. The span routines make the same decision from
/// their const parameters (`TEX == 1 && !GOURAUD && !DITHER`).
fn uses_lut(texture: Option<&Texture>, gouraud: bool, dither: bool) -> bool {
    texture_kind(texture) == 1 && !gouraud && !dither
}

/// `$body` with `$m` a const item holding the texture cache mode `$mode` (one of
/// [`crate::texture_cache::mode`]), so that `$body` can pass it as a const argument.
/// Only the modes listed are built, the last for any other value.
macro_rules! with_cache_mode {
    ($mode:expr, $m:ident => $body:expr; $($name:ident),* ; $last:ident) => {
        match $mode {
            $(mode::$name => {
                const $m: u8 = mode::$name;
                $body
            })*
            _ => {
                const $m: u8 = mode::$last;
                $body
            }
        }
    };
}

/// Expand runtime booleans into const generic arguments: `dispatch!(f(args); [prefix]; a, b)`
/// calls `f::<prefix.., a?, b?>(args)` with each flag as a literal.
macro_rules! dispatch {
    ($f:ident $args:tt; [$($done:tt)*];) => {
        $f::<$($done)*> $args
    };
    ($f:ident $args:tt; [$($done:tt)*]; $b:expr $(, $rest:expr)*) => {
        if $b {
            dispatch!($f $args; [$($done)* true,]; $($rest),*)
        } else {
            dispatch!($f $args; [$($done)* false,]; $($rest),*)
        }
    };
}

/// Per-primitive constants of the pixel pipeline.
#[derive(Clone, Copy)]
pub(crate) struct PixelEnv<'a> {
    /// OR-ed into every written pixel (E6 bit 0).
    pub mask_or: u16,
    /// Semi-transparency mode.
    pub blend: BlendMode,
    /// Texture fetch state (unused by untextured primitives).
    pub sampler: Sampler<'a>,
    /// A 4-bit texture's 16 CLUT entries already shaded with the primitive's one colour,
    /// for primitives whose colour is the same at every pixel (flat, undithered, or raw):
    /// 0 for a transparent entry (CLUT value 0000h), else `10000h | shaded | texel bit 15`.
    /// Filled only when a span routine reads it (see [`shaded_clut4`]).
    pub lut: [u32; 16],
    /// For a dithered 4-bit texture under one colour, its CLUT entries shaded in every
    /// dither cell ([`crate::color::dithered_clut4`]), when the CLUT cache holds them or the primitive is
    /// large enough to pay for shading them; `None` otherwise.
    pub dithered: Option<&'a DitheredCells>,
    /// For a wide opaque flat primitive, a VRAM line's worth of its pixel value: long spans
    /// are copied from it, which the platform's block copy does with the widest stores the
    /// CPU has. Empty otherwise (see [`fill_span`]).
    pub line: &'a [u16],
    /// Which build of the textured triangles' span loops runs.
    pub host: HostCpu,
}

/// Shade and write one pixel (docs/hardware/gpu.md §6): texel fetch and transparency, modulation or raw
/// texel, dithering, blending (per texel bit 15 when textured), mask check and set.
/// `rgb` holds 8-bit channels; `shade` is the dither cell's table for this pixel (or the
/// undithered one). With `lut` (4-bit textures only; a constant in every span routine, so
/// the branch on it is folded away) the texel's shaded colour comes from that table of
/// shaded CLUT entries ([`shaded_clut4`], [`crate::color::dithered_clut4`]) and `rgb` and `shade` are not
/// read. With `CACHE` the texel is read through the texture cache (docs/hardware/gpu.md §10).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn shade_pixel<
    const TEX: u8,
    const RAW: bool,
    const BLEND: bool,
    const MASK_CHECK: bool,
    const CACHE: u8,
>(
    vram: &mut [u16; VRAM_LEN],
    index: usize,
    rgb: [i32; 3],
    u: u8,
    v: u8,
    shade: &ShadeTable,
    env: &PixelEnv,
    lut: Option<&[u32; 16]>,
    cache: &mut TextureCache,
) {
    if TEX == TEX_NONE {
        let dst = vram[index & (VRAM_LEN - 1)];
        if MASK_CHECK && dst & 0x8000 != 0 {
            return;
        }
        let c5 = |i: i32| shade[(i & 511) as usize] as u16;
        let color = pack555(c5(rgb[0]), c5(rgb[1]), c5(rgb[2]));
        let color = if BLEND {
            blend(env.blend, dst, color)
        } else {
            color
        };
        vram[index & (VRAM_LEN - 1)] = color | env.mask_or;
    } else if let Some(lut) = lut {
        let e = lut[env.sampler.index4::<CACHE>(vram, cache, u, v)];
        write_shaded::<BLEND, MASK_CHECK>(vram, index, e, env.mask_or, env.blend);
    } else {
        // The texel is read whether or not the mask check keeps the pixel: the read goes
        // through the texture cache (docs/hardware/gpu.md §10).
        let t = env.sampler.fetch::<TEX, CACHE>(vram, cache, u, v);
        write_texel::<RAW, BLEND, MASK_CHECK>(vram, index, t, rgb, shade, env);
    }
}

/// Write one textured pixel whose texel `t` (a 15-bit texel or a CLUT entry) has been read,
/// as [`shade_pixel`] does after its fetch: texel 0000h leaves the pixel alone, then the
/// modulation by `rgb` through `shade` (or the raw texel), blending when the texel's bit 15
/// is set, mask check and set (docs/hardware/gpu.md §6).
#[inline(always)]
pub(crate) fn write_texel<const RAW: bool, const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    index: usize,
    t: u16,
    rgb: [i32; 3],
    shade: &ShadeTable,
    env: &PixelEnv,
) {
    let dst = vram[index & (VRAM_LEN - 1)];
    if t == 0 || (MASK_CHECK && dst & 0x8000 != 0) {
        return;
    }
    let c5 = |i: i32| shade[(i & 511) as usize] as u16;
    let color = if RAW {
        t & 0x7FFF
    } else {
        // (docs/hardware/gpu.md §6) c5 = clamp(((t5 * c8) >> 4) + dither, 0, 255) >> 3.
        let t = t as i32;
        pack555(
            c5(((t & 0x1F) * rgb[0]) >> 4),
            c5((((t >> 5) & 0x1F) * rgb[1]) >> 4),
            c5((((t >> 10) & 0x1F) * rgb[2]) >> 4),
        )
    };
    // Textured pixels blend per texel (bit 15), which varies pixel to pixel: both results are
    // computed and one is selected, with no branch to mispredict.
    let color = if BLEND {
        let keep = 0u16.wrapping_sub(u16::from(t & 0x8000 == 0));
        (blend(env.blend, dst, color) & !keep) | (color & keep)
    } else {
        color
    };
    vram[index & (VRAM_LEN - 1)] = color | (t & 0x8000) | env.mask_or;
}

/// Write one pixel of a primitive whose texel colours come shaded from a table
/// ([`shaded_clut4`], [`crate::color::dithered_clut4`]): `e` is the texel's entry, 0 for a transparent
/// texel (the pixel is left alone), else `10000h | colour | texel bit 15`; blending per texel
/// bit 15 with `mode`, mask check, and `mask_or` as [`shade_pixel`] does (docs/hardware/gpu.md
/// §6).
#[inline(always)]
pub(crate) fn write_shaded<const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    index: usize,
    e: u32,
    mask_or: u16,
    mode: BlendMode,
) {
    put_shaded::<BLEND, MASK_CHECK>(&mut vram[index & (VRAM_LEN - 1)], e, mask_or, mode);
}

/// [`write_shaded`] into the pixel `dst`.
#[inline(always)]
pub(crate) fn put_shaded<const BLEND: bool, const MASK_CHECK: bool>(
    dst: &mut u16,
    e: u32,
    mask_or: u16,
    mode: BlendMode,
) {
    if e == 0 || (MASK_CHECK && *dst & 0x8000 != 0) {
        return;
    }
    let t = e as u16;
    let (color, bit15) = (t & 0x7FFF, t & 0x8000);
    let color = if BLEND {
        let keep = 0u16.wrapping_sub(u16::from(bit15 == 0));
        (blend(mode, *dst, color) & !keep) | (color & keep)
    } else {
        color
    };
    *dst = color | bit15 | mask_or;
}

/// [`put_shaded`] for eight pixels at once, `dst` read once and written once: lane `k` takes
/// the texel value `texels[k]` (colour and texel bit 15) where `drawn[k]` is FFFFh (a texel
/// that is not transparent, inside the span) and keeps its pixel where it is 0; blending per
/// texel bit 15 with `mode`, the mask check and `mask_or` as [`put_shaded`] applies them to
/// each pixel (docs/hardware/gpu.md §6).
#[inline(always)]
pub(crate) fn put_shaded_lanes<const BLEND: bool, const MASK_CHECK: bool>(
    dst: &mut [u16; 8],
    texels: wide::u16x8,
    drawn: wide::u16x8,
    mask_or: u16,
    mode: BlendMode,
) {
    use wide::u16x8;
    let old = u16x8::new(*dst);
    let bit15 = u16x8::splat(0x8000);
    // FFFFh in the lanes whose texel has bit 15 set.
    let semi = (texels & bit15).simd_eq(bit15);
    let color = if BLEND {
        semi.bitselect(blend_lanes(mode, old, texels) | bit15, texels)
    } else {
        texels
    };
    let write = if MASK_CHECK {
        drawn & !(old & bit15).simd_eq(bit15)
    } else {
        drawn
    };
    *dst = write
        .bitselect(color | u16x8::splat(mask_or), old)
        .to_array();
}

/// `(delta << 32) / steps` in 32.32 fixed point, rounded away from zero (docs/hardware/gpu.md §3.4, §4).
/// `steps` > 0.
#[inline]
pub(crate) fn step_away_from_zero(delta: i32, steps: i32) -> i64 {
    let magnitude = (u64::from(delta.unsigned_abs()) << 32) + (steps.max(1) - 1) as u64;
    let q = match RECIPROCALS.get(steps as usize) {
        // Edges and lines span at most 1023 steps of at most 2047 pixels.
        Some(&r) if steps > 1 && magnitude < 1 << 54 => divide_by_reciprocal(magnitude, r) as i64,
        _ => (magnitude / steps.max(1) as u64) as i64,
    };
    if delta < 0 { -q } else { q }
}

/// `floor(n / d)` as `(n * r) >> 64` with `r = floor(2^64 / d) + 1`, `2 <= d < 1024`. Exact
/// for `n < 2^54`: with `e = r * d - 2^64` (`0 < e <= d`), `n * r / 2^64 = n / d + n * e /
/// (d * 2^64)`, and the excess stays below `1 / d` when `n * e < 2^64`, too little to reach
/// the next multiple of `1 / d`. Edge steps divide at most 2047 * 2^32 + 1022 < 2^43.
#[inline(always)]
fn divide_by_reciprocal(n: u64, r: u64) -> u64 {
    ((u128::from(n) * u128::from(r)) >> 64) as u64
}

/// `floor(2^64 / d) + 1` for `d` in 2..1024 (entries 0 and 1 unused).
static RECIPROCALS: [u64; 1024] = reciprocals();

const fn reciprocals() -> [u64; 1024] {
    let mut t = [0u64; 1024];
    let mut d = 2;
    while d < 1024 {
        t[d] = ((1u128 << 64) / d as u128) as u64 + 1;
        d += 1;
    }
    t
}

/// The pixel an opaque, unmasked, undithered flat primitive writes: its colour to 5 bits
/// per channel (docs/hardware/gpu.md §6), with the mask bit E6h sets.
#[inline(always)]
pub(crate) fn flat_color(flat: [i32; 3], mask_or: u16) -> u16 {
    pack555(
        (flat[0] >> 3) as u16,
        (flat[1] >> 3) as u16,
        (flat[2] >> 3) as u16,
    ) | mask_or
}

/// Spans this wide or wider are copied from [`PixelEnv::line`] when it is filled.
pub(crate) const COPY_SPAN: i32 = 32;

/// Primitives whose drawn width reaches this get a filled [`PixelEnv::line`].
const LINE_WIDTH: i32 = 2 * COPY_SPAN;

/// Write `c` to `[x_start, x_end)` of the VRAM line starting at `row`: the whole pixel
/// pipeline of an opaque, unmasked, undithered flat primitive. `line` is empty or holds `c`
/// in every entry.
#[inline(always)]
pub(crate) fn fill_span(
    vram: &mut [u16; VRAM_LEN],
    row: usize,
    x_start: i32,
    x_end: i32,
    c: u16,
    line: &[u16],
) {
    if let Some(s) = vram.get_mut(row + x_start as usize..row + x_end as usize) {
        fill_row(s, c, line);
    }
}

/// Write `c` to every entry of `s`, copying from `line` (empty, or `c` in every entry) when
/// `s` is long enough to pay.
#[inline(always)]
pub(crate) fn fill_row(s: &mut [u16], c: u16, line: &[u16]) {
    if s.len() >= COPY_SPAN as usize
        && let Some(src) = line.get(..s.len())
    {
        s.copy_from_slice(src);
    } else {
        fill_stores(s, c);
    }
}

/// Write `c` to every entry of `s` with a few fixed-size stores that may overlap instead of
/// one store per entry: two or four stores of eight entries (the first and last eight, or
/// the first sixteen and the last sixteen) for 8 to 32 entries, eight at a time and a last
/// eight ending at the end of `s` beyond that; the first and last four, or two, or the one
/// entry below eight. No entry outside `s` is written.
#[inline(always)]
pub(crate) fn fill_stores(s: &mut [u16], c: u16) {
    let n = s.len();
    let c8 = wide::u16x8::splat(c).to_array();
    let mut put8 = |at: usize| {
        if let Some(d) = s.get_mut(at..).and_then(|d| d.first_chunk_mut::<8>()) {
            *d = c8;
        }
    };
    if n >= 8 {
        if n <= 16 {
            put8(0);
            put8(n - 8);
        } else if n <= 32 {
            put8(0);
            put8(8);
            put8(n - 16);
            put8(n - 8);
        } else {
            for at in (0..n - 8).step_by(8) {
                put8(at);
            }
            put8(n - 8);
        }
    } else if n >= 4 {
        // Four or two entries as one 64- or 32-bit value: one store each.
        let c4 = wide::bytemuck::cast::<u64, [u16; 4]>(u64::from(c) * 0x0001_0001_0001_0001);
        if let Some(d) = s.first_chunk_mut::<4>() {
            *d = c4;
        }
        if let Some(d) = s.last_chunk_mut::<4>() {
            *d = c4;
        }
    } else if n >= 2 {
        let c2 = wide::bytemuck::cast::<u32, [u16; 2]>(u32::from(c) * 0x0001_0001);
        if let Some(d) = s.first_chunk_mut::<2>() {
            *d = c2;
        }
        if let Some(d) = s.last_chunk_mut::<2>() {
            *d = c2;
        }
    } else if let Some(p) = s.first_mut() {
        *p = c;
    }
}

/// Sign-extend an 11-bit coordinate (docs/hardware/gpu.md §2, §3.5).
#[inline(always)]
pub(crate) const fn wrap11(v: i32) -> i32 {
    (v << 21) >> 21
}

/// The CLUT in a line's pixel environment: lines are never textured, so it is never read.
static NO_CLUT: [u16; 256] = [0; 256];

/// A primitive's pixel environment, its texture's CLUT latched. `dithered`, for a dithered
/// 4-bit triangle under one colour, asks for that colour's [`PixelEnv::dithered`] table,
/// shaded when the CLUT cache does not hold it if the triangle is large enough
/// ([`worth_shading`]).
fn env<'a>(
    vram: &[u16; VRAM_LEN],
    state: &DrawState,
    clut: &'a mut ClutCache,
    texture: Option<&Texture>,
    blend: Option<BlendMode>,
    dithered: Option<&Triangle>,
) -> PixelEnv<'a> {
    let (page_x, page_y) = texture.map_or((0, 0), |t| (t.page_x as usize, t.page_y as usize));
    let (clut, dithered) = match (texture, dithered) {
        (Some(t), Some(tri)) => {
            clut.latch_dithered(vram, t, tri.vertices[0].color, || worth_shading(tri))
        }
        (Some(t), None) => (clut.latch(vram, t), None),
        (None, _) => (clut.entries(), None),
    };
    PixelEnv {
        mask_or: if state.mask.set { 0x8000 } else { 0 },
        blend: blend.unwrap_or_default(),
        sampler: Sampler::new(clut, page_x, page_y, state.window),
        lut: [0; 16],
        dithered,
        line: &[],
        host: HostCpu::default(),
    }
}

/// A dithered 4-bit texture under one colour whose shaded table is not cached is shaded for
/// every dither cell (256 entries) when its bounding box holds at least twice this many
/// pixels; smaller ones shade pixel by pixel.
const DITHERED_CLUT_PIXELS: i32 = 256;

/// Whether a triangle is large enough to pay for shading its CLUT for every dither cell
/// (see [`DITHERED_CLUT_PIXELS`]).
fn worth_shading(tri: &Triangle) -> bool {
    let [a, b, c] = tri.vertices.map(|p| (wrap11(p.x), wrap11(p.y)));
    let w = a.0.max(b.0).max(c.0) - a.0.min(b.0).min(c.0);
    let h = a.1.max(b.1).max(c.1) - a.1.min(b.1).min(c.1);
    w * h >= 2 * DITHERED_CLUT_PIXELS
}

/// Whether a triangle is flat, modulated, dithered and 4-bit textured: one colour over a
/// 4-bit CLUT in every dither cell.
fn dithered_clut4_triangle(tri: &Triangle) -> bool {
    texture_kind(tri.texture.as_ref()) == 1
        && !tri.gouraud
        && tri.dither
        && !tri.texture.is_some_and(|t| t.raw)
}

/// Draw one triangle (docs/hardware/gpu.md §3): size drop, fill rule, attribute stepping, texture,
/// blending, dithering, mask, writing only the lines `rows` keeps, texels read through
/// `cache` when it is on (§10), its spans in the build `host` chooses. Returns what was drawn.
pub(crate) fn draw_triangle_rows(
    vram: &mut Vram,
    state: &DrawState,
    clut: &mut ClutCache,
    cache: &mut TextureCache,
    tri: &Triangle,
    (rows, host): (Rows, HostCpu),
) -> DrawCount {
    let vram = vram.as_array_mut();
    let line;
    let dithered = dithered_clut4_triangle(tri).then_some(tri);
    let mut env = env(vram, state, clut, tri.texture.as_ref(), tri.blend, dithered);
    env.host = host;
    if tri.texture.is_none()
        && !tri.gouraud
        && !tri.dither
        && tri.blend.is_none()
        && !state.mask.check
    {
        let xs = tri.vertices.map(|p| wrap11(p.x));
        let width = xs.iter().max().unwrap_or(&0) - xs.iter().min().unwrap_or(&0);
        if width.min(state.area.right as i32 + 1 - state.area.left as i32) >= LINE_WIDTH {
            let rgb = tri.vertices[0].color.map(i32::from);
            line = [flat_color(rgb, env.mask_or); crate::VRAM_WIDTH];
            env.line = &line;
        }
    }
    let raw = tri.texture.is_some_and(|t| t.raw);
    if uses_lut(tri.texture.as_ref(), tri.gouraud, tri.dither) {
        let rgb = tri.vertices[0].color.map(i32::from);
        env.lut = shaded_clut4(env.sampler.clut, rgb, raw);
    }
    let (g, b, d, m) = (
        tri.gouraud,
        tri.blend.is_some(),
        tri.dither,
        state.mask.check,
    );
    use triangle::draw;
    let c = cache.mode();
    match texture_kind(tri.texture.as_ref()) {
        0 => {
            dispatch!(draw(vram, state, &env, tri, rows, cache); [0, {mode::OFF},]; g, false, b, d, m)
        }
        1 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, rows, cache); [1, M,]; g, raw, b, d, m); OFF, TAGS; COPIES)
        }
        2 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, rows, cache); [2, M,]; g, raw, b, d, m); OFF, TAGS; COPIES)
        }
        _ => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, rows, cache); [3, M,]; g, raw, b, d, m); OFF, TAGS; COPIES)
        }
    }
}

/// Draw a flat, untextured, opaque triangle (GP0 20h) without mask check, corners `p`
/// (offset applied), colour `rgb` (docs/hardware/gpu.md §3, §6): what [`draw_triangle_rows`]
/// does for it, without the pixel environment of other primitives.
pub(crate) fn draw_flat_triangle_rows(
    vram: &mut Vram,
    state: &DrawState,
    p: [(i32, i32); 3],
    rgb: [u8; 3],
    rows: Rows,
) -> DrawCount {
    let color = flat_color(rgb.map(i32::from), if state.mask.set { 0x8000 } else { 0 });
    let xs = p.map(|p| wrap11(p.0));
    let width = xs[0].max(xs[1]).max(xs[2]) - xs[0].min(xs[1]).min(xs[2]);
    let vram = vram.as_array_mut();
    if width.min(state.area.right as i32 + 1 - state.area.left as i32) >= LINE_WIDTH {
        let line = [color; crate::VRAM_WIDTH];
        triangle::draw_flat(vram, state, p, color, &line, rows)
    } else {
        triangle::draw_flat(vram, state, p, color, &[], rows)
    }
}

/// Draw a Gouraud-shaded, untextured, opaque triangle (GP0 30h) without mask check,
/// dithered when `tri.dither` (docs/hardware/gpu.md §3, §6): what [`draw_triangle_rows`]
/// does for it, without the CLUT cache and texture state of textured polygons.
#[inline(always)]
pub(crate) fn draw_gouraud_triangle_rows(
    vram: &mut Vram,
    state: &DrawState,
    cache: &mut TextureCache,
    tri: &Triangle,
    rows: Rows,
) -> DrawCount {
    let vram = vram.as_array_mut();
    let env = PixelEnv {
        mask_or: if state.mask.set { 0x8000 } else { 0 },
        blend: BlendMode::default(),
        sampler: Sampler::new(&NO_CLUT, 0, 0, state.window),
        lut: [0; 16],
        dithered: None,
        line: &[],
        host: HostCpu::default(),
    };
    if tri.dither {
        triangle::draw_inline::<TEX_NONE, { mode::OFF }, true, false, false, true, false>(
            vram, state, &env, tri, rows, cache,
        )
    } else {
        triangle::draw_inline::<TEX_NONE, { mode::OFF }, true, false, false, false, false>(
            vram, state, &env, tri, rows, cache,
        )
    }
}

/// Draw one triangle with sub-pixel vertex positions and, when `perspective`, perspective-
/// correct texture coordinates: a non-hardware path for accuracy studies (see [`precise`]).
/// The triangle's own vertex positions are ignored in favour of `at`.
#[cfg(feature = "precise")]
pub(crate) fn draw_triangle_precise(
    vram: &mut Vram,
    state: &DrawState,
    clut: &mut ClutCache,
    cache: &mut TextureCache,
    tri: &Triangle,
    at: &[precise::PreciseVertex; 3],
    perspective: bool,
) {
    let vram = vram.as_array_mut();
    let env = env(vram, state, clut, tri.texture.as_ref(), tri.blend, None);
    let raw = tri.texture.is_some_and(|t| t.raw);
    let (b, m, p) = (tri.blend.is_some(), state.mask.check, perspective);
    use precise::draw;
    let c = cache.mode();
    match texture_kind(tri.texture.as_ref()) {
        0 => {
            dispatch!(draw(vram, state, &env, tri, at, cache); [0, {mode::OFF},]; false, b, m, false)
        }
        1 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, at, cache); [1, M,]; raw, b, m, p); OFF, TAGS; COPIES)
        }
        2 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, at, cache); [2, M,]; raw, b, m, p); OFF, TAGS; COPIES)
        }
        _ => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, tri, at, cache); [3, M,]; raw, b, m, p); OFF, TAGS; COPIES)
        }
    }
}

/// The columns `[x0, x1)` and lines `[y0, y1)` two triangles of a quad cover when they tile
/// an axis-aligned rectangle: the four vertices are its four corners, and the second and
/// third (the edge the two triangles share, docs/hardware/gpu.md §3.1) are opposite
/// corners. Under the fill rule (§3.5: left and top edges drawn, right and bottom edges not,
/// the shared diagonal drawn by exactly one of the two) every pixel of the rectangle is then
/// covered exactly once and no other. `None` for any other quad, and for one the size limit
/// drops (§3.2).
fn tiled_rectangle(v: [(i32, i32); 4]) -> Option<(i32, i32, i32, i32)> {
    let v = v.map(|(x, y)| (wrap11(x), wrap11(y)));
    let (x0, x1) = (v[1].0.min(v[2].0), v[1].0.max(v[2].0));
    let (y0, y1) = (v[1].1.min(v[2].1), v[1].1.max(v[2].1));
    let corner = |p: (i32, i32)| (p.0 == x0 || p.0 == x1) && (p.1 == y0 || p.1 == y1);
    let tiles = x0 < x1
        && y0 < y1
        && x1 - x0 < 1024
        && y1 - y0 < 512
        && v.iter().all(|&p| corner(p))
        && v[0].0 != v[3].0
        && v[0].1 != v[3].1
        && v[0] != v[1]
        && v[0] != v[2];
    tiles.then_some((x0, x1, y0, y1))
}

/// Draw a flat, untextured, opaque quad without mask check whose two triangles tile an
/// axis-aligned rectangle (see `tiled_rectangle`) as one span per line instead of two:
/// the same pixels, with the same value, as drawing the triangles one after the other.
/// Returns the pixels drawn, or `None` (nothing drawn) when the quad does not qualify.
pub(crate) fn draw_tiled_quad(
    vram: &mut Vram,
    state: &DrawState,
    first: &Triangle,
    second: &Triangle,
    rows: Rows,
) -> Option<DrawCount> {
    if first.texture.is_some()
        || first.gouraud
        || first.blend.is_some()
        || first.dither
        || state.mask.check
    {
        return None;
    }
    let [a, b, c] = first.vertices;
    let d = second.vertices[2];
    let (x0, x1, y0, y1) = tiled_rectangle([a, b, c, d].map(|p| (p.x, p.y)))?;
    let area = &state.area;
    let (x_start, x_end) = (x0.max(area.left as i32), x1.min(area.right as i32 + 1));
    let (y_start, y_end) = (y0.max(area.top as i32), y1.min(area.bottom as i32 + 1));
    let mut drawn = DrawCount::default();
    if x_start >= x_end || y_start >= y_end {
        return Some(drawn);
    }
    let color = flat_color(
        a.color.map(i32::from),
        if state.mask.set { 0x8000 } else { 0 },
    );
    let line_buf;
    let line: &[u16] = if x_end - x_start >= LINE_WIDTH {
        line_buf = [color; crate::VRAM_WIDTH];
        &line_buf
    } else {
        &[]
    };
    let vram = vram.as_array_mut();
    rows.each(y_start, y_end, |y| {
        let row = ((y & 511) as usize) * crate::VRAM_WIDTH;
        fill_span(vram, row, x_start, x_end, color, line);
    });
    let row_count = rows.count(y_start, y_end);
    drawn.pixels = (x_end - x_start) as u32 * row_count;
    // Each of the two triangles spans every row of the rectangle.
    drawn.rows = 2 * row_count;
    Some(drawn)
}

/// Draw one line segment, both endpoints included (docs/hardware/gpu.md §4), writing only the
/// lines `rows` keeps. Returns the points stepped. Lines test each pixel's row, so the filter
/// is a const parameter: an unfiltered line has no row test.
pub(crate) fn draw_line_rows(
    vram: &mut Vram,
    state: &DrawState,
    cache: &mut TextureCache,
    line: &Line,
    rows: Rows,
) -> DrawCount {
    let vram = vram.as_array_mut();
    let filtered = rows != Rows::All;
    if !line.gouraud && line.blend.is_none() && !line.dither && !state.mask.check && !filtered {
        let p = line.vertices.map(|v| (v.x, v.y));
        let value = flat_color(
            line.vertices[0].color.map(i32::from),
            if state.mask.set { 0x8000 } else { 0 },
        );
        if let Some(drawn) = line::draw_flat_inside(vram, &state.area, p, value) {
            return drawn;
        }
    }
    let env = PixelEnv {
        mask_or: if state.mask.set { 0x8000 } else { 0 },
        blend: line.blend.unwrap_or_default(),
        sampler: Sampler::new(&NO_CLUT, 0, 0, state.window),
        lut: [0; 16],
        dithered: None,
        line: &[],
        host: HostCpu::default(),
    };
    let (g, b, d, m) = (
        line.gouraud,
        line.blend.is_some(),
        line.dither,
        state.mask.check,
    );
    use line::draw;
    dispatch!(draw(vram, state, &env, line, rows, cache); []; g, b, d, m, filtered)
}

/// Draw a flat, opaque line segment (GP0 40h) from `p[0]` to `p[1]` (offset applied) in
/// colour `rgb`, undithered, without mask check, on every row, when both endpoints lie
/// inside the drawing area: what [`draw_line_rows`] does for it. `None` (nothing drawn)
/// otherwise.
pub(crate) fn draw_flat_line(
    vram: &mut Vram,
    state: &DrawState,
    p: [(i32, i32); 2],
    rgb: [u8; 3],
) -> Option<DrawCount> {
    let value = flat_color(rgb.map(i32::from), if state.mask.set { 0x8000 } else { 0 });
    line::draw_flat_inside(vram.as_array_mut(), &state.area, p, value)
}

/// Draw one rectangle (docs/hardware/gpu.md §5), writing only the lines `rows` keeps. Returns
/// what was drawn.
pub(crate) fn draw_rectangle_rows(
    vram: &mut Vram,
    state: &DrawState,
    clut: &mut ClutCache,
    cache: &mut TextureCache,
    rect: &Rectangle,
    rows: Rows,
) -> DrawCount {
    let vram = vram.as_array_mut();
    let line;
    let mut env = env(vram, state, clut, rect.texture.as_ref(), rect.blend, None);
    if rect.texture.is_none()
        && rect.blend.is_none()
        && !state.mask.check
        && rectangle::clip(rect, &state.area).is_some_and(|(x0, x1, _, _)| x1 - x0 >= LINE_WIDTH)
    {
        line = [flat_color(rect.origin.color.map(i32::from), env.mask_or); crate::VRAM_WIDTH];
        env.line = &line;
    }
    let raw = rect.texture.is_some_and(|t| t.raw);
    if uses_lut(rect.texture.as_ref(), false, false) {
        env.lut = shaded_clut4(env.sampler.clut, rect.origin.color.map(i32::from), raw);
    }
    let (b, m) = (rect.blend.is_some(), state.mask.check);
    use rectangle::draw;
    // A rectangle reads its texels along each row in VRAM order: with tags tracked, they
    // are checked once per run of reads in one entry.
    let c = match cache.mode() {
        mode::TAGS => {
            cache.begin_runs();
            mode::RUNS
        }
        other => other,
    };
    match texture_kind(rect.texture.as_ref()) {
        0 => dispatch!(draw(vram, state, &env, rect, rows, cache); [0, {mode::OFF},]; false, b, m),
        1 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, rect, rows, cache); [1, M,]; raw, b, m); OFF, RUNS; COPIES)
        }
        2 => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, rect, rows, cache); [2, M,]; raw, b, m); OFF, RUNS; COPIES)
        }
        _ => {
            with_cache_mode!(c, M => dispatch!(draw(vram, state, &env, rect, rows, cache); [3, M,]; raw, b, m); OFF, RUNS; COPIES)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reciprocal division equals i64 division, rounded away from zero as the
    /// docs/hardware/gpu.md §3.4 formula states, for every delta an edge or line can have
    /// (11-bit coordinates) and every step count up to 1023, and at the extremes beyond.
    #[test]
    fn steps_equal_plain_division() {
        let plain = |delta: i32, steps: i32| {
            let n = (delta as i64) << 32;
            let bias = steps as i64 - 1;
            (if n < 0 { n - bias } else { n + bias }) / steps as i64
        };
        for steps in 1..1024 {
            for delta in -2047..=2047 {
                assert_eq!(
                    step_away_from_zero(delta, steps),
                    plain(delta, steps),
                    "{delta}/{steps}"
                );
            }
        }
        for (delta, steps) in [
            (i32::MAX, 1023),
            (i32::MIN + 1, 1023),
            (i32::MAX, 5000),
            (7, 1024),
        ] {
            assert_eq!(step_away_from_zero(delta, steps), plain(delta, steps));
        }
    }
}
