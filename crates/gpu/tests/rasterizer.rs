//! Rasterization rules on small hand-worked cases (docs/hardware/gpu.md §3-§7). Expected pixels and colours
//! are worked out from the hardware reference's formulas in the comments, not taken from the code.

use gpu::Gpu;
use proptest::prelude::*;

fn gpu() -> Gpu {
    let mut g = Gpu::new();
    g.gp0(0xE300_0000); // drawing area 0,0 ..
    g.gp0(0xE407_FFFF); // .. 1023,511
    g.gp0(0xE500_0000); // offset 0,0
    g
}

fn xy(x: i32, y: i32) -> u32 {
    ((y as u32 & 0x7FF) << 16) | (x as u32 & 0x7FF)
}

fn px(g: &Gpu, x: usize, y: usize) -> u16 {
    g.vram().pixel(x, y)
}

fn covered(g: &Gpu, w: usize, h: usize) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if px(g, x, y) != 0 {
                v.push((x, y));
            }
        }
    }
    v
}

/// Right triangle (0,0) (4,0) (0,4): row y covers x in [0, 4-y) (top-left rule: the
/// hypotenuse and the bottom row are excluded), 10 pixels.
#[test]
fn small_triangle_coverage() {
    let mut g = gpu();
    g.gp0_words(&[0x2000_00FF, xy(0, 0), xy(4, 0), xy(0, 4)]);
    let mut expected = Vec::new();
    for y in 0..4 {
        for x in 0..4 - y {
            expected.push((x, y));
        }
    }
    assert_eq!(covered(&g, 8, 8), expected);
    assert_eq!(px(&g, 0, 0), 0x001F); // FFh >> 3 = 31 red
}

/// A quad is two triangles sharing the v1-v2 diagonal; with additive blending a pixel drawn
/// twice would read double. The 8x8 square is covered exactly once, nothing outside it.
#[test]
fn split_quad_covers_each_pixel_once() {
    let mut g = gpu();
    g.gp0(0xE100_0020); // blend mode 1 (B + F)
    // Semi-transparent flat quad, colour (40, 40, 40) -> 5-bit 5.
    g.gp0_words(&[0x2A28_2828, xy(0, 0), xy(8, 0), xy(0, 8), xy(8, 8)]);
    let five = 5 | 5 << 5 | 5 << 10;
    for y in 0..10 {
        for x in 0..10 {
            let want = if x < 8 && y < 8 { five } else { 0 };
            assert_eq!(px(&g, x, y), want, "({x},{y})");
        }
    }
}

/// Gouraud ramp: A=(0,0) r=0, B=(64,0) r=128, C=(0,64) r=0. den = 64*64 = 4096;
/// d/dx = (128*64) * 4096 / 4096 = 8192 -> << 12 = 2.0 per pixel in 8.24; d/dy = 0.
/// Core vertex A, start 0.5, so r8(x) = floor(0.5 + 2x) = 2x and r5 = 2x >> 3.
#[test]
fn gouraud_ramp_undithered() {
    let mut g = gpu();
    g.gp0_words(&[
        0x3000_0000,
        xy(0, 0),
        0x0000_0080,
        xy(64, 0),
        0x0000_0000,
        xy(0, 64),
    ]);
    for (x, y) in [(0, 0), (5, 3), (20, 10), (40, 0), (63, 0), (31, 32)] {
        assert_eq!(px(&g, x, y) & 0x1F, ((2 * x) >> 3) as u16, "({x},{y})");
    }
}

/// The same ramp dithered: r5 = clamp(2x + D[y&3][x&3], 0, 255) >> 3 with the §6 matrix.
#[test]
fn gouraud_ramp_dithered() {
    let mut g = gpu();
    g.gp0(0xE100_0200); // dither on
    g.gp0_words(&[
        0x3000_0000,
        xy(0, 0),
        0x0000_0080,
        xy(64, 0),
        0x0000_0000,
        xy(0, 64),
    ]);
    // (16,0): 32 - 4 = 28 -> 3 (undithered it would be 4). (4,1): 8 + 2 = 10 -> 1.
    // (15,3): 30 - 2 = 28 -> 3. (0,0): 0 - 4 -> clamped 0.
    for (x, y, r) in [(16, 0, 3), (4, 1, 1), (15, 3, 3), (0, 0, 0), (23, 2, 5)] {
        assert_eq!(px(&g, x, y) & 0x1F, r, "({x},{y})");
    }
}

/// Flat untextured polygons are never dithered, even with E1.9 set.
#[test]
fn flat_polygon_not_dithered() {
    let mut g = gpu();
    g.gp0(0xE100_0200);
    g.gp0_words(&[0x2000_0084, xy(0, 0), xy(16, 0), xy(0, 16)]);
    // 84h = 132 >> 3 = 16 everywhere.
    for x in 0..8 {
        assert_eq!(px(&g, x, 0), 16);
    }
}

/// Size limits: an extent of 1024 horizontally (or 512 vertically) drops the polygon;
/// 1023 (511) draws.
#[test]
fn size_drop() {
    let mut g = gpu();
    g.gp0_words(&[0x2000_00FF, xy(0, 0), xy(1024, 0), xy(0, 10)]);
    assert!(covered(&g, 16, 16).is_empty());
    g.gp0_words(&[0x2000_00FF, xy(0, 0), xy(1023, 0), xy(0, 10)]);
    assert_ne!(px(&g, 0, 0), 0);
    let mut g = gpu();
    g.gp0_words(&[0x2000_00FF, xy(0, 0), xy(10, 0), xy(0, 512)]);
    assert!(covered(&g, 16, 16).is_empty());
}

