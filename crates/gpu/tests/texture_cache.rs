//! The texture cache (docs/hardware/gpu.md §10): a directed test per rule, expected values
//! worked out by hand from the rule, and property tests of sprites (raw 15-bit and 4-bit) and
//! fills against a model of the cache written from the fact sheet.

#[path = "support/quiet.rs"]
mod quiet;

use gpu::{Gpu, TextureCacheEntry};
use proptest::prelude::*;
use std::collections::HashMap;

/// The sampled page: 15-bit at (512, 0) (E1h page X 512 / 64 = 8, depth 2 in bits 7-8).
const E1_PAGE15: u32 = 0xE100_0108;
/// The same page at 8-bit and at 4-bit.
const E1_PAGE8: u32 = 0xE100_0088;
const E1_PAGE4: u32 = 0xE100_0008;
const PAGE_X: u32 = 512;
/// Where samples are drawn, clear of the page.
const OUT: (u32, u32) = (0, 480);

fn xy(x: u32, y: u32) -> u32 {
    y << 16 | x
}

/// Drawing area over the whole of VRAM when `area_over_page`, else lines 400-511 only (clear
/// of the page), no offset, the 15-bit page selected. Both must behave the same; the first
/// has primitives that may draw over the page.
fn gpu(area_over_page: bool) -> Gpu {
    let mut g = quiet::quiet();
    let top = if area_over_page { 0 } else { 400 };
    g.gp0_words(&[
        0xE300_0000 | top << 10,
        0xE400_0000 | 1023 | 511 << 10,
        0xE500_0000,
    ]);
    g.gp0(E1_PAGE15);
    g
}

/// GP0(02h) filling `w` x `h` at (x, y) with the 15-bit value `c` (bit 15 clear): the 24-bit
/// colour whose channels >> 3 give `c` (docs/hardware/gpu.md §8).
fn fill(g: &mut Gpu, c: u16, (x, y): (u32, u32), (w, h): (u32, u32)) {
    let c = u32::from(c);
    let rgb = (c & 31) << 3 | ((c >> 5) & 31) << 11 | ((c >> 10) & 31) << 19;
    g.gp0_words(&[0x0200_0000 | rgb, xy(x, y), xy(w, h)]);
}

/// The texel at (u, v) of the selected page: a 1x1 raw-textured sprite (GP0(6Dh)) drawn at
/// `OUT` with the CLUT at `clut`, read back (a raw texel is written as it is, §6).
fn sample(g: &mut Gpu, (u, v): (u32, u32), clut: u32) -> u16 {
    g.gp0_words(&[0x6D00_0000, xy(OUT.0, OUT.1), clut << 16 | v << 8 | u]);
    g.vram().pixel(OUT.0 as usize, OUT.1 as usize)
}

fn resident(g: &Gpu) -> usize {
    (0..=255u8)
        .filter(|&i| g.texture_cache_entry(i).is_some())
        .count()
}

const A: u16 = 0x0421;
const B: u16 = 0x7C1F;

/// A fill leaves the texels of resident entries in use; an entry holds four halfwords, so a
/// texel sharing the first's four halfwords is stale too and the next one is not.
#[test]
fn a_fill_under_cached_texels_is_not_seen() {
    for over_page in [false, true] {
        let mut g = gpu(over_page);
        fill(&mut g, A, (PAGE_X, 0), (16, 1));
        assert_eq!(sample(&mut g, (0, 0), 0), A);
        fill(&mut g, B, (PAGE_X, 0), (16, 1));
        assert_eq!(g.vram().pixel(PAGE_X as usize, 0), B);
        assert_eq!(sample(&mut g, (0, 0), 0), A, "stale texel");
        assert_eq!(sample(&mut g, (3, 0), 0), A, "same entry, loaded with A");
        assert_eq!(sample(&mut g, (4, 0), 0), B, "next entry, loaded now");
    }
}

/// Drawing under a resident entry (a flat rectangle, GP0(60h)) is not seen either.
#[test]
fn drawing_under_cached_texels_is_not_seen() {
    let mut g = gpu(true);
    fill(&mut g, A, (PAGE_X, 0), (16, 1));
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    // Flat rectangle of 24-bit colour R F8h, G 0, B F8h: 15-bit 7C1Fh (B).
    g.gp0_words(&[0x60F8_00F8, xy(PAGE_X, 0), xy(16, 1)]);
    assert_eq!(g.vram().pixel(PAGE_X as usize, 0), B);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    assert_eq!(sample(&mut g, (4, 0), 0), B);
}

/// The stale set-up of the two tests above: A cached at texel (0, 0), B in VRAM.
fn stale(over_page: bool) -> Gpu {
    let mut g = gpu(over_page);
    fill(&mut g, A, (PAGE_X, 0), (16, 1));
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    fill(&mut g, B, (PAGE_X, 0), (16, 1));
    g
}

#[test]
fn gp0_01_empties_the_cache() {
    for over_page in [false, true] {
        let mut g = stale(over_page);
        g.gp0(0x0100_0000);
        assert_eq!(resident(&g), 0);
        assert_eq!(sample(&mut g, (0, 0), 0), B);
    }
}

#[test]
fn gp1_00_empties_the_cache() {
    let mut g = stale(false);
    assert_eq!(resident(&g), 1);
    g.gp1(0x0000_0000);
    assert_eq!(resident(&g), 0);
}

/// GP0(01h)'s neighbours among the one-word commands, GP1(01h) and E2h (window) leave it.
#[test]
fn gp1_01_nop_and_window_leave_the_cache() {
    let mut g = stale(false);
    g.gp1(0x0100_0000);
    g.gp0(0x0000_0000);
    g.gp0(0xE200_0000);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
}

