//! 480i drawing: with GP1(08h) bits 2 and 5 set and GP0(E1h) bit 10 clear, polygons, lines,
//! rectangles and fills skip the VRAM lines of the field being displayed (docs/hardware/gpu.md §8:
//! Mednafen's LineSkipTest, DuckStation's interlaced fill; psx-spx "GP1(08h)"). Expected
//! images: the same commands drawn progressively, with the skipped lines blanked by the
//! test's own parity rule.

use gpu::Gpu;
use gpu::encode;
use proptest::prelude::*;

const MODE_480I: u32 = 0x0800_0025;

fn setup(mode: u32, e1: u32, start_y: u32) -> Gpu {
    let mut g = Gpu::new();
    g.gp1(mode);
    g.gp1(0x0500_0000 | start_y << 10);
    g.gp0_words(&[
        encode::area_top_left(0, 0),
        encode::area_bottom_right(1023, 511),
        encode::drawing_offset(0, 0),
        e1,
    ]);
    g
}

/// Run until the field (GPUSTAT.13) changes.
fn next_field(g: &mut Gpu) {
    let f = g.gpustat() >> 13 & 1;
    while g.gpustat() >> 13 & 1 == f {
        g.run(g.cycles_until_next_event());
    }
}

/// `reference` with every line whose bit 0 is `skipped` reset to zero.
fn without_lines(reference: &Gpu, skipped: usize) -> Vec<u16> {
    let mut v = reference.vram().as_slice().to_vec();
    for (y, row) in v.chunks_mut(1024).enumerate() {
        if y % 2 == skipped {
            row.fill(0);
        }
    }
    v
}

fn draw(g: &mut Gpu, words: &[u32]) {
    g.gp0_words(words);
}

const SHAPES: &[&[u32]] = &[
    // Gouraud triangle.
    &[
        0x3000_00FF,
        0x0005_0003,
        0x0000_FF00,
        0x0040_0030,
        0x00FF_0000,
        0x0021_0070,
    ],
    // Flat quad.
    &[
        0x2800_8040,
        0x0010_0010,
        0x0010_0050,
        0x0050_0010,
        0x0057_0052,
    ],
    // Steep flat line and a Gouraud polyline.
    &[0x4000_FFFF, 0x0003_0100, 0x0060_0108],
    &[
        0x5800_00FF,
        0x0002_0200,
        0x0000_FF00,
        0x0030_0240,
        0x00FF_0000,
        0x0011_0280,
        0x5555_5555,
    ],
    // Variable-size flat rectangle with an odd top, and a 16x16 one.
    &[0x6000_1F1F, 0x0007_0300, 0x0021_0013],
    &[0x7800_7F00, 0x0100_0100],
    // Fill.
    &[0x0200_FF00, 0x0003_0380, 0x0011_0020],
];

#[test]
fn each_primitive_skips_the_displayed_field() {
    for (i, words) in SHAPES.iter().enumerate() {
        let mut reference = setup(0x0800_0001, 0xE100_0000, 0);
        draw(&mut reference, words);
        // Field 0, display start line 0: even lines are displayed, odd ones drawn.
        let mut g = setup(MODE_480I, 0xE100_0000, 0);
        draw(&mut g, words);
        assert!(
            g.vram().as_slice() == without_lines(&reference, 0).as_slice(),
            "shape {i}, field 0"
        );
        // Next field: odd lines displayed, even ones drawn.
        let mut g = setup(MODE_480I, 0xE100_0000, 0);
        next_field(&mut g);
        assert_eq!(g.gpustat() >> 13 & 1, 1);
        draw(&mut g, words);
        assert!(
            g.vram().as_slice() == without_lines(&reference, 1).as_slice(),
            "shape {i}, field 1"
        );
        // An odd display start line swaps the lines of each field.
        let mut g = setup(MODE_480I, 0xE100_0000, 1);
        draw(&mut g, words);
        assert!(
            g.vram().as_slice() == without_lines(&reference, 1).as_slice(),
            "shape {i}, start line 1"
        );
        // E1 bit 10 set (draw to the displayed area): every line.
        let mut g = setup(MODE_480I, 0xE100_0400, 0);
        draw(&mut g, words);
        assert!(g.vram() == reference.vram(), "shape {i}, E1.10");
        // Interlace without 480 lines, or 480 lines without interlace: every line.
        for mode in [0x0800_0021, 0x0800_0005] {
            let mut g = setup(mode, 0xE100_0000, 0);
            draw(&mut g, words);
            assert!(g.vram() == reference.vram(), "shape {i}, mode {mode:#x}");
        }
    }
}

#[test]
fn a_sixteen_line_rectangle_keeps_eight_lines() {
    // Hand-counted: a 16x16 rectangle at (0, 0) in field 0 writes lines 1, 3, ..., 15.
    let mut g = setup(MODE_480I, 0xE100_0000, 0);
    draw(&mut g, &[0x7800_00F8, 0x0000_0000]);
    for y in 0..16 {
        let expected = if y % 2 == 1 { 0x001F } else { 0 };
        for x in 0..16 {
            assert_eq!(g.vram().pixel(x, y), expected, "({x}, {y})");
        }
    }
}

#[test]
fn copies_and_uploads_are_not_filtered() {
    let mut g = setup(MODE_480I, 0xE100_0000, 0);
    draw(
        &mut g,
        &[0xA000_0000, 0x0000_0000, 0x0002_0001, 0x7FFF_7FFF],
    );
    assert_eq!(g.vram().pixel(0, 0), 0x7FFF);
    assert_eq!(g.vram().pixel(0, 1), 0x7FFF);
    draw(
        &mut g,
        &[0x8000_0000, 0x0000_0000, 0x0000_0010, 0x0002_0001],
    );
    assert_eq!(g.vram().pixel(16, 0), 0x7FFF);
    assert_eq!(g.vram().pixel(16, 1), 0x7FFF);
}

proptest! {
    #[test]
    fn triangles_and_lines_skip_exactly_one_parity(
        v in prop::array::uniform6(-200i32..600),
        c in any::<u32>(),
        field in 0u8..2,
        start in 0u32..4,
    ) {
        let pos = |x: i32, y: i32| (x as u32 & 0x7FF) | (y as u32 & 0x7FF) << 16;
        let shapes = [
            vec![0x3000_0000 | (c & 0xFF_FFFF), pos(v[0], v[1]), c.rotate_left(8) & 0xFF_FFFF,
                 pos(v[2], v[3]), c.rotate_left(16) & 0xFF_FFFF, pos(v[4], v[5])],
            vec![0x4000_0000 | (c & 0xFF_FFFF), pos(v[0], v[1]), pos(v[2], v[3])],
            vec![0x6000_0000 | (c & 0xFF_FFFF), pos(v[0], v[1]),
                 (v[2] as u32 & 0x3F) | (v[3] as u32 & 0x3F) << 16],
        ];
        for words in &shapes {
            let mut reference = setup(0x0800_0001, 0xE100_0000, start);
            draw(&mut reference, words);
            let mut g = setup(MODE_480I, 0xE100_0000, start);
            if field == 1 {
                next_field(&mut g);
            }
            draw(&mut g, words);
            let skipped = ((start + field as u32) % 2) as usize;
            prop_assert!(g.vram().as_slice() == without_lines(&reference, skipped).as_slice());
        }
    }
}
