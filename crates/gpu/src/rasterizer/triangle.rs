//! Triangle rasterization (docs/hardware/gpu.md §3): core vertex, Y sort, 32.32 edge walking with the
//! 1<<11 epsilon, spans [left, right), and 8.24 attribute gradients evaluated from the core
//! vertex.

use super::coverage::{Coverage, triangle_coverage};
use super::{DrawCount, PixelEnv, TEX_NONE, shade_pixel, span, wrap11};
use crate::color::{DITHER_TABLES, DitheredCells, PLAIN_TABLE};
use crate::primitive::Triangle;
use crate::state::BlendMode;
use crate::state::DrawState;
use crate::texture::texture_halfword;
use crate::texture_cache::mode::{self, COPIES};
use crate::texture_cache::{SlowReads, TextureCache, steps_slowly};
use crate::{VRAM_LEN, VRAM_WIDTH};

/// `$body` with `$mode` bound to the blend mode `$value`: when `$blend` (a const parameter)
/// is set, in one copy per mode with the mode a constant, so that a pixel loop inlined into
/// `$body` does not choose its blend function per pixel (docs/hardware/gpu.md §6).
macro_rules! with_blend_mode {
    ($blend:expr, $value:expr, $mode:ident => $body:expr) => {
        if $blend {
            match $value {
                BlendMode::Average => with_blend_mode!(@as BlendMode::Average, $mode => $body),
                BlendMode::Add => with_blend_mode!(@as BlendMode::Add, $mode => $body),
                BlendMode::Subtract => with_blend_mode!(@as BlendMode::Subtract, $mode => $body),
                BlendMode::AddQuarter => {
                    with_blend_mode!(@as BlendMode::AddQuarter, $mode => $body)
                }
            }
        } else {
            with_blend_mode!(@as $value, $mode => $body)
        }
    };
    (@as $constant:expr, $mode:ident => $body:expr) => {{
        let $mode = $constant;
        $body
    }};
}

#[derive(Clone, Copy, Default)]
struct Vtx {
    x: i32,
    y: i32,
    attr: [i32; 5],
}

/// A triangle edge: its 32.32 X at row `y` is `edge_start(x) + (row - y) * step`
/// (docs/hardware/gpu.md §3.4).
#[derive(Clone, Copy)]
struct Edge {
    x: i32,
    y: i32,
    step: i64,
}

impl Edge {
    /// The edge's X at `row`, 32.32 fixed point.
    #[inline(always)]
    fn at(self, row: i32) -> i64 {
        edge_start(self.x) + (row - self.y) as i64 * self.step
    }
}

/// An edge's start: x + 1 minus a small epsilon, in 32.32 fixed point (docs/hardware/gpu.md §3.4).
fn edge_start(x: i32) -> i64 {
    ((x as i64) << 32) + (1i64 << 32) - (1 << 11)
}

/// An edge's step per line, rounded away from zero (docs/hardware/gpu.md §3.4). `dy` > 0.
#[inline(always)]
fn edge_step(dx: i32, dy: i32) -> i64 {
    super::step_away_from_zero(dx, dy)
}

/// The rows `[top, bottom)` of one part of a triangle and the edges bounding them
/// (docs/hardware/gpu.md §3.4): spans are `[left, right)` at each row.
#[derive(Clone, Copy)]
struct Part {
    top: i32,
    bottom: i32,
    left: Edge,
    right: Edge,
}

/// A triangle's core vertex and edges (docs/hardware/gpu.md §3.3-§3.4).
struct Setup {
    /// Sorted position of the core vertex.
    core: usize,
    /// Rows `[y0, y1)` bounded by v0->v1, then `[y1, y2)` bounded by v1->v2, each with the
    /// base edge v0->v2.
    parts: [Part; 2],
}

/// Core vertex, Y sort and edges (docs/hardware/gpu.md §3.3-§3.4) of the vertices `v`, whose
/// wrapped positions `at` gives, for a triangle [`triangle_coverage`] draws (not collinear, so
/// y0 < y2 and the gradient denominator is not 0); returns them in sorted order with the
/// set-up.
#[inline(always)]
fn setup<T: Copy>(mut v: [T; 3], at: impl Fn(&T) -> (i32, i32)) -> ([T; 3], Setup) {
    // Core vertex from X before sorting (docs/hardware/gpu.md §3.3).
    let p = v.each_ref().map(&at);
    let mut core = if p[1].0 <= p[0].0 {
        if p[2].0 <= p[1].0 { 2 } else { 1 }
    } else if p[2].0 < p[0].0 {
        2
    } else {
        0
    };
    for (i, j) in [(1, 2), (0, 1), (1, 2)] {
        if at(&v[j]).1 < at(&v[i]).1 {
            v.swap(i, j);
            if core == i {
                core = j;
            } else if core == j {
                core = i;
            }
        }
    }
    let [a, b, c] = v.each_ref().map(&at);
    let base_step = edge_step(c.0 - a.0, c.1 - a.1);
    let (upper_step, right_facing) = if b.1 == a.1 {
        (0, b.0 > a.0)
    } else {
        let s = edge_step(b.0 - a.0, b.1 - a.1);
        (s, s > base_step)
    };
    let lower_step = if c.1 == b.1 {
        0
    } else {
        edge_step(c.0 - b.0, c.1 - b.1)
    };
    // The two parts (docs/hardware/gpu.md §3.4): rows [a.y, b.y) bounded by a->b and rows
    // [b.y, c.y) bounded by b->c; the base edge a->c is measured from a. A part touching the
    // core vertex from below is walked bottom-up on the console: its bound edge starts at the
    // lower vertex and each row pre-decrements. Each edge is thus linear in y from an anchor
    // row: core a, the bound edges are anchored at a (upper part) and b (lower part); core b,
    // both at b; core c, at b (upper part) and c (lower part). Rows are independent, so they
    // are drawn top-down with the edges stepped by addition from the first drawn row.
    let base = Edge {
        x: a.0,
        y: a.1,
        step: base_step,
    };
    let (upper_anchor, lower_anchor) = match core {
        0 => (a, b),
        1 => (b, b),
        _ => (b, c),
    };
    let part = |top, bottom, anchor: (i32, i32), step| {
        let bound = Edge {
            x: anchor.0,
            y: anchor.1,
            step,
        };
        let (left, right) = if right_facing {
            (base, bound)
        } else {
            (bound, base)
        };
        Part {
            top,
            bottom,
            left,
            right,
        }
    };
    (
        v,
        Setup {
            core,
            parts: [
                part(a.1, b.1, upper_anchor, upper_step),
                part(b.1, c.1, lower_anchor, lower_step),
            ],
        },
    )
}

/// The order the console walks a triangle's two parts in (docs/hardware/gpu.md §3.4), as
/// `(part, upward)` pairs, part 0 the rows `[y0, y1)` and part 1 `[y1, y2)` of the sorted
/// vertices, `core` the core vertex's sorted position: core 0, both parts downward; core 1,
/// the lower part downward, then the upper part upward from its bottom row; core 2, the
/// lower part upward, then the upper part upward. Each row is drawn left to right.
const fn console_order(core: usize) -> [(usize, bool); 2] {
    match core {
        0 => [(0, false), (1, false)],
        1 => [(1, false), (0, true)],
        _ => [(1, true), (0, true)],
    }
}

/// Truncating division by a triangle's gradient denominator, one hardware divide per
/// triangle instead of two per attribute: `n / den` (rounded toward zero) as
/// `((|n| + 1) * r) >> 64` with `r = floor((2^64 - 1) / |den|)`, without a branch.
///
/// Exact for every 32-bit `n` and `0 < |den| < 2^32`: with `2^64 - 1 = r * |den| + s`,
/// `0 <= s < |den|`, the product over 2^64 is `(|n| + 1) / |den| * (1 - (1 + s) / 2^64)`. That
/// is below `(|n| + 1) / |den|`, at most `floor(|n| / |den|) + 1`, and short of
/// `(|n| + 1) / |den|` by at most `(|n| + 1) / 2^64`, no more than `1 / |den|` while
/// `(|n| + 1) * |den| <= 2^64`; so its integer part is `floor(|n| / |den|)`. The gradient
/// maths is 32-bit (docs/hardware/gpu.md §3.6) and `|den|` < 2^21 (§3.2).
#[derive(Clone, Copy)]
struct Divisor {
    reciprocal: u64,
    negative: bool,
}

