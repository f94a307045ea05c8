//! The arithmetic every command shares, as docs/hardware/gte.md §3-§4 state it: MAC1-3 sums
//! in 44 bits with a test and a wrap after each addition, IR1-3 saturation, MAC0 in 64 bits,
//! and the colour FIFO push. Every value is kept exact beside what the registers receive.

use crate::{Flag, Registers};

/// FLAG bits by condition (docs/hardware/gte.md §3).
pub(super) mod bit {
    /// MACn above 2^43 - 1, n = 1..=3.
    pub const fn mac_positive(n: usize) -> u32 {
        1 << (31 - n)
    }
    /// MACn below -2^43.
    pub const fn mac_negative(n: usize) -> u32 {
        1 << (28 - n)
    }
    /// IRn saturated.
    pub const fn ir(n: usize) -> u32 {
        1 << (25 - n)
    }
    /// Colour channel n (1 = R) saturated.
    pub const fn color(n: usize) -> u32 {
        1 << (22 - n)
    }
    pub const SZ3_OTZ: u32 = 1 << 18;
    pub const DIVIDE: u32 = 1 << 17;
    pub const MAC0_POSITIVE: u32 = 1 << 16;
    pub const MAC0_NEGATIVE: u32 = 1 << 15;
    pub const SX2: u32 = 1 << 14;
    pub const SY2: u32 = 1 << 13;
    pub const IR0: u32 = 1 << 12;
}

/// FLAG holding condition bits `bits` with bit 31 set from them as a command leaves it: the
/// OR of bits 30-23 and 18-13 (docs/hardware/gte.md §3).
pub(super) fn flag(bits: u32) -> Flag {
    let summary = if bits & 0x7F87_E000 != 0 { 1 << 31 } else { 0 };
    Flag::from_bits(bits | summary)
}

/// The 44-bit range of MAC1-3's accumulator.
const ACC_MAX: i64 = (1 << 43) - 1;
const ACC_MIN: i64 = -(1 << 43);

/// `value` wrapped to 44-bit two's complement.
fn wrap44(value: i64) -> i64 {
    let low = value.rem_euclid(1 << 44);
    if low > ACC_MAX { low - (1 << 44) } else { low }
}

/// One row of a step: a MAC1-3 sum and the IR saturated from it (docs/hardware/gte.md §4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Row {
    /// The start value plus every product, never wrapped: the mathematical sum.
    pub exact: i64,
    /// The 44-bit accumulator after the last addition, tested and wrapped after each one.
    pub acc: i64,
    /// MACn: the low 32 bits of `acc` SAR (sf × 12).
    pub mac: i32,
    /// IRn: `mac` saturated to the step's range (-8000h or 0 up to 7FFFh).
    pub ir: i16,
}

/// One step of a command: three rows (MAC1-3, IR1-3) and the FLAG bits they set (MAC1-3
/// overflows 30-25, IR saturations 24-22, with bit 31 when one of them is an error source).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Step {
    /// Rows 1, 2, 3.
    pub rows: [Row; 3],
    /// The FLAG bits this step set.
    pub flag: Flag,
}

impl Step {
    /// The three exact sums.
    pub fn exact(&self) -> [i64; 3] {
        self.rows.map(|r| r.exact)
    }

    /// MAC1-3.
    pub fn mac(&self) -> [i32; 3] {
        self.rows.map(|r| r.mac)
    }

    /// IR1-3.
    pub fn ir(&self) -> [i16; 3] {
        self.rows.map(|r| r.ir)
    }
}

/// IR's lower limit: 0 with lm, -8000h without.
pub(super) fn ir_min(lm: bool) -> i64 {
    if lm { 0 } else { -0x8000 }
}

/// A MAC1-3 sum for row `n` (1..=3): start from `start`, add each product in turn, testing the
/// running sum against the 44-bit range and wrapping it after each addition
/// (docs/hardware/gte.md §4). Returns the exact sum, the wrapped accumulator and the bits.
pub(super) fn sum(n: usize, start: i64, products: &[i64]) -> (i64, i64, u32) {
    let mut exact = start;
    let mut acc = start;
    let mut bits = 0;
    for &p in products {
        exact += p;
        acc += p;
        if acc > ACC_MAX {
            bits |= bit::mac_positive(n);
        } else if acc < ACC_MIN {
            bits |= bit::mac_negative(n);
        }
        acc = wrap44(acc);
    }
    (exact, acc, bits)
}

/// MACn = low 32 bits of `acc` SAR `shift` (arithmetic: floor).
pub(super) fn mac_of(acc: i64, shift: u32) -> i32 {
    (acc >> shift) as i32
}

/// `value` saturated to `min..=max`, and whether it was outside.
pub(super) fn saturate(value: i64, min: i64, max: i64) -> (i64, bool) {
    (value.clamp(min, max), value < min || value > max)
}