/// A VRAM-to-VRAM copy, a CPU-to-VRAM transfer and a VRAM-to-CPU transfer each empty the
/// cache, even when they touch VRAM far from the page.
#[test]
fn vram_transfers_empty_the_cache() {
    let copy = [0x8000_0000, xy(0, 300), xy(100, 300), xy(4, 1)];
    let upload = [0xA000_0000, xy(0, 300), xy(1, 1), 0x1234];
    let read = [0xC000_0000, xy(0, 300), xy(2, 1)];
    for words in [&copy[..], &upload[..], &read[..]] {
        let mut g = stale(false);
        g.gp0_words(words);
        if words[0] >> 24 == 0xC0 {
            g.gpuread();
        }
        assert_eq!(resident(&g), 0, "{:08x}", words[0]);
        assert_eq!(sample(&mut g, (0, 0), 0), B, "{:08x}", words[0]);
    }
}

/// GP0(E1h): other bits than the page and depth leave the cache; 8-bit and 15-bit share it;
/// a change to 4-bit and back, or of the page X or Y, empties it.
#[test]
fn texture_page_changes() {
    // Semi-transparency mode 1 and dithering on: no page change.
    let mut g = stale(false);
    g.gp0(E1_PAGE15 | 1 << 5 | 1 << 9);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    // 15-bit to 8-bit and back.
    g.gp0(E1_PAGE8);
    g.gp0(E1_PAGE15);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    // 4-bit and back.
    g.gp0(E1_PAGE4);
    assert_eq!(resident(&g), 0);
    g.gp0(E1_PAGE15);
    assert_eq!(sample(&mut g, (0, 0), 0), B);
    // Page X, page Y.
    for other in [E1_PAGE15 + 1, E1_PAGE15 | 1 << 4] {
        let mut g = stale(false);
        g.gp0(other);
        assert_eq!(resident(&g), 0, "{other:08x}");
    }
}

/// A textured polygon's texpage attribute is a texture page change like E1h: the same page
/// leaves the cache, another empties it (the polygon here has no area and draws nothing).
#[test]
fn polygon_texpage_attribute_changes() {
    let point = |page: u32| [0x2500_0000, 0, 0, 0, page << 16, 0, 0];
    let mut g = stale(false);
    g.gp0_words(&point(0x108));
    assert_eq!(resident(&g), 1);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    g.gp0_words(&point(0x109));
    assert_eq!(resident(&g), 0);
}

/// E1h bit 11 (texture disable) empties the cache when it changes, which it can only do after
/// GP1(09h) allowed it.
#[test]
fn texture_disable_changes() {
    let mut g = stale(false);
    g.gp0(E1_PAGE15 | 1 << 11);
    assert_eq!(resident(&g), 1, "not allowed: the bit stays clear");
    g.gp1(0x0900_0001);
    g.gp0(E1_PAGE15 | 1 << 11);
    assert_eq!(resident(&g), 0);
}

/// 15-bit blocks are 32x32 texels: texels (0, 0), (0, 32) and (32, 0) share entry 0 and
/// replace each other; (4, 0) is entry 1 and stays.
#[test]
fn blocks_at_15_bit() {
    let mut g = gpu(false);
    fill(&mut g, A, (PAGE_X, 0), (64, 64));
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    assert_eq!(sample(&mut g, (4, 0), 0), A);
    fill(&mut g, B, (PAGE_X, 0), (64, 64));
    assert_eq!(sample(&mut g, (0, 32), 0), B);
    let entry = |x: u32, y: u32, c: u16| TextureCacheEntry {
        x: x as u16,
        y: y as u16,
        halfwords: [c; 4],
    };
    assert_eq!(g.texture_cache_entry(0), Some(entry(PAGE_X, 32, B)));
    assert_eq!(sample(&mut g, (0, 0), 0), B, "reloaded");
    assert_eq!(sample(&mut g, (4, 0), 0), A, "entry 1, still stale");
    assert_eq!(sample(&mut g, (32, 0), 0), B);
    assert_eq!(g.texture_cache_entry(0), Some(entry(PAGE_X + 32, 0, B)));
    assert_eq!(g.texture_cache_entry(1), Some(entry(PAGE_X + 4, 0, A)));
}

/// A CLUT whose entry i (i < `n`) is `0x0100 + i`, at (0, y), written before any texel is
/// cached.
fn clut(g: &mut Gpu, y: usize, n: usize) -> u32 {
    for i in 0..n {
        g.vram_mut().set_pixel(i, y, 0x0100 + i as u16);
    }
    (y as u32) << 6
}

/// 4-bit blocks are 64x64 texels: texel (0, 64) replaces (0, 0), (0, 32) is another entry.
#[test]
fn blocks_at_4_bit() {
    let mut g = gpu(false);
    let c = clut(&mut g, 500, 16);
    g.gp0(E1_PAGE4);
    // Every texel index 1, then every index 2 (four texels a halfword).
    fill(&mut g, 0x1111, (PAGE_X, 0), (16, 128));
    assert_eq!(sample(&mut g, (0, 0), c), 0x0101);
    assert_eq!(sample(&mut g, (0, 32), c), 0x0101);
    fill(&mut g, 0x2222, (PAGE_X, 0), (16, 128));
    assert_eq!(sample(&mut g, (0, 64), c), 0x0102);
    assert_eq!(
        sample(&mut g, (0, 0), c),
        0x0102,
        "replaced by (0, 64), reloaded"
    );
    assert_eq!(sample(&mut g, (0, 32), c), 0x0101, "still stale");
}

