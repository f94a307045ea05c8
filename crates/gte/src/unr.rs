//! The UNR divide of RTPS/RTPT: H / SZ3 by a 257-entry reciprocal table and Newton-Raphson
//! refinement, with the hardware's overflow rule (docs/hardware/gte.md §6).
//!
//! Why this shape: the divide is the middle of RTPS's dependency chain (docs/performance.md,
//! "Rows under 2x on Zen 4"), so it normalises SZ3 with one bit scan ("Store forwarding", the
//! last row) and reads its seeds from a table indexed by the normalised divisor's top ten
//! bits, one shift on the chain and no bounds check ("The plain loop: the divide's seed and
//! the dispatch").

/// Overflow result and the largest quotient: 1FFFFh (docs/hardware/gte.md §6).
pub const QUOTIENT_MAX: u32 = 0x1_FFFF;

/// The reciprocal seed table T[0..=256] (docs/hardware/gte.md §6):
/// `T[i] = max(0, ((40000h div (i + 100h)) + 1) div 2 - 101h)`, built at compile time.
pub(crate) const UNR_TABLE: [u8; 257] = build_table();

const fn build_table() -> [u8; 257] {
    let mut table = [0u8; 257];
    let mut i = 0;
    while i < 257 {
        let v = ((0x40000 / (i as i32 + 0x100)) + 1) / 2 - 0x101;
        table[i] = if v < 0 { 0 } else { v as u8 };
        i += 1;
    }
    table
}

/// How RTPS/RTPT divide H by SZ3. Only [`DivideMode::Unr`] is hardware behaviour; the others
/// are accuracy knobs for measuring what the UNR approximation costs (docs/gte.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum DivideMode {
    /// The console's table + Newton-Raphson divide (docs/hardware/gte.md §6).
    #[default]
    Unr,
    /// `round(H * 10000h / SZ3)` in integers, same overflow rule and 1FFFFh clamp.
    Exact,
    /// The same quotient computed in `f32`, same overflow rule and clamp.
    F32,
}

/// Whether `H / SZ3` overflows: the hardware computes a quotient only when `H < 2 * SZ3`
/// (docs/hardware/gte.md §6); this covers SZ3 = 0.
pub const fn divide_overflows(h: u16, sz3: u16) -> bool {
    (h as u32) >= 2 * (sz3 as u32)
}

/// The hardware UNR quotient `H * 10000h / SZ3` (docs/hardware/gte.md §6). Returns the quotient
/// (0..=1FFFFh) and whether the divide overflowed (FLAG.17). The final clamp to 1FFFFh sets
/// no flag.
pub const fn unr_divide(h: u16, sz3: u16) -> (u32, bool) {
    if divide_overflows(h, sz3) {
        return (QUOTIENT_MAX, true);
    }
    (unr_quotient(h, sz3), false)
}

/// The reciprocal seeds `T[i] + 101h` of the table, by the top ten bits of the normalised
/// divisor `d` (8000h..=FFFFh): entry `j` = `d >> 6` (200h..=3FFh) holds the seed of index
/// `i` = `(d - 7FC0h) SAR 7` (docs/hardware/gte.md §6), which is `((j + 1) >> 1) - 100h` for
/// every `d` with those top bits. Indexed by `d >> 6` alone, the seed's load waits on one
/// shift of `d` rather than a subtraction and a shift, on RTPS's chain from SZ3 to SXY2;
/// the array is as long as a 10-bit index reaches, so the index needs no bounds check.
/// Entries below 200h are never read.
const UNR_SEEDS: [u16; 1024] = {
    let mut seeds = [0u16; 1024];
    let mut j = 0x200;
    while j < 0x400 {
        seeds[j] = UNR_TABLE[((j + 1) >> 1) - 0x100] as u16 + 0x101;
        j += 1;
    }
    seeds
};

/// The UNR quotient for a divide that does not overflow (`H < 2 * SZ3`).
#[inline(always)]
pub(crate) const fn unr_quotient(h: u16, sz3: u16) -> u32 {
    // sz3 > h / 2 >= 0, so sz3 != 0. Normalising shifts sz3 and h left by 15 - log2(sz3),
    // 0..=15: the same as shifting left by 15 and right by the log, which drops only the 15
    // zero bits the first shift brought in. ORing in bit 0 keeps the log and tells the
    // compiler the operand is not 0.
    let log = (sz3 as u32 | 1).ilog2();
    let n = ((h as u64) << 15) >> log;
    let d = (((sz3 as u32) << 15) >> log) as u16; // 8000h..=FFFFh
    let u = UNR_SEEDS[(d >> 6) as usize] as i64;
    let d = d as i64;
    let d = (0x200_0080 - d * u) >> 8;
    let d = (0x80 + d * u) >> 8;
    let q = (n as i64 * d + 0x8000) >> 16;
    if q > QUOTIENT_MAX as i64 {
        QUOTIENT_MAX
    } else {
        q as u32
    }
}