impl Divisor {
    /// The divisor `den`; 0 (a collinear triangle, never drawn, §3.6) divides as 1.
    fn new(den: i32) -> Self {
        Self {
            reciprocal: u64::MAX / u64::from(den.unsigned_abs().max(1)),
            negative: den < 0,
        }
    }

    /// `n / den`, rounded toward zero.
    #[inline(always)]
    fn divide(self, n: i32) -> i32 {
        let m = u64::from(n.unsigned_abs()) + 1;
        let q = ((u128::from(m) * u128::from(self.reciprocal)) >> 64) as u32 as i32;
        if (n < 0) != self.negative {
            q.wrapping_neg()
        } else {
            q
        }
    }
}

/// d/dx and d/dy of one attribute in 8.24 (docs/hardware/gpu.md §3.6), 32-bit signed maths
/// with truncating division: attributes of 8 bits and vertices the size limit keeps within
/// 1023 columns and 511 rows of each other (§3.2) keep each numerator times 4096 under 2^31.
#[inline(always)]
fn gradient(v: &[Vtx; 3], i: usize, den: Divisor) -> (u32, u32) {
    let (a, b, c) = (&v[0], &v[1], &v[2]);
    let (aa, ba, ca) = (a.attr[i], b.attr[i], c.attr[i]);
    let ddx = (ba - aa)
        .wrapping_mul(c.y - b.y)
        .wrapping_sub((ca - ba).wrapping_mul(b.y - a.y));
    let ddy = (b.x - a.x)
        .wrapping_mul(ca - ba)
        .wrapping_sub((c.x - b.x).wrapping_mul(ba - aa));
    let (ddx, ddy) = (den.divide(ddx << 12), den.divide(ddy << 12));
    ((ddx as u32) << 12, (ddy as u32) << 12)
}

/// Draw a flat, untextured, opaque, undithered triangle without mask check with corners `p`
/// (offset applied, not yet wrapped): every pixel of a span is the primitive's one pixel
/// value `color` (docs/hardware/gpu.md §3.7, §6), written with plain stores. `line` is
/// empty or holds `color` in every entry (see [`super::fill_span`]).
pub(super) fn draw_flat(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    p: [(i32, i32); 3],
    color: u16,
    line: &[u16],
    rows: super::Rows,
) -> DrawCount {
    let mut drawn = DrawCount::default();
    let p = p.map(|(x, y)| (wrap11(x), wrap11(y)));
    // Size drop, zero area, clipped away (docs/hardware/gpu.md §3.2, §3.6).
    if let Coverage::Dropped(_) = triangle_coverage(p, &state.area) {
        return drawn;
    }
    let (_, setup) = setup(p, |&p| p);
    let area = state.area;
    let (clip_top, clip_bottom) = (area.top as i32, area.bottom as i32 + 1);
    let clip = (area.left as i32, area.right as i32 + 1);
    // On every row of its part an edge's integer part lies between the X of its two
    // vertices: it starts 2^-21 of a pixel short of x + 1, and its rounded-away step gains
    // less than 2^-32 of a pixel per row over the exact slope, under 2^-23 over 511 rows
    // (docs/hardware/gpu.md §3.4). So a triangle whose vertices lie inside the drawing
    // area's columns needs no per-row clip (§3.5).
    let (min_x, max_x) = (
        p[0].0.min(p[1].0).min(p[2].0),
        p[0].0.max(p[1].0).max(p[2].0),
    );
    let inside = min_x >= clip.0 && max_x <= clip.1;
    let stride = match rows {
        super::Rows::All => 1,
        super::Rows::SkipParity(_) => 2,
    };
    for part in setup.parts {
        let first = rows.first(part.top.max(clip_top));
        let last = part.bottom.min(clip_bottom);
        if first >= last {
            continue;
        }
        drawn.rows += rows.count(first, last);
        let walk = FlatRows {
            y: first,
            last,
            stride,
            l: part.left.at(first),
            r: part.right.at(first),
            dl: part.left.step * stride as i64,
            dr: part.right.step * stride as i64,
            clip,
            color,
        };
        drawn.pixels += match (inside, line.is_empty()) {
            (true, true) => walk.draw::<false, false>(vram, &[]),
            (false, true) => walk.draw::<true, false>(vram, &[]),
            (true, false) => walk.draw::<false, true>(vram, line),
            (false, false) => walk.draw::<true, true>(vram, line),
        };
    }
    drawn
}

/// The rows of one part of a flat triangle: from row `y` to `last` (exclusive) every
/// `stride` rows, the span `[l >> 32, r >> 32)` at each, the edges stepping by `dl` and
/// `dr`, clipped to the columns `clip` (docs/hardware/gpu.md §3.4-§3.5).
struct FlatRows {
    y: i32,
    last: i32,
    stride: i32,
    l: i64,
    r: i64,
    dl: i64,
    dr: i64,
    clip: (i32, i32),
    color: u16,
}

impl FlatRows {
    /// Write the spans; returns the pixels written. Without `CLIP` every span lies inside
    /// the clip columns already. With `LINE`, `line` holds the pixel value in every entry and
    /// long spans are copied from it (see [`super::fill_span`]).
    #[inline(never)]
    fn draw<const CLIP: bool, const LINE: bool>(
        self,
        vram: &mut [u16; VRAM_LEN],
        line: &[u16],
    ) -> u32 {
        let Self {
            mut y,
            last,
            stride,
            mut l,
            mut r,
            dl,
            dr,
            clip,
            color,
        } = self;
        let mut pixels = 0;
        let (lines, _) = vram.as_chunks_mut::<VRAM_WIDTH>();
        while y < last {
            let (mut x_start, mut x_end) = ((l >> 32) as i32, (r >> 32) as i32);
            if CLIP {
                x_start = x_start.max(clip.0);
                x_end = x_end.min(clip.1);
            }
            l = l.wrapping_add(dl);
            r = r.wrapping_add(dr);
            if x_start < x_end {
                pixels += (x_end - x_start) as u32;
                // `x_start` is at or right of the clip's left column, 0 or more.
                let span = x_start as u32 as usize..x_end as u32 as usize;
                if let Some(s) = lines[(y & 511) as usize].get_mut(span) {
                    if LINE {
                        super::fill_row(s, color, line);
                    } else {
                        super::fill_stores(s, color);
                    }
                }
            }
            y += stride;
        }
        pixels
    }
}

/// The rows of one part of a triangle, walked by a routine of their own: the rows from `y`
/// to `end` (exclusive), `stride` rows apart (negative when walked upward), `end` a whole
/// number of strides from `y`, the span `[l >> 32, r >> 32)` at each clipped to the columns
/// `clip`, the edges stepping by `dl` and `dr`; `attr` holds the attributes at column 0 of
/// row `y` and steps by `attr_step` per row walked (docs/hardware/gpu.md §3.4-§3.6). The
/// routines are not inlined into the triangle set-up, so that their pixel loops keep their
/// registers whatever the set-up around the call holds.
struct PartRows {
    y: i32,
    end: i32,
    stride: i32,
    l: i64,
    r: i64,
    dl: i64,
    dr: i64,
    clip: (i32, i32),
    attr: [u32; 5],
    attr_step: [u32; 5],
}

