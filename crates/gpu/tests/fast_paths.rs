//! The rasterizer's specialised routines held bit for bit to per-pixel models of the fact
//! sheet (docs/hardware/gpu.md §2-§7) on random primitives: flat untextured polygons
//! (plain span stores), flat-modulated and raw textured polygons (the pre-shaded 4-bit CLUT
//! table), rectangles of every size and texture depth, each with the four semi-transparency
//! modes and both mask bits, random drawing areas and offsets. The whole VRAM is compared.
//! Two exhaustive cases follow: every background halfword under each blend mode, and every
//! colour byte times every 5-bit texel value through the 4-bit CLUT path.
//!
//! VRAM starts as random data (a seeded generator: about 1/8 of the halfwords 0000h, 1/16
//! 8000h, the rest uniform, so backgrounds, texels and CLUT entries include transparent,
//! opaque-black and bit-15 values). Primitives draw into x 0-511 (the drawing area never
//! extends further right) and textures and CLUTs are placed in x 512-1023 without wrapping
//! back, so every texel the model reads is the value before drawing: the model does not
//! need the order in which the hardware reads and writes.

use gpu::encode;
use gpu::{Gpu, Vram};
use proptest::prelude::*;

#[path = "support/cost.rs"]
mod cost;
#[path = "support/model.rs"]
mod model;
#[path = "support/pixel.rs"]
mod pixel;
#[path = "support/quiet.rs"]
mod quiet;

use pixel::{Mask, Texture};

/// A GP0 vertex word: X in bits 0-10, Y in bits 16-26 (docs/hardware/gpu.md §2).
fn xy(x: i32, y: i32) -> u32 {
    ((y as u32 & 0x7FF) << 16) | (x as u32 & 0x7FF)
}

/// A signed 11-bit value (§2, §3.5, §5).
fn sext11(v: i64) -> i64 {
    ((v & 0x7FF) ^ 0x400) - 0x400
}

fn rgb_word(c: [u8; 3]) -> u32 {
    c[0] as u32 | (c[1] as u32) << 8 | (c[2] as u32) << 16
}

fn rgb8(c: [u8; 3]) -> [u32; 3] {
    c.map(|c| c as u32)
}

/// The drawing environment of one case: area corners (inclusive), offset, E6h, E1h dither
/// and the seed of the VRAM contents.
#[derive(Clone, Debug)]
struct Env {
    area: (u32, u32, u32, u32),
    offset: (i32, i32),
    mask: Mask,
    dither: bool,
    seed: u64,
}

impl Env {
    /// E3h, E4h, E5h and E6h (§2).
    fn words(&self) -> [u32; 4] {
        let a = self.area;
        [
            encode::area_top_left(a.0 as u16, a.1 as u16),
            encode::area_bottom_right(a.2 as u16, a.3 as u16),
            encode::drawing_offset(self.offset.0 as i16, self.offset.1 as i16),
            self.mask.e6(),
        ]
    }

    fn inside(&self, x: i64, y: i64) -> bool {
        let a = self.area;
        x >= a.0 as i64 && x <= a.2 as i64 && y >= a.1 as i64 && y <= a.3 as i64
    }

    fn clip(&self) -> (i64, i64, i64, i64) {
        let a = self.area;
        (a.0 as i64, a.1 as i64, a.2 as i64, a.3 as i64)
    }

    /// A vertex as the rasterizer places it: command coordinate (11-bit signed) plus the
    /// drawing offset; `model::triangle` then wraps the sum to 11 bits (§3.5).
    fn vertex(&self, x: i32, y: i32, a: [i64; 5]) -> model::V {
        model::V {
            x: sext11(x as i64) + self.offset.0 as i64,
            y: sext11(y as i64) + self.offset.1 as i64,
            a,
        }
    }
}

/// A right or bottom drawing-area corner: mostly past the left/top corner (0-63), sometimes
/// before it, which leaves an empty area.
/// `(x, y)` moved onto, or `d` pixels beside, one edge of the drawing area (`side`: left,
/// right, top, bottom), where a span's clip starts to matter; unmoved for `None`.
fn near_area_edge(env: &Env, (x, y): (i32, i32), snap: Option<(usize, i32)>) -> (i32, i32) {
    let a = env.area;
    match snap {
        Some((side, d)) => {
            let edge = [a.0 as i32, a.2 as i32 + 1, a.1 as i32, a.3 as i32 + 1][side] + d;
            if side < 2 {
                (edge - env.offset.0, y)
            } else {
                (x, edge - env.offset.1)
            }
        }
        None => (x, y),
    }
}

/// A GPU for timing the drawing ([`quiet::quiet`]), in 480i drawing from field line `start`
/// when `interlace` is given.
fn gpu_without_video_events(interlace: Option<u32>) -> Gpu {
    let mut g = quiet::quiet();
    if let Some(start) = interlace {
        g.gp1(0x0800_0025);
        g.gp1(0x0500_0000 | start << 10);
    }
    g
}

fn corner() -> impl Strategy<Value = u32> {
    prop_oneof![6 => 64u32..512, 1 => 0u32..512]
}

fn env() -> impl Strategy<Value = Env> {
    let offset = prop_oneof![5 => (-32i32..32, -32i32..32), 1 => (-1024i32..1024, -1024i32..1024)];
    (
        (0u32..64, 0u32..64, corner(), corner()),
        offset,
        any::<(bool, bool, bool)>(),
        any::<u64>(),
    )
        .prop_map(|(a, offset, (set, check, dither), seed)| Env {
            area: a,
            offset,
            mask: Mask { set, check },
            dither,
            seed,
        })
}

/// A GPU whose VRAM holds the case's random data, and a copy of that VRAM.
fn gpu_with_background(seed: u64) -> (Gpu, Vram) {
    let mut g = Gpu::new();
    let mut state = seed;
    for p in g.vram_mut().as_mut_slice() {
        // SplitMix64.
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        *p = match z >> 60 {
            0 | 1 => 0x0000,
            2 => 0x8000,
            _ => z as u16,
        };
    }
    let background = g.vram().clone();
    (g, background)
}

