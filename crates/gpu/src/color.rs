//! The colour pipeline: 15-bit packing, the 4x4 dither matrix, texture modulation and the
//! four semi-transparency modes (docs/hardware/gpu.md §6).

use crate::state::BlendMode;
use wide::u16x8;

/// The dither offsets, indexed `[y & 3][x & 3]` (docs/hardware/gpu.md §6).
pub const DITHER_MATRIX: [[i32; 4]; 4] = [
    [-4, 0, -3, 1],
    [2, -2, 3, -1],
    [-3, 1, -4, 0],
    [3, -1, 2, -2],
];

/// A 9-bit intensity (an 8-bit colour, or a modulated texel channel `(t5 * c8) >> 4`, at
/// most 494) to its 5-bit value for one dither offset: `clamp(i + offset, 0, 255) >> 3`
/// (docs/hardware/gpu.md §6). Indexed with `i & 511`.
pub type ShadeTable = [u8; 512];

const fn shade_table(offset: i32) -> ShadeTable {
    let mut t = [0u8; 512];
    let mut i = 0;
    while i < 512 {
        let c = i as i32 + offset;
        let c = if c < 0 {
            0
        } else if c > 255 {
            255
        } else {
            c
        };
        t[i] = (c >> 3) as u8;
        i += 1;
    }
    t
}

const fn dither_tables() -> [[ShadeTable; 4]; 4] {
    let mut t = [[[0u8; 512]; 4]; 4];
    let mut y = 0;
    while y < 4 {
        let mut x = 0;
        while x < 4 {
            t[y][x] = shade_table(DITHER_MATRIX[y][x]);
            x += 1;
        }
        y += 1;
    }
    t
}

/// One [`ShadeTable`] per dither matrix cell, indexed `[y & 3][x & 3]` (docs/hardware/gpu.md §6).
pub static DITHER_TABLES: [[ShadeTable; 4]; 4] = dither_tables();

/// The [`ShadeTable`] of undithered pixels: `min(i, 255) >> 3` (docs/hardware/gpu.md §6).
pub static PLAIN_TABLE: ShadeTable = shade_table(0);

/// 8-bit channel to 5 bits with a dither offset: clamp(c + d, 0, 255) >> 3 (docs/hardware/gpu.md §6).
#[inline(always)]
#[cfg(test)]
pub fn dither_channel(c: i32, offset: i32) -> u16 {
    ((c + offset).clamp(0, 255) >> 3) as u16
}

/// Pack 5-bit R, G, B into 15-bit BGR (docs/hardware/gpu.md §1).
#[inline(always)]
pub const fn pack555(r: u16, g: u16, b: u16) -> u16 {
    r | (g << 5) | (b << 10)
}

/// A 24-bit command colour (R in bits 0-7) as 8-bit channels.
#[inline(always)]
pub const fn unpack888(color: u32) -> [u8; 3] {
    [color as u8, (color >> 8) as u8, (color >> 16) as u8]
}

/// Modulate a 5-bit texel channel by an 8-bit colour and dither:
/// clamp(((t5 * c8) >> 4) + dither, 0, 255) >> 3 (docs/hardware/gpu.md §6). 80h is the identity.
#[inline(always)]
#[cfg(test)]
pub fn modulate_channel(t5: u16, c8: i32, offset: i32) -> u16 {
    dither_channel((t5 as i32 * c8) >> 4, offset)
}

/// The three 5-bit channels of a 15-bit colour spread to bits 0-4, 6-10 and 12-16, so that a
/// per-channel sum or difference carries into the free bit above its channel (5, 11, 17)
/// instead of into the next channel.
#[inline(always)]
const fn spread(c: u16) -> u32 {
    let c = c as u32;
    (c & 0x1F) | ((c & 0x3E0) << 1) | ((c & 0x7C00) << 2)
}

/// The inverse of [`spread`] on the channel bits.
#[inline(always)]
const fn compact(s: u32) -> u16 {
    ((s & 0x1F) | ((s >> 1) & 0x3E0) | ((s >> 2) & 0x7C00)) as u16
}

/// The carry bit above each spread channel.
const CARRIES: u32 = 1 << 5 | 1 << 11 | 1 << 17;

/// 31 in every spread channel whose carry bit is set in `carries`, 0 elsewhere.
#[inline(always)]
const fn fill_channels(carries: u32) -> u32 {
    carries - (carries >> 5)
}

