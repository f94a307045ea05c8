//! The arithmetic every command shares: 44-bit MAC1-3 accumulation with per-step overflow
//! flags and wrap, MAC0 flags, and the IR / colour saturation (docs/hardware/gte.md §4).
//!
//! Why this shape: this is every command's FLAG and saturation work, and on an emulator's
//! inputs most of those tests never fire. Values that seldom leave their range are tested
//! together (`all_within`: one compare for a group) or one by one with the saturation out of
//! line (`ir_test`); values that often do keep in-line clamps. The form of each step was
//! measured per command, and selects or one unsigned compare per clamp measured slower
//! (docs/performance.md, "Saturation tests", "Straight paths and tests folded into others").

use crate::Gte;

/// Largest 44-bit accumulator value, 2^43 - 1.
pub const MAC_MAX: i64 = (1 << 43) - 1;
/// Smallest 44-bit accumulator value, -2^43.
pub const MAC_MIN: i64 = -(1 << 43);

/// Largest magnitude of one product added into MAC1-3: a 16-bit by 16-bit product, 2^30.
const PRODUCT_MAX: i64 = 1 << 30;

/// Wrap to 44-bit two's complement.
pub const fn wrap44(value: i64) -> i64 {
    (value << 20) >> 20
}

/// Whether an accumulation of `terms` products (each at most 2^30 in magnitude) from `start`
/// keeps every partial sum inside the 44-bit range (docs/hardware/gte.md §4): then it is plain
/// addition, with no flag and no wrap.
#[inline(always)]
pub const fn is_plain_start(start: i64, terms: usize) -> bool {
    let margin = terms as i64 * PRODUCT_MAX;
    start >= MAC_MIN + margin && start <= MAC_MAX - margin
}

/// Accumulate into MACn (n = 1..3): `start` plus each product in turn, FLAG bit 31-n or
/// 28-n into `flags` and a wrap to 44 bits after every addition (docs/hardware/gte.md §4).
/// `plain` says that `start` satisfies [`is_plain_start`], so that no step can overflow and
/// the sum is plain addition.
#[inline(always)]
pub(crate) fn accumulate(
    flags: &mut u32,
    n: usize,
    start: i64,
    products: &[i64],
    plain: bool,
) -> i64 {
    debug_assert!(products.iter().all(|p| p.abs() <= PRODUCT_MAX));
    if plain {
        debug_assert!(is_plain_start(start, products.len()));
        return products.iter().fold(start, |sum, &p| sum + p);
    }
    let mut sum = start;
    for &p in products {
        sum += p;
        if sum > MAC_MAX {
            *flags |= bit::mac_positive(n);
        } else if sum < MAC_MIN {
            *flags |= bit::mac_negative(n);
        }
        sum = wrap44(sum);
    }
    sum
}

/// Saturate to `min..=max`, reporting whether the value was out of range.
pub const fn clamp(value: i64, min: i64, max: i64) -> (i64, bool) {
    if value < min {
        (min, true)
    } else if value > max {
        (max, true)
    } else {
        (value, false)
    }
}

/// Whether every value lies in `min..=min + span`, where `span` is one less than a power of
/// two: the OR of the offsets from `min` is then at most `span`. Saturation tests that
/// rarely fire become one compare and one branch; values outside are clamped one by one.
#[inline(always)]
pub(crate) fn all_within<const N: usize>(values: [i64; N], min: i64, span: u64) -> bool {
    debug_assert!((span + 1).is_power_of_two());
    values
        .iter()
        .fold(0u64, |offsets, &v| offsets | v.wrapping_sub(min) as u64)
        <= span
}

/// [`all_within`] for 32-bit values (MAC1-3), in 32-bit arithmetic.
#[inline(always)]
pub(crate) fn all_within_32<const N: usize>(values: [i32; N], min: i32, span: u32) -> bool {
    debug_assert!((span as u64 + 1).is_power_of_two());
    values
        .iter()
        .fold(0u32, |offsets, &v| offsets | v.wrapping_sub(min) as u32)
        <= span
}