/// The first pixel where the two VRAMs differ, for the failure message.
fn difference(got: &Vram, want: &Vram, background: &Vram) -> String {
    let first = got
        .as_slice()
        .iter()
        .zip(want.as_slice())
        .position(|(a, b)| a != b);
    let count = got
        .as_slice()
        .iter()
        .zip(want.as_slice())
        .filter(|(a, b)| a != b)
        .count();
    match first {
        Some(i) => format!(
            "{count} pixels differ; first ({}, {}): got {:04X}, model {:04X}, before {:04X}",
            i % 1024,
            i / 1024,
            got.as_slice()[i],
            want.as_slice()[i],
            background.as_slice()[i]
        ),
        None => String::new(),
    }
}

/// Mostly near the drawing area, sometimes far enough to hit the size drop and the 11-bit
/// wrap.
fn coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![9 => -40i32..400, 1 => -1100i32..1100]
}

/// A rectangle's top-left corner: mostly where most of the rectangle lands in the drawing
/// area, sometimes anywhere in (and beyond) the 11-bit range.
fn corner_coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![9 => 10i32..250, 1 => -1100i32..1100]
}

/// A texture placed in x 512-1023 with nothing wrapping past x 1023 (see the file comment):
/// page X 8-15 (4-bit), 8-14 (8-bit), 8-12 (15-bit: 256 halfwords); CLUT X 512-1008
/// (4-bit, 16 entries) or 512-768 (8-bit, 256 entries), any CLUT row.
fn texture() -> impl Strategy<Value = Texture> {
    let depth = prop_oneof![5 => Just(0u32), 2 => Just(1u32), 1 => Just(2u32), 1 => Just(3u32)];
    let window = prop_oneof![1 => Just([0u32; 4]), 2 => [0u32..32, 0u32..32, 0u32..32, 0u32..32]];
    (depth, 8u32..16, 0u32..2, 0u32..32, 0u32..512, window).prop_map(
        |(depth, page_x, page_y, clut_x, clut_y, window)| {
            let (max_page, clut_span) = match depth {
                0 => (15, 32),
                1 => (14, 17),
                _ => (12, 32),
            };
            Texture {
                page_x: page_x.min(max_page),
                page_y,
                depth,
                clut: (32 + clut_x % clut_span) | clut_y << 6,
                window,
            }
        },
    )
}

/// A modulation colour: often 808080h (neutral), otherwise any.
fn color() -> impl Strategy<Value = [u8; 3]> {
    prop_oneof![1 => Just([0x80u8; 3]), 3 => any::<[u8; 3]>()]
}