/// 8-bit blocks are 64x32 texels (Mednafen's, not psx-spx's 32x64; docs/gpu.md, "Texture
/// cache"): texel (0, 32) replaces (0, 0); (32, 0), 16 halfwords right, is another entry of
/// the same block.
#[test]
fn blocks_at_8_bit() {
    let mut g = gpu(false);
    let c = clut(&mut g, 501, 256);
    g.gp0(E1_PAGE8);
    fill(&mut g, 0x0101, (PAGE_X, 0), (64, 64));
    assert_eq!(sample(&mut g, (0, 0), c), 0x0101);
    assert_eq!(sample(&mut g, (32, 0), c), 0x0101);
    fill(&mut g, 0x0202, (PAGE_X, 0), (64, 64));
    assert_eq!(sample(&mut g, (0, 32), c), 0x0102);
    assert_eq!(
        sample(&mut g, (0, 0), c),
        0x0102,
        "replaced by (0, 32), reloaded"
    );
    assert_eq!(sample(&mut g, (32, 0), c), 0x0101, "entry 4, still stale");
}

/// A 16x16 sprite reading from an empty cache misses once per entry its rows reach: a row of
/// 16 texels is one entry at 4-bit, two at 8-bit, four at 15-bit; drawn again, nothing. Each
/// miss adds 2255/256 (8.81) CPU cycles of drawing time, the figure calibrated on the
/// console's textured quads (docs/emulator.md, "Drawing time"): a raw 15-bit 16x16 sprite from
/// an empty cache (64 misses) takes 64 x 2255 / 256 = 563.75 CPU cycles longer than with the
/// cache off (563 or 564 whole cycles, as the carried fraction falls), and drawn a second time
/// (no miss) no longer again. With the cache off nothing is counted.
#[test]
fn misses_and_their_time() {
    for (e1, per_row) in [(E1_PAGE4, 1), (E1_PAGE8, 2), (E1_PAGE15, 4)] {
        let mut g = gpu(false);
        let c = clut(&mut g, 501, 256);
        g.gp0(e1);
        let sprite = [0x7D00_0000, xy(100, 450), c << 16];
        for expected in [16 * per_row, 0] {
            let before = g.texture_cache_misses();
            g.gp0_words(&sprite);
            assert_eq!(g.texture_cache_misses() - before, expected, "{e1:08x}");
        }
    }
    let sprite = [0x7D00_0000, xy(100, 450), 0];
    let time = |cache: bool, times: usize| {
        let mut g = gpu(false);
        g.set_texture_cache(cache);
        for _ in 0..times {
            g.gp0_words(&sprite);
        }
        (
            g.cycles_until(gpu::EventKind::DrawingDone),
            g.texture_cache_misses(),
        )
    };
    let (off, off_misses) = time(false, 1);
    let (cold, misses) = time(true, 1);
    assert_eq!((off_misses, misses), (0, 64));
    let within_a_cycle = |extra: u32| (extra * 256).abs_diff(64 * 2255) < 256;
    assert!(within_a_cycle(cold - off), "{cold} - {off}");
    let (off_twice, _) = time(false, 2);
    let (on_twice, _) = time(true, 2);
    assert!(
        within_a_cycle(on_twice - off_twice),
        "{on_twice} - {off_twice}"
    );
}

/// Pixels the mask check keeps from being written still read their texels: a 4x1 sprite over
/// four pixels with bit 15 set under E6h bit 1 writes nothing but loads its entry.
#[test]
fn masked_pixels_still_read_their_texels() {
    let mut g = gpu(false);
    for x in 0..4 {
        g.vram_mut().set_pixel(100 + x, 450, 0x8000);
    }
    g.gp0(0xE600_0002);
    let before = g.texture_cache_misses();
    g.gp0_words(&[0x6500_0000, xy(100, 450), 0, xy(4, 1)]);
    assert_eq!(g.texture_cache_misses() - before, 1);
    assert!(g.texture_cache_entry(0).is_some());
    assert_eq!(g.vram().pixel(100, 450), 0x8000);
}

/// The texel at (x, y) of the page [`draw_over_own_texture`] reads: distinct in each of the
/// first 31 columns of a row, never 0.
fn own_texel(x: usize, y: usize) -> u16 {
    (((x + 3 * y) % 31 + 1) | ((y % 31 + 1) << 5)) as u16
}

/// A Gouraud-textured triangle (GP0(34h), neutral colour 80h, undithered: each pixel its
/// texel, §6) drawn over its own 15-bit page at (0, 0), filled with [`own_texel`], one pixel to
/// the right of the texels it reads: pixel x of a row reads texel x - 1. Rows 0-29 draw
/// pixels 1 to 30 - y. GP0(E1h) selects the same page first.
fn draw_over_own_texture(g: &mut Gpu) {
    g.gp0(0xE100_0100);
    for y in 0..40 {
        for x in 0..40 {
            g.vram_mut().set_pixel(x, y, own_texel(x, y));
        }
    }
    g.gp0_words(&[
        0x3480_8080,
        xy(1, 0),
        0,
        0x0080_8080,
        xy(33, 0),
        32 | 0x100 << 16,
        0x0080_8080,
        xy(1, 32),
        32 << 8,
    ]);
}