/// The drawing area clips: area (2,2)-(5,5) keeps a 16x16 rectangle to 4x4 pixels.
#[test]
fn drawing_area_clip() {
    let mut g = gpu();
    g.gp0(0xE300_0000 | 2 << 10 | 2);
    g.gp0(0xE400_0000 | 5 << 10 | 5);
    g.gp0_words(&[0x7800_00FF, xy(0, 0)]);
    let c = covered(&g, 16, 16);
    assert_eq!(c.len(), 16);
    assert!(
        c.iter()
            .all(|&(x, y)| (2..=5).contains(&x) && (2..=5).contains(&y))
    );
}

/// Drawing offset is added to every vertex.
#[test]
fn drawing_offset() {
    let mut g = gpu();
    g.gp0(0xE500_0000 | 20 << 11 | 10);
    g.gp0_words(&[0x6800_00FF, xy(1, 2)]); // 1x1 rectangle
    assert_eq!(px(&g, 11, 22), 0x1F);
    assert_eq!(covered(&g, 8, 8).len(), 0);
}

/// Semi-transparency modes on a rectangle over a filled background (docs/hardware/gpu.md §6):
/// B = (31,10,0), F = (16,4,31): mode 0 (23,7,15), 1 (31,14,31), 2 (15,6,0), 3 (31,11,7).
#[test]
fn blend_modes() {
    let expected = [(23, 7, 15), (31, 14, 31), (15, 6, 0), (31, 11, 7)];
    for (mode, (r, gr, b)) in expected.into_iter().enumerate() {
        let mut g = gpu();
        g.gp0_words(&[0x0200_50F8, 0, 0x0010_0010]); // fill 16x16 with (F8h,50h,00h)
        g.gp0(0xE100_0000 | (mode as u32) << 5);
        g.gp0_words(&[0x6AF8_2080, xy(0, 0)]); // 1x1 semi rect, colour (80h,20h,F8h)
        assert_eq!(px(&g, 0, 0), r | gr << 5 | b << 10, "mode {mode}");
    }
}

/// Mask bit: E6.0 forces bit 15 on drawn pixels; E6.1 protects pixels with bit 15 set.
#[test]
fn mask_set_and_check() {
    let mut g = gpu();
    g.gp0(0xE600_0001);
    g.gp0_words(&[0x6800_00FF, xy(0, 0)]);
    assert_eq!(px(&g, 0, 0), 0x801F);
    g.gp0(0xE600_0002);
    g.gp0_words(&[0x6800_FF00, xy(0, 0)]);
    assert_eq!(px(&g, 0, 0), 0x801F, "protected pixel kept");
    g.gp0_words(&[0x6800_FF00, xy(1, 0)]);
    assert_eq!(px(&g, 1, 0), 0x03E0, "unprotected pixel drawn, no bit 15");
}

/// Upload halfwords with GP0(A0h).
fn upload(g: &mut Gpu, x: u32, y: u32, w: u32, h: u32, pixels: &[u16]) {
    g.gp0_words(&[0xA000_0000, y << 16 | x, h << 16 | w]);
    for pair in pixels.chunks(2) {
        let lo = pair[0] as u32;
        let hi = pair.get(1).copied().unwrap_or(0) as u32;
        g.gp0(hi << 16 | lo);
    }
}

/// 4-bit texture through a CLUT: word 3210h at page (64,0) holds indices 0,1,2,3; CLUT at
/// (0,256) maps them to transparent, red, green, blue+bit15. A raw-textured 4x1 rectangle
/// at (100,100) therefore leaves x=100 untouched and draws red, green, blue|8000h (bit 15
/// from the texel, no blending because the rectangle is opaque).
#[test]
fn texture_4bit_clut() {
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x3210]);
    upload(&mut g, 0, 256, 4, 1, &[0x0000, 0x001F, 0x03E0, 0xFC00]);
    g.gp0(0xE100_0001); // page x = 64, 4-bit
    g.gp0_words(&[0x6500_0000, xy(100, 100), 0x4000_0000, 0x0001_0004]);
    assert_eq!(px(&g, 100, 100), 0);
    assert_eq!(px(&g, 101, 100), 0x001F);
    assert_eq!(px(&g, 102, 100), 0x03E0);
    assert_eq!(px(&g, 103, 100), 0xFC00);
}

/// 8-bit texture: word 0201h holds indices 1, 2; 15-bit: the texel itself.
#[test]
fn texture_8bit_and_15bit() {
    let mut g = gpu();
    upload(&mut g, 128, 0, 1, 1, &[0x0201]);
    upload(&mut g, 16, 300, 3, 1, &[0x0000, 0x1111, 0x2222]);
    g.gp0(0xE100_0082); // page x = 128, 8-bit
    // clut attr: x = 16/16 = 1, y = 300 -> 1 | 300 << 6
    let clut = (1 | 300 << 6) << 16;
    g.gp0_words(&[0x6500_0000, xy(0, 50), clut, 0x0001_0002]);
    assert_eq!(px(&g, 0, 50), 0x1111);
    assert_eq!(px(&g, 1, 50), 0x2222);
    upload(&mut g, 192, 0, 2, 1, &[0x1234, 0x0000]);
    g.gp0(0xE100_0103); // page x = 192, 15-bit
    g.gp0_words(&[0x6500_0000, xy(0, 60), 0, 0x0001_0002]);
    assert_eq!(px(&g, 0, 60), 0x1234);
    assert_eq!(px(&g, 1, 60), 0, "0000h texel is transparent");
}