/// The triangles a triangle or a quad is drawn as: (v0, v1, v2), then (v1, v2, v3) (§3.1).
fn halves(quad: bool) -> &'static [[usize; 3]] {
    if quad {
        &[[0, 1, 2], [1, 2, 3]]
    } else {
        &[[0, 1, 2]]
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Flat untextured triangles and quads (GP0 20h/22h/28h/2Ah): every covered pixel gets
    /// c8 >> 3 per channel, never dithered even with E1h bit 9 (§6), blended with the E1h
    /// mode when semi-transparent, under the E6h mask rules (§6), coverage from the §3 model.
    #[test]
    fn flat_polygons_match_model(
        pts in prop::collection::vec((coordinate(), coordinate()), 4),
        quad in any::<bool>(),
        rgb in any::<[u8; 3]>(),
        semi in any::<bool>(),
        mode in 0u32..4,
        page in 0u32..0x200,
        env in env(),
    ) {
        let (mut g, background) = gpu_with_background(env.seed);
        // E1h: random page/depth bits (unused), the blend mode, dither.
        g.gp0(0xE100_0000 | (page & !0x60) | mode << 5 | (env.dither as u32) << 9);
        g.gp0_words(&env.words());
        let cmd = 0x20 | (semi as u32) << 1 | (quad as u32) << 3;
        let mut words = vec![cmd << 24 | rgb_word(rgb)];
        let n = if quad { 4 } else { 3 };
        words.extend(pts[..n].iter().map(|p| xy(p.0, p.1)));
        g.gp0_words(&words);

        let mut expected = background.clone();
        let c = rgb8(rgb).map(|c| c as i64);
        let color = pixel::flat(rgb8(rgb));
        for tri in halves(quad) {
            let v = tri.map(|i| env.vertex(pts[i].0, pts[i].1, [c[0], c[1], c[2], 0, 0]));
            for p in model::triangle(v, env.clip()) {
                pixel::plot(&mut expected, (p.x, p.y), color, false, semi.then_some(mode), env.mask);
            }
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &background));
    }

    /// Flat opaque triangles without the E6h mask check (GP0 20h, and 21h whose raw bit an
    /// untextured polygon ignores), on a cleared VRAM with the mask bit set so that every
    /// drawn pixel is non-zero: the pixels of the §3 model, only on the lines 480i drawing
    /// keeps (interlaced 480-line mode with E1h bit 10 clear skips the lines whose bit 0 is
    /// that of the display start line plus the field, §8), and a drawing time of the
    /// triangle set-up, the rows walked and the pixels drawn (docs/emulator.md, "Drawing
    /// time").
    #[test]
    fn flat_triangles_draw_and_count_the_model_pixels(
        pts in prop::collection::vec((coordinate(), coordinate()), 3),
        snap in prop::collection::vec(prop::option::of((0usize..4, -2i32..3)), 3),
        rgb in any::<[u8; 3]>(),
        raw in any::<bool>(),
        interlace in prop::option::of(0u32..2),
        env in env(),
    ) {
        let env = Env { mask: Mask { set: true, check: false }, ..env };
        // Some vertices on or next to an edge of the drawing area.
        let pts: Vec<(i32, i32)> =
            pts.iter().zip(&snap).map(|(&p, &s)| near_area_edge(&env, p, s)).collect();
        let mut g = gpu_without_video_events(interlace);
        g.gp0(0xE100_0000 | (env.dither as u32) << 9);
        g.gp0_words(&env.words());
        let mut words = vec![(0x20 | raw as u32) << 24 | rgb_word(rgb)];
        words.extend(pts.iter().map(|p| xy(p.0, p.1)));
        g.gp0_words(&words);

        let mut expected = Vram::new();
        let c = rgb8(rgb).map(|c| c as i64);
        let v = [0, 1, 2].map(|i| env.vertex(pts[i].0, pts[i].1, [c[0], c[1], c[2], 0, 0]));
        let keep = |y: i64| interlace.is_none_or(|start| y.rem_euclid(2) != start as i64);
        let rows = model::rows(&v, env.clip(), keep) as f64;
        let mut drawn = 0u32;
        for p in model::triangle(v, env.clip()) {
            if interlace.is_some_and(|start| p.y.rem_euclid(2) == start as i64) {
                continue;
            }
            pixel::plot(&mut expected, (p.x, p.y), pixel::flat(rgb8(rgb)), false, None, env.mask);
            drawn += 1;
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &Vram::new()));
        let time = cost::TRIANGLE_SETUP + rows * cost::ROW + drawn as f64 * cost::PIXEL;
        prop_assert_eq!(g.cycles_until(gpu::EventKind::DrawingDone), cost::cycles_to_idle(time));
    }

    /// Gouraud-shaded opaque triangles without the E6h mask check (GP0 30h, and 31h whose
    /// raw bit an untextured polygon ignores), dithered under E1h bit 9, on a cleared VRAM
    /// with the mask bit set: the pixels and §3.6 colours of the model, only on the lines
    /// 480i drawing keeps (§8), and a drawing time of the set-up, the Gouraud set-up, the
    /// rows walked and the pixels drawn (docs/emulator.md, "Drawing time").
    #[test]
    fn gouraud_triangles_draw_and_count_the_model_pixels(
        pts in prop::collection::vec((coordinate(), coordinate(), any::<[u8; 3]>()), 3),
        snap in prop::collection::vec(prop::option::of((0usize..4, -2i32..3)), 3),
        raw in any::<bool>(),
        interlace in prop::option::of(0u32..2),
        env in env(),
    ) {
        let env = Env { mask: Mask { set: true, check: false }, ..env };
        let pts: Vec<(i32, i32, [u8; 3])> = pts.iter().zip(&snap).map(|(&(x, y, c), &s)| {
            let (x, y) = near_area_edge(&env, (x, y), s);
            (x, y, c)
        }).collect();
        let mut g = gpu_without_video_events(interlace);
        g.gp0(0xE100_0000 | (env.dither as u32) << 9);
        g.gp0_words(&env.words());
        let mut words = vec![];
        for (i, p) in pts.iter().enumerate() {
            let cmd = if i == 0 { (0x30 | raw as u32) << 24 } else { 0 };
            words.push(cmd | rgb_word(p.2));
            words.push(xy(p.0, p.1));
        }
        g.gp0_words(&words);

        let mut expected = Vram::new();
        let v = [0, 1, 2].map(|i| {
            let c = rgb8(pts[i].2).map(|c| c as i64);
            env.vertex(pts[i].0, pts[i].1, [c[0], c[1], c[2], 0, 0])
        });
        let keep = |y: i64| interlace.is_none_or(|start| y.rem_euclid(2) != start as i64);
        let rows = model::rows(&v, env.clip(), keep) as f64;
        let mut drawn = 0u32;
        for p in model::triangle(v, env.clip()) {
            if interlace.is_some_and(|start| p.y.rem_euclid(2) == start as i64) {
                continue;
            }
            let c = [0, 1, 2].map(|i| model::channel(p.attr[i], p.x, p.y, env.dither));
            let color = c[0] | c[1] << 5 | c[2] << 10;
            pixel::plot(&mut expected, (p.x, p.y), color, false, None, env.mask);
            drawn += 1;
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &Vram::new()));
        let time = cost::TRIANGLE_SETUP
            + cost::GOURAUD_SETUP
            + rows * cost::ROW
            + drawn as f64 * (cost::PIXEL + cost::SHADED_PIXEL);
        prop_assert_eq!(g.cycles_until(gpu::EventKind::DrawingDone), cost::cycles_to_idle(time));
    }

    /// Flat quads whose vertices are the corners of an axis-aligned rectangle, in every
    /// order (some orders tile the rectangle with the two triangles, others cross; some
    /// rectangles exceed the size limit): the same model as above, two triangles each.
    #[test]
    fn axis_aligned_flat_quads_match_model(
        (x, y) in (coordinate(), coordinate()),
        (w, h) in prop_oneof![4 => (1i32..400, 1i32..300), 1 => (1i32..1100, 1i32..600)],
        order in Just([0usize, 1, 2, 3]).prop_shuffle(),
        rgb in any::<[u8; 3]>(),
        semi in any::<bool>(),
        mode in 0u32..4,
        env in env(),
    ) {
        let (mut g, background) = gpu_with_background(env.seed);
        g.gp0(0xE100_0000 | mode << 5 | (env.dither as u32) << 9);
        g.gp0_words(&env.words());
        let corners = [(x, y), (x + w, y), (x, y + h), (x + w, y + h)];
        let pts = order.map(|i| corners[i]);
        let cmd = 0x28 | (semi as u32) << 1;
        let mut words = vec![cmd << 24 | rgb_word(rgb)];
        words.extend(pts.iter().map(|p| xy(p.0, p.1)));
        g.gp0_words(&words);

        let mut expected = background.clone();
        let c = rgb8(rgb).map(|c| c as i64);
        let color = pixel::flat(rgb8(rgb));
        for tri in halves(true) {
            let v = tri.map(|i| env.vertex(pts[i].0, pts[i].1, [c[0], c[1], c[2], 0, 0]));
            for p in model::triangle(v, env.clip()) {
                pixel::plot(&mut expected, (p.x, p.y), color, false, semi.then_some(mode), env.mask);
            }
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &background));
    }

    /// Textured triangles and quads, flat or Gouraud-shaded, modulated or raw, opaque or
    /// semi-transparent (GP0 24h-27h, 2Ch-2Fh, 34h-37h, 3Ch-3Fh), mostly 4-bit: texel from §7 (window, page, CLUT; 0000h not
    /// drawn), modulated per §6 and dithered when E1h bit 9 is set unless raw (§6 "When
    /// dithering applies"), blended with the texpage attribute's mode only where the texel
    /// has bit 15, which is also written (§6). UV and Gouraud colours from the §3.6 model.
    #[test]
    fn textured_polygons_match_model(
        pts in prop::collection::vec((coordinate(), coordinate(), any::<[u8; 2]>()), 4),
        (quad, gouraud) in (any::<bool>(), any::<bool>()),
        shades in prop::collection::vec(color(), 4),
        (rgb, raw, semi) in (color(), any::<bool>(), any::<bool>()),
        (mode, e1_mode) in (0u32..4, 0u32..4),
        tex in texture(),
        env in env(),
    ) {
        let case = TexturedPolygon { pts, quad, gouraud, shades, rgb, raw, semi, mode, e1_mode, tex };
        check_textured_polygon(&case, &env)?;
    }

    /// Raw 15-bit textured polygons, the case whose pages under the identity window are read
    /// straight from VRAM (GP0 25h, 27h, 2Dh, 2Fh, ...; §6, §7), against the model as above:
    /// pages at x 512-768, mostly the identity window.
    #[test]
    fn raw15_polygons_match_model(
        pts in prop::collection::vec((coordinate(), coordinate(), any::<[u8; 2]>()), 4),
        (quad, gouraud, semi) in any::<(bool, bool, bool)>(),
        shades in prop::collection::vec(color(), 4),
        (mode, e1_mode) in (0u32..4, 0u32..4),
        (page_x, page_y) in (8u32..13, 0u32..2),
        window in prop_oneof![3 => Just([0u32; 4]), 1 => [0u32..32, 0u32..32, 0u32..32, 0u32..32]],
        env in env(),
    ) {
        let tex = Texture { page_x, page_y, depth: 2, clut: 0, window };
        let case = TexturedPolygon {
            pts, quad, gouraud, shades, rgb: [0x80; 3], raw: true, semi, mode, e1_mode, tex,
        };
        check_textured_polygon(&case, &env)?;
    }

    /// [`raw15_identity_window_case`]: triangles around their own page, which sits anywhere
    /// in VRAM (its 256 halfwords wrap past x 1023 from page X 13 on), so that many draw over
    /// the texels they read.
    #[test]
    fn raw15_page_read_directly_matches_the_window_path(
        around in prop::collection::vec((-64i32..320, -64i32..320, any::<[u8; 2]>()), 3),
        (page_x, page_y) in (0u32..16, 0u32..2),
        semi_mode in (any::<bool>(), 0u32..4),
        (set, check) in any::<(bool, bool)>(),
        seed in any::<u64>(),
    ) {
        let pts: Vec<_> = around
            .iter()
            .map(|&(dx, dy, uv)| ((64 * page_x as i32 + dx).clamp(0, 1023), (256 * page_y as i32 + dy).clamp(0, 511), uv))
            .collect();
        raw15_identity_window_case(&pts, (page_x, page_y), semi_mode, Mask { set, check }, seed)?;
    }

    /// [`page_addressed_groups_case`]: modulated textured triangles drawn eight pixels at a
    /// time (opaque, no mask check), on lines 260-499 with their page on lines 0-255 of any
    /// page column, so that 8-bit and 15-bit pages from page X 15 and 13 on wrap past x 1023.
    #[test]
    fn page_addressed_groups_match_the_window_path(
        pts in prop::collection::vec((-40i32..560, 260i32..500, any::<[u8; 2]>()), 3),
        (depth, page_x) in (0u32..3, 0u32..16),
        (gouraud, dither) in any::<(bool, bool)>(),
        shades in prop::collection::vec(color(), 3),
        clut in (0u32..48, 0u32..256),
        seed in any::<u64>(),
    ) {
        page_addressed_groups_case(&pts, (depth, page_x), (gouraud, dither), &shades, clut, seed)?;
    }

    /// Rectangles (GP0 60h-7Fh): variable size (W & 3FFh by H & 1FFh), 1x1, 8x8, 16x16;
    /// untextured or 4/8/15-bit textured, raw or modulated, opaque or semi-transparent, with
    /// the E1h X/Y flips and the E2h window. Pixel (x0 + i, y0 + j) inside the drawing area
    /// samples u = u0 + i (X flip: (u0 | 1) - i), v = v0 + j (Y flip: v0 - j), wrapping at
    /// 256, then the window (§5, §7); never dithered (§5); blending and mask per §6.
    #[test]
    fn rectangles_match_model(
        pos in (corner_coordinate(), corner_coordinate()),
        (size, w, h) in (0u32..4, prop_oneof![3 => 0u32..40, 1 => 0u32..0x800], prop_oneof![3 => 0u32..40, 1 => 0u32..0x400]),
        (textured, raw, semi, mode) in (prop_oneof![1 => Just(false), 3 => Just(true)], any::<bool>(), any::<bool>(), 0u32..4),
        (rgb, uv, flips) in (color(), any::<[u8; 2]>(), any::<(bool, bool)>()),
        tex in texture(),
        env in env(),
    ) {
        let raw = raw && textured;
        let (mut g, background) = gpu_with_background(env.seed);
        let (xflip, yflip) = flips;
        g.gp0(
            0xE100_0000
                | tex.page_bits()
                | mode << 5
                | (env.dither as u32) << 9
                | (xflip as u32) << 12
                | (yflip as u32) << 13,
        );
        g.gp0(tex.e2());
        g.gp0_words(&env.words());
        let cmd = 0x60 | size << 3 | (textured as u32) << 2 | (semi as u32) << 1 | raw as u32;
        let mut words = vec![cmd << 24 | rgb_word(rgb), xy(pos.0, pos.1)];
        if textured {
            words.push(uv[0] as u32 | (uv[1] as u32) << 8 | tex.clut << 16);
        }
        if size == 0 {
            words.push(h << 16 | w);
        }
        g.gp0_words(&words);

        let mut expected = background.clone();
        let (width, height) = match size {
            0 => ((w & 0x3FF) as i64, (h & 0x1FF) as i64),
            1 => (1, 1),
            2 => (8, 8),
            _ => (16, 16),
        };
        // §5: position = vertex + offset, wrapped to signed 11 bits.
        let x0 = sext11(sext11(pos.0 as i64) + env.offset.0 as i64);
        let y0 = sext11(sext11(pos.1 as i64) + env.offset.1 as i64);
        let c = rgb8(rgb);
        let (u0, v0) = (uv[0] as i64, uv[1] as i64);
        for j in 0..height {
            for i in 0..width {
                let (x, y) = (x0 + i, y0 + j);
                if !env.inside(x, y) {
                    continue;
                }
                if !textured {
                    pixel::plot(&mut expected, (x, y), pixel::flat(c), false, semi.then_some(mode), env.mask);
                    continue;
                }
                let u = if xflip { (u0 | 1) - i } else { u0 + i } & 0xFF;
                let v = if yflip { v0 - j } else { v0 + j } & 0xFF;
                let t = tex.texel(&background, u as u32, v as u32);
                if t == 0 {
                    continue;
                }
                let color = if raw { t } else { pixel::modulate(t, c, x, y, false) };
                let bit15 = t & 0x8000 != 0;
                let blend = (semi && bit15).then_some(mode);
                pixel::plot(&mut expected, (x, y), color, bit15, blend, env.mask);
            }
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &background));
    }
}