/// IRn's range by lm (docs/hardware/gte.md §4): its start (0 with lm, otherwise -8000h) and
/// its span up to 7FFFh, as [`all_within_32`] takes them.
#[inline(always)]
pub(crate) const fn ir_range(lm: bool) -> (i32, u32) {
    if lm { (0, 0x7FFF) } else { (-0x8000, 0xFFFF) }
}

/// IRn for a MAC value: saturated to 0 (`lm`) or -8000h up to 7FFFh, FLAG bit 25-n into
/// `flags` (docs/hardware/gte.md §4).
#[inline(always)]
pub(crate) fn saturate_ir(flags: &mut u32, n: usize, value: i32, lm: bool) -> i16 {
    let (ir, saturated) = clamp(value as i64, if lm { 0 } else { -0x8000 }, 0x7FFF);
    if saturated {
        *flags |= bit::ir(n);
    }
    ir as i16
}

/// MACn = low 32 bits of (sum SAR sf) and IRn from it, as [`saturate_ir`]
/// (docs/hardware/gte.md §4). With `RARE`, for values that seldom leave IRn's range, the
/// test is made on the shifted sum before its truncation to 32 bits: inside IRn's range it
/// equals MACn, and IRn is that value with no conversion; outside, the saturation, by MACn,
/// is kept out of the straight path (`cold_path`).
#[inline(always)]
pub(crate) fn mac_ir<const RARE: bool>(
    flags: &mut u32,
    n: usize,
    sum: i64,
    shift: u32,
    lm: bool,
) -> (i32, i64) {
    let wide = sum >> shift;
    let mac = wide as i32;
    if RARE {
        // IR's start as an i64 here, not through `ir_range`'s i32: widened from that, it
        // cost DPCS 5 more instructions a call in the probe loop.
        let min = if lm { 0 } else { -0x8000 };
        if wide < min || wide > 0x7FFF {
            core::hint::cold_path();
            return (mac, saturate_ir(flags, n, mac, lm) as i64);
        }
        return (mac, wide);
    }
    (mac, saturate_ir(flags, n, mac, lm) as i64)
}

/// Colour FIFO entry from MAC1-3: Cn = clamp(MACn SAR 4, 0, FFh) with FLAG bit 22-n into
/// `flags`, packed R | G << 8 | B << 16 over `code`, the CODE byte in place
/// (docs/hardware/gte.md §4).
#[inline(always)]
pub(crate) fn color_entry(flags: &mut u32, mac: [i32; 3], code: u32) -> u32 {
    let mut packed = code;
    for n in 1..=3 {
        let (c, saturated) = clamp((mac[n - 1] >> 4) as i64, 0, 0xFF);
        if saturated {
            *flags |= bit::color(n);
        }
        packed |= (c as u32) << (8 * (n - 1));
    }
    packed
}

/// FLAG bits of colours 1-3 by the mask of those inside their range (bit n - 1 for colour n).
const COLOR_FLAGS: [u32; 8] = {
    let mut table = [0; 8];
    let mut mask = 0;
    while mask < 8 {
        let mut n = 1;
        while n <= 3 {
            if mask >> (n - 1) & 1 == 0 {
                table[mask] |= bit::color(n);
            }
            n += 1;
        }
        mask += 1;
    }
    table
};

/// [`color_entry`] with the three channels side by side as the lanes of one vector, with no
/// branch: Cn = clamp(MACn SAR 4, 0, FFh) is MACn SAR 4 narrowed with signed saturation to 16
/// bits, then with unsigned saturation to 8 (each narrowing clamps to exactly that range, and
/// the first keeps the sign the second clamps to 0), and Cn is inside its range exactly when
/// MACn SAR 12 is 0. For commands whose colours leave the range on a large share of calls
/// (GPF, GPL), where a clamp per channel is a branch that goes either way (docs/performance.md,
/// "Colours in vector lanes").
#[inline(always)]
pub(crate) fn color_entry_lanes(flags: &mut u32, mac: [i32; 3], code: u32) -> u32 {
    use wide::{i16x8, i32x4, i32x8, u8x16};
    let [m1, m2, m3] = mac;
    let quarters = i32x8::new([m1, m2, m3, 0, 0, 0, 0, 0]) >> 4i32;
    let bytes = u8x16::narrow_i16x8(i16x8::from_i32x8_saturate(quarters), i16x8::ZERO);
    let inside = (i32x4::new([m1, m2, m3, 0]) >> 12i32).simd_eq(i32x4::ZERO);
    *flags |= COLOR_FLAGS[(inside.to_bitmask() & 7) as usize];
    // The fourth lane holds 0, and so its byte.
    let [r, g, b, zero, ..] = bytes.to_array();
    code | u32::from_le_bytes([r, g, b, zero])
}