/// Modulation: texel (10,20,31) times colour 80h is the identity; times 40h halves:
/// (t * 64) >> 4 >> 3 = t >> 1.
#[test]
fn texture_modulation() {
    let mut g = gpu();
    let t = 10 | 20 << 5 | 31 << 10;
    upload(&mut g, 192, 0, 1, 1, &[t]);
    g.gp0(0xE100_0103);
    // 1x1 modulated textured rectangles (6Ch).
    g.gp0_words(&[0x6C80_8080, xy(0, 0), 0]);
    g.gp0_words(&[0x6C40_4040, xy(0, 1), 0]);
    assert_eq!(px(&g, 0, 0), t & 0x7FFF);
    assert_eq!(px(&g, 0, 1), 5 | 10 << 5 | 15 << 10);
}

/// An 8000h texel in an opaque primitive draws black with bit 15 set (docs/hardware/gpu.md §1).
#[test]
fn texel_8000_is_opaque_black() {
    let mut g = gpu();
    g.gp0_words(&[0x0200_FFFF, 0, 0x0010_0010]);
    upload(&mut g, 192, 0, 1, 1, &[0x8000]);
    g.gp0(0xE100_0103);
    g.gp0_words(&[0x6D00_0000, xy(0, 0), 0]); // 1x1 raw textured rectangle
    assert_eq!(px(&g, 0, 0), 0x8000);
}

/// Texture window: mask X = 1 (8 texels), offset 0 -> u' = u & !8, so u = 9 samples u = 1.
#[test]
fn texture_window() {
    let mut g = gpu();
    let row: Vec<u16> = (0..16).map(|i| 0x100 + i).collect();
    upload(&mut g, 192, 0, 16, 1, &row);
    g.gp0(0xE100_0103);
    g.gp0(0xE200_0001);
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0x0000_0009, 0x0001_0001]);
    assert_eq!(px(&g, 0, 0), 0x101);
}

/// CLUT cache (docs/hardware/gpu.md §7): overwriting the CLUT with a fill does not refresh the latched
/// entries; GP0(01h) does.
#[test]
fn clut_cache_latch() {
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x1111]); // indices 1,1,1,1
    upload(&mut g, 0, 256, 2, 1, &[0, 0x001F]);
    g.gp0(0xE100_0001);
    let rect =
        |g: &mut Gpu, y: i32| g.gp0_words(&[0x6500_0000, xy(0, y), 0x4000_0000, 0x0001_0001]);
    rect(&mut g, 10);
    assert_eq!(px(&g, 0, 10), 0x001F);
    g.gp0_words(&[0x0200_F800, 256 << 16, 0x0001_0010]); // fill CLUT row with green
    rect(&mut g, 11);
    assert_eq!(px(&g, 0, 11), 0x001F, "cached entry still red");
    g.gp0(0x0100_0000);
    rect(&mut g, 12);
    assert_eq!(px(&g, 0, 12), 0x03E0, "reloaded after GP0(01h)");
}

/// Rectangle texture coordinates wrap at 256 and, with E1.12 set, count down.
#[test]
fn rectangle_uv_wrap_and_flip() {
    let mut g = gpu();
    let row: Vec<u16> = (0..256).map(|i| 0x100 + i).collect();
    upload(&mut g, 192, 0, 256, 1, &row);
    g.gp0(0xE100_0103);
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0x0000_00FE, 0x0001_0004]);
    let got: Vec<u16> = (0..4).map(|x| px(&g, x, 0)).collect();
    assert_eq!(got, [0x1FE, 0x1FF, 0x100, 0x101]);
    g.gp0(0xE100_1103);
    g.gp0_words(&[0x6500_0000, xy(0, 1), 0x0000_0001, 0x0001_0003]);
    let got: Vec<u16> = (0..3).map(|x| px(&g, x, 1)).collect();
    assert_eq!(got, [0x101, 0x100, 0x1FF]);
}

/// Lines include both endpoints: (0,0)-(3,0) draws 4 pixels; a polyline joint drawn twice
/// blends twice (docs/hardware/gpu.md §4).
#[test]
fn line_endpoints_and_polyline_joint() {
    let mut g = gpu();
    g.gp0_words(&[0x4000_00FF, xy(0, 0), xy(3, 0)]);
    assert_eq!(covered(&g, 8, 8).len(), 4);
    let mut g = gpu();
    g.gp0(0xE100_0020); // additive
    // Semi-transparent mono polyline (0,2)-(2,2)-(2,4), colour 40h -> 8 per draw.
    g.gp0_words(&[0x4A00_0040, xy(0, 2), xy(2, 2), xy(2, 4), 0x5555_5555]);
    assert_eq!(px(&g, 0, 2), 8);
    assert_eq!(px(&g, 2, 2), 16, "joint blended twice");
    assert_eq!(px(&g, 2, 4), 8);
    // The terminator ended the polyline: the next word is a command again.
    g.gp0_words(&[0x6800_001F, xy(9, 9)]);
    assert_eq!(px(&g, 9, 9), 3);
}