/// One textured polygon (GP0 24h-3Fh) for [`check_textured_polygon`].
struct TexturedPolygon {
    pts: Vec<(i32, i32, [u8; 2])>,
    quad: bool,
    gouraud: bool,
    shades: Vec<[u8; 3]>,
    rgb: [u8; 3],
    raw: bool,
    semi: bool,
    mode: u32,
    e1_mode: u32,
    tex: Texture,
}

/// Draw `case` over the random VRAM of `env` and compare the whole VRAM with the model:
/// texel from §7 (window, page, CLUT; 0000h not drawn), modulated per §6 and dithered when
/// E1h bit 9 is set unless raw (§6 "When dithering applies"), blended with the texpage
/// attribute's mode only where the texel has bit 15, which is also written (§6). UV and
/// Gouraud colours from the §3.6 model.
fn check_textured_polygon(case: &TexturedPolygon, env: &Env) -> Result<(), TestCaseError> {
    let TexturedPolygon {
        pts,
        quad,
        gouraud,
        shades,
        rgb,
        raw,
        semi,
        mode,
        e1_mode,
        tex,
    } = case;
    let (quad, gouraud, raw, semi, rgb) = (*quad, *gouraud, *raw, *semi, *rgb);
    let (mut g, background) = gpu_with_background(env.seed);
    // E1h with another blend mode and page: the polygon's texpage replaces bits 0-8 (§2).
    g.gp0(0xE100_0000 | e1_mode << 5 | (env.dither as u32) << 9 | 0x1F);
    g.gp0(tex.e2());
    g.gp0_words(&env.words());
    // Gouraud-textured polygons (34h-3Fh) carry one colour per vertex (§2).
    let cmd = 0x24 | raw as u32 | (semi as u32) << 1 | (quad as u32) << 3 | (gouraud as u32) << 4;
    let texpage = tex.page_bits() | mode << 5;
    let n = if quad { 4 } else { 3 };
    let vertex_rgb = |i: usize| if gouraud { shades[i] } else { rgb };
    let mut words = vec![cmd << 24 | rgb_word(vertex_rgb(0))];
    for (i, p) in pts[..n].iter().enumerate() {
        let attr = match i {
            0 => tex.clut << 16,
            1 => texpage << 16,
            _ => 0,
        };
        if i > 0 && gouraud {
            words.push(rgb_word(shades[i]));
        }
        words.push(xy(p.0, p.1));
        words.push(p.2[0] as u32 | (p.2[1] as u32) << 8 | attr);
    }
    g.gp0_words(&words);

    let mut expected = background.clone();
    for tri in halves(quad) {
        let v = tri.map(|i| {
            let p = &pts[i];
            let c = rgb8(vertex_rgb(i));
            env.vertex(
                p.0,
                p.1,
                [
                    c[0] as i64,
                    c[1] as i64,
                    c[2] as i64,
                    p.2[0] as i64,
                    p.2[1] as i64,
                ],
            )
        });
        for p in model::triangle(v, env.clip()) {
            let t = tex.texel(&background, p.attr[3], p.attr[4]);
            if t == 0 {
                continue;
            }
            // Flat polygons use their one colour; Gouraud ones the §3.6 colour at the pixel.
            let c = if gouraud {
                [p.attr[0], p.attr[1], p.attr[2]]
            } else {
                rgb8(rgb)
            };
            let color = if raw {
                t
            } else {
                pixel::modulate(t, c, p.x, p.y, env.dither)
            };
            let bit15 = t & 0x8000 != 0;
            let blend = (semi && bit15).then_some(*mode);
            pixel::plot(&mut expected, (p.x, p.y), color, bit15, blend, env.mask);
        }
    }
    let vram = g.vram();
    prop_assert!(
        *vram == expected,
        "{}",
        difference(vram, &expected, &background)
    );
    Ok(())
}