/// Per-channel `min(b + f, 31)` on spread channels (each input channel at most 31).
#[inline(always)]
const fn add_saturate(b: u32, f: u32) -> u16 {
    let sum = b + f;
    compact(sum | fill_channels(sum & CARRIES))
}

/// Blend new pixel `f` over VRAM pixel `b` per 5-bit channel (docs/hardware/gpu.md §6):
/// B/2+F/2 (floored), B+F, B-F and B+F/4, each clamped to 0..31. Bit 15 of the result is
/// zero. All three channels are computed at once, branch-free, in one 32-bit word.
#[inline(always)]
pub fn blend(mode: BlendMode, b: u16, f: u16) -> u16 {
    let (b, f) = (b & 0x7FFF, f & 0x7FFF);
    match mode {
        // (b + f) >> 1 = (b >> 1) + (f >> 1) + (b & f & 1) per channel.
        BlendMode::Average => ((b & 0x7BDE) >> 1) + ((f & 0x7BDE) >> 1) + (b & f & 0x0421),
        BlendMode::Add => add_saturate(spread(b), spread(f)),
        BlendMode::Subtract => {
            // 32 + b - f per channel: the carry bit survives exactly when b >= f.
            let diff = (spread(b) | CARRIES) - spread(f);
            compact(diff & fill_channels(diff & CARRIES))
        }
        BlendMode::AddQuarter => add_saturate(spread(b), (spread(f) >> 2) & 0x71C7),
    }
}

/// Red and blue of a 15-bit colour (bits 0-4 and 10-14): each has five free bits or the top
/// of the halfword above it, so a per-channel sum carries into bit 5 or 15.
const RED_BLUE: u16 = 0x7C1F;

/// Green of a 15-bit colour (bits 5-9), whose sum carries into bit 10.
const GREEN: u16 = 0x03E0;

/// The carry bits of [`RED_BLUE`] sums.
const RED_BLUE_CARRIES: u16 = 0x8020;

/// The carry bit of [`GREEN`] sums.
const GREEN_CARRY: u16 = 0x0400;

/// 31 in every channel whose carry bit (5, 10 or 15) is set in `carries`, 0 elsewhere.
#[inline(always)]
fn fill_lanes(carries: u16x8) -> u16x8 {
    carries - carries.unbounded_shr_scalar(5)
}

/// Per-channel `min(b + f, 31)` of eight pixels: red and blue summed in one halfword, green in
/// another, each channel's carry filling it with 31.
#[inline(always)]
fn add_saturate_lanes(b: u16x8, f: u16x8) -> u16x8 {
    let (rb_mask, g_mask) = (u16x8::splat(RED_BLUE), u16x8::splat(GREEN));
    let rb = (b & rb_mask) + (f & rb_mask);
    let g = (b & g_mask) + (f & g_mask);
    let sums = (rb & rb_mask) | (g & g_mask);
    sums | fill_lanes((rb & u16x8::splat(RED_BLUE_CARRIES)) | (g & u16x8::splat(GREEN_CARRY)))
}

/// [`blend`] of eight pixels at once, VRAM pixels `b` over new pixels `f` lane by lane
/// (docs/hardware/gpu.md §6): B/2+F/2 (floored), B+F, B-F and B+F/4, each channel clamped to
/// 0..31. Bit 15 of each result is zero.
#[inline(always)]
pub(crate) fn blend_lanes(mode: BlendMode, b: u16x8, f: u16x8) -> u16x8 {
    let splat = u16x8::splat;
    match mode {
        // (b + f) >> 1 = (b >> 1) + (f >> 1) + (b & f & 1) per channel.
        BlendMode::Average => {
            let halves = splat(0x7BDE);
            (b & halves).unbounded_shr_scalar(1)
                + (f & halves).unbounded_shr_scalar(1)
                + (b & f & splat(0x0421))
        }
        BlendMode::Add => add_saturate_lanes(b, f),
        BlendMode::Subtract => {
            // 32 + b - f per channel: the carry bit survives exactly when b >= f.
            let (rb_mask, g_mask) = (splat(RED_BLUE), splat(GREEN));
            let (rb_carries, g_carry) = (splat(RED_BLUE_CARRIES), splat(GREEN_CARRY));
            let rb = ((b & rb_mask) | rb_carries) - (f & rb_mask);
            let g = ((b & g_mask) | g_carry) - (f & g_mask);
            let carries = (rb & rb_carries) | (g & g_carry);
            ((rb & rb_mask) | (g & g_mask)) & fill_lanes(carries)
        }
        BlendMode::AddQuarter => add_saturate_lanes(b, f.unbounded_shr_scalar(2) & splat(0x1CE7)),
    }
}

