//! H / SZ3 as docs/hardware/gte.md §6 states it, step by step, and the two non-hardware
//! divides of [`DivideMode`] by their definitions (docs/gte.md).

use crate::DivideMode;

/// The quotient's limit and overflow value, 1FFFFh (docs/hardware/gte.md §6).
pub const QUOTIENT_LIMIT: u32 = 0x1_FFFF;

/// The seed table T[0..=256] of docs/hardware/gte.md §6:
/// `T[i] = max(0, ((40000h div (i + 100h)) + 1) div 2 - 101h)`.
pub const SEEDS: [u8; 257] = {
    let mut t = [0u8; 257];
    let mut i = 0;
    while i <= 256 {
        let v = (0x40000 / (i as i64 + 0x100) + 1) / 2 - 0x101;
        t[i] = if v > 0 { v as u8 } else { 0 };
        i += 1;
    }
    t
};

/// One divide of H by SZ3: the quotient and whether it overflowed (FLAG bit 17).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Quotient {
    /// The quotient, 0..=1FFFFh (16.16 fixed point: 10000h is 1.0).
    pub value: u32,
    /// Whether H >= 2 × SZ3, which gives 1FFFFh and sets FLAG bit 17.
    pub overflow: bool,
}

/// The hardware divide of docs/hardware/gte.md §6, written out as the section gives it:
/// unless H < 2 × SZ3 the result is 1FFFFh with the overflow; otherwise SZ3 is normalised by
/// its leading zeros k (as a 16-bit value), a seed from [`SEEDS`] is refined twice, and
/// (n × d + 8000h) SAR 16 is limited to 1FFFFh (a limit that sets no flag).
pub fn unr(h: u16, sz3: u16) -> Quotient {
    let (h, sz3) = (h as i64, sz3 as i64);
    if h >= 2 * sz3 {
        return Quotient {
            value: QUOTIENT_LIMIT,
            overflow: true,
        };
    }
    let k = (sz3 as u16).leading_zeros();
    let n = h << k;
    let d = sz3 << k;
    let u = SEEDS[((d - 0x7FC0) >> 7) as usize] as i64 + 0x101;
    let d = (0x200_0080 - d * u) >> 8;
    let d = (0x80 + d * u) >> 8;
    let q = (n * d + 0x8000) >> 16;
    Quotient {
        value: q.min(QUOTIENT_LIMIT as i64) as u32,
        overflow: false,
    }
}

/// H / SZ3 by `mode`: [`unr`] for the hardware; for [`DivideMode::Exact`], round(H × 10000h /
/// SZ3) with halves rounded up; for [`DivideMode::F32`], (H × 65536 / SZ3 + 0.5) in `f32`
/// arithmetic, truncated. Both knobs keep the overflow rule and the 1FFFFh limit
/// (docs/gte.md, "The UNR divide").
pub fn divide(mode: DivideMode, h: u16, sz3: u16) -> Quotient {
    if mode == DivideMode::Unr || h as u32 >= 2 * sz3 as u32 {
        return unr(h, sz3);
    }
    let value = match mode {
        DivideMode::Exact => {
            let (h, sz3) = (h as u64, sz3 as u64);
            ((h * 0x2_0000 + sz3) / (2 * sz3)) as u32
        }
        _ => ((h as f32) * 65536.0 / (sz3 as f32) + 0.5) as u32,
    };
    Quotient {
        value: value.min(QUOTIENT_LIMIT),
        overflow: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_table_matches_the_printed_one() {
        // docs/hardware/gte.md §6 (psx-spx's table): FFh, FDh, FBh, F9h ... 01h, 00h, 00h.
        assert_eq!(&SEEDS[..4], &[0xFF, 0xFD, 0xFB, 0xF9]);
        assert_eq!(&SEEDS[252..], &[0x01, 0x01, 0x00, 0x00, 0x00]);
    }

    #[test]
    fn examples_from_the_fact_sheet() {
        // §6: FE3Fh / 7F20h reaches 20000h and is limited with no flag.
        let q = unr(0xFE3F, 0x7F20);
        assert_eq!((q.value, q.overflow), (0x1_FFFF, false));
        let q = unr(0xF015, 0x780B);
        assert_eq!((q.value, q.overflow), (0x1_FFFF, false));
        // H = 2 × SZ3 overflows; SZ3 = 0 overflows.
        assert!(unr(0x1000, 0x800).overflow);
        assert!(unr(0, 0).overflow);
        // H = SZ3: exactly 1.0.
        assert_eq!(unr(0x1234, 0x1234).value, 0x1_0000);
        assert_eq!(divide(DivideMode::Exact, 1, 3).value, 0x5555);
        assert_eq!(divide(DivideMode::Exact, 2, 3).value, 0xAAAB);
    }
}