/// A raw 15-bit triangle whose UVs stay below 128 samples the same texels under the identity
/// window and under a window that masks texel X and Y bit 7 (§7), but only the first reads
/// its page straight from VRAM: the two must leave the same VRAM, also where the triangle
/// draws over its own page, which the console reads and writes pixel by pixel.
fn raw15_identity_window_case(
    pts: &[(i32, i32, [u8; 2])],
    (page_x, page_y): (u32, u32),
    (semi, mode): (bool, u32),
    mask: Mask,
    seed: u64,
) -> Result<(), TestCaseError> {
    let draw = |window: u32| {
        let (mut g, _) = gpu_with_background(seed);
        g.gp0_words(&[
            0xE300_0000,
            0xE400_0000 | 1023 | 511 << 10,
            0xE500_0000,
            mask.e6(),
        ]);
        g.gp0(0xE200_0000 | window);
        let texpage = page_x | page_y << 4 | 2 << 7 | mode << 5;
        let cmd = 0x25 | (semi as u32) << 1;
        let mut words = vec![cmd << 24];
        for (i, p) in pts.iter().enumerate() {
            let attr = if i == 1 { texpage << 16 } else { 0 };
            words.push(xy(p.0, p.1));
            words.push((p.2[0] & 0x7F) as u32 | ((p.2[1] & 0x7F) as u32) << 8 | attr);
        }
        g.gp0_words(&words);
        g.vram().clone()
    };
    same_under_bit7_window(draw)
}

