//! Depth-cue and interpolation commands: DPCS, DPCT, DCPL, INTPL, GPF, GPL (docs/hardware/gte.md §8).
//!
//! Why this shape: DPCS, DPCT, DCPL and INTPL test each IR alone with the saturation out of
//! the straight path (`ir_test::EACH_RARE`), which measured faster than the grouped test
//! though it runs more instructions (docs/performance.md, "Saturation tests", "Straight paths
//! and tests folded into others"); GPF and GPL keep their clamps in line, as IR * IR0 leaves
//! IR's range on a large share of calls (GPF 7.9 → 9.1 ns with the out-of-line form), and
//! clamp their colours side by side in vector lanes (`color_entry_lanes`), as the colours
//! saturate on a large share of calls too: 100 → 89 instructions a GPF call in a plain loop
//! (docs/performance.md, "Colours in vector lanes").

use crate::Gte;
use crate::mac::{Step, bit, color_entry_lanes, ir_test, saturate_ir, step_with};

/// Interpolate `input` towards the far colour `fc` (FC << 12) by `ir0` (docs/hardware/gte.md
/// §8): first MACn = ((FCn << 12) - in_n) SAR sf with IRn saturated to the lm=0 range
/// whatever lm is, then MACn = (IRn * IR0 + in_n) SAR sf with IRn by lm. `plain` says that
/// every FCn << 12 leaves room for one product (docs/hardware/gte.md §4); every input is below
/// 2^27 in magnitude, so the second sum is plain addition. Both steps test their IRs in the
/// form `TEST` ([`ir_test`]): DPCS, DPCT, DCPL and INTPL one by one with the saturation out
/// of the way, the lighting commands' depth cue together, whichever measured faster for each
/// (docs/performance.md, "Saturation tests" and "Straight paths and tests folded into
/// others").
#[inline(always)]
pub(crate) fn interpolate<const TEST: u8>(
    flags: &mut u32,
    input: [i64; 3],
    fc: [i64; 3],
    ir0: i64,
    plain: bool,
    shift: u32,
    lm: bool,
) -> Step {
    let far = step_with::<1, TEST>(flags, fc, input.map(|i| [-i]), plain, shift, false);
    let products = [0, 1, 2].map(|n| [far.ir[n] * ir0]);
    step_with::<1, TEST>(flags, input, products, true, shift, lm)
}

impl Gte {
    /// MAC1-3 and IR1-3 from [`interpolate`] of `input` towards FC by IR0.
    #[inline(always)]
    pub(crate) fn depth_cue_interpolate(&mut self, input: [i64; 3], shift: u32, lm: bool) {
        let fc = self.regs.fc().map(|f| (f as i64) << 12);
        let plain = self.regs.fc_plain();
        let ir0 = self.regs.ir(0) as i64;
        let last = interpolate::<{ ir_test::EACH_RARE }>(
            &mut self.flag_bits,
            input,
            fc,
            ir0,
            plain,
            shift,
            lm,
        );
        self.store_step(last);
    }

    /// Colour bytes R, G, B of `rgb` shifted left 16.
    fn color_input(rgb: u32) -> [i64; 3] {
        [
            ((rgb & 0xFF) as i64) << 16,
            (((rgb >> 8) & 0xFF) as i64) << 16,
            (((rgb >> 16) & 0xFF) as i64) << 16,
        ]
    }

    /// DPCS: depth-cue the RGBC colour.
    #[inline(always)]
    pub(crate) fn dpcs(&mut self, shift: u32, lm: bool) {
        let input = Self::color_input(self.regs.rgbc());
        self.depth_cue_interpolate(input, shift, lm);
        self.push_color();
    }

    /// DPCT: DPCS three times on RGB0, the FIFO bottom, re-read after each push (docs/hardware/gte.md §8).
    pub(crate) fn dpct(&mut self, shift: u32, lm: bool) {
        for _ in 0..3 {
            let input = Self::color_input(self.regs.rgb(0));
            self.depth_cue_interpolate(input, shift, lm);
            self.push_color();
        }
    }