/// [`color_entry`] for MAC values that seldom leave the colour range: Cn lies inside
/// 0..=FFh exactly when MACn lies in 0..=FFFh, so the three channels are one test
/// ([`all_within_32`]) and the saturation is kept out of line.
#[inline(always)]
pub(crate) fn color_entry_rare(flags: &mut u32, mac: [i32; 3], code: u32) -> u32 {
    if all_within_32(mac, 0, 0xFFF) {
        let [r, g, b] = mac.map(|m| (m >> 4) as u32);
        return code | r | g << 8 | b << 16;
    }
    saturate_color(flags, mac, code)
}

/// [`color_entry`] out of line, for [`color_entry_rare`]'s values outside the range.
#[cold]
#[inline(never)]
fn saturate_color(flags: &mut u32, mac: [i32; 3], code: u32) -> u32 {
    color_entry(flags, mac, code)
}

/// FLAG bits 16/15 into `flags` for a MAC0-path value outside the 32-bit range
/// (docs/hardware/gte.md §4). Leaving it takes extreme operands (a quotient near its limit
/// times an IR near its own), so the test is a branch marked cold rather than a select.
#[inline(always)]
pub(crate) fn mac0_flags(flags: &mut u32, value: i64) {
    if value as i32 as i64 != value {
        core::hint::cold_path();
        *flags |= if value < 0 {
            bit::MAC0_NEGATIVE
        } else {
            bit::MAC0_POSITIVE
        };
    }
}

/// MAC1-3 and IR1-3 after one step of a command. Commands carry a step's values to the next
/// step in locals and store the last step's at the end, which leaves the registers as the
/// hardware's step-by-step writes do.
#[derive(Clone, Copy, Default)]
pub(crate) struct Step {
    pub(crate) mac: [i32; 3],
    pub(crate) ir: [i64; 3],
}

/// How a step tests IR1-3 against their range, as the const parameter of [`step_with`]
/// (docs/performance.md, "Saturation tests" and "Straight paths and tests folded into
/// others"): each form measured fastest where it is used.
pub(crate) mod ir_test {
    /// One test for the three IRs, the saturation out of line ([`super::mac_ir_rows`]): steps
    /// whose IRs seldom leave their range (RTPS/RTPT, the lighting commands' later steps).
    pub(crate) const GROUPED: u8 = 0;
    /// A test per IR, the saturation in line ([`super::saturate_ir`]): steps whose IRs
    /// leave their range often, such as the light step of the normal-colour commands, whose
    /// dot products are negative for a normal facing away from a light (with lm, IR then
    /// saturates at 0). GPF and GPL, whose products pass the range whenever IR0 passes
    /// 1000h, saturate each IR the same way in their own 32-bit rows.
    pub(crate) const EACH: u8 = 1;
    /// A test per IR, the saturation out of the straight path ([`super::mac_ir`]):
    /// steps whose IRs seldom leave their range but where the grouped test measured slower
    /// (DPCS/DPCT/DCPL/INTPL, MVMVA).
    pub(crate) const EACH_RARE: u8 = 2;
}