/// A modulated 4/8/15-bit triangle (GP0 24h or 34h) whose UVs stay below 128 samples the same
/// texels under the identity window and under a window that masks texel X and Y bit 7 (§7):
/// the first has its eight texel addresses of a group computed together when its page lies
/// inside VRAM, and must leave the same VRAM as the second, which goes through the window
/// (and wraps past x 1023) texel by texel. The CLUT sits on lines 0-255, clear of the drawing.
fn page_addressed_groups_case(
    pts: &[(i32, i32, [u8; 2])],
    (depth, page_x): (u32, u32),
    (gouraud, dither): (bool, bool),
    shades: &[[u8; 3]],
    (clut_x, clut_y): (u32, u32),
    seed: u64,
) -> Result<(), TestCaseError> {
    let draw = |window: u32| {
        let (mut g, _) = gpu_with_background(seed);
        g.gp0_words(&[
            0xE100_0000 | (dither as u32) << 9,
            0xE300_0000,
            0xE400_0000 | 1023 | 511 << 10,
            0xE500_0000,
        ]);
        g.gp0(0xE200_0000 | window);
        let texpage = page_x | depth << 7;
        let cmd = 0x24 | (gouraud as u32) << 4;
        let mut words = vec![cmd << 24 | rgb_word(shades[0])];
        for (i, p) in pts.iter().enumerate() {
            let attr = match i {
                0 => clut_x | clut_y << 6,
                1 => texpage,
                _ => 0,
            };
            if i > 0 && gouraud {
                words.push(rgb_word(shades[i]));
            }
            words.push(xy(p.0, p.1));
            words.push((p.2[0] & 0x7F) as u32 | ((p.2[1] & 0x7F) as u32) << 8 | attr << 16);
        }
        g.gp0_words(&words);
        g.vram().clone()
    };
    same_under_bit7_window(draw)
}

/// `draw(E2h window bits)` leaves the same VRAM under the identity window and under the
/// window that masks texel X and Y bit 7 (E2h mask X and Y = 10h, offsets 0; §7): for UVs
/// below 128 the two sample the same texels.
fn same_under_bit7_window(draw: impl Fn(u32) -> Vram) -> Result<(), TestCaseError> {
    let (direct, windowed) = (draw(0), draw(0x10 | 0x10 << 5));
    prop_assert!(
        direct == windowed,
        "{}",
        difference(&direct, &windowed, &windowed)
    );
    Ok(())
}

/// Every background value under every blend mode (§6 "Semi-transparency"), so a carry or
/// borrow between packed channels cannot hide: rows 0-63 hold the 65,536 halfwords (bit 15
/// included) and two 512x64 semi-transparent flat rectangles cover them with a foreground
/// whose 5-bit channels take the edge values 0, 1, 16, 30, 31 in every combination; the
/// mask bits alternate between the four E6h settings. The whole VRAM is compared.
#[test]
fn blend_modes_over_every_background() {
    let levels = [0u32, 1, 16, 30, 31];
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE400_0000 | 1023 | 511 << 10, 0xE500_0000]);
    let mut case = 0u32;
    for mode in 0..4u32 {
        for r in levels {
            for gr in levels {
                for b in levels {
                    let mask = Mask {
                        set: case & 1 != 0,
                        check: case & 2 != 0,
                    };
                    case += 1;
                    for (i, p) in g.vram_mut().as_mut_slice()[..65536].iter_mut().enumerate() {
                        *p = i as u16;
                    }
                    let background = g.vram().clone();
                    let rgb = [r << 3, gr << 3, b << 3];
                    let color = rgb[0] | rgb[1] << 8 | rgb[2] << 16;
                    g.gp0(0xE100_0000 | mode << 5);
                    g.gp0(mask.e6());
                    for x in [0, 512] {
                        g.gp0_words(&[0x6200_0000 | color, xy(x, 0), 64 << 16 | 512]);
                    }
                    let mut expected = background.clone();
                    let f = pixel::flat(rgb);
                    for y in 0..64 {
                        for x in 0..1024 {
                            pixel::plot(&mut expected, (x, y), f, false, Some(mode), mask);
                        }
                    }
                    let vram = g.vram();
                    assert!(
                        *vram == expected,
                        "mode {mode}, F ({r}, {gr}, {b}), {mask:?}: {}",
                        difference(vram, &expected, &background)
                    );
                }
            }
        }
    }
}