/// `round(H * 10000h / SZ3)` with the hardware overflow rule and clamp: the exact quotient the
/// UNR divide approximates.
pub const fn exact_divide(h: u16, sz3: u16) -> (u32, bool) {
    if divide_overflows(h, sz3) {
        return (QUOTIENT_MAX, true);
    }
    (exact_quotient(h, sz3), false)
}

/// The exact quotient for a divide that does not overflow.
#[inline(always)]
pub(crate) const fn exact_quotient(h: u16, sz3: u16) -> u32 {
    let sz3 = sz3 as u64;
    let q = (((h as u64) << 16) + sz3 / 2) / sz3;
    if q > QUOTIENT_MAX as u64 {
        QUOTIENT_MAX
    } else {
        q as u32
    }
}

/// The quotient in `f32` maths (rounded to nearest), with the hardware overflow rule and clamp.
pub fn f32_divide(h: u16, sz3: u16) -> (u32, bool) {
    if divide_overflows(h, sz3) {
        return (QUOTIENT_MAX, true);
    }
    (f32_quotient(h, sz3), false)
}

/// The `f32` quotient for a divide that does not overflow.
#[inline(always)]
pub(crate) fn f32_quotient(h: u16, sz3: u16) -> u32 {
    let q = (h as f32) * 65536.0 / (sz3 as f32) + 0.5;
    // `as` saturates; q is positive and finite because sz3 > 0.
    (q as u32).min(QUOTIENT_MAX)
}

/// `H * 10000h / SZ3` by the given mode: the quotient and whether the divide overflowed.
///
/// A plain function, available in every build: the `divide-modes` feature only decides
/// whether a [`Gte`](crate::Gte) can be set to run the non-hardware modes.
pub fn divide(mode: DivideMode, h: u16, sz3: u16) -> (u32, bool) {
    match mode {
        DivideMode::Unr => unr_divide(h, sz3),
        DivideMode::Exact => exact_divide(h, sz3),
        DivideMode::F32 => f32_divide(h, sz3),
    }
}

impl DivideMode {
    /// Whether a [`Gte`](crate::Gte) of this build can run the mode: [`DivideMode::Unr`]
    /// always; [`DivideMode::Exact`] and [`DivideMode::F32`] only with the `divide-modes`
    /// feature.
    pub const fn is_supported(self) -> bool {
        matches!(self, DivideMode::Unr) || cfg!(feature = "divide-modes")
    }
}

/// A divide mode this build of the engine cannot run: [`DivideMode::Exact`] or
/// [`DivideMode::F32`] without the `divide-modes` feature (docs/gte.md, "Features").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct UnsupportedDivideMode(pub DivideMode);

impl core::fmt::Display for UnsupportedDivideMode {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "divide mode {:?} needs the `divide-modes` feature of the gte crate",
            self.0
        )
    }
}

impl core::error::Error for UnsupportedDivideMode {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_matches_printed_endpoints() {
        // psx-spx prints the table starting FFh,FDh,FBh,F9h and ending ...,01h,00h,00h.
        assert_eq!(&UNR_TABLE[..4], &[0xFF, 0xFD, 0xFB, 0xF9]);
        assert_eq!(UNR_TABLE[255], 0x00);
        assert_eq!(UNR_TABLE[256], 0x00);
    }

    #[test]
    fn overflow_rule() {
        assert_eq!(unr_divide(0, 0), (QUOTIENT_MAX, true));
        assert_eq!(unr_divide(100, 50), (QUOTIENT_MAX, true));
        assert!(!unr_divide(100, 51).1);
    }

    #[test]
    fn final_clamp_cases_from_fact_sheet() {
        // docs/hardware/gte.md §6: FE3Fh/7F20h and F015h/780Bh reach 20000h before the clamp.
        assert_eq!(unr_divide(0xFE3F, 0x7F20), (QUOTIENT_MAX, false));
        assert_eq!(unr_divide(0xF015, 0x780B), (QUOTIENT_MAX, false));
    }

    #[test]
    fn seeds_by_top_bits_match_the_table_index() {
        // Every normalised divisor: the seed read by its top ten bits is the one the fact
        // sheet's index (d - 7FC0h) SAR 7 names.
        for d in 0x8000u32..=0xFFFF {
            let i = ((d as i32 - 0x7FC0) >> 7) as usize;
            assert!(i <= 256, "{d:#x}");
            assert_eq!(
                UNR_SEEDS[(d >> 6) as usize],
                UNR_TABLE[i] as u16 + 0x101,
                "{d:#x}"
            );
        }
    }

    #[test]
    fn powers_of_two_are_exact() {
        // H = SZ3: the quotient is 1.0 = 10000h.
        assert_eq!(unr_divide(0x4000, 0x4000), (0x10000, false));
        assert_eq!(unr_divide(1, 1), (0x10000, false));
    }
}