/// One step: MACn = (start_n + the products of row n) SAR sf and IRn from it by lm, for
/// n = 1..3, FLAG bits into `flags` (docs/hardware/gte.md §4). `plain` as for
/// [`accumulate`], for every row. IR1-3 are tested together ([`ir_test::GROUPED`]).
#[inline(always)]
pub(crate) fn step<const TERMS: usize>(
    flags: &mut u32,
    start: [i64; 3],
    products: [[i64; TERMS]; 3],
    plain: bool,
    shift: u32,
    lm: bool,
) -> Step {
    step_with::<TERMS, { ir_test::GROUPED }>(flags, start, products, plain, shift, lm)
}

/// [`step`], with IR1-3 tested in the form `TEST` ([`ir_test`]).
#[inline(always)]
pub(crate) fn step_with<const TERMS: usize, const TEST: u8>(
    flags: &mut u32,
    start: [i64; 3],
    products: [[i64; TERMS]; 3],
    plain: bool,
    shift: u32,
    lm: bool,
) -> Step {
    // `plain` tested once for the three rows.
    let sums = row_sums(flags, start, &products, plain);
    match TEST {
        ir_test::GROUPED => mac_ir_rows(flags, sums, shift, lm),
        ir_test::EACH => mac_ir_each_row::<false>(flags, sums, shift, lm),
        _ => mac_ir_each_row::<true>(flags, sums, shift, lm),
    }
}

/// MAC1-3 = each sum SAR sf and IR1-3 from them by lm, each IR saturated on its own with
/// its flag (docs/hardware/gte.md §4), as [`mac_ir`] with `RARE`.
#[inline(always)]
pub(crate) fn mac_ir_each_row<const RARE: bool>(
    flags: &mut u32,
    sums: [i64; 3],
    shift: u32,
    lm: bool,
) -> Step {
    let mut step = Step::default();
    for (n, &sum) in sums.iter().enumerate() {
        (step.mac[n], step.ir[n]) = mac_ir::<RARE>(flags, n + 1, sum, shift, lm);
    }
    step
}

/// MAC1-3 = each sum SAR sf and IR1-3 from them by lm, FLAG bits into `flags`
/// (docs/hardware/gte.md §4). IR1-3 all inside their range is one test ([`all_within_32`]);
/// otherwise each saturates with its flag.
#[inline(always)]
fn mac_ir_rows(flags: &mut u32, sums: [i64; 3], shift: u32, lm: bool) -> Step {
    let mac = sums.map(|s| (s >> shift) as i32);
    let [m1, m2, m3] = mac;
    let (min, span) = ir_range(lm);
    let ir = if all_within_32(mac, min, span) {
        [m1 as i64, m2 as i64, m3 as i64]
    } else {
        saturate_irs(flags, mac, lm)
    };
    Step { mac, ir }
}

/// IR1-3 from MAC1-3 one of which leaves its range, each saturated with its flag.
#[cold]
#[inline(never)]
fn saturate_irs(flags: &mut u32, [m1, m2, m3]: [i32; 3], lm: bool) -> [i64; 3] {
    [
        saturate_ir(flags, 1, m1, lm) as i64,
        saturate_ir(flags, 2, m2, lm) as i64,
        saturate_ir(flags, 3, m3, lm) as i64,
    ]
}

/// The three rows' accumulations of one step, as [`accumulate`]: `plain` is tested once for
/// the three rows.
#[inline(always)]
pub(crate) fn row_sums<const TERMS: usize>(
    flags: &mut u32,
    start: [i64; 3],
    products: &[[i64; TERMS]; 3],
    plain: bool,
) -> [i64; 3] {
    // Written out row by row rather than through `core::array::from_fn`, which the
    // compiler does not always inline.
    if plain {
        [
            accumulate(flags, 1, start[0], &products[0], true),
            accumulate(flags, 2, start[1], &products[1], true),
            accumulate(flags, 3, start[2], &products[2], true),
        ]
    } else {
        [
            accumulate(flags, 1, start[0], &products[0], false),
            accumulate(flags, 2, start[1], &products[1], false),
            accumulate(flags, 3, start[2], &products[2], false),
        ]
    }
}