/// [`draw_over_own_texture`] with the cache on: pixel x of a row reads texel x - 1 from the
/// cache. A row's entries are loaded as the row reaches them, each when its first halfword c
/// is read by pixel c + 1, after pixel c wrote halfword c: so texel c of every entry but the
/// first comes out as pixel c wrote it (texel c - 1), the three others as they were.
#[test]
fn a_primitive_reads_the_cache_not_its_own_pixels() {
    let mut g = gpu(true);
    draw_over_own_texture(&mut g);
    for y in 0..30usize {
        for x in 1..31 - y {
            let u = x - 1;
            let expected = if u % 4 == 0 && u > 0 {
                own_texel(u - 1, y)
            } else {
                own_texel(u, y)
            };
            assert_eq!(g.vram().pixel(x, y), expected, "({x}, {y})");
        }
    }
}

/// [`draw_over_own_texture`] with the cache off: each pixel reads from VRAM the texel its left
/// neighbour has just written, so every row repeats the texel left of its first pixel.
#[test]
fn with_the_cache_off_a_primitive_reads_its_own_pixels() {
    let mut g = gpu(true);
    g.set_texture_cache(false);
    draw_over_own_texture(&mut g);
    for y in 0..30usize {
        for x in 1..31 - y {
            assert_eq!(g.vram().pixel(x, y), own_texel(0, y), "({x}, {y})");
        }
    }
}

/// A sprite drawn over its own 8-bit texels with the cache off: a raw 16x16 sprite (GP0(7Dh))
/// at (0, y) on the page at (0, 0), CLUT at (0, 256). Pixel i of a row reads texel i, the
/// byte i & 1 of halfword i / 2, straight from VRAM, after pixels 0..i have been written, so
/// from pixel 1 on it reads bytes the sprite itself wrote (§7, §10). The expected row is
/// worked out pixel by pixel in that order from the CLUT and the VRAM before the draw.
#[test]
fn with_the_cache_off_a_sprite_reads_its_own_pixels() {
    let mut g = gpu(true);
    g.set_texture_cache(false);
    g.gp0(0xE100_0080);
    let clut = |i: u16| 0x0400 | (i * 3 + 1);
    for i in 0..256u16 {
        g.vram_mut().set_pixel(usize::from(i), 256, clut(i));
    }
    let before = |x: usize, y: usize| (x as u16 * 0x0101 + y as u16 * 0x3B) | 0x0100;
    for y in 0..16 {
        for x in 0..16 {
            g.vram_mut().set_pixel(x, y, before(x, y));
        }
    }
    g.gp0_words(&[0x7D00_0000, xy(0, 0), 0x4000 << 16]);
    for y in 0..16 {
        let mut row: Vec<u16> = (0..16).map(|x| before(x, y)).collect();
        for i in 0..16 {
            let byte = row[i / 2] >> (8 * (i & 1)) & 0xFF;
            row[i] = clut(byte);
        }
        for (x, &expected) in row.iter().enumerate() {
            assert_eq!(g.vram().pixel(x, y), expected, "({x}, {y})");
        }
    }
}

/// A 4-bit sprite drawn over its own texel line with the cache on reads each entry when its
/// first texel is needed, after the pixels before it are written (§10): a raw 16x1 sprite
/// (GP0(65h)) at (0, 0) on the page at (0, 0), CLUT at (0, 256), reading u 8-23. Pixels 0-7
/// take texels 8-15 from entry 0 (halfwords 0-3, loaded before any write) and overwrite
/// halfwords 0-7; pixels 8-15 take texels 16-23 from entry 1 (halfwords 4-7), loaded only then,
/// so from the values pixels 4 and 5 wrote. The expected row is worked out in that order.
#[test]
fn a_sprite_over_its_own_texel_line_loads_each_entry_when_it_reaches_it() {
    let mut g = gpu(true);
    g.gp0(0xE100_0000);
    let clut = |i: u16| 0x0400 | (i * 0x0123 + 0x0031) & 0x3FFF;
    for i in 0..16u16 {
        g.vram_mut().set_pixel(usize::from(i), 256, clut(i));
    }
    let before = |x: usize| (x as u16).wrapping_mul(0x1357).wrapping_add(0x2468) | 0x0001;
    for x in 0..16 {
        g.vram_mut().set_pixel(x, 0, before(x));
    }
    g.gp0_words(&[0x6500_0000, xy(0, 0), 0x4000 << 16 | 8, 1 << 16 | 16]);
    let mut row: Vec<u16> = (0..16).map(before).collect();
    let mut entry: Option<(usize, [u16; 4])> = None;
    for p in 0..16 {
        let u = 8 + p;
        let e = u / 16;
        let halfwords = match entry {
            Some((k, h)) if k == e => h,
            _ => {
                let h = [0, 1, 2, 3].map(|i| row[4 * e + i]);
                entry = Some((e, h));
                h
            }
        };
        let texel = halfwords[(u % 16) / 4] >> (4 * (u % 4)) & 0xF;
        row[p] = clut(texel);
    }
    for (x, &expected) in row.iter().enumerate() {
        assert_eq!(g.vram().pixel(x, 0), expected, "x {x}");
    }
}