/// One of [`PartRows`]'s row loops, `$rows`, in two builds (`crate::host_cpu`): `$base`
/// compiled for the baseline instruction set and, with the `std` feature on x86-64, `$avx2`
/// compiled for x86-64-v3 (AVX2, BMI1, BMI2, FMA, LZCNT, POPCNT); `$built` runs the second
/// when its `avx2` says the host has those instructions, else the first. The same source, so
/// the same pixels either way.
macro_rules! two_builds {
    ($built:ident, $base:ident, $avx2:ident => $rows:ident
        <$(const $g:ident: $gt:ty),*> ($($p:ident: $pt:ty),*) -> $ret:ty) => {
        #[doc = concat!("[`PartRows::", stringify!($rows), "`] in the build `avx2` chooses.")]
        #[inline(always)]
        fn $built<$(const $g: $gt),*>(self, avx2: bool, $($p: $pt),*) -> $ret {
            #[cfg(all(feature = "std", target_arch = "x86_64"))]
            if avx2 {
                // SAFETY: the AVX2 build needs the instruction sets of its `target_feature`
                // list, and `avx2` is `HostCpu::avx2`, true only once `host_cpu`'s detection
                // has found every one of them on this host.
                #[allow(unsafe_code)]
                return unsafe { self.$avx2::<$($g),*>($($p),*) };
            }
            let _ = avx2;
            self.$base::<$($g),*>($($p),*)
        }

        #[doc = concat!("[`PartRows::", stringify!($rows), "`], the baseline build.")]
        #[inline(never)]
        fn $base<$(const $g: $gt),*>(self, $($p: $pt),*) -> $ret {
            self.$rows::<$($g),*>($($p),*)
        }

        #[doc = concat!("[`PartRows::", stringify!($rows), "`] built for x86-64-v3.")]
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        #[inline(never)]
        #[target_feature(enable = "avx2,bmi1,bmi2,fma,lzcnt,popcnt")]
        fn $avx2<$(const $g: $gt),*>(self, $($p: $pt),*) -> $ret {
            self.$rows::<$($g),*>($($p),*)
        }
    };
}

impl PartRows {
    /// The `count` rows of `part` from row `start`, `stride` apart, the attributes `attrs`
    /// at column 0 of each.
    #[inline(always)]
    fn new(
        part: &Part,
        (start, count, stride): (i32, i32, i32),
        attrs: &Attributes,
        clip: (i32, i32),
    ) -> Self {
        let Attributes { cv, origin, grads } = attrs;
        // Attribute `i` at column 0 of row `start`, 8.24 with 32-bit wrap (§3.6).
        let dy = start.wrapping_sub(cv.y) as u32;
        let dx = cv.x.wrapping_neg() as u32;
        PartRows {
            y: start,
            end: start + count * stride,
            stride,
            l: part.left.at(start),
            r: part.right.at(start),
            dl: part.left.step * stride as i64,
            dr: part.right.step * stride as i64,
            clip,
            attr: core::array::from_fn(|i| {
                origin[i]
                    .wrapping_add(grads[i].0.wrapping_mul(dx))
                    .wrapping_add(grads[i].1.wrapping_mul(dy))
            }),
            attr_step: core::array::from_fn(|i| grads[i].1.wrapping_mul(stride as u32)),
        }
    }

    /// [`PartRows::draw`] with its clip and page variants chosen for the sorted vertices
    /// `v`; returns the pixels drawn.
    #[inline(always)]
    fn groups<const TEX: u8, const GOURAUD: bool, const DITHER: bool, const CACHE: u8>(
        self,
        vram: &mut [u16; VRAM_LEN],
        v: &[Vtx; 3],
        (step, flat): ([u32; 5], [i32; 3]),
        env: &PixelEnv,
        cache: &mut TextureCache,
    ) -> u32 {
        // As for flat triangles (see `draw_flat`), spans of a triangle whose vertices lie
        // inside the area's columns need no clip.
        let (a, b, c) = (v[0], v[1], v[2]);
        let (left, right) = self.clip;
        let inside = a.x.min(b.x).min(c.x) >= left && a.x.max(b.x).max(c.x) <= right;
        let plain = TEX != TEX_NONE && span::plain_page(&env.sampler, TEX).is_some();
        // Untextured spans take the baseline build.
        let avx2 = TEX != TEX_NONE && env.host.avx2();
        match (inside, plain) {
            (true, false) => self.draw_built::<TEX, GOURAUD, DITHER, false, false, CACHE>(
                avx2, vram, step, flat, env, cache,
            ),
            (false, false) => self.draw_built::<TEX, GOURAUD, DITHER, true, false, CACHE>(
                avx2, vram, step, flat, env, cache,
            ),
            (true, true) => self.draw_built::<TEX, GOURAUD, DITHER, false, true, CACHE>(
                avx2, vram, step, flat, env, cache,
            ),
            (false, true) => self.draw_built::<TEX, GOURAUD, DITHER, true, true, CACHE>(
                avx2, vram, step, flat, env, cache,
            ),
        }
    }

    two_builds!(raw15_built, raw15, raw15_avx2 => raw15_rows<
        const BLEND: bool, const MASK_CHECK: bool, const CACHE: u8, const SLOW: bool
    >(
        vram: &mut [u16; VRAM_LEN],
        duv: (u32, u32),
        page: (usize, &mut TextureCache),
        mask: (u16, BlendMode)
    ) -> DrawCount);

    /// Draw the spans of a raw 15-bit texture in a page the window and the VRAM wraps
    /// leave alone (`page`, see [`raw15_span`]), U and V stepping by `duv` per pixel, slowly
    /// (`steps_slowly`) when `SLOW`; returns what was drawn.
    #[inline(always)]
    fn raw15_rows<const BLEND: bool, const MASK_CHECK: bool, const CACHE: u8, const SLOW: bool>(
        self,
        vram: &mut [u16; VRAM_LEN],
        duv: (u32, u32),
        page: (usize, &mut TextureCache),
        mask: (u16, BlendMode),
    ) -> DrawCount {
        let (page, cache) = page;
        self.walk(
            BLEND || MASK_CHECK,
            // Inlined into each build's row walk (a call per span otherwise).
            #[inline(always)]
            |y, (x_start, x_end), attr| {
                let row = ((y & 511) as usize) * VRAM_WIDTH;
                let at = |i: usize, d: u32| attr[i].wrapping_add(d.wrapping_mul(x_start as u32));
                let uv = (at(3, duv.0), at(4, duv.1));
                raw15_span::<BLEND, MASK_CHECK, CACHE>(
                    vram,
                    (row, x_start, x_end),
                    uv,
                    duv,
                    (page, &mut *cache, SLOW),
                    mask,
                );
            },
        )
    }

    /// Walk the rows: for each whose span `[x_start, x_end)` (clipped) is not empty, count
    /// it in what was drawn (its pixel pairs read back when `read_back`) and call `span`
    /// with the row's line, the span and the attributes at column 0 of the row.
    #[inline(always)]
    fn walk(self, read_back: bool, mut span: impl FnMut(i32, (i32, i32), &[u32; 5])) -> DrawCount {
        let Self {
            mut y,
            end,
            stride,
            mut l,
            mut r,
            dl,
            dr,
            clip,
            mut attr,
            attr_step,
        } = self;
        let mut drawn = DrawCount::default();
        while y != end {
            let x_start = ((l >> 32) as i32).max(clip.0);
            let x_end = ((r >> 32) as i32).min(clip.1);
            l = l.wrapping_add(dl);
            r = r.wrapping_add(dr);
            if x_start < x_end {
                drawn.span(x_start, x_end, read_back);
                span(y, (x_start, x_end), &attr);
            }
            for (a, s) in attr.iter_mut().zip(attr_step) {
                *a = a.wrapping_add(s);
            }
            y += stride;
        }
        drawn
    }