/// The products of each row of `m` with `v`, in column order (the terms of a matrix row's
/// sum, docs/hardware/gte.md §4).
#[inline(always)]
pub(crate) fn matrix_products(m: &[[i64; 3]; 3], v: [i64; 3]) -> [[i64; 3]; 3] {
    m.map(|r| [r[0] * v[0], r[1] * v[1], r[2] * v[2]])
}

/// What a command ORs into FLAG for each condition, by bit position (docs/hardware/gte.md
/// §3). A condition that feeds the error summary carries bit 31 with it, so the bits a
/// command collects are FLAG as the command leaves it.
pub mod bit {
    use crate::Flag;

    /// `b` with bit 31 when `b` is among the error sources (docs/hardware/gte.md §3).
    const fn raise(b: u32) -> u32 {
        if b & Flag::ERROR_SOURCES != 0 {
            b | 1 << 31
        } else {
            b
        }
    }

    /// MACn > 2^43 - 1: bit 31 - n (an error source).
    pub const fn mac_positive(n: usize) -> u32 {
        raise(1 << (31 - n))
    }
    /// MACn < -2^43: bit 28 - n (an error source).
    pub const fn mac_negative(n: usize) -> u32 {
        raise(1 << (28 - n))
    }
    /// IRn saturated: bit 25 - n (IR1 and IR2 are error sources, IR3 is not).
    pub const fn ir(n: usize) -> u32 {
        const IR: [u32; 4] = [0, raise(1 << 24), raise(1 << 23), raise(1 << 22)];
        IR[n]
    }
    /// Colour channel n (1 = R) saturated: bit 22 - n (not an error source).
    pub const fn color(n: usize) -> u32 {
        raise(1 << (22 - n))
    }
    /// SZ3 / OTZ saturated.
    pub const SZ3_OTZ: u32 = raise(1 << 18);
    /// Divide overflow.
    pub const DIVIDE: u32 = raise(1 << 17);
    /// MAC0 > 2^31 - 1.
    pub const MAC0_POSITIVE: u32 = raise(1 << 16);
    /// MAC0 < -2^31.
    pub const MAC0_NEGATIVE: u32 = raise(1 << 15);
    /// SX2 saturated.
    pub const SX2: u32 = raise(1 << 14);
    /// SY2 saturated.
    pub const SY2: u32 = raise(1 << 13);
    /// IR0 saturated (not an error source).
    pub const IR0: u32 = raise(1 << 12);
}

impl Gte {
    /// Accumulate into MACn (n = 1..3): start from `start` (an add-vector component already
    /// shifted left 12, or 0), add each product in turn, flag and wrap to 44 bits after every
    /// addition (docs/hardware/gte.md §4). Returns the wrapped 44-bit sum.
    ///
    /// Every product is at most 2^30 in magnitude (a 16-bit by 16-bit product, or less), so
    /// when `start` lies far enough inside the 44-bit range no partial sum can leave it: the
    /// sum is then plain addition, with no flag and no wrap. With `start` 0 that holds always.
    #[inline(always)]
    pub(crate) fn accumulate(&mut self, n: usize, start: i64, products: &[i64]) -> i64 {
        let plain = is_plain_start(start, products.len());
        accumulate(&mut self.flag_bits, n, start, products, plain)
    }

    /// MACn = low 32 bits of (sum SAR shift) (docs/hardware/gte.md §4).
    #[inline(always)]
    pub(crate) fn set_mac(&mut self, n: usize, sum: i64, shift: u32) -> i32 {
        let mac = (sum >> shift) as i32;
        self.regs.set_mac(n, mac);
        mac
    }

    /// Saturate a MAC value to IRn's range (0 or -8000h up to 7FFFh), setting FLAG bit 25-n,
    /// without storing it.
    #[inline(always)]
    pub(crate) fn saturate_ir(&mut self, n: usize, value: i32, lm: bool) -> i16 {
        saturate_ir(&mut self.flag_bits, n, value, lm)
    }

    /// IRn = clamp(value) with FLAG bit 25-n (docs/hardware/gte.md §4); returns IRn.
    #[inline(always)]
    pub(crate) fn set_ir(&mut self, n: usize, value: i32, lm: bool) -> i16 {
        let v = self.saturate_ir(n, value, lm);
        self.regs.set_ir(n, v);
        v
    }