/// A triangle whose core vertex sorts last is walked upward, both parts (§3.4): the entry two
/// of its rows share ends up holding the upper row's halfwords. Raw 15-bit, vertices (100,
/// 400), (100, 420), (36, 464) reading u = x - 36, v = y - 400 (the core vertex is the third:
/// x1 <= x0 and x2 <= x1, §3.3; it sorts last): row v 5 spans x 95-99 (u 59-63, the left edge
/// at x = 100 - v drawn, the right one not), row v 37 spans x 63-75 (u 27-39, the right edge
/// from (100, 20) to (36, 64) at x 75.3); entry 47 (u / 4 = 7 mod 8, v = 5 mod 32) is read by
/// both, at u 60-63 of row 5 and u 28-31 of row 37. Row 37 is walked first, row 5 after: the
/// entry holds (512 + 60, 5). Walked downward it would hold (512 + 28, 37).
#[test]
fn triangle_rows_in_the_console_order() {
    let mut g = gpu(false);
    g.gp0_words(&[
        0x2500_0000,
        xy(100, 400),
        64,
        xy(100, 420),
        0x108 << 16 | 20 << 8 | 64,
        xy(36, 464),
        64 << 8,
    ]);
    let e = g.texture_cache_entry(47).expect("entry 47 loaded");
    assert_eq!((e.x, e.y), (512 + 60, 5));
}

/// Off: texels straight from VRAM, nothing cached; on again, the cache starts empty.
#[test]
fn the_switch() {
    let mut g = stale(false);
    g.set_texture_cache(false);
    assert!(!g.texture_cache_enabled());
    assert_eq!(resident(&g), 0);
    assert_eq!(sample(&mut g, (0, 0), 0), B);
    assert_eq!(resident(&g), 0);
    fill(&mut g, A, (PAGE_X, 0), (16, 1));
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    g.set_texture_cache(true);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    assert_eq!(resident(&g), 1);
}

/// `Gpu::vram_mut` writes like a fill: cached texels keep their values.
#[test]
fn direct_vram_edits_are_writes() {
    let mut g = gpu(false);
    fill(&mut g, A, (PAGE_X, 0), (16, 1));
    assert_eq!(sample(&mut g, (0, 0), 0), A);
    g.vram_mut().set_pixel(PAGE_X as usize, 0, B);
    assert_eq!(sample(&mut g, (0, 0), 0), A);
}

/// One step of [`sprites_and_fills_match_the_model`].
#[derive(Clone, Debug)]
enum Step {
    /// A raw 15-bit sprite (GP0(65h)) of `w` x `h` at (x, y) reading from (u, v).
    Sprite {
        at: (u32, u32),
        uv: (u32, u32),
        size: (u32, u32),
    },
    /// GP0(02h) over the page.
    Fill {
        at: (u32, u32),
        size: (u32, u32),
        c: u16,
    },
    /// GP0(01h).
    Clear,
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        4 => ((0u32..200, 300u32..460), (0u32..96, 0u32..96), (1u32..24, 1u32..24))
            .prop_map(|(at, uv, size)| Step::Sprite { at, uv, size }),
        2 => ((0u32..6, 0u32..96), (1u32..4, 1u32..40), 1u16..0x7FFF)
            .prop_map(|((x, y), (w, h), c)| Step::Fill {
                at: (PAGE_X + 16 * x, y),
                size: (16 * w, h),
                c,
            }),
        1 => Just(Step::Clear),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Raw 15-bit sprites reading a page that fills overwrite, against a model of §10 written
    /// from the fact sheet: 256 entries, entry `((a >> 2) & 7) | ((a >> 7) & F8h)` for VRAM
    /// address a, tag a / 4, four halfwords loaded on a miss, texels read row by row from the
    /// top and left to right, GP0(01h) emptying it. The drawn pixels and the misses agree,
    /// whether or not the drawing area lets sprites draw over the page.
    #[test]
    fn sprites_and_fills_match_the_model(
        steps in prop::collection::vec(step(), 1..40),
        over_page in any::<bool>(),
    ) {
        let mut g = gpu(over_page);
        let mut m = Model::new(&g);
        for s in &steps {
            match *s {
                Step::Sprite { at, uv, size } => {
                    g.gp0_words(&[0x6500_0000, xy(at.0, at.1), uv.1 << 8 | uv.0, xy(size.0, size.1)]);
                    // Rows above the drawing area are not drawn, nor their texels read.
                    let top = if over_page { 0 } else { 400 };
                    for row in (0..size.1).filter(|&r| at.1 + r >= top) {
                        for col in 0..size.0 {
                            let a = (uv.1 + row) as usize * 1024 + (PAGE_X + uv.0 + col) as usize;
                            let t = m.read(a, ((a >> 2) & 7) | ((a >> 7) & 0xF8))[a & 3];
                            m.draw((at.0 + col, at.1 + row), t);
                        }
                    }
                }
                _ => m.fill_or_clear(&mut g, s),
            }
        }
        m.check(&g)?;
    }
}