/// Gouraud line colour steps from c0 to c1 over k = max(|dx|,|dy|) steps:
/// (0,0) red 0 -> (8,0) red 248: c = 0.5 + 31*x -> r5 = (31x) >> 3.
#[test]
fn gouraud_line() {
    let mut g = gpu();
    g.gp0_words(&[0x5000_0000, xy(0, 0), 0x0000_00F8, xy(8, 0)]);
    for x in 0..=8usize {
        assert_eq!(px(&g, x, 0) & 0x1F, ((31 * x) >> 3) as u16, "x={x}");
    }
}

/// Run a GP0(02h) fill of `w`x`h` at (`x`,`y`) with 24-bit `color`.
fn fill(g: &mut Gpu, color: u32, x: u32, y: u32, w: u32, h: u32) {
    g.gp0_words(&[0x0200_0000 | color, y << 16 | x, h << 16 | w]);
}

/// CLUT cache (docs/hardware/gpu.md §7): an 8-bit draw caches 256 entries, so a following 4-bit draw with
/// the same CLUT uses them even after the VRAM copy changed; a 4-bit draw caches only 16, so
/// a following 8-bit draw reloads.
#[test]
fn clut_cache_depth_rules() {
    let clut = 0x4000_0000; // CLUT at (0, 256)
    // 8-bit then 4-bit: no reload.
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x0101]); // 8-bit: indices 1, 1; 4-bit: 1, 0, 1, 0
    upload(&mut g, 0, 256, 2, 1, &[0, 0x001F]);
    g.gp0(0xE100_0081); // page x 64, 8-bit
    g.gp0_words(&[0x6500_0000, xy(0, 0), clut, 0x0001_0001]);
    assert_eq!(px(&g, 0, 0), 0x001F);
    fill(&mut g, 0x00_F800, 0, 256, 16, 1); // CLUT row now green
    g.gp0(0xE100_0001); // 4-bit, same CLUT
    g.gp0_words(&[0x6500_0000, xy(0, 1), clut, 0x0001_0001]);
    assert_eq!(px(&g, 0, 1), 0x001F, "8 -> 4 keeps the cached entries");
    // 4-bit then 8-bit: reload.
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x0101]);
    upload(&mut g, 0, 256, 2, 1, &[0, 0x001F]);
    g.gp0(0xE100_0001);
    g.gp0_words(&[0x6500_0000, xy(0, 0), clut, 0x0001_0001]);
    assert_eq!(px(&g, 0, 0), 0x001F);
    fill(&mut g, 0x00_F800, 0, 256, 16, 1);
    g.gp0(0xE100_0081);
    g.gp0_words(&[0x6500_0000, xy(0, 1), clut, 0x0001_0001]);
    assert_eq!(px(&g, 0, 1), 0x03E0, "4 -> 8 reloads");
}

/// CLUT cache (docs/hardware/gpu.md §7): a different CLUT position reloads, and so does returning to the
/// first one; E1 changes alone (a 15-bit page in between) invalidate nothing.
#[test]
fn clut_cache_position_rules() {
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x1111]);
    upload(&mut g, 0, 256, 2, 1, &[0, 0x001F]); // CLUT A at (0, 256): red
    upload(&mut g, 16, 256, 2, 1, &[0, 0x7C00]); // CLUT B at (16, 256): blue
    let (a, b) = (0x4000_0000u32, 0x4001_0000u32);
    g.gp0(0xE100_0001);
    let rect = |g: &mut Gpu, y: i32, clut: u32| {
        g.gp0_words(&[0x6500_0000, xy(0, y), clut, 0x0001_0001]);
    };
    rect(&mut g, 0, a);
    fill(&mut g, 0x00_F800, 0, 256, 16, 1); // A now green in VRAM
    g.gp0(0xE100_0103); // 15-bit page, then back to 4-bit
    g.gp0(0xE100_0001);
    rect(&mut g, 1, a);
    assert_eq!(px(&g, 0, 1), 0x001F, "E1 changes keep the cache");
    rect(&mut g, 2, b);
    assert_eq!(px(&g, 0, 2), 0x7C00, "new position reloads");
    rect(&mut g, 3, a);
    assert_eq!(px(&g, 0, 3), 0x03E0, "back to A reloads from VRAM");
}

/// Texel bit 15 decides blending in a semi-transparent textured primitive (docs/hardware/gpu.md §6):
/// over a background of 10 red, texel 8000h|20 red averages to 15 (bit 15 kept), texel
/// 20 red is written as is.
#[test]
fn textured_blend_follows_texel_bit15() {
    let mut g = gpu();
    fill(&mut g, 80, 0, 0, 16, 1); // 80 >> 3 = 10
    upload(&mut g, 192, 0, 2, 1, &[0x8014, 0x0014]);
    g.gp0(0xE100_0103); // page 192, 15-bit, mode 0
    g.gp0_words(&[0x6700_0000, xy(0, 0), 0, 0x0001_0002]); // raw, semi-transparent
    assert_eq!(px(&g, 0, 0), 0x800F);
    assert_eq!(px(&g, 1, 0), 0x0014);
}