    /// DCPL: depth-cue (RGBC * IR) << 4.
    #[inline]
    pub(crate) fn dcpl(&mut self, shift: u32, lm: bool) {
        let input = self.color_times_ir();
        self.depth_cue_interpolate(input, shift, lm);
        self.push_color();
    }

    /// INTPL: interpolate IR << 12 towards FC.
    #[inline]
    pub(crate) fn intpl(&mut self, shift: u32, lm: bool) {
        let input = self.ir_vector().map(|v| v << 12);
        self.depth_cue_interpolate(input, shift, lm);
        self.push_color();
    }

    /// GPF: MACn = (IRn * IR0) SAR sf. Returns the FLAG bits.
    #[inline(always)]
    pub(crate) fn gpf(&mut self, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.general_interpolate::<false>(shift, lm))
    }

    /// GPL: MACn = ((MACn << sf) + IRn * IR0) SAR sf. Returns the FLAG bits.
    #[inline(always)]
    pub(crate) fn gpl(&mut self, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.general_interpolate::<true>(shift, lm))
    }

    /// MACn = (start_n + IRn * IR0) SAR sf, IRn by lm, and the colour pushed (GPF, GPL),
    /// start_n being MACn << sf with `FROM_MAC` (GPL) and 0 otherwise (GPF). Returns the
    /// FLAG bits.
    ///
    /// In 32-bit arithmetic (docs/hardware/gte.md §4): IRn * IR0 is at most 2^30 in
    /// magnitude. With sf = 0 the sum of MACn and the product is below 2^32 in magnitude,
    /// far inside the 44-bit range, and MACn is its low 32 bits, a wrapping addition. With
    /// sf = 1 the sum (MACn << 12) + product leaves the 44-bit range exactly when MACn +
    /// (product SAR 12) leaves the 32-bit range (2^43 is 2^31 << 12), and the wrapped sum
    /// SAR 12 is that addition wrapped to 32 bits: one add, whose overflow gives the FLAG
    /// bit without a branch (in a loop of GPL the sums leave the range on every call, in
    /// alternate directions). The FLAG bits are a local, returned to the dispatch (docs/
    /// performance.md, "The plain loop" and "The plain loop: short paths").
    #[inline(always)]
    fn general_interpolate<const FROM_MAC: bool>(&mut self, shift: u32, lm: bool) -> u32 {
        let ir0 = self.regs.ir(0) as i32;
        let mut flags = 0;
        // Written out row by row: `core::array::map` is not always inlined.
        let mac = [
            self.general_row::<FROM_MAC>(&mut flags, 1, ir0, shift, lm),
            self.general_row::<FROM_MAC>(&mut flags, 2, ir0, shift, lm),
            self.general_row::<FROM_MAC>(&mut flags, 3, ir0, shift, lm),
        ];
        let code = self.regs.rgbc() & 0xFF00_0000;
        let color = color_entry_lanes(&mut flags, mac, code);
        self.regs.push_rgb(color);
        flags
    }

    /// Row `n` of [`Gte::general_interpolate`]: MACn and IRn stored, MACn returned.
    #[inline(always)]
    fn general_row<const FROM_MAC: bool>(
        &mut self,
        flags: &mut u32,
        n: usize,
        ir0: i32,
        shift: u32,
        lm: bool,
    ) -> i32 {
        use core::hint::select_unpredictable as select;
        let term = (self.regs.ir(n) as i32 * ir0) >> shift;
        let mac = if FROM_MAC {
            let (sum, overflow) = self.regs.mac(n).overflowing_add(term);
            if shift != 0 {
                let side = select(term < 0, bit::mac_negative(n), bit::mac_positive(n));
                *flags |= side & (overflow as u32).wrapping_neg();
            }
            sum
        } else {
            term
        };
        self.regs.set_mac(n, mac);
        let ir = saturate_ir(flags, n, mac, lm);
        self.regs.set_ir(n, ir);
        mac
    }
}
