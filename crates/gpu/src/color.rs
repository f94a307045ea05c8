//! The colour pipeline: 15-bit packing, the 4x4 dither matrix, texture modulation and the
//! four semi-transparency modes (docs/hardware/gpu.md §6).

use crate::state::BlendMode;

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

/// Blend new pixel `f` over VRAM pixel `b` per 5-bit channel (docs/hardware/gpu.md §6). Bit 15 of the
/// result is zero.
#[inline(always)]
pub fn blend(mode: BlendMode, b: u16, f: u16) -> u16 {
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