/// The mask check is applied to blended pixels too: a protected destination stays.
#[test]
fn mask_check_with_blending() {
    let mut g = gpu();
    g.gp0(0xE600_0001);
    fill(&mut g, 0xF8, 0, 0, 16, 1);
    g.gp0_words(&[0x6800_00F8, xy(0, 0)]); // opaque, sets bit 15 -> 801Fh
    g.gp0(0xE600_0002);
    g.gp0(0xE100_0040); // mode 2: B - F
    g.gp0_words(&[0x6A00_0080, xy(0, 0), 0x6A00_0080, xy(1, 0)]);
    assert_eq!(px(&g, 0, 0), 0x801F, "protected");
    assert_eq!(px(&g, 1, 0), 31 - 16, "31 - 16 drawn");
}

/// Lines (docs/hardware/gpu.md §4): a shallow line steps Y from y0 + 0.5; when Y goes up the start is
/// lowered by 1024/2^32, so (0,1)-(4,0) reaches row 0 at the middle point:
/// y = 1.5-e, 1.25-e, 1.0-e, 0.75-e, 0.5-e. Going down, (0,0)-(4,1): 0.5, 0.75, 1.0, ...
/// X always starts at x0 + 0.5 - e: the steep (0,0)-(1,4) gives x = 0.5-e, 0.75-e, 1.0-e ->
/// 0, 0, 0, 1, 1.
#[test]
fn line_start_bias() {
    type Case = ((i32, i32), (i32, i32), [(usize, usize); 5]);
    let cases: [Case; 4] = [
        ((0, 1), (4, 0), [(0, 1), (1, 1), (2, 0), (3, 0), (4, 0)]),
        ((0, 0), (4, 1), [(0, 0), (1, 0), (2, 1), (3, 1), (4, 1)]),
        ((0, 0), (1, 4), [(0, 0), (0, 1), (0, 2), (1, 3), (1, 4)]),
        // x0 > x1: the endpoints are swapped, so this is the first case.
        ((4, 0), (0, 1), [(0, 1), (1, 1), (2, 0), (3, 0), (4, 0)]),
    ];
    for (a, b, want) in cases {
        let mut g = gpu();
        g.gp0_words(&[0x4000_00FF, xy(a.0, a.1), xy(b.0, b.1)]);
        let mut want = want.to_vec();
        want.sort_by_key(|&(x, y)| (y, x));
        assert_eq!(covered(&g, 8, 8), want, "{a:?}-{b:?}");
    }
}

/// Flat lines are dithered when E1.9 is set (docs/hardware/gpu.md §6): 130 plus row 0 of the matrix
/// (-4, 0, -3, 1) gives 126, 130, 127, 131 -> 15, 16, 15, 16.
#[test]
fn flat_line_dithered() {
    let mut g = gpu();
    g.gp0(0xE100_0200);
    g.gp0_words(&[0x4000_0082, xy(0, 0), xy(3, 0)]);
    let got: Vec<u16> = (0..4).map(|x| px(&g, x, 0)).collect();
    assert_eq!(got, [15, 16, 15, 16]);
}

/// Line size drop (docs/hardware/gpu.md §4): |dx| = 1024 is dropped, 1023 drawn.
#[test]
fn line_size_drop() {
    let mut g = gpu();
    g.gp0_words(&[0x4000_00FF, xy(-512, 0), xy(512, 0)]);
    assert!(covered(&g, 1024, 1).is_empty());
    g.gp0_words(&[0x4000_00FF, xy(-511, 0), xy(512, 0)]);
    assert_eq!(covered(&g, 1024, 1).len(), 513, "x = 0..=512 inside VRAM");
    let mut g = gpu();
    g.gp0_words(&[0x4000_00FF, xy(0, -256), xy(0, 256)]);
    assert!(covered(&g, 1, 512).is_empty());
}

/// Rectangle V flip (E1.13) and clipping: a rectangle starting left of the drawing area
/// keeps its texel mapping, u = u0 + (x - x0).
#[test]
fn rectangle_v_flip_and_clipped_u() {
    let mut g = gpu();
    // Column x = 192 of page (192, 0): texel(v) = 200h + v for v = 0..4 and 255.
    let column: [u16; 4] = [0x200, 0x201, 0x202, 0x203];
    for (v, t) in column.iter().enumerate() {
        upload(&mut g, 192, v as u32, 1, 1, &[*t]);
    }
    upload(&mut g, 192, 255, 1, 1, &[0x2FF]);
    g.gp0(0xE100_2103); // page 192, 15-bit, Y flip
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0x0000_0100, 0x0003_0001]); // v0 = 1, 1x3
    let got: Vec<u16> = (0..3).map(|y| px(&g, 0, y)).collect();
    assert_eq!(got, [0x201, 0x200, 0x2FF]);

    let mut g = gpu();
    let row: Vec<u16> = (0..8).map(|i| 0x100 + i).collect();
    upload(&mut g, 192, 0, 8, 1, &row);
    g.gp0(0xE100_0103);
    g.gp0(0xE300_0002); // left = 2
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0, 0x0001_0004]);
    let got: Vec<u16> = (0..4).map(|x| px(&g, x, 0)).collect();
    assert_eq!(got, [0, 0, 0x102, 0x103]);
    // X-flipped from u0 = 5: x = 2, 3 sample u = 5 - 2, 5 - 3.
    g.gp0(0xE100_1103);
    g.gp0_words(&[0x6500_0000, xy(0, 1), 0x0000_0005, 0x0001_0004]);
    let got: Vec<u16> = (0..4).map(|x| px(&g, x, 1)).collect();
    assert_eq!(got, [0, 0, 0x103, 0x102]);
}