/// The 4-bit CLUT path shaded under one colour, for every 8-bit colour value and every 5-bit
/// texel value on each channel (§6 "Modulation", §7). Two CLUTs of 16 entries hold red
/// 0-31, green 31-0 and blue 0-31 (even in the first, odd in the second), some with bit 15;
/// row c is drawn with colour (c, 255 - c, 37c mod 256) as a modulated 4-bit sprite per CLUT
/// (never dithered, §5) and as a flat-modulated 4-bit quad per CLUT (dithered on odd rows
/// with E1h bit 9, §6), whose UV comes from the §3.6 model.
#[test]
fn clut4_modulation_every_texel_and_colour() {
    let (mut g, _) = gpu_with_background(0x4B1D);
    // 4-bit page 8 (x 512), row 0: u = 0..15 hold indices 0..15.
    for (k, word) in [0x3210u16, 0x7654, 0xBA98, 0xFEDC].into_iter().enumerate() {
        g.vram_mut().set_pixel(512 + k, 0, word);
    }
    let cluts = [(512usize, 300usize), (528, 300)];
    for (n, &(cx, cy)) in cluts.iter().enumerate() {
        for i in 0..16u16 {
            let r = i + 16 * n as u16;
            let t = r | (31 - r) << 5 | (2 * i + n as u16) << 10 | ((i % 3 == 0) as u16) << 15;
            g.vram_mut().set_pixel(cx + i as usize, cy, t);
        }
    }
    let background = g.vram().clone();
    let tex = |n: usize| Texture {
        page_x: 8,
        page_y: 0,
        depth: 0,
        clut: (cluts[n].0 / 16) as u32 | (cluts[n].1 as u32) << 6,
        window: [0; 4],
    };
    g.gp0_words(&[
        0xE300_0000,
        0xE400_0000 | 511 | 511 << 10,
        0xE500_0000,
        0xE200_0000,
    ]);
    let mut expected = background.clone();
    for c in 0..256u32 {
        let rgb = [c, 255 - c, (37 * c) & 0xFF];
        let color = rgb[0] | rgb[1] << 8 | rgb[2] << 16;
        let dither = c & 1 == 1;
        let y = c as i32;
        for n in 0..2 {
            let t = tex(n);
            g.gp0(0xE100_0000 | t.page_bits() | (dither as u32) << 9);
            // Sprite 64h, 16x1 at x = 16n.
            let x0 = 16 * n as i32;
            g.gp0_words(&[0x6400_0000 | color, xy(x0, y), t.clut << 16, 1 << 16 | 16]);
            for i in 0..16 {
                let texel = t.texel(&background, i as u32, 0);
                let f = pixel::modulate(texel, rgb, (x0 + i) as i64, y as i64, false);
                let m = Mask {
                    set: false,
                    check: false,
                };
                pixel::plot(
                    &mut expected,
                    ((x0 + i) as i64, y as i64),
                    f,
                    texel & 0x8000 != 0,
                    None,
                    m,
                );
            }
            // Flat-modulated quad 2Ch over x 32 + 16n .. +16, rows y..y+1 (the bottom row
            // is not drawn, §3.5), u 0..16, v 0.
            let x0 = 32 + 16 * n as i32;
            let corners = [
                (x0, y, 0),
                (x0 + 16, y, 16),
                (x0, y + 1, 0),
                (x0 + 16, y + 1, 16),
            ];
            let mut words = vec![0x2C00_0000 | color];
            for (k, &(x, vy, u)) in corners.iter().enumerate() {
                let attr = match k {
                    0 => t.clut << 16,
                    1 => t.page_bits() << 16,
                    _ => 0,
                };
                words.extend([xy(x, vy), u as u32 | attr]);
            }
            g.gp0_words(&words);
            let env = |(x, vy, u): (i32, i32, i64)| model::V {
                x: x as i64,
                y: vy as i64,
                a: [0, 0, 0, u, 0],
            };
            for tri in halves(true) {
                let v = tri.map(|k| env(corners[k]));
                for p in model::triangle(v, (0, 0, 511, 511)) {
                    let texel = t.texel(&background, p.attr[3], p.attr[4]);
                    if texel == 0 {
                        continue;
                    }
                    let f = pixel::modulate(texel, rgb, p.x, p.y, dither);
                    let m = Mask {
                        set: false,
                        check: false,
                    };
                    pixel::plot(&mut expected, (p.x, p.y), f, texel & 0x8000 != 0, None, m);
                }
            }
        }
    }
    let vram = g.vram();
    assert!(
        *vram == expected,
        "{}",
        difference(vram, &expected, &background)
    );
}

/// One step of a dithered 4-bit sequence: a flat-modulated polygon (vertices, quad, semi,
/// blend mode, colour 0 or 1, texture 0 or 1), a CPU-to-VRAM write of 16 halfwords over a
/// texture's CLUT, or GP0(01h).
#[derive(Clone, Debug)]
enum Step {
    Polygon {
        pts: Vec<(i32, i32, [u8; 2])>,
        quad: bool,
        semi: bool,
        mode: u32,
        color: usize,
        texture: usize,
    },
    ClutWrite {
        texture: usize,
        halfwords: [u16; 16],
    },
    Invalidate,
}

fn step() -> impl Strategy<Value = Step> {
    // Small polygons (the common case of a mesh) and some large ones.
    let point = prop_oneof![
        3 => (0i32..24, 0i32..24, any::<[u8; 2]>()),
        1 => (coordinate(), coordinate(), any::<[u8; 2]>()),
    ];
    let polygon = (
        (0i32..300, 0i32..300),
        prop::collection::vec(point, 4),
        any::<(bool, bool)>(),
        0u32..4,
        prop_oneof![3 => Just(0usize), 1 => Just(1usize)],
        0usize..2,
    )
        .prop_map(
            |(at, pts, (quad, semi), mode, color, texture)| Step::Polygon {
                // Small polygons are placed at `at`; large ones are where they are.
                pts: pts
                    .into_iter()
                    .map(|(x, y, uv)| {
                        if x < 24 && y < 24 && x >= 0 && y >= 0 {
                            (at.0 + x, at.1 + y, uv)
                        } else {
                            (x, y, uv)
                        }
                    })
                    .collect(),
                quad,
                semi,
                mode,
                color,
                texture,
            },
        );
    prop_oneof![
        8 => polygon,
        1 => (0usize..2, any::<[u16; 16]>()).prop_map(|(texture, halfwords)| Step::ClutWrite { texture, halfwords }),
        1 => Just(Step::Invalidate),
    ]
}