    /// Draw the spans one by one ([`span_pixels`]), the attributes stepping by `step` per
    /// pixel, slowly for the texels (`steps_slowly`) when `SLOW`, with the span routines
    /// `plan` chose; returns what was drawn.
    #[inline(never)]
    fn spans<
        const TEX: u8,
        const GOURAUD: bool,
        const RAW: bool,
        const BLEND: bool,
        const DITHER: bool,
        const MASK_CHECK: bool,
        const CACHE: u8,
        const SLOW: bool,
    >(
        self,
        vram: &mut [u16; VRAM_LEN],
        (step, flat): ([u32; 5], [i32; 3]),
        (plan, env): (&SpanPlan, &PixelEnv),
        cache: &mut TextureCache,
    ) -> DrawCount {
        self.walk(
            BLEND || MASK_CHECK,
            // Inlined into the row walk, which the compiler stopped doing by itself when the
            // 4-bit groups were unrolled: a call per span otherwise.
            #[inline(always)]
            |y, (x_start, x_end), attr| {
                let acc: [u32; 5] = core::array::from_fn(|i| {
                    attr[i].wrapping_add(step[i].wrapping_mul(x_start as u32))
                });
                let span = (((y & 511) as usize) * VRAM_WIDTH, y, x_start, x_end);
                span_pixels::<TEX, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK, CACHE>(
                    vram,
                    span,
                    (acc, step),
                    flat,
                    (plan, env),
                    (cache, SLOW),
                );
            },
        )
    }

    two_builds!(draw_built, draw_baseline, draw_avx2 => draw<
        const TEX: u8,
        const GOURAUD: bool,
        const DITHER: bool,
        const CLIP: bool,
        const PLAIN: bool,
        const CACHE: u8
    >(
        vram: &mut [u16; VRAM_LEN],
        step: [u32; 5],
        flat: [i32; 3],
        env: &PixelEnv,
        cache: &mut TextureCache
    ) -> u32);

    /// Draw the spans in eight-pixel groups (see [`span::draw`]), the attributes stepping by
    /// `step` per pixel; returns the pixels drawn. Textured spans under
    /// [`span::MIN_TEXTURED_PIXELS`] go pixel by pixel.
    #[inline(always)]
    fn draw<
        const TEX: u8,
        const GOURAUD: bool,
        const DITHER: bool,
        const CLIP: bool,
        const PLAIN: bool,
        const CACHE: u8,
    >(
        self,
        vram: &mut [u16; VRAM_LEN],
        step: [u32; 5],
        flat: [i32; 3],
        env: &PixelEnv,
        cache: &mut TextureCache,
    ) -> u32 {
        let Self {
            mut y,
            end,
            stride,
            mut l,
            mut r,
            dl,
            dr,
            clip,
            mut attr,
            attr_step,
        } = self;
        let lanes = &span::LaneSteps::new::<TEX>(step);
        let mut pixels = 0;
        while y != end {
            let (mut x_start, mut x_end) = ((l >> 32) as i32, (r >> 32) as i32);
            if CLIP {
                x_start = x_start.max(clip.0);
                x_end = x_end.min(clip.1);
            }
            l = l.wrapping_add(dl);
            r = r.wrapping_add(dr);
            if x_start < x_end {
                pixels += (x_end - x_start) as u32;
                let row = ((y & 511) as usize) * VRAM_WIDTH;
                let mut acc: [u32; 5] = core::array::from_fn(|i| {
                    attr[i].wrapping_add(step[i].wrapping_mul(x_start as u32))
                });
                if TEX == TEX_NONE || x_end - x_start >= span::MIN_TEXTURED_PIXELS {
                    span::draw::<TEX, GOURAUD, DITHER, PLAIN, CACHE>(
                        vram, row, y, x_start, x_end, acc, lanes, flat, env, cache,
                    );
                } else {
                    let dither_row = &DITHER_TABLES[(y & 3) as usize];
                    for x in x_start..x_end {
                        let rgb = if GOURAUD {
                            [
                                (acc[0] >> 24) as i32,
                                (acc[1] >> 24) as i32,
                                (acc[2] >> 24) as i32,
                            ]
                        } else {
                            flat
                        };
                        shade_pixel::<TEX, false, false, false, CACHE>(
                            vram,
                            row + x as usize,
                            rgb,
                            (acc[3] >> 24) as u8,
                            (acc[4] >> 24) as u8,
                            if DITHER {
                                &dither_row[(x & 3) as usize]
                            } else {
                                &PLAIN_TABLE
                            },
                            env,
                            None,
                            cache,
                        );
                        for (a, s) in acc.iter_mut().zip(step) {
                            *a = a.wrapping_add(s);
                        }
                    }
                }
            }
            for (a, s) in attr.iter_mut().zip(attr_step) {
                *a = a.wrapping_add(s);
            }
            y += stride;
        }
        pixels
    }
}

/// Draw with the pixel pipeline fixed by the const parameters, texels read in the texture
/// cache mode `CACHE` (docs/hardware/gpu.md §10).
pub(super) fn draw<
    const TEX: u8,
    const CACHE: u8,
    const GOURAUD: bool,
    const RAW: bool,
    const BLEND: bool,
    const DITHER: bool,
    const MASK_CHECK: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    env: &PixelEnv,
    tri: &Triangle,
    rows: super::Rows,
    cache: &mut TextureCache,
) -> DrawCount {
    draw_inline::<TEX, CACHE, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK>(
        vram, state, env, tri, rows, cache,
    )
}

/// [`draw`], inlined into a caller that builds the triangle itself, so that its vertices
/// need not pass through memory. Its steps: a flat untextured opaque triangle goes to
/// [`draw_flat`]; otherwise the vertices wrapped with the attributes the pipeline
/// interpolates ([`wrapped_vertices`]), the coverage tests, core vertex, sort and edges
/// ([`setup`]), the attribute gradients ([`Attributes`]) and the span routine
/// ([`SpanPlan`]); then each part's rows ([`part_rows`], in the console's order when texels
/// go through the texture cache) in eight-pixel groups ([`PartRows::groups`]), as a raw
/// 15-bit page ([`PartRows::raw15`]) or span by span ([`span_pixels`]).
#[inline(always)]
pub(super) fn draw_inline<
    const TEX: u8,
    const CACHE: u8,
    const GOURAUD: bool,
    const RAW: bool,
    const BLEND: bool,
    const DITHER: bool,
    const MASK_CHECK: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    env: &PixelEnv,
    tri: &Triangle,
    rows: super::Rows,
    cache: &mut TextureCache,
) -> DrawCount {
    if TEX == TEX_NONE && !GOURAUD && !BLEND && !MASK_CHECK && !DITHER {
        let color = super::flat_color(tri.vertices[0].color.map(i32::from), env.mask_or);
        let p = tri.vertices.map(|v| (v.x, v.y));
        return draw_flat(vram, state, p, color, env.line, rows);
    }
    let mut drawn = DrawCount::default();
    let verts = wrapped_vertices::<TEX, GOURAUD>(tri);
    // Size drop, zero area, clipped away (docs/hardware/gpu.md §3.2, §3.6).
    let corners = verts.map(|v| (v.x, v.y));
    if let Coverage::Dropped(_) = triangle_coverage(corners, &state.area) {
        return drawn;
    }
    let (v, setup) = setup(verts, |v| (v.x, v.y));
    let attrs = Attributes::new::<TEX, GOURAUD>(&v, setup.core);
    let flat = tri.vertices[0].color.map(|c| c as i32);
    let area = state.area;
    let clip_rows = (area.top as i32, area.bottom as i32 + 1);
    let clip = (area.left as i32, area.right as i32 + 1);
    let step = attrs.grads.map(|g| g.0);
    let plan = SpanPlan::new::<TEX, CACHE, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK>(
        env,
        &v,
        (clip_rows.0, clip_rows.1, clip.0, clip.1),
        (step[3], step[4]),
    );
    // Rows are independent, so they are walked top-down, except where a texel read can
    // change what a later one sees: through the texture cache, in the console's order (§3.4).
    let order = if CACHE != mode::OFF && TEX != TEX_NONE {
        console_order(setup.core)
    } else {
        [(0, false), (1, false)]
    };
    for (part, upward) in order {
        let part = &setup.parts[part];
        let Some((walk, walked)) = part_rows(part, rows, clip_rows, upward) else {
            continue;
        };
        drawn.rows += walked;
        let walk = PartRows::new(part, walk, &attrs, clip);
        if plan.groups {
            let pixels =
                walk.groups::<TEX, GOURAUD, DITHER, CACHE>(vram, &v, (step, flat), env, cache);
            drawn.pixels += pixels;
            continue;
        }
        // Each read mode of a span has a row walk of its own, so that its pixel loop is the
        // only one there.
        let slow = CACHE == mode::TAGS && plan.slow_reads;
        let d = match (plan.raw15_page, slow) {
            (Some(page), slow) => {
                let (duv, mask) = ((step[3], step[4]), (env.mask_or, env.blend));
                let avx2 = env.host.avx2();
                if slow {
                    walk.raw15_built::<BLEND, MASK_CHECK, CACHE, true>(
                        avx2,
                        vram,
                        duv,
                        (page, cache),
                        mask,
                    )
                } else {
                    walk.raw15_built::<BLEND, MASK_CHECK, CACHE, false>(
                        avx2,
                        vram,
                        duv,
                        (page, cache),
                        mask,
                    )
                }
            }
            (None, true) => walk
                .spans::<TEX, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK, CACHE, true>(
                    vram,
                    (step, flat),
                    (&plan, env),
                    cache,
                ),
            (None, false) => walk
                .spans::<TEX, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK, CACHE, false>(
                    vram,
                    (step, flat),
                    (&plan, env),
                    cache,
                ),
        };
        (drawn.pixels, drawn.pairs) = (drawn.pixels + d.pixels, drawn.pairs + d.pairs);
    }
    drawn
}