/// [`blend`] one channel at a time: the reference the packed form is tested against.
#[cfg(test)]
pub fn blend_per_channel(mode: BlendMode, b: u16, f: u16) -> u16 {
    let mut out = 0;
    let mut shift = 0;
    while shift < 15 {
        let bc = ((b >> shift) & 0x1F) as i32;
        let fc = ((f >> shift) & 0x1F) as i32;
        let c = match mode {
            BlendMode::Average => (bc + fc) >> 1,
            BlendMode::Add => (bc + fc).min(31),
            BlendMode::Subtract => (bc - fc).max(0),
            BlendMode::AddQuarter => (bc + (fc >> 2)).min(31),
        };
        out |= (c as u16) << shift;
        shift += 5;
    }
    out
}

/// A 4-bit CLUT's 16 entries modulated by one colour and dithered, for each of the 16 cells
/// of the dither matrix (docs/hardware/gpu.md §6), indexed `[y & 3][x & 3][entry]`. Entries are
/// coded as [`shaded_clut4`] codes them.
pub(crate) type DitheredCells = [[[u32; 16]; 4]; 4];

/// The 16 CLUT entries of a 4-bit texture shaded once for a primitive whose colour `rgb` and
/// shade table are the same at every pixel (docs/hardware/gpu.md §6): what the rasterizer's
/// `shade_pixel` computes per texel, per entry instead. Raw textures keep the entry as it
/// is; a shaded entry is coded `1_0000h | colour | bit 15`, a transparent one 0.
pub(crate) fn shaded_clut4(clut: &[u16; 256], rgb: [i32; 3], raw: bool) -> [u32; 16] {
    // The channels of a command colour are 0..=255, so (t5 * c8) >> 4 is at most 494 and
    // the undithered table's `min(i, 255) >> 3` is worked out: no lookup, so the 16 entries
    // are shaded side by side.
    let rgb = rgb.map(|c| c.clamp(0, 255) as u32);
    let c5 = |t: u32, c: u32| (((t & 0x1F) * c) >> 4).min(255) >> 3;
    core::array::from_fn(|i| {
        let t = u32::from(clut[i]);
        let shaded = if raw {
            t & 0x7FFF
        } else {
            c5(t, rgb[0]) | c5(t >> 5, rgb[1]) << 5 | c5(t >> 10, rgb[2]) << 10
        };
        let entry = 0x1_0000 | shaded | (t & 0x8000);
        if t == 0 { 0 } else { entry }
    })
}

