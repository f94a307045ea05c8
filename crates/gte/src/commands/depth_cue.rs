//! Depth-cue and interpolation commands: DPCS, DPCT, DCPL, INTPL, GPF, GPL (docs/hardware/gte.md §8).

use crate::Gte;
use crate::mac::accumulate;

impl Gte {
    /// Interpolate `input` towards the far colour by IR0 (docs/hardware/gte.md §8): first
    /// MACn = ((FCn << 12) minus in_n) SAR sf with IRn saturated to the lm=0 range whatever lm
    /// is, then MACn = (IRn * IR0 + in_n) SAR sf with IRn by lm. Every input is below 2^27 in
    /// magnitude, so the second sum is plain addition.
    #[inline(always)]
    pub(crate) fn depth_cue_interpolate(&mut self, input: [i64; 3], shift: u32, lm: bool) {
        let fc = self.regs.fc();
        for n in 1..=3 {
            let sum = self.accumulate(n, (fc[n - 1] as i64) << 12, &[-input[n - 1]]);
            self.set_mac_ir(n, sum, shift, false);
        }
        let ir0 = self.regs.ir(0) as i64;
        let ir = self.ir_vector();
        for n in 1..=3 {
            let sum = accumulate(
                &mut self.flag_bits,
                n,
                input[n - 1],
                &[ir[n - 1] * ir0],
                true,
            );
            self.set_mac_ir(n, sum, shift, lm);
        }
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
    #[inline]
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

    /// GPF: MACn = (IRn * IR0) SAR sf.
    #[inline]
    pub(crate) fn gpf(&mut self, shift: u32, lm: bool) {
        let ir0 = self.regs.ir(0) as i64;
        let ir = self.ir_vector();
        for n in 1..=3 {
            let sum = self.accumulate(n, 0, &[ir[n - 1] * ir0]);
            self.set_mac_ir(n, sum, shift, lm);
        }
        self.push_color();
    }

    /// GPL: MACn = ((MACn << sf) + IRn * IR0) SAR sf.
    #[inline]
    pub(crate) fn gpl(&mut self, shift: u32, lm: bool) {
        let ir0 = self.regs.ir(0) as i64;
        let ir = self.ir_vector();
        for n in 1..=3 {
            let base = (self.regs.mac(n) as i64) << shift;
            let sum = self.accumulate(n, base, &[ir[n - 1] * ir0]);
            self.set_mac_ir(n, sum, shift, lm);
        }
        self.push_color();
    }
}