/// The rows of `part` a primitive drawing `rows` walks inside the clip rows
/// `[top, bottom)`: `(start, count, stride)`, `count` rows from `start`, `stride` apart
/// (negative when `upward`: from the part's bottom row), and the rows walked as the
/// drawing-time model counts them; `None` when there are none (docs/hardware/gpu.md §3.4).
#[inline(always)]
fn part_rows(
    part: &Part,
    rows: super::Rows,
    (top, bottom): (i32, i32),
    upward: bool,
) -> Option<((i32, i32, i32), u32)> {
    let first = rows.first(part.top.max(top));
    let last = part.bottom.min(bottom);
    if first >= last {
        return None;
    }
    let every = match rows {
        super::Rows::All => 1,
        super::Rows::SkipParity(_) => 2,
    };
    // `first` is a drawn row, so the rows walked are the rows drawn: no division here.
    let walked = rows.count(first, last);
    let count = walked as i32;
    let walk = if upward {
        (first + (count - 1) * every, count, -every)
    } else {
        (first, count, every)
    };
    Some((walk, walked))
}

/// Whether the pipeline interpolates attribute `i` (0-2 colour, 3-4 U and V).
#[inline(always)]
const fn used<const TEX: u8, const GOURAUD: bool>(i: usize) -> bool {
    (GOURAUD && i < 3) || (TEX != TEX_NONE && i >= 3)
}

/// The triangle's vertices wrapped to 11 bits (docs/hardware/gpu.md §3.5), with the
/// attributes the pipeline does not interpolate 0, so that the Y sort does not carry them.
#[inline(always)]
fn wrapped_vertices<const TEX: u8, const GOURAUD: bool>(tri: &Triangle) -> [Vtx; 3] {
    let (shaded, textured) = (GOURAUD, TEX != TEX_NONE);
    tri.vertices.map(|p| Vtx {
        x: wrap11(p.x),
        y: wrap11(p.y),
        attr: [
            if shaded { p.color[0] as i32 } else { 0 },
            if shaded { p.color[1] as i32 } else { 0 },
            if shaded { p.color[2] as i32 } else { 0 },
            if textured { p.u as i32 } else { 0 },
            if textured { p.v as i32 } else { 0 },
        ],
    })
}

/// A triangle's attributes (0-2 colour, 3-4 U and V): the core vertex, their 8.24 values
/// there and their gradients per column and per row (docs/hardware/gpu.md §3.6).
struct Attributes {
    cv: Vtx,
    origin: [u32; 5],
    /// (d/dx, d/dy) of each attribute; 0 for those not interpolated.
    grads: [(u32, u32); 5],
}

impl Attributes {
    /// The set-up of the sorted vertices `v` with the core vertex at `core`.
    #[inline(always)]
    fn new<const TEX: u8, const GOURAUD: bool>(v: &[Vtx; 3], core: usize) -> Self {
        let (a, b, c) = (v[0], v[1], v[2]);
        // A select, not an index: the sorted vertices then stay in registers.
        let cv = match core {
            0 => a,
            1 => b,
            _ => c,
        };
        // Coordinates of 11 bits keep this under 2^23 in magnitude (docs/hardware/gpu.md §3.6).
        let den = (b.x - a.x) * (c.y - b.y) - (c.x - b.x) * (b.y - a.y);
        let mut grads = [(0u32, 0u32); 5];
        let mut origin = [0u32; 5];
        let divisor = Divisor::new(den);
        for i in 0..5 {
            if used::<TEX, GOURAUD>(i) {
                grads[i] = gradient(v, i, divisor);
            }
            origin[i] = (((cv.attr[i] as u32) << 12) + (1 << 11)) << 12;
        }
        Self { cv, origin, grads }
    }
}

/// How a triangle's spans are drawn, chosen once per triangle.
struct SpanPlan<'a> {
    /// In eight-pixel groups ([`PartRows::groups`]).
    groups: bool,
    /// A flat-modulated dithered 4-bit texture's CLUT shaded for every dither cell.
    dithered: Option<&'a DitheredCells>,
    /// A 4-bit page the window and VRAM wraps leave alone (`span::plain_page`).
    plain_page: Option<usize>,
    /// A raw 15-bit page the window and VRAM wraps leave alone.
    raw15_page: Option<usize>,
    /// The texels step slowly (`steps_slowly`).
    slow_reads: bool,
}

impl<'a> SpanPlan<'a> {
    /// The plan for the sorted vertices `v` clipped to rows `top..bottom` and columns
    /// `left..right`, U and V stepping by `duv` per pixel, under the pipeline of the const
    /// parameters.
    #[inline(always)]
    fn new<
        const TEX: u8,
        const CACHE: u8,
        const GOURAUD: bool,
        const RAW: bool,
        const BLEND: bool,
        const DITHER: bool,
        const MASK_CHECK: bool,
    >(
        env: &PixelEnv<'a>,
        v: &[Vtx; 3],
        (top, bottom, left, right): (i32, i32, i32, i32),
        duv: (u32, u32),
    ) -> Self {
        let (a, b, c) = (v[0], v[1], v[2]);
        // Opaque, unmasked spans whose pixels each need their own colour or texel go eight
        // at a time; a 4-bit texture under one colour keeps its shaded CLUT instead
        // (undithered, or dithered with the table of every dither cell,
        // `PixelEnv::dithered`, at hand). Raw textures need no colour maths and stay pixel by
        // pixel, as does a primitive that may read texels it has itself written (see
        // `span::texture_clear_of`).
        let dithered = if TEX == 1 && !GOURAUD && DITHER {
            env.dithered
        } else {
            None
        };
        let shaded_clut = TEX == 1 && !GOURAUD && (!DITHER || dithered.is_some());
        // Reads from the cache's copies go pixel by pixel: a rare mode (docs/gpu.md,
        // "Texture cache") that the fast paths need not be built for.
        let copies = CACHE == COPIES;
        let groups = !copies
            && !BLEND
            && !MASK_CHECK
            && !RAW
            && (GOURAUD || TEX != TEX_NONE)
            && !shaded_clut
            && (TEX == TEX_NONE || {
                let xs = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x) + 1);
                span::texture_clear_of(
                    &env.sampler,
                    TEX,
                    (xs.0.max(left), xs.1.min(right)),
                    (a.y.max(top), c.y.min(bottom)),
                )
            });
        // A page the window and the VRAM wraps leave alone (`span::plain_page`): a 4-bit or
        // raw 15-bit span reads texel (u, v) from the halfword at its index plus
        // v * 1024 + u / 4 or + u, and eight-pixel groups compute their eight texel
        // addresses together.
        let plain_page = if TEX == 1 && !copies {
            span::plain_page(&env.sampler, TEX)
        } else {
            None
        };
        let raw15_page = if TEX == 3 && RAW && !copies {
            span::plain_page(&env.sampler, TEX)
        } else {
            None
        };
        Self {
            groups,
            dithered,
            plain_page,
            raw15_page,
            slow_reads: TEX != TEX_NONE && steps_slowly::<TEX>(duv),
        }
    }
}

