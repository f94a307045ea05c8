//! NCLIP, AVSZ3 and AVSZ4 as docs/hardware/gte.md §7 states them.

use super::arithmetic::{self, bit, flag, saturate};
use crate::{Flag, Registers};

/// NCLIP's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Nclip {
    /// SX0·SY1 + SX1·SY2 + SX2·SY0 - SX0·SY2 - SX1·SY0 - SX2·SY1, exact: twice the signed
    /// area of the triangle SXY0, SXY1, SXY2.
    pub exact: i64,
    /// MAC0: the low 32 bits of `exact` (FLAG bit 16 or 15 when it does not fit).
    pub mac0: i32,
    /// FLAG after the command.
    pub flag: Flag,
}

/// AVSZ3's or AVSZ4's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct AverageZ {
    /// SZ1 + SZ2 + SZ3 (AVSZ3) or SZ0 + SZ1 + SZ2 + SZ3 (AVSZ4).
    pub sum: i64,
    /// S = ZSF3 × sum or ZSF4 × sum, exact.
    pub exact: i64,
    /// MAC0: the low 32 bits of S (FLAG bit 16 or 15 when it does not fit).
    pub mac0: i32,
    /// S SAR 12 (arithmetic: floor), before OTZ's saturation.
    pub unsaturated_otz: i64,
    /// OTZ: S SAR 12 saturated to 0..=FFFFh (FLAG bit 18).
    pub otz: u16,
    /// FLAG after the command.
    pub flag: Flag,
}

/// NCLIP (docs/hardware/gte.md §7). Updates `regs`, FLAG included.
pub fn nclip(regs: &mut Registers) -> Nclip {
    let p = regs
        .sxy
        .map(|w| ((w as u16 as i16) as i64, ((w >> 16) as u16 as i16) as i64));
    let [(x0, y0), (x1, y1), (x2, y2)] = p;
    let exact = x0 * y1 + x1 * y2 + x2 * y0 - x0 * y2 - x1 * y0 - x2 * y1;
    let flag = flag(arithmetic::mac0_bits(exact));
    regs.mac[0] = exact as i32;
    regs.flag = flag;
    Nclip {
        exact,
        mac0: exact as i32,
        flag,
    }
}

fn average(regs: &mut Registers, scale: i16, sum: i64) -> AverageZ {
    let exact = scale as i64 * sum;
    let mut bits = arithmetic::mac0_bits(exact);
    let unsaturated_otz = exact >> 12;
    let (otz, saturated) = saturate(unsaturated_otz, 0, 0xFFFF);
    if saturated {
        bits |= bit::SZ3_OTZ;
    }
    let flag = flag(bits);
    regs.mac[0] = exact as i32;
    regs.otz = otz as u16;
    regs.flag = flag;
    AverageZ {
        sum,
        exact,
        mac0: exact as i32,
        unsaturated_otz,
        otz: otz as u16,
        flag,
    }
}

/// AVSZ3 (docs/hardware/gte.md §7): ZSF3 × (SZ1 + SZ2 + SZ3). Updates `regs`, FLAG included.
pub fn avsz3(regs: &mut Registers) -> AverageZ {
    let sum = regs.sz[1..].iter().map(|&z| z as i64).sum();
    average(regs, regs.zsf3, sum)
}

/// AVSZ4 (docs/hardware/gte.md §7): ZSF4 × (SZ0 + SZ1 + SZ2 + SZ3). Updates `regs`, FLAG
/// included.
pub fn avsz4(regs: &mut Registers) -> AverageZ {
    let sum = regs.sz.iter().map(|&z| z as i64).sum();
    average(regs, regs.zsf4, sum)
}