/// 4-bit sprites of [`clut4_sprites_and_fills_match_the_model`]: at (x, y), reading from
/// (u, v), `w` x `h`, up to 48 wide so that rows take several entries and wrap at U 256.
fn clut4_step() -> impl Strategy<Value = Step> {
    prop_oneof![
        4 => ((0u32..200, 300u32..460), (0u32..256, 0u32..96), (1u32..48, 1u32..24))
            .prop_map(|(at, uv, size)| Step::Sprite { at, uv, size }),
        2 => step().prop_filter("a fill or a clear", |s| !matches!(s, Step::Sprite { .. })),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Raw 4-bit sprites (GP0(65h), CLUT at (0, 496) with one transparent entry) reading the
    /// 4-bit page at (512, 0) that fills overwrite, against the model of
    /// [`sprites_and_fills_match_the_model`] with the 4-bit tiling: entry `((a >> 2) & 3) |
    /// ((a >> 8) & FCh)`, texel u the nibble `u & 3` of halfword `u / 4`, U wrapping at 256
    /// (§7, §10). The drawn pixels and the misses agree, whether or not the drawing area
    /// lets sprites draw over the page.
    #[test]
    fn clut4_sprites_and_fills_match_the_model(
        steps in prop::collection::vec(clut4_step(), 1..40),
        over_page in any::<bool>(),
    ) {
        let mut g = gpu(over_page);
        g.gp0(E1_PAGE4);
        let clut: [u16; 16] = core::array::from_fn(|i| if i == 5 { 0 } else { 0x0421 * i as u16 + 0x8003 * (i as u16 & 1) });
        for (i, &c) in clut.iter().enumerate() {
            g.vram_mut().set_pixel(i, 496, c);
        }
        let mut m = Model::new(&g);
        for s in &steps {
            match *s {
                Step::Sprite { at, uv, size } => {
                    g.gp0_words(&[0x6500_0000, xy(at.0, at.1), (496 << 6) << 16 | uv.1 << 8 | uv.0, xy(size.0, size.1)]);
                    let top = if over_page { 0 } else { 400 };
                    for row in (0..size.1).filter(|&r| at.1 + r >= top) {
                        for col in 0..size.0 {
                            let u = (uv.0 + col) & 255;
                            let a = (uv.1 + row) as usize * 1024 + (PAGE_X + u / 4) as usize;
                            let h = m.read(a, ((a >> 2) & 3) | ((a >> 8) & 0xFC))[a & 3];
                            m.draw((at.0 + col, at.1 + row), clut[usize::from(h >> (4 * (u & 3)) & 0xF)]);
                        }
                    }
                }
                _ => m.fill_or_clear(&mut g, s),
            }
        }
        m.check(&g)?;
    }
}

/// The fact-sheet model of §10 the sprite property tests hold the GPU to: VRAM as it should
/// be, the cache's entries (index -> tag a / 4 and the four halfwords loaded on a miss) and
/// the misses counted since the model was made.
struct Model {
    vram: Vec<u16>,
    cache: HashMap<usize, (usize, [u16; 4])>,
    misses: u64,
    start: u64,
}

impl Model {
    fn new(g: &Gpu) -> Model {
        Model {
            vram: g.vram().as_slice().to_vec(),
            cache: HashMap::new(),
            misses: 0,
            start: g.texture_cache_misses(),
        }
    }

    /// The halfwords of the entry `i` that holds VRAM address `a`, loaded on a miss.
    fn read(&mut self, a: usize, i: usize) -> [u16; 4] {
        let tag = a >> 2;
        if self.cache.get(&i).map(|e| e.0) != Some(tag) {
            let f = tag * 4;
            let h = [
                self.vram[f],
                self.vram[f + 1],
                self.vram[f + 2],
                self.vram[f + 3],
            ];
            self.cache.insert(i, (tag, h));
            self.misses += 1;
        }
        self.cache[&i].1
    }

    /// A sprite pixel at (x, y): texel value 0000h leaves it as it is (§6).
    fn draw(&mut self, (x, y): (u32, u32), t: u16) {
        if t != 0 {
            self.vram[y as usize * 1024 + x as usize] = t;
        }
    }

    /// A fill (on the GPU and in the model's VRAM, the cache untouched) or a GP0(01h), which
    /// empties the cache.
    fn fill_or_clear(&mut self, g: &mut Gpu, s: &Step) {
        match *s {
            Step::Fill { at, size, c } => {
                fill(g, c, at, size);
                for row in 0..size.1 {
                    for col in 0..size.0 {
                        self.vram[(at.1 + row) as usize * 1024 + (at.0 + col) as usize] = c;
                    }
                }
            }
            Step::Clear => {
                g.gp0(0x0100_0000);
                self.cache.clear();
            }
            Step::Sprite { .. } => {}
        }
    }

    /// The GPU's VRAM and misses against the model's.
    fn check(&self, g: &Gpu) -> Result<(), TestCaseError> {
        prop_assert!(g.vram().as_slice() == &self.vram[..]);
        prop_assert_eq!(g.texture_cache_misses() - self.start, self.misses);
        Ok(())
    }
}

/// A textured triangle of [`triangles_track_reads_as_pixel_by_pixel`]: its kind (0 flat
/// 4-bit, 1 flat dithered 4-bit, 2 Gouraud 4-bit, 3 Gouraud 8-bit, 4 Gouraud 15-bit, 5 raw
/// 15-bit), vertices and texel coordinates.
#[derive(Clone, Debug)]
struct Textured {
    kind: u32,
    at: [(u32, u32); 3],
    uv: [(u32, u32); 3],
}

/// Triangles in lines 400-507 that step through their texels at or near their size (a
/// vertex's U and V follow its position, scaled by a quarter to two) or, one time in four,
/// anywhere in the page.
fn textured(kind: u32) -> impl Strategy<Value = Textured> {
    let corner = (0u32..400, 400u32..508);
    let scale = prop_oneof![Just(1u32), Just(2), Just(4), Just(8)];
    (
        [corner.clone(), corner.clone(), corner],
        (0u32..256, 0u32..256),
        scale,
        prop::bool::weighted(0.25),
        [(0u32..256, 0u32..256), (0u32..256, 0u32..256)],
    )
        .prop_map(move |(at, (u0, v0), scale, anywhere, far)| {
            // U and V move by `scale / 4` texels a pixel from vertex 0, kept in the page.
            let near = |(x, y): (u32, u32)| {
                let du = (x as i32 - at[0].0 as i32) * scale as i32 / 4;
                let dv = (y as i32 - at[0].1 as i32) * scale as i32 / 4;
                (
                    (u0 as i32 + du).clamp(0, 255) as u32,
                    (v0 as i32 + dv).clamp(0, 255) as u32,
                )
            };
            let uv = if anywhere {
                [(u0, v0), far[0], far[1]]
            } else {
                [(u0, v0), near(at[1]), near(at[2])]
            };
            Textured { kind, at, uv }
        })
}

/// Draw `t` with its texture page attribute naming the page at `PAGE_X` (CLUT at (0, 511)).
fn draw_textured(g: &mut Gpu, t: &Textured) {
    let depth = match t.kind {
        0..=2 => 0,
        3 => 1,
        _ => 2,
    };
    let texpage = (PAGE_X / 64) | (depth << 7);
    let clut = 511 << 6;
    let [a, b, c] = t.at;
    let [ua, ub, uc] = t.uv.map(|(u, v)| v << 8 | u);
    if t.kind == 1 {
        g.gp0(0xE100_0200 | texpage);
    }
    match t.kind {
        0 | 1 | 5 => {
            let cmd = if t.kind == 5 {
                0x2500_0000
            } else {
                0x2400_0000
            };
            g.gp0_words(&[
                cmd | 0x60_7080,
                xy(a.0, a.1),
                clut << 16 | ua,
                xy(b.0, b.1),
                texpage << 16 | ub,
                xy(c.0, c.1),
                uc,
            ]);
        }
        _ => g.gp0_words(&[
            0x3400_4080,
            xy(a.0, a.1),
            clut << 16 | ua,
            0x0080_6040,
            xy(b.0, b.1),
            texpage << 16 | ub,
            0x0020_C0A0,
            xy(c.0, c.1),
            uc,
        ]),
    }
    if t.kind == 1 {
        g.gp0(0xE100_0000 | texpage);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Textured triangles of every span routine that tracks its reads eight at a time (the
    /// eight-pixel groups at 4, 8 and 15-bit, the shaded and dithered 4-bit CLUT spans, raw
    /// 15-bit), mostly stepping through their texels slowly, leave the misses, the 256
    /// entries and the pixels of the same triangles drawn where the drawing area covers the
    /// page too, which keeps the entries' copies and reads them pixel by pixel, one read at
    /// a time (docs/gpu.md, "Texture cache").
    #[test]
    fn triangles_track_reads_as_pixel_by_pixel(
        tris in (0u32..6).prop_flat_map(|kind| prop::collection::vec(textured(kind), 1..5)),
    ) {
        let (mut lanes, mut one) = (gpu(false), gpu(true));
        for g in [&mut lanes, &mut one] {
            // Texels 1-255 of a diagonal ramp, so that 4-bit and 8-bit texels vary, and a
            // CLUT of non-zero colours.
            for y in 0..256u32 {
                let words: Vec<u32> = (0..128u32)
                    .map(|x| {
                        let t = |x: u32| (x + y) % 255 + 1;
                        t(2 * x) | t(2 * x + 1) << 16
                    })
                    .collect();
                g.gp0_words(&[0xA000_0000, xy(PAGE_X, y), xy(256, 1)]);
                g.gp0_words(&words);
            }
            let clut: Vec<u32> = (0..128u32).map(|i| (0x0421 * (2 * i % 31 + 1)) | (0x0421 * ((2 * i + 1) % 31 + 1)) << 16).collect();
            g.gp0_words(&[0xA000_0000, xy(0, 511), xy(256, 1)]);
            g.gp0_words(&clut);
        }
        let start = (lanes.texture_cache_misses(), one.texture_cache_misses());
        for t in &tris {
            draw_textured(&mut lanes, t);
            draw_textured(&mut one, t);
        }
        prop_assert_eq!(
            lanes.texture_cache_misses() - start.0,
            one.texture_cache_misses() - start.1
        );
        for i in 0..=255u8 {
            prop_assert_eq!(lanes.texture_cache_entry(i), one.texture_cache_entry(i), "entry {}", i);
        }
        prop_assert!(lanes.vram().as_slice() == one.vram().as_slice());
    }
}

/// The xorshift32 sequence from `seed` (made odd): a case's VRAM contents.
fn xorshift(seed: u32) -> impl FnMut() -> u32 {
    let mut state = seed | 1;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

/// A texel from `next`: 0000h (a transparent texel) one time in four, else a halfword with
/// bit 0 set.
fn texel_of(next: &mut impl FnMut() -> u32) -> u16 {
    let r = next();
    if r & 3 == 0 { 0 } else { (r >> 8) as u16 | 1 }
}

/// Upload `w` x `h` halfwords at (x, y) (GP0(A0h)), taken from `next`.
fn upload(g: &mut Gpu, (x, y): (u32, u32), (w, h): (u32, u32), mut next: impl FnMut() -> u16) {
    g.gp0_words(&[0xA000_0000, xy(x, y), xy(w, h)]);
    let words: Vec<u32> = (0..w * h / 2)
        .map(|_| u32::from(next()) | u32::from(next()) << 16)
        .collect();
    g.gp0_words(&words);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Raw 15-bit triangles whose page lies clear of the drawing area are drawn with the tags
    /// tracked eight pixels at a time, each group's texels read before its pixels are
    /// written (docs/gpu.md, "Texture cache"). Over a page of random texels, about one in
    /// four 0000h (transparent: the pixel keeps its value) and half of the others with bit
    /// 15 set, onto random pixels, opaque or semi-transparent, with the mask bit set or not
    /// and checked or not (E6h), they leave the pixels of the same triangles drawn with the
    /// cache off, pixel by pixel, reading VRAM (docs/hardware/gpu.md §6). The triangles reach
    /// the right edge and the last line of VRAM, where a group of eight runs past its end.
    #[test]
    fn raw15_groups_draw_as_pixel_by_pixel(
        tris in prop::collection::vec(
            ([(0u32..1024, 400u32..512), (0u32..1024, 400u32..512), (0u32..1024, 400u32..512)],
             [(0u32..256, 0u32..256), (0u32..256, 0u32..256), (0u32..256, 0u32..256)],
             any::<bool>()),
            1..6,
        ),
        (set, check) in any::<(bool, bool)>(),
        seed in any::<u32>(),
    ) {
        let (mut groups, mut pixels) = (gpu(false), gpu(false));
        pixels.set_texture_cache(false);
        for g in [&mut groups, &mut pixels] {
            let mut next = xorshift(seed);
            let mut texel = || texel_of(&mut next);
            upload(g, (PAGE_X, 0), (256, 256), &mut texel);
            upload(g, (0, 400), (1024, 112), || next() as u16);
            g.gp0(0xE600_0000 | u32::from(set) | u32::from(check) << 1);
            for (at, uv, semi) in &tris {
                let [a, b, c] = *at;
                let [ua, ub, uc] = uv.map(|(u, v)| v << 8 | u);
                let texpage = (PAGE_X / 64) | 2 << 7;
                g.gp0_words(&[
                    0x2500_0000 | u32::from(*semi) << 25,
                    xy(a.0, a.1),
                    ua,
                    xy(b.0, b.1),
                    texpage << 16 | ub,
                    xy(c.0, c.1),
                    uc,
                ]);
            }
        }
        prop_assert!(groups.vram().as_slice() == pixels.vram().as_slice());
    }
}

/// A flat textured triangle of [`blended_groups_draw_as_pixel_by_pixel`]: its texture (0
/// 4-bit modulated, 1 4-bit raw, 2 15-bit raw, 3 15-bit modulated), semi-transparent or not,
/// its blend mode (texpage bits 5-6), dithered or not, its colour, vertices and texel
/// coordinates.
#[derive(Clone, Debug)]
struct Blended {
    kind: u32,
    semi: bool,
    mode: u32,
    dither: bool,
    color: u32,
    at: [(u32, u32); 3],
    uv: [(u32, u32); 3],
}

fn blended() -> impl Strategy<Value = Blended> {
    let corner = (0u32..1024, 400u32..512);
    let uv = (0u32..256, 0u32..256);
    (
        (0u32..4, prop::bool::weighted(0.8), 0u32..4, any::<bool>()),
        0u32..0x100_0000,
        [corner.clone(), corner.clone(), corner],
        [uv.clone(), uv.clone(), uv],
    )
        .prop_map(|((kind, semi, mode, dither), color, at, uv)| Blended {
            kind,
            semi,
            mode,
            dither,
            color,
            at,
            uv,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Semi-transparent and mask-checked 4-bit CLUT and raw 15-bit triangles whose page lies
    /// clear of the drawing area are written eight pixels at a time, the group's texels read
    /// before its eight pixels are read back, blended and written (docs/gpu.md, "Texture
    /// cache"). In every blend mode, with the mask bit set or not and checked or not (E6h),
    /// over texels and CLUT entries of which some are 0000h (transparent) and half the others
    /// have bit 15 set (blended), onto random pixels half of which have bit 15 set, they
    /// leave the pixels, the misses and the 256 entries of the same triangles drawn where the
    /// drawing area covers the page, which reads the entries' copies and writes pixel by
    /// pixel (docs/hardware/gpu.md §6, §10). The triangles reach the right edge and the last
    /// line of VRAM, where a group of eight runs past its end.
    #[test]
    fn blended_groups_draw_as_pixel_by_pixel(
        tris in prop::collection::vec(blended(), 1..6),
        (set, check) in any::<(bool, bool)>(),
        seed in any::<u32>(),
    ) {
        let (mut groups, mut pixels) = (gpu(false), gpu(true));
        // The CLUT, on a line neither primitive draws.
        let clut_y = 300;
        for g in [&mut groups, &mut pixels] {
            let mut next = xorshift(seed);
            let mut texel = || texel_of(&mut next);
            upload(g, (PAGE_X, 0), (256, 256), &mut texel);
            upload(g, (0, clut_y), (16, 1), &mut texel);
            upload(g, (0, 400), (1024, 112), || next() as u16);
            g.gp0(0xE600_0000 | u32::from(set) | u32::from(check) << 1);
            for t in &tris {
                let depth = if t.kind < 2 { 0 } else { 2 };
                let texpage = (PAGE_X / 64) | t.mode << 5 | depth << 7;
                g.gp0(0xE100_0000 | u32::from(t.dither) << 9 | texpage);
                let raw = u32::from(t.kind == 1 || t.kind == 2);
                let [a, b, c] = t.at;
                let [ua, ub, uc] = t.uv.map(|(u, v)| v << 8 | u);
                g.gp0_words(&[
                    0x2400_0000 | u32::from(t.semi) << 25 | raw << 24 | t.color,
                    xy(a.0, a.1),
                    (clut_y << 6) << 16 | ua,
                    xy(b.0, b.1),
                    texpage << 16 | ub,
                    xy(c.0, c.1),
                    uc,
                ]);
            }
        }
        prop_assert_eq!(groups.texture_cache_misses(), pixels.texture_cache_misses());
        for i in 0..=255u8 {
            prop_assert_eq!(groups.texture_cache_entry(i), pixels.texture_cache_entry(i), "entry {}", i);
        }
        prop_assert!(groups.vram().as_slice() == pixels.vram().as_slice());
    }
}