/// The span `[x_start, x_end)` of line `y` (VRAM row offset `row`), its attributes at
/// `x_start` and their steps `(acc, step)`, with one copy of the pixel loop per table kind,
/// chosen per span by `plan`; texels read in the texture cache mode `CACHE`, through `cache`,
/// the reads of texels that step slowly (`steps_slowly`) tracked as such when `slow`.
#[inline(always)]
fn span_pixels<
    const TEX: u8,
    const GOURAUD: bool,
    const RAW: bool,
    const BLEND: bool,
    const DITHER: bool,
    const MASK_CHECK: bool,
    const CACHE: u8,
>(
    vram: &mut [u16; VRAM_LEN],
    span: (usize, i32, i32, i32),
    (acc, step): ([u32; 5], [u32; 5]),
    flat: [i32; 3],
    (plan, env): (&SpanPlan, &PixelEnv),
    (cache, slow): (&mut TextureCache, bool),
) {
    let (row, y, x_start, x_end) = span;
    let (uv, duv, mask) = (
        (acc[3], acc[4]),
        (step[3], step[4]),
        (env.mask_or, env.blend),
    );
    let line = (y & 3) as usize;
    match (plan.dithered, plan.plain_page) {
        (Some(c), Some(page)) => clut4_span::<BLEND, MASK_CHECK, true, CACHE>(
            vram,
            (row, x_start, x_end),
            uv,
            duv,
            (page, cache, slow),
            (&c[line], &env.lut),
            mask,
        ),
        (None, Some(page)) if TEX == 1 && !GOURAUD && !DITHER => {
            clut4_span::<BLEND, MASK_CHECK, false, CACHE>(
                vram,
                (row, x_start, x_end),
                uv,
                duv,
                (page, cache, slow),
                (&NO_CELLS, &env.lut),
                mask,
            )
        }
        (Some(c), None) => pixels::<TEX, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK, CACHE>(
            vram,
            span,
            acc,
            step,
            flat,
            env,
            Some(&c[line]),
            cache,
        ),
        (None, _) => pixels::<TEX, GOURAUD, RAW, BLEND, DITHER, MASK_CHECK, CACHE>(
            vram, span, acc, step, flat, env, None, cache,
        ),
    }
}

/// Shade `[x_start, x_end)` of line `y` (VRAM row offset `row`) pixel by pixel from the
/// attributes `acc` at `x_start`, stepped by `step`. `cells` holds the shaded CLUT entries of
/// this line's four dither cells for a dithered 4-bit texture under one colour
/// ([`super::dithered_clut4`]); an undithered one reads `env.lut`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn pixels<
    const TEX: u8,
    const GOURAUD: bool,
    const RAW: bool,
    const BLEND: bool,
    const DITHER: bool,
    const MASK_CHECK: bool,
    const CACHE: u8,
>(
    vram: &mut [u16; VRAM_LEN],
    (row, y, x_start, x_end): (usize, i32, i32, i32),
    mut acc: [u32; 5],
    step: [u32; 5],
    flat: [i32; 3],
    env: &PixelEnv,
    cells: Option<&[[u32; 16]; 4]>,
    cache: &mut TextureCache,
) {
    let used = |i: usize| (GOURAUD && i < 3) || (TEX != TEX_NONE && i >= 3);
    let dither_row = &DITHER_TABLES[(y & 3) as usize];
    for x in x_start..x_end {
        let rgb = if GOURAUD {
            [
                (acc[0] >> 24) as i32,
                (acc[1] >> 24) as i32,
                (acc[2] >> 24) as i32,
            ]
        } else {
            flat
        };
        let lut = match cells {
            Some(cells) => Some(&cells[(x & 3) as usize]),
            None if TEX == 1 && !GOURAUD && !DITHER => Some(&env.lut),
            None => None,
        };
        shade_pixel::<TEX, RAW, BLEND, MASK_CHECK, CACHE>(
            vram,
            row + x as usize,
            rgb,
            (acc[3] >> 24) as u8,
            (acc[4] >> 24) as u8,
            if DITHER {
                &dither_row[(x & 3) as usize]
            } else {
                &PLAIN_TABLE
            },
            env,
            lut,
            cache,
        );
        for i in 0..5 {
            if used(i) {
                acc[i] = acc[i].wrapping_add(step[i]);
            }
        }
    }
}

/// The dither cells of a span that reads the one undithered table.
static NO_CELLS: [[u32; 16]; 4] = [[0; 16]; 4];

/// Shade `[x_start, x_end)` of the VRAM line at `row` for a 4-bit texture under one colour,
/// the identity window and a page inside VRAM (docs/hardware/gpu.md §6, §7): each pixel is
/// its texel's CLUT entry read from a shaded table, that of its dither cell among this line's
/// four (`CELLS`, [`super::dithered_clut4`]) or the one undithered table
/// ([`super::shaded_clut4`]); the texel index is read from the halfword
/// `page + v * 1024 + u / 4`, through the texture cache when `CACHE` (§10). U and V start at
/// `uv` and step by `duv` (8.24); `page` is the page's VRAM index, the cache, and whether the
/// texels step slowly (`steps_slowly`).
#[inline(always)]
fn clut4_span<const BLEND: bool, const MASK_CHECK: bool, const CELLS: bool, const CACHE: u8>(
    vram: &mut [u16; VRAM_LEN],
    span: (usize, i32, i32),
    uv: (u32, u32),
    duv: (u32, u32),
    page: (usize, &mut TextureCache, bool),
    tables: (&[[u32; 16]; 4], &[u32; 16]),
    (mask_or, blend): (u16, BlendMode),
) {
    with_blend_mode!(BLEND, blend, mode => {
        clut4_pixels::<BLEND, MASK_CHECK, CELLS, CACHE>(
            vram, span, uv, duv, page, tables, (mask_or, mode),
        )
    });
}

/// [`clut4_span`]'s pixel loop, for one blend mode.
#[inline(always)]
fn clut4_pixels<const BLEND: bool, const MASK_CHECK: bool, const CELLS: bool, const CACHE: u8>(
    vram: &mut [u16; VRAM_LEN],
    (row, x_start, x_end): (usize, i32, i32),
    (mut u, mut v): (u32, u32),
    (du, dv): (u32, u32),
    (page, cache, slow): (usize, &mut TextureCache, bool),
    (cells, lut): (&[[u32; 16]; 4], &[u32; 16]),
    (mask_or, blend): (u16, BlendMode),
) {
    if CACHE == mode::TAGS {
        // With the tags tracked, eight pixels' reads are worked out at a time, those of a span
        // whose texels step slowly looked up only where they leave an entry.
        let span = ((row, x_start, x_end), (u, v), (du, dv), page);
        let (tables, mask) = ((cells, lut), (mask_or, blend));
        if slow {
            let mut reads = SlowReads::new();
            let mut before = BeforeReads::new(page, (u, v), (du, dv));
            clut4_groups::<BLEND, MASK_CHECK, CELLS, true>(
                vram,
                span,
                tables,
                mask,
                move |a, n| {
                    cache.track_slow_lanes::<1>(a, before.next::<1>(), n, &mut reads);
                },
            );
        } else {
            clut4_groups::<BLEND, MASK_CHECK, CELLS, false>(
                vram,
                span,
                tables,
                mask,
                move |a, n| {
                    cache.track_lanes::<1>(a, n);
                },
            );
        }
        return;
    }
    // The four cells' tables as one: entry `cell * 16 + texel`, the cell stepping by 16.
    let cells = cells.as_flattened();
    let mut cell = ((x_start & 3) as usize) << 4;
    for x in x_start..x_end {
        let (tu, tv) = ((u >> 24) as usize, (v >> 24) as usize);
        let word = texture_halfword::<1, CACHE>(vram, cache, page + tv * VRAM_WIDTH + (tu >> 2));
        let texel = usize::from((word >> ((tu & 3) * 4)) & 0xF);
        let e = if CELLS {
            cells[(cell | texel) & 63]
        } else {
            lut[texel]
        };
        super::write_shaded::<BLEND, MASK_CHECK>(vram, row + x as usize, e, mask_or, blend);
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
        cell = (cell + 16) & 48;
    }
}