/// One step of three rows: row n sums `start[n]` and `products[n]` (§4), MACn from it, IRn
/// from MACn saturated by `lm` (FLAG bit 25 - n). The caller stores the result.
pub(super) fn step(start: [i64; 3], products: [&[i64]; 3], shift: u32, lm: bool) -> Step {
    let mut bits = 0;
    let mut rows = [Row::default(); 3];
    for (i, row) in rows.iter_mut().enumerate() {
        let n = i + 1;
        let (exact, acc, overflow) = sum(n, start[i], products[i]);
        let mac = mac_of(acc, shift);
        let (ir, saturated) = saturate(mac as i64, ir_min(lm), 0x7FFF);
        bits |= overflow;
        if saturated {
            bits |= bit::ir(n);
        }
        *row = Row {
            exact,
            acc,
            mac,
            ir: ir as i16,
        };
    }
    Step {
        rows,
        flag: flag(bits),
    }
}

/// MAC1-3 and IR1-3 of `step` written to the registers.
pub(super) fn store(regs: &mut Registers, step: &Step) {
    for n in 0..3 {
        regs.mac[n + 1] = step.rows[n].mac;
        regs.ir[n + 1] = step.rows[n].ir;
    }
}

/// The rows of `m` times `v`, each row's products in column order.
pub(super) fn products(m: [[i16; 3]; 3], v: [i64; 3]) -> [[i64; 3]; 3] {
    m.map(|row| [0, 1, 2].map(|c| row[c] as i64 * v[c]))
}

/// MAC0 from a 64-bit value: FLAG bit 16 above 2^31 - 1, bit 15 below -2^31, the low 32 bits
/// kept (docs/hardware/gte.md §4).
pub(super) fn mac0_bits(value: i64) -> u32 {
    if value > i32::MAX as i64 {
        bit::MAC0_POSITIVE
    } else if value < i32::MIN as i64 {
        bit::MAC0_NEGATIVE
    } else {
        0
    }
}

/// A colour FIFO entry as a command pushes it (docs/hardware/gte.md §4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Color {
    /// MAC1-3 SAR 4 (arithmetic: floor), before the saturation to 0..=FFh.
    pub exact: [i32; 3],
    /// R, G, B as pushed: `exact` saturated to 0..=FFh (FLAG bits 21, 20, 19).
    pub rgb: [u8; 3],
    /// The CODE byte, from RGBC bits 24-31.
    pub code: u8,
    /// The FLAG bits the saturation set.
    pub flag: Flag,
}

/// Push MAC1-3 as a colour: Cn = clamp(MACn SAR 4, 0, FFh), RGB0 takes RGB1, RGB1 takes RGB2,
/// RGB2 = R | G << 8 | B << 16 | CODE << 24 (docs/hardware/gte.md §4).
pub(super) fn push_color(regs: &mut Registers) -> Color {
    let exact = [1, 2, 3].map(|n| regs.mac[n] >> 4);
    let mut bits = 0;
    let mut rgb = [0u8; 3];
    for i in 0..3 {
        let (c, saturated) = saturate(exact[i] as i64, 0, 0xFF);
        rgb[i] = c as u8;
        if saturated {
            bits |= bit::color(i + 1);
        }
    }
    let code = (regs.rgbc >> 24) as u8;
    regs.rgb = [
        regs.rgb[1],
        regs.rgb[2],
        u32::from_le_bytes([rgb[0], rgb[1], rgb[2], code]),
    ];
    Color {
        exact,
        rgb,
        code,
        flag: flag(bits),
    }
}

/// IR1-3 as a vector.
pub(super) fn ir_vector(regs: &Registers) -> [i64; 3] {
    [1, 2, 3].map(|n| regs.ir[n] as i64)
}

/// The union of FLAG sets.
pub(super) fn union(flags: &[Flag]) -> Flag {
    flag(
        flags
            .iter()
            .fold(0, |bits, f| bits | (f.bits() & 0x7FFF_F000)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_and_flags() {
        assert_eq!(wrap44(ACC_MAX + 1), ACC_MIN);
        assert_eq!(wrap44(ACC_MIN - 1), ACC_MAX);
        // Past the top after the first product, so wrapped to the bottom, then below it after
        // the second: both flags, and the sum wraps back (docs/hardware/gte.md §4).
        let (exact, acc, bits) = sum(1, ACC_MAX, &[1, -1]);
        assert_eq!((exact, acc), (ACC_MAX, ACC_MAX));
        assert_eq!(bits, bit::mac_positive(1) | bit::mac_negative(1));
        let (exact, acc, bits) = sum(2, ACC_MAX - 5, &[3, 3, -10]);
        assert_eq!((exact, acc), (ACC_MAX - 9, ACC_MAX - 9));
        assert_eq!(bits, bit::mac_positive(2) | bit::mac_negative(2));
        assert_eq!(flag(bit::IR0).bits(), 0x1000);
        assert_eq!(flag(bit::ir(1)).bits(), 0x8100_0000);
    }
}