/// The 4-bit texel index at (u, v): texture window, then the halfword and nibble (§7).
fn index4(tex: &Texture, vram: &Vram, u: u32, v: u32) -> usize {
    let [mx, my, ox, oy] = tex.window;
    let u = ((u & 0xFF) & !(mx * 8)) | ((ox & mx) * 8);
    let v = ((v & 0xFF) & !(my * 8)) | ((oy & my) * 8);
    let word = vram.pixel(
        (64 * tex.page_x as usize + (u as usize >> 2)) & 1023,
        256 * tex.page_y as usize + v as usize,
    );
    ((word >> ((u & 3) * 4)) & 0xF) as usize
}

/// A 4-bit texture (page X 8-15, any CLUT in x 512-1008) with a window.
fn texture4() -> impl Strategy<Value = Texture> {
    texture().prop_map(|t| Texture {
        depth: 0,
        clut: (32 + (t.clut & 0x3F) % 32) | (t.clut & !0x3F),
        ..t
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Sequences of flat-modulated, dithered 4-bit polygons (GP0 24h-27h, 2Ch-2Fh) in two
    /// colours over two CLUTs, with CPU-to-VRAM writes over a CLUT and GP0(01h) between
    /// them: each polygon shades the CLUT entries the CLUT cache holds (§7 "CLUT cache": loaded
    /// when a primitive's CLUT position differs from the cached one or after GP0(01h), not
    /// refreshed by VRAM writes), modulated and dithered per pixel (§6), whichever colour and
    /// CLUT the polygons before it used. The model keeps its own copy of the cached entries.
    #[test]
    fn dithered_clut4_sequences_match_model(
        steps in prop::collection::vec(step(), 1..10),
        colors in (color(), color()),
        textures in (texture4(), texture4()),
        env in env(),
    ) {
        let (mut g, background) = gpu_with_background(env.seed);
        // Both textures share one E2h window; the first texture's window applies.
        let textures = [textures.0, Texture { window: textures.0.window, ..textures.1 }];
        let colors = [colors.0, colors.1];
        g.gp0(0xE100_0000 | 1 << 9);
        g.gp0(textures[0].e2());
        g.gp0_words(&env.words());
        let mut expected = background.clone();
        // The model's CLUT cache: the CLUT attribute and the 16 entries it loaded.
        let mut cache: Option<(u32, [u16; 16])> = None;
        for step in &steps {
            match step {
                Step::Polygon { pts, quad, semi, mode, color, texture } => {
                    let (tex, rgb) = (&textures[*texture], colors[*color]);
                    let cmd = 0x24 | (*semi as u32) << 1 | (*quad as u32) << 3;
                    let texpage = tex.page_bits() | mode << 5;
                    let n = if *quad { 4 } else { 3 };
                    let mut words = vec![cmd << 24 | rgb_word(rgb)];
                    for (i, p) in pts[..n].iter().enumerate() {
                        let attr = match i {
                            0 => tex.clut << 16,
                            1 => texpage << 16,
                            _ => 0,
                        };
                        words.push(xy(p.0, p.1));
                        words.push(p.2[0] as u32 | (p.2[1] as u32) << 8 | attr);
                    }
                    g.gp0_words(&words);
                    let entries = match cache {
                        Some((clut, entries)) if clut == tex.clut => entries,
                        _ => {
                            let (cx, cy) = ((tex.clut & 0x3F) as usize * 16, (tex.clut >> 6) as usize);
                            let entries = core::array::from_fn(|i| expected.pixel(cx + i, cy));
                            cache = Some((tex.clut, entries));
                            entries
                        }
                    };
                    let before = expected.clone();
                    for tri in halves(*quad) {
                        let v = tri.map(|i| {
                            let p = &pts[i];
                            env.vertex(p.0, p.1, [0, 0, 0, p.2[0] as i64, p.2[1] as i64])
                        });
                        for p in model::triangle(v, env.clip()) {
                            let t = entries[index4(tex, &before, p.attr[3], p.attr[4])];
                            if t == 0 {
                                continue;
                            }
                            let color = pixel::modulate(t, rgb8(rgb), p.x, p.y, true);
                            let bit15 = t & 0x8000 != 0;
                            let blend = (*semi && bit15).then_some(*mode);
                            pixel::plot(&mut expected, (p.x, p.y), color, bit15, blend, env.mask);
                        }
                    }
                }
                Step::ClutWrite { texture, halfwords } => {
                    let clut = textures[*texture].clut;
                    let (cx, cy) = ((clut & 0x3F) * 16, clut >> 6);
                    // Written without the mask rules (E6h cleared for the transfer, §8).
                    g.gp0(0xE600_0000);
                    g.gp0_words(&[0xA000_0000, cy << 16 | cx, 1 << 16 | 16]);
                    for pair in halfwords.chunks(2) {
                        g.gp0(pair[0] as u32 | (pair[1] as u32) << 16);
                    }
                    g.gp0(env.mask.e6());
                    for (i, &h) in halfwords.iter().enumerate() {
                        expected.set_pixel(cx as usize + i, cy as usize, h);
                    }
                }
                Step::Invalidate => {
                    g.gp0(0x0100_0000);
                    cache = None;
                }
            }
        }
        let vram = g.vram();
        prop_assert!(*vram == expected, "{}", difference(vram, &expected, &background));
    }
}