/// A 4-bit textured triangle: a 4x4 texture whose texel index is u + 1 except u = 3 (index
/// 0, transparent). Raw texturing and the +0.5 UV bias map pixel x to u = x for the
/// triangle (0,0)/u0 (8,0)/u8 (0,8)/u0 with v = y; the CLUT maps index i to i.
#[test]
fn textured_triangle_4bit_with_transparent_texel() {
    let mut g = gpu();
    for v in 0..8 {
        upload(&mut g, 64, v, 2, 1, &[0x0321, 0x7654]); // u 0..7 -> 1,2,3,0,4,5,6,7
    }
    let clut: Vec<u16> = (0..16).collect();
    upload(&mut g, 0, 256, 16, 1, &clut);
    g.gp0_words(&[
        0x2500_0000,
        xy(20, 0),
        0x4000_0000,
        xy(28, 0),
        0x0001_0008, // texpage: x 64, 4-bit; u = 8
        xy(20, 8),
        0x0000_0800, // v = 8
    ]);
    let expected_index = [1u16, 2, 3, 0, 4, 5, 6, 7];
    for y in 0..8usize {
        for (x, &index) in expected_index.iter().enumerate() {
            let want = if x < 8 - y { index } else { 0 };
            assert_eq!(px(&g, 20 + x, y), want, "({x},{y})");
        }
    }
}

#[path = "support/cost.rs"]
mod cost;
#[path = "support/quiet.rs"]
mod quiet;

/// The per-pixel §3 triangle model, shared with `fast_paths.rs` (see the file for how it is
/// derived from the fact sheet).
#[path = "support/model.rs"]
mod model;

/// An 11-bit signed GP0 vertex coordinate as the GPU reads it (docs/hardware/gpu.md §2).
fn sext11(v: i32) -> i64 {
    (((v as i64) & 0x7FF) ^ 0x400) - 0x400
}

fn coordinate() -> impl Strategy<Value = i32> {
    prop_oneof![4 => -40i32..120, 1 => -1100i32..1100]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Gouraud (optionally dithered) and raw 15-bit textured triangles drawn by the
    /// rasterizer equal the §3 model pixel for pixel over the whole VRAM, with a random
    /// drawing area. The texture at page (512, 256) holds texel(u, v) = u | (v & 7Fh) << 8,
    /// so each drawn texel names the UV the rasterizer computed.
    #[test]
    fn triangles_match_model(
        pts in prop::collection::vec((coordinate(), coordinate(), any::<[u8; 5]>()), 3),
        textured in any::<bool>(),
        dither in any::<bool>(),
        clip in (0u16..30, 0u16..30, 40u16..1024, 40u16..300),
    ) {
        // Drawn through GP0: drawing area E3h/E4h, E1h dithering (and the 15-bit page at
        // (512, 256) for the textured case, which its texpage attribute also selects), then
        // a Gouraud triangle (30h) or a raw-textured one (25h).
        let mut g = Gpu::new();
        for v in 0..256usize {
            for u in 0..256usize {
                g.vram_mut().set_pixel(512 + u, 256 + v, (u | (v & 0x7F) << 8) as u16);
            }
        }
        let background = g.vram().clone();
        let area = (clip.0, clip.1, clip.2.min(511), clip.3.min(255));
        let texpage = 8 | 1 << 4 | 2 << 7;
        g.gp0_words(&[
            0xE100_0000 | texpage | (dither as u32) << 9,
            0xE300_0000 | area.0 as u32 | (area.1 as u32) << 10,
            0xE400_0000 | area.2 as u32 | (area.3 as u32) << 10,
            0xE500_0000,
        ]);
        let rgb = |p: &(i32, i32, [u8; 5])| {
            p.2[0] as u32 | (p.2[1] as u32) << 8 | (p.2[2] as u32) << 16
        };
        let pos = |p: &(i32, i32, [u8; 5])| xy(p.0, p.1);
        let uv = |p: &(i32, i32, [u8; 5])| p.2[3] as u32 | (p.2[4] as u32) << 8;
        if textured {
            g.gp0_words(&[
                0x2500_0000,
                pos(&pts[0]),
                uv(&pts[0]),
                pos(&pts[1]),
                uv(&pts[1]) | texpage << 16,
                pos(&pts[2]),
                uv(&pts[2]),
            ]);
        } else {
            g.gp0_words(&[
                0x3000_0000 | rgb(&pts[0]),
                pos(&pts[0]),
                rgb(&pts[1]),
                pos(&pts[1]),
                rgb(&pts[2]),
                pos(&pts[2]),
            ]);
        }
        let vram = g.vram();

        let mut expected = background;
        // GP0 vertex coordinates are 11-bit signed (docs/hardware/gpu.md §2).
        let input = pts.iter().map(|p| model::V {
            x: sext11(p.0),
            y: sext11(p.1),
            a: [p.2[0], p.2[1], p.2[2], p.2[3], p.2[4]].map(|c| c as i64),
        });
        let input: Vec<model::V> = input.collect();
        let input: [model::V; 3] = input.try_into().ok().unwrap();
        let a = area;
        for p in model::triangle(input, (a.0 as i64, a.1 as i64, a.2 as i64, a.3 as i64)) {
            let value = if textured {
                let t = (p.attr[3] | (p.attr[4] & 0x7F) << 8) as u16;
                if t == 0 {
                    continue;
                }
                t
            } else {
                let d = dither; // Gouraud untextured triangles follow E1 bit 9 (§6)
                model::channel(p.attr[0], p.x, p.y, d)
                    | model::channel(p.attr[1], p.x, p.y, d) << 5
                    | model::channel(p.attr[2], p.x, p.y, d) << 10
            };
            expected.set_pixel(p.x as usize, p.y as usize, value);
        }
        prop_assert!(*vram == expected, "VRAM differs from the model");
    }
}