    /// The common tail of a matrix-vector row: MACn from the sum, IRn from MACn.
    #[inline(always)]
    pub(crate) fn set_mac_ir(&mut self, n: usize, sum: i64, shift: u32, lm: bool) {
        let mac = self.set_mac(n, sum, shift);
        self.set_ir(n, mac, lm);
    }

    /// MAC0 from a 64-bit value: flags 16/15 on the full value, low 32 bits kept (docs/hardware/gte.md §4).
    #[inline(always)]
    pub(crate) fn set_mac0(&mut self, value: i64) {
        self.flag_mac0(value);
        self.regs.set_mac(0, value as i32);
    }

    /// FLAG bits 16/15 for a MAC0-path value ([`mac0_flags`]).
    #[inline(always)]
    pub(crate) fn flag_mac0(&mut self, value: i64) {
        mac0_flags(&mut self.flag_bits, value);
    }

    /// Colour FIFO push: Cn = clamp(MACn SAR 4, 0, FFh) with FLAG bit 22-n; RGB2 gets
    /// R | G << 8 | B << 16 | CODE << 24 (docs/hardware/gte.md §4).
    #[inline(always)]
    pub(crate) fn push_color(&mut self) {
        let mac = [self.regs.mac(1), self.regs.mac(2), self.regs.mac(3)];
        let code = self.regs.rgbc() & 0xFF00_0000;
        let packed = color_entry(&mut self.flag_bits, mac, code);
        self.regs.push_rgb(packed);
    }

    /// Store a step's MAC1-3 and IR1-3.
    #[inline(always)]
    pub(crate) fn store_step(&mut self, last: Step) {
        for n in 0..3 {
            self.regs.set_mac(n + 1, last.mac[n]);
            self.regs.set_ir(n + 1, last.ir[n] as i16);
        }
    }

    /// Store a step's MAC1-3 and IR1-3 and push `colors` in order onto the colour FIFO.
    #[inline(always)]
    pub(crate) fn step_result(&mut self, last: Step, colors: &[u32]) {
        self.store_step(last);
        for &c in colors {
            self.regs.push_rgb(c);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grouped colour test and the colour lanes against each channel clamped on its own
    /// (docs/hardware/gte.md §4), with every channel at and around the edges of 0..=FFFh and
    /// of the 16-bit range that MACn SAR 4 passes through in the lanes, the other two
    /// anywhere among them.
    #[test]
    fn color_entries_match_each_channel() {
        let edges = [
            i32::MIN,
            -0x8_0010,
            -0x8_0000,
            -0x10,
            -1,
            0,
            0xF,
            0x10,
            0xFFF,
            0x1000,
            0x7FFF,
            0x7_FFF0,
            0x8_0000,
            i32::MAX,
        ];
        for r in edges {
            for g in edges {
                for b in edges {
                    let mut expected_flags = 0;
                    let mut expected = 0xAB00_0000;
                    for (n, m) in [r, g, b].into_iter().enumerate() {
                        let c = (m >> 4).clamp(0, 0xFF);
                        if c != m >> 4 {
                            expected_flags |= 1 << (21 - n);
                        }
                        expected |= (c as u32) << (8 * n);
                    }
                    let mut flags = 0;
                    let packed = color_entry_rare(&mut flags, [r, g, b], 0xAB00_0000);
                    assert_eq!((packed, flags), (expected, expected_flags), "{r} {g} {b}");
                    let mut flags = 0;
                    let packed = color_entry_lanes(&mut flags, [r, g, b], 0xAB00_0000);
                    assert_eq!((packed, flags), (expected, expected_flags), "{r} {g} {b}");
                }
            }
        }
    }

    #[test]
    fn wrap44_examples() {
        assert_eq!(wrap44(MAC_MAX + 1), MAC_MIN);
        assert_eq!(wrap44(MAC_MIN - 1), MAC_MAX);
        assert_eq!(wrap44(-5), -5);
    }
}