/// [`clut4_pixels`] with the tags tracked: eight pixels' texel reads worked out at a time and
/// handed to `track` (their halfwords' addresses in lanes, and how many of the eight are
/// read) before they are read. The eight pixels are then read with one load, blended and
/// mask-checked in lanes and written with one store ([`super::put_shaded_lanes`]), a
/// transparent entry (and a lane past the span, left unread) keeping the pixel's value
/// (docs/hardware/gpu.md §6); a group that would run past VRAM's end goes pixel by pixel.
/// The group's reads come before its writes, which pixel by pixel they do not: the two agree
/// because with the tags tracked and no copies kept the page lies clear of the drawing area
/// (`TextureCache::prepare`). `NEAR`: the texels step slowly (`steps_slowly`), so the last
/// group reads all eight lanes' texels and keeps the span's by a lane mask.
#[inline(always)]
fn clut4_groups<const BLEND: bool, const MASK_CHECK: bool, const CELLS: bool, const NEAR: bool>(
    vram: &mut [u16; VRAM_LEN],
    ((row, x_start, x_end), (mut u, mut v), (du, dv), page): SlowSpan,
    (cells, lut): (&[[u32; 16]; 4], &[u32; 16]),
    (mask_or, blend): (u16, BlendMode),
    mut track: impl FnMut(wide::u32x8, usize),
) {
    // The four cells' tables as one: entry `cell * 16 + texel`. A group starts eight pixels
    // after the one before it, so lane `k` is in cell `(x_start + k) & 3` in every group.
    let cells = cells.as_flattened();
    let first_cell = (x_start & 3) as usize;
    let steps = span::PlainReads::steps((du, dv));
    let mut x = x_start;
    while x < x_end {
        let r = span::PlainReads::new::<1>(page, (u, v), &steps);
        let n = ((x_end - x) as usize).min(LANES);
        track(r.lanes, n);
        let at = row + x as usize;
        let entry = |k: usize| {
            let word = vram[r.address[k] as usize & (VRAM_LEN - 1)];
            let texel = usize::from((word >> r.shift[k]) & 0xF);
            if CELLS {
                cells[(((first_cell + k) & 3) << 4) | texel]
            } else {
                lut[texel]
            }
        };
        // The span's entries, lanes past it left at 0 (transparent). Texels that step slowly
        // (`NEAR`) lie close together, so all eight are read and those past the span dropped
        // with no test a lane; others are left unread.
        let entries: [u32; LANES] = if NEAR {
            let all = wide::u32x8::new(core::array::from_fn(entry));
            let inside = wide::u32x8::splat(n as u32).simd_gt(span::LANE_INDEX);
            (all & inside).to_array()
        } else if n == LANES {
            core::array::from_fn(entry)
        } else {
            core::array::from_fn(|k| if k < n { entry(k) } else { 0 })
        };
        match vram
            .get_mut(at..)
            .and_then(|d| d.first_chunk_mut::<LANES>())
        {
            Some(dst) => {
                let texels = wide::u16x8::new(entries.map(|e| e as u16));
                let drawn = wide::u16x8::new(entries.map(|e| 0u16.wrapping_sub((e >> 16) as u16)));
                super::put_shaded_lanes::<BLEND, MASK_CHECK>(dst, texels, drawn, mask_or, blend);
            }
            None => {
                for (k, &e) in entries.iter().enumerate().take(n) {
                    super::write_shaded::<BLEND, MASK_CHECK>(vram, at + k, e, mask_or, blend);
                }
            }
        }
        u = u.wrapping_add(du.wrapping_mul(8));
        v = v.wrapping_add(dv.wrapping_mul(8));
        x += 8;
    }
}

/// The texel reads one pixel before those of the groups of a span over a plain page (see
/// [`span::PlainReads`]) whose texels step slowly, for [`TextureCache::track_slow_lanes`]:
/// U and V stepped back by one pixel, so that they do not wait on the groups tracked before.
struct BeforeReads {
    page: usize,
    uv: (u32, u32),
    group: (u32, u32),
    steps: (wide::u32x8, wide::u32x8),
}

impl BeforeReads {
    /// For a span whose first pixel has U and V `uv`, stepping by `duv` per pixel (8.24).
    #[inline(always)]
    fn new(page: usize, (u, v): (u32, u32), (du, dv): (u32, u32)) -> Self {
        Self {
            page,
            uv: (u.wrapping_sub(du), v.wrapping_sub(dv)),
            group: (du.wrapping_mul(LANES as u32), dv.wrapping_mul(LANES as u32)),
            steps: span::PlainReads::steps((du, dv)),
        }
    }

    /// The addresses read one pixel before each pixel of the next group of eight.
    #[inline(always)]
    fn next<const TEX: u8>(&mut self) -> wide::u32x8 {
        let r = span::PlainReads::new::<TEX>(self.page, self.uv, &self.steps);
        self.uv = (
            self.uv.0.wrapping_add(self.group.0),
            self.uv.1.wrapping_add(self.group.1),
        );
        r.lanes
    }
}

/// A span of [`clut4_groups`] or [`raw15_groups`]: its row offset and columns, U and V at its
/// first pixel and their steps per pixel (8.24), and the page's VRAM index.
type SlowSpan = ((usize, i32, i32), (u32, u32), (u32, u32), usize);

/// Write `[x_start, x_end)` of the VRAM line at `row` from a raw 15-bit texture under the
/// identity window whose page lies inside VRAM (docs/hardware/gpu.md §6, §7): each pixel is
/// its texel, the halfword `page + v * 1024 + u` (through the texture cache when `CACHE`,
/// §10), unmodulated; a texel of 0000h leaves the pixel as it is, and bit 15 of the others
/// selects blending. U and V start at `uv` and step by `duv` (8.24); `page` is the page's
/// VRAM index, the cache, and whether the texels step slowly (`steps_slowly`).
#[inline(always)]
fn raw15_span<const BLEND: bool, const MASK_CHECK: bool, const CACHE: u8>(
    vram: &mut [u16; VRAM_LEN],
    span: (usize, i32, i32),
    uv: (u32, u32),
    duv: (u32, u32),
    page: (usize, &mut TextureCache, bool),
    (mask_or, blend): (u16, BlendMode),
) {
    with_blend_mode!(BLEND, blend, mode => {
        raw15_pixels::<BLEND, MASK_CHECK, CACHE>(vram, span, uv, duv, page, (mask_or, mode))
    });
}

/// [`raw15_span`]'s pixel loop, for one blend mode.
#[inline(always)]
fn raw15_pixels<const BLEND: bool, const MASK_CHECK: bool, const CACHE: u8>(
    vram: &mut [u16; VRAM_LEN],
    (row, x_start, x_end): (usize, i32, i32),
    (mut u, mut v): (u32, u32),
    (du, dv): (u32, u32),
    (page, cache, slow): (usize, &mut TextureCache, bool),
    (mask_or, blend): (u16, BlendMode),
) {
    if CACHE == mode::TAGS {
        // With the tags tracked, eight pixels' reads are worked out at a time, those of a span
        // whose texels step slowly looked up only where they leave an entry.
        let span = ((row, x_start, x_end), (u, v), (du, dv), page);
        if slow {
            let mut reads = SlowReads::new();
            let mut before = BeforeReads::new(page, (u, v), (du, dv));
            raw15_groups::<BLEND, MASK_CHECK>(vram, span, (mask_or, blend), move |a, n| {
                cache.track_slow_lanes::<3>(a, before.next::<3>(), n, &mut reads);
            });
        } else {
            // The whole groups pass LANES and the last group fewer, so each call names its
            // routine rather than have `track_lanes` test `n` again for the last group.
            raw15_groups::<BLEND, MASK_CHECK>(vram, span, (mask_or, blend), move |a, n| {
                if n == LANES {
                    cache.track_group::<3>(a);
                } else {
                    cache.track_some_lanes::<3>(a, n);
                }
            });
        }
        return;
    }
    for x in x_start..x_end {
        let (tu, tv) = ((u >> 24) as usize, (v >> 24) as usize);
        let texel = texture_halfword::<3, CACHE>(vram, cache, page + tv * VRAM_WIDTH + tu);
        let e = if texel == 0 {
            0
        } else {
            0x1_0000 | u32::from(texel)
        };
        super::write_shaded::<BLEND, MASK_CHECK>(vram, row + x as usize, e, mask_or, blend);
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
    }
}

