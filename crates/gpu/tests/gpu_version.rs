//! Behaviour of the modelled v2 (208-pin) GPU where the GPU versions differ (docs/gpu.md
//! "Modelled GPU version"; docs/hardware/gpu.md §2, §5, §6, §9).

use gpu::Gpu;

fn gpu() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
    g
}

fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// Flat opaque white rectangle of w x h at (x, y).
fn rect(g: &mut Gpu, x: u32, y: u32, w: u32, h: u32) {
    g.gp0_words(&[0x6000_FFFF | 0xFF << 16, xy(x, y), h << 16 | w]);
}

fn rows_drawn(g: &Gpu, x: usize) -> Vec<usize> {
    (0..512).filter(|&y| g.vram().pixel(x, y) != 0).collect()
}

/// GP1(10h) index 7 answers 2 on the v2 GPU; older GPUs answer nothing (psx-spx "GP1(10h)").
#[test]
fn version_register_reads_2() {
    let mut g = gpu();
    g.gp1(0x1000_0007);
    assert_eq!(g.gpuread(), 2);
}

/// E3/E4 Y is bits 10-19 on v2: a bottom edge of 600 lets a rectangle from y = 500 to 549
/// through, rows at or past 512 landing at y & 511 (0-37). With a 9-bit Y the bottom would
/// read 600 & 511 = 88 and nothing at y >= 500 would be drawn.
#[test]
fn drawing_area_bottom_600() {
    let mut g = gpu();
    g.gp0(0xE400_0000 | 600 << 10 | 1023);
    rect(&mut g, 10, 500, 1, 50);
    let want: Vec<usize> = (0..38).chain(500..512).collect();
    assert_eq!(rows_drawn(&g, 10), want);
    g.gp1(0x1000_0004);
    assert_eq!(g.gpuread(), 600 << 10 | 1023);
    assert_eq!(g.draw_state().area.bottom, 600);
}

/// E3 top = 600: a rectangle covering y = 590..609 draws only its rows 600..609, written at
/// rows 88..97. A 9-bit top (88) would draw all 20 rows, 78..97.
#[test]
fn drawing_area_top_600() {
    let mut g = gpu();
    g.gp0(0xE300_0000 | 600 << 10);
    g.gp0(0xE400_0000 | 1023 << 10 | 1023);
    rect(&mut g, 10, 590, 1, 20);
    assert_eq!(rows_drawn(&g, 10), (88..98).collect::<Vec<_>>());
    g.gp1(0x1000_0003);
    assert_eq!(g.gpuread(), 600 << 10);
}

/// Bits above 19 of E3/E4 are ignored: Y = 1023 from bits 10-19, bit 20+ set.
#[test]
fn drawing_area_y_is_ten_bits() {
    let mut g = gpu();
    g.gp0(0xE4F0_0000 | 1023 << 10 | 5);
    g.gp1(0x1000_0004);
    assert_eq!(g.gpuread(), 1023 << 10 | 5);
}

/// Rectangle flips (E1.12/13) exist on v2 only: a 2x1 15-bit raw rectangle from U0 = 0 with
/// the X flip reads texels 1 then 0 (docs/hardware/gpu.md §5).
#[test]
fn rectangle_flip_is_honoured() {
    let mut g = gpu();
    g.gp0_words(&[0xA000_0000, xy(512, 0), 1 << 16 | 2, 0x0222_0111]);
    g.gp0(0xE100_1000 | 2 << 7 | 8);
    g.gp0_words(&[0x6500_0000, xy(0, 10), 0, 1 << 16 | 2]);
    assert_eq!(
        (g.vram().pixel(0, 10), g.vram().pixel(1, 10)),
        (0x0222, 0x0111)
    );
}

/// GP1(09h) bit 0 allows E1.11 texture disable (v2); without it the bit is ignored and
/// GPUSTAT.15 stays clear.
#[test]
fn texture_disable_needs_gp1_09() {
    let mut g = gpu();
    g.gp0(0xE100_0800);
    assert_eq!(g.gpustat() >> 15 & 1, 0);
    g.gp1(0x0900_0001);
    g.gp0(0xE100_0800);
    assert_eq!(g.gpustat() >> 15 & 1, 1);
}

/// Modulation is the v2 formula, undithered `min(31, (t5 * c8) >> 7)` (docs/hardware/gpu.md
/// §6): texel channel 31 with colour 47h gives (31 * 71) >> 7 = 17, where the v0 formula
/// `((c8 & F8h) * t5) >> 7` would give (64 * 31) >> 7 = 15.
#[test]
fn modulation_uses_full_8_bit_colour() {
    let mut g = gpu();
    g.gp0_words(&[0xA000_0000, xy(512, 0), 1 << 16 | 1, 0x0000_001F]);
    g.gp0(0xE100_0000 | 2 << 7 | 8);
    g.gp0_words(&[0x6400_0047, xy(0, 20), 0, 1 << 16 | 1]);
    assert_eq!(g.vram().pixel(0, 20) & 0x1F, 17);
}
