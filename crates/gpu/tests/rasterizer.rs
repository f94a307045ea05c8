//! Rasterization rules on small hand-worked cases (gpu.md §3-§7). Expected pixels and colours
//! are worked out from the fact sheet's formulas in the comments, not taken from the code.

use gpu::Gpu;

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

/// Semi-transparency modes on a rectangle over a filled background (gpu.md §6):
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

/// An 8000h texel in an opaque primitive draws black with bit 15 set (gpu.md §1).
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

/// CLUT cache (gpu.md §7): overwriting the CLUT with a fill does not refresh the latched
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
/// blends twice (gpu.md §4).
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