/// [`raw15_pixels`] with the tags tracked: eight pixels' texel reads worked out at a time and
/// handed to `track` (their halfwords' addresses in lanes, and how many of the eight are
/// read) before they are read. The eight pixels are then written with one store from the
/// span's texels, a texel of 0000h (and a lane past the span, left unread as 0000h) keeping
/// the pixel's value; blended or mask-checked groups read the eight pixels with one load
/// first and blend and check them in lanes ([`super::put_shaded_lanes`],
/// docs/hardware/gpu.md §6). A group that would run past VRAM's end goes pixel by pixel.
/// The group's reads come before its writes, which pixel by pixel they do not: the two
/// agree because with the tags tracked and no copies kept the page lies clear of the drawing
/// area (`TextureCache::prepare`). The span's whole groups come first, then the pixels left.
#[inline(always)]
fn raw15_groups<const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    ((row, x_start, x_end), (mut u, mut v), (du, dv), page): SlowSpan,
    (mask_or, blend): (u16, BlendMode),
    mut track: impl FnMut(wide::u32x8, usize),
) {
    let steps = span::PlainReads::steps((du, dv));
    let (step_u, step_v) = (du.wrapping_mul(8), dv.wrapping_mul(8));
    let mut x = x_start;
    while x_end - x >= LANES as i32 {
        let r = span::PlainReads::new::<3>(page, (u, v), &steps);
        raw15_group::<BLEND, MASK_CHECK>(
            vram,
            row + x as usize,
            &r,
            LANES,
            (mask_or, blend),
            &mut track,
        );
        u = u.wrapping_add(step_u);
        v = v.wrapping_add(step_v);
        x += LANES as i32;
    }
    if x < x_end {
        let r = span::PlainReads::new::<3>(page, (u, v), &steps);
        let n = (x_end - x) as usize;
        raw15_group::<BLEND, MASK_CHECK>(
            vram,
            row + x as usize,
            &r,
            n,
            (mask_or, blend),
            &mut track,
        );
    }
}

/// One group of [`raw15_groups`]: the first `n` (at most eight) of the reads `r`, written
/// from VRAM index `at` on.
#[inline(always)]
fn raw15_group<const BLEND: bool, const MASK_CHECK: bool>(
    vram: &mut [u16; VRAM_LEN],
    at: usize,
    r: &span::PlainReads,
    n: usize,
    (mask_or, blend): (u16, BlendMode),
    track: &mut impl FnMut(wide::u32x8, usize),
) {
    track(r.lanes, n);
    let mut texels = [0; LANES];
    for (t, &a) in texels.iter_mut().zip(&r.address).take(n) {
        *t = vram[a as usize & (VRAM_LEN - 1)];
    }
    match vram
        .get_mut(at..)
        .and_then(|d| d.first_chunk_mut::<LANES>())
    {
        Some(dst) if !BLEND && !MASK_CHECK => {
            let t = wide::u16x8::new(texels);
            let keep = t.simd_eq(wide::u16x8::ZERO);
            let out = t | wide::u16x8::splat(mask_or);
            *dst = keep.bitselect(wide::u16x8::new(*dst), out).to_array();
        }
        Some(dst) => {
            let t = wide::u16x8::new(texels);
            let drawn = !t.simd_eq(wide::u16x8::ZERO);
            super::put_shaded_lanes::<BLEND, MASK_CHECK>(dst, t, drawn, mask_or, blend);
        }
        None => {
            for (k, &texel) in texels.iter().enumerate().take(n) {
                let e = if texel == 0 {
                    0
                } else {
                    0x1_0000 | u32::from(texel)
                };
                super::write_shaded::<BLEND, MASK_CHECK>(vram, at + k, e, mask_or, blend);
            }
        }
    }
}

/// Pixels in a group of eight.
const LANES: usize = 8;

#[cfg(test)]
mod tests {
    use super::{Divisor, Vtx, gradient};
    use proptest::prelude::*;

    proptest! {
        /// The reciprocal divide truncates toward zero as i64 division does, for every
        /// 32-bit numerator and denominator, and over the range of gradient denominators.
        #[test]
        fn divisor_truncates_like_division(
            n in any::<i32>(),
            den in prop_oneof![any::<i32>(), -(1i32 << 21)..(1i32 << 21), -4i32..4],
        ) {
            prop_assume!(den != 0);
            let quotient = i64::from(n) / i64::from(den);
            // i32::MIN / -1 does not fit 32 bits; it wraps, as on a 32-bit machine.
            prop_assert_eq!(Divisor::new(den).divide(n), quotient as i32);
        }
    }

    proptest! {
        /// Each gradient equals §3.6's formula worked in i64: numerators times 4096 divided
        /// with truncation, then taken as 32 bits and shifted into 8.24, for vertices the
        /// size limit lets through (§3.2) and 8-bit attributes, at the limits' extremes too.
        #[test]
        fn gradients_match_wide_division(
            origin in (-1024i32..1024, -1024i32..1024),
            offsets in prop::array::uniform3((
                prop_oneof![0i32..1024, Just(0), Just(1023)],
                prop_oneof![0i32..512, Just(0), Just(511)],
            )),
            attr in prop::array::uniform3(prop::array::uniform5(
                prop_oneof![0i32..256, Just(0), Just(255)],
            )),
        ) {
            // Within 1023 columns and 511 rows of each other: what the size limit draws.
            let v: [Vtx; 3] = core::array::from_fn(|k| Vtx {
                x: origin.0 + offsets[k].0,
                y: origin.1 + offsets[k].1,
                attr: attr[k],
            });
            let (a, b, c) = (v[0], v[1], v[2]);
            let den = i64::from(b.x - a.x) * i64::from(c.y - b.y)
                - i64::from(c.x - b.x) * i64::from(b.y - a.y);
            prop_assume!(den != 0);
            for i in 0..5 {
                let (aa, ba, ca) = (i64::from(a.attr[i]), i64::from(b.attr[i]), i64::from(c.attr[i]));
                let nx = (ba - aa) * i64::from(c.y - b.y) - (ca - ba) * i64::from(b.y - a.y);
                let ny = i64::from(b.x - a.x) * (ca - ba) - i64::from(c.x - b.x) * (ba - aa);
                let expected = ((((nx * 4096) / den) as u32) << 12, (((ny * 4096) / den) as u32) << 12);
                prop_assert_eq!(gradient(&v, i, Divisor::new(den as i32)), expected);
            }
        }
    }

    #[test]
    fn divisor_edges() {
        for den in [
            1i32,
            -1,
            2,
            -2,
            3,
            1 << 20,
            -(1 << 20),
            (1 << 21) - 1,
            4095,
            4096,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
        ] {
            for n in [
                0i32,
                1,
                -1,
                den,
                den.wrapping_neg(),
                den.wrapping_sub(1),
                den.wrapping_add(1),
                i32::MAX,
                i32::MIN,
                i32::MIN + 1,
                1 << 30,
            ] {
                let quotient = (i64::from(n) / i64::from(den)) as i32;
                assert_eq!(Divisor::new(den).divide(n), quotient, "{n} / {den}");
            }
        }
    }
}