/// The 16 CLUT entries of a 4-bit texture modulated by one colour `rgb` and dithered, for
/// each cell of the dither matrix (docs/hardware/gpu.md §6): [`shaded_clut4`] with the cell's
/// table instead of the undithered one, coded the same way.
pub(crate) fn dithered_clut4(clut: &[u16; 256], rgb: [u8; 3], out: &mut DitheredCells) {
    let rgb = rgb.map(i32::from);
    // Each entry's three modulated channels, (t5 * c8) >> 4, before the dither.
    let modulated: [[usize; 3]; 16] = core::array::from_fn(|i| {
        let t = i32::from(clut[i]);
        [
            (((t & 0x1F) * rgb[0]) >> 4) as usize & 511,
            ((((t >> 5) & 0x1F) * rgb[1]) >> 4) as usize & 511,
            ((((t >> 10) & 0x1F) * rgb[2]) >> 4) as usize & 511,
        ]
    });
    for (row, tables) in out.iter_mut().zip(&DITHER_TABLES) {
        for (cell, table) in row.iter_mut().zip(tables) {
            for ((entry, &t), m) in cell.iter_mut().zip(clut.iter()).zip(&modulated) {
                let c = |i: usize| u16::from(table[i]);
                let shaded = pack555(c(m[0]), c(m[1]), c(m[2]));
                *entry = if t == 0 {
                    0
                } else {
                    0x1_0000 | u32::from(shaded | (t & 0x8000))
                };
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blend_modes_on_chosen_colours() {
        let b = pack555(31, 10, 0);
        let f = pack555(16, 4, 31);
        // docs/hardware/gpu.md §6: mode 0 floors, (31+16)>>1 = 23.
        assert_eq!(blend(BlendMode::Average, b, f), pack555(23, 7, 15));
        assert_eq!(blend(BlendMode::Add, b, f), pack555(31, 14, 31));
        assert_eq!(blend(BlendMode::Subtract, b, f), pack555(15, 6, 0));
        assert_eq!(blend(BlendMode::AddQuarter, b, f), pack555(31, 11, 7));
    }

    const MODES: [BlendMode; 4] = [
        BlendMode::Average,
        BlendMode::Add,
        BlendMode::Subtract,
        BlendMode::AddQuarter,
    ];

    /// Every channel pair, in all three channels at once and in each channel alone with the
    /// other channels at their extremes, bit 15 set or not on either side.
    #[test]
    fn packed_blend_equals_per_channel_blend_on_every_channel_pair() {
        for mode in MODES {
            for bc in 0..32u16 {
                for fc in 0..32u16 {
                    let same = |c: u16| pack555(c, c, c);
                    let check = |b: u16, f: u16| {
                        let expected = blend_per_channel(mode, b, f);
                        assert_eq!(blend(mode, b, f), expected, "{mode:?} {b:04x} {f:04x}");
                        let lanes = blend_lanes(mode, u16x8::splat(b), u16x8::splat(f));
                        assert_eq!(lanes, u16x8::splat(expected), "{mode:?} {b:04x} {f:04x}");
                    };
                    check(same(bc), same(fc));
                    check(same(bc) | 0x8000, same(fc) | 0x8000);
                    for shift in [0, 5, 10] {
                        for other in [0u16, 31] {
                            let rest = same(other) & !(0x1F << shift);
                            check(rest | bc << shift, rest | fc << shift);
                            check(rest | bc << shift, (0x7FFF & !rest) | fc << shift);
                        }
                    }
                }
            }
        }
    }

    proptest::proptest! {
        #[test]
        fn packed_blend_equals_per_channel_blend(b: u16, f: u16) {
            for mode in MODES {
                proptest::prop_assert_eq!(blend(mode, b, f), blend_per_channel(mode, b, f));
            }
        }

        /// Each lane of the eight-pixel blend is the blend of its own two pixels.
        #[test]
        fn lane_blend_equals_per_channel_blend(b: [u16; 8], f: [u16; 8]) {
            for mode in MODES {
                let lanes = blend_lanes(mode, u16x8::new(b), u16x8::new(f)).to_array();
                let expected: [u16; 8] =
                    core::array::from_fn(|k| blend_per_channel(mode, b[k], f[k]));
                proptest::prop_assert_eq!(lanes, expected, "{:?}", mode);
            }
        }
    }

    #[test]
    fn modulation_identity_and_range() {
        // (t5 * 128) >> 4 = t5 << 3, and >> 3 gives t5 back.
        for t in 0..32 {
            assert_eq!(modulate_channel(t, 128, 0), t);
        }
        // (31 * 255) >> 4 = 494, clamped to 255 -> 31.
        assert_eq!(modulate_channel(31, 255, 0), 31);
        // (10 * 64) >> 4 = 40, + dither 3 = 43 -> 5.
        assert_eq!(modulate_channel(10, 64, 3), 5);
    }

    #[test]
    fn tables_agree_with_the_formulas() {
        for y in 0..4 {
            for x in 0..4 {
                let d = DITHER_MATRIX[y][x];
                for (i, &c5) in DITHER_TABLES[y][x].iter().enumerate() {
                    assert_eq!(c5 as i32, (i as i32 + d).clamp(0, 255) >> 3);
                }
            }
        }
        assert_eq!(PLAIN_TABLE[0], 0);
        assert_eq!(PLAIN_TABLE[255], 31);
        assert_eq!(PLAIN_TABLE[494], 31);
        assert_eq!(PLAIN_TABLE[132], 16);
    }

    #[test]
    fn dither_clamps() {
        assert_eq!(dither_channel(2, -4), 0);
        assert_eq!(dither_channel(254, 3), 31);
        assert_eq!(dither_channel(15, 1), 2);
    }
}