/// Choice (docs/rasterizer.md): the CLUT is latched by every 4/8-bit textured primitive the
/// GPU receives, even one that draws no pixel (here a zero-height triangle), so a later
/// primitive with that CLUT uses the entries read at that moment.
#[test]
fn clut_latched_by_undrawn_primitive() {
    let mut g = gpu();
    upload(&mut g, 64, 0, 1, 1, &[0x1111]);
    upload(&mut g, 0, 256, 2, 1, &[0, 0x001F]);
    g.gp0_words(&[
        0x2500_0000,
        xy(5, 5),
        0x4000_0000,
        xy(9, 5),
        0x0001_0000,
        xy(7, 5),
        0,
    ]);
    assert!(covered(&g, 16, 16).is_empty());
    fill(&mut g, 0x00_F800, 0, 256, 16, 1);
    g.gp0(0xE100_0001);
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0x4000_0000, 0x0001_0001]);
    assert_eq!(px(&g, 0, 0), 0x001F);
}

/// An independent model of docs/hardware/gpu.md §4 lines: every point the line plots inside `clip`, with
/// its 8-bit colour.
fn model_line(
    ends: [(i64, i64, [i64; 3]); 2],
    gouraud: bool,
    clip: (i64, i64, i64, i64),
) -> Vec<(i64, i64, [i64; 3])> {
    let sext11 = |v: i64| ((v & 0x7FF) ^ 0x400) - 0x400;
    let [mut p, mut q] = ends.map(|(x, y, c)| (sext11(x), sext11(y), c));
    if !gouraud {
        q.2 = p.2;
    }
    let mut out = Vec::new();
    if (q.0 - p.0).abs() >= 1024 || (q.1 - p.1).abs() >= 512 {
        return out;
    }
    if p.0 > q.0 {
        std::mem::swap(&mut p, &mut q);
    }
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let k = dx.abs().max(dy.abs());
    let step = |d: i64| -> i128 {
        if k == 0 {
            return 0;
        }
        let n = (d as i128) << 32;
        let n = n + n.signum() * (k as i128 - 1);
        n / k as i128
    };
    let mut x = ((p.0 as i128) << 32) + (1 << 31) - 1024;
    let mut y = ((p.1 as i128) << 32) + (1 << 31) - if dy < 0 { 1024 } else { 0 };
    let mut c = p.2.map(|c| (c << 12) | (1 << 11));
    let cs: [i64; 3] = std::array::from_fn(|i| {
        if k == 0 {
            0
        } else {
            ((q.2[i] - p.2[i]) << 12) / k
        }
    });
    for _ in 0..=k {
        let (px, py) = (((x >> 32) & 2047) as i64, ((y >> 32) & 2047) as i64);
        if px >= clip.0 && px <= clip.2 && py >= clip.1 && py <= clip.3 {
            out.push((px, py, c.map(|c| c >> 12)));
        }
        x += step(dx);
        y += step(dy);
        for i in 0..3 {
            c[i] += cs[i];
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Lines drawn by the rasterizer equal the §4 model over the whole VRAM (random
    /// endpoints, Gouraud or flat, dithered or not, random drawing area).
    #[test]
    fn lines_match_model(
        ends in prop::collection::vec((coordinate(), coordinate(), any::<[u8; 3]>()), 2),
        gouraud in any::<bool>(),
        dither in any::<bool>(),
        clip in (0u16..30, 0u16..30, 40u16..1024, 40u16..512),
    ) {
        // Drawn through GP0: drawing area, E1h dithering, then a flat (40h) or Gouraud
        // (50h) line.
        let mut g = Gpu::new();
        let area = (clip.0, clip.1, clip.2.min(1023), clip.3.min(511));
        g.gp0_words(&[
            0xE100_0000 | (dither as u32) << 9,
            0xE300_0000 | area.0 as u32 | (area.1 as u32) << 10,
            0xE400_0000 | area.2 as u32 | (area.3 as u32) << 10,
            0xE500_0000,
        ]);
        let rgb = |e: &(i32, i32, [u8; 3])| {
            e.2[0] as u32 | (e.2[1] as u32) << 8 | (e.2[2] as u32) << 16
        };
        let pos = |e: &(i32, i32, [u8; 3])| xy(e.0, e.1);
        if gouraud {
            g.gp0_words(&[
                0x5000_0000 | rgb(&ends[0]),
                pos(&ends[0]),
                rgb(&ends[1]),
                pos(&ends[1]),
            ]);
        } else {
            g.gp0_words(&[0x4000_0000 | rgb(&ends[0]), pos(&ends[0]), pos(&ends[1])]);
        }
        let vram = g.vram();
        let mut expected = gpu::Vram::new();
        let e = |i: usize| (sext11(ends[i].0), sext11(ends[i].1), ends[i].2.map(|c| c as i64));
        let clip = (area.0 as i64, area.1 as i64, area.2 as i64, area.3 as i64);
        for (x, y, c) in model_line([e(0), e(1)], gouraud, clip) {
            let c = c.map(|c| model::channel(c as u32, x, y, dither));
            expected.set_pixel(x as usize, y as usize, c[0] | c[1] << 5 | c[2] << 10);
        }
        prop_assert!(*vram == expected, "VRAM differs from the model");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Flat lines (GP0 40h; 41h, 44h and 45h set bits a line ignores; 42h semi-transparent)
    /// with both endpoints inside the drawing area, or on or next to its edges, equal the §4
    /// model, with the mask bit E6h sets (docs/hardware/gpu.md §7) on every point and the
    /// E1h dither (lines dither whenever it is set, §6), and cost 8 CPU cycles plus 1 per step
    /// along the major axis (docs/emulator.md, "Drawing time").
    #[test]
    fn flat_lines_inside_the_area_match_model(
        ends in prop::collection::vec((0i32..330, 0i32..230, any::<[u8; 3]>()), 2),
        snap in prop::collection::vec(prop::option::of((0usize..4, -1i32..2)), 2),
        area in (0u32..30, 0u32..30, 200u32..320, 150u32..220),
        (set_mask, dither, ignored) in (any::<bool>(), any::<bool>(), 0u32..4),
        semi in prop::option::of(0u32..4),
    ) {
        // Some endpoints on or next to an edge of the area (left, right, top, bottom).
        let mut ends = ends;
        for (e, s) in ends.iter_mut().zip(&snap) {
            if let Some((side, d)) = *s {
                let edge = [area.0, area.2, area.1, area.3][side] as i32 + d;
                if side < 2 { e.0 = edge } else { e.1 = edge }
            }
        }
        // The end of drawing, timed apart from the video events.
        let mut g = quiet::quiet();
        g.gp0_words(&[
            0xE100_0000 | (dither as u32) << 9 | semi.unwrap_or(0) << 5,
            0xE300_0000 | area.0 | area.1 << 10,
            0xE400_0000 | area.2 | area.3 << 10,
            0xE500_0000,
            0xE600_0000 | set_mask as u32,
        ]);
        let c = ends[0].2;
        let cmd = 0x40 | (ignored & 1) | (semi.is_some() as u32) << 1 | (ignored >> 1) << 2;
        g.gp0_words(&[
            cmd << 24 | c[0] as u32 | (c[1] as u32) << 8 | (c[2] as u32) << 16,
            xy(ends[0].0, ends[0].1),
            xy(ends[1].0, ends[1].1),
        ]);
        let mut expected = gpu::Vram::new();
        let e = |i: usize| (ends[i].0 as i64, ends[i].1 as i64, ends[i].2.map(|c| c as i64));
        let clip = (area.0 as i64, area.1 as i64, area.2 as i64, area.3 as i64);
        for (x, y, c) in model_line([e(0), e(1)], false, clip) {
            // Semi-transparent over the cleared VRAM (B = 0): F / 2, F, 0 or F / 4 per
            // channel (§6).
            let c = c.map(|c| {
                let f = model::channel(c as u32, x, y, dither);
                match semi {
                    None | Some(1) => f,
                    Some(0) => f >> 1,
                    Some(2) => 0,
                    Some(_) => f >> 2,
                }
            });
            let mask = if set_mask { 0x8000 } else { 0 };
            expected.set_pixel(x as usize, y as usize, c[0] | c[1] << 5 | c[2] << 10 | mask);
        }
        prop_assert!(*g.vram() == expected, "VRAM differs from the model");
        let steps = (ends[1].0 - ends[0].0).abs().max((ends[1].1 - ends[0].1).abs());
        let time = cost::LINE_SETUP + steps as f64 * cost::LINE_STEP;
        prop_assert_eq!(g.cycles_until(gpu::EventKind::DrawingDone), cost::cycles_to_idle(time));
    }
}

/// A vertical Gouraud line is not swapped (x0 > x1 is false), so its colour is stepped from
/// the first vertex (docs/hardware/gpu.md §4, Mednafen's `>`). Red 1 -> 14 over k = 6: step
/// (13 << 12) / 6 = 8874, so at y = 3 the colour is (1 << 12 | 2048) + 3 * 8874 = 32766 -> 7
/// -> 5-bit 0. Drawn from the other end, (14 << 12 | 2048) - 3 * 8874 = 32770 -> 8 -> 1.
#[test]
fn vertical_gouraud_line_keeps_command_order() {
    let mut g = gpu();
    g.gp0_words(&[0x5000_F801, xy(0, 0), 0x0000_F80E, xy(0, 6)]);
    g.gp0_words(&[0x5000_F80E, xy(1, 6), 0x0000_F801, xy(1, 0)]);
    assert_eq!(px(&g, 0, 3), 31 << 5);
    assert_eq!(px(&g, 1, 3), 31 << 5 | 1);
}
