//! Depth-cue and interpolation commands: DPCS, DPCT, DCPL, INTPL, GPF, GPL (docs/hardware/gte.md §8).
//!
//! Why this shape: DPCS, DPCT, DCPL and INTPL test each IR alone with the saturation out of
//! the straight path (`ir_test::EACH_RARE`), which measured faster than the grouped test
//! though it runs more instructions (docs/performance.md, "Saturation tests", "Straight paths
//! and tests folded into others"); GPF and GPL keep their clamps in line, as IR * IR0 leaves
//! IR's range on a large share of calls (GPF 7.9 → 9.1 ns with the out-of-line form).

use crate::Gte;
use crate::mac::{Step, color_entry, ir_test, is_plain_start, step_with};

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
        self.step_result(last, &[], 0);
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
        self.general_interpolate::<false>(shift, lm)
    }

    /// GPL: MACn = ((MACn << sf) + IRn * IR0) SAR sf. Returns the FLAG bits.
    #[inline(always)]
    pub(crate) fn gpl(&mut self, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.general_interpolate::<true>(shift, lm))
    }

    /// MACn = (start_n + IRn * IR0) SAR sf, IRn by lm, and the colour pushed (GPF, GPL),
    /// start_n being MACn << sf with `FROM_MAC` (GPL) and 0 otherwise (GPF). Returns the
    /// FLAG bits.
    #[inline(always)]
    fn general_interpolate<const FROM_MAC: bool>(&mut self, shift: u32, lm: bool) -> u32 {
        let start = if FROM_MAC {
            [1, 2, 3].map(|n| (self.regs.mac(n) as i64) << shift)
        } else {
            [0; 3]
        };
        let ir0 = self.regs.ir(0) as i64;
        let products = self.ir_vector().map(|ir| [ir * ir0]);
        let plain = start.iter().all(|&s| is_plain_start(s, 1));
        // IR * IR0 leaves IR's range whenever IR0 is past 1000h with IR large, so the rows
        // saturate one by one.
        // The FLAG bits in a local, returned to the dispatch: GPL's sums leave the 44-bit
        // range in a loop of the command, and flagged through a field on each addition they
        // cost GPL 2.5 times its time (docs/performance.md, "The plain loop").
        let mut flags = 0;
        let last = step_with::<1, { ir_test::EACH }>(&mut flags, start, products, plain, shift, lm);
        self.store_step(last);
        let code = self.regs.rgbc() & 0xFF00_0000;
        let color = color_entry(&mut flags, last.mac, code);
        self.regs.push_rgb(color);
        flags
    }
}
