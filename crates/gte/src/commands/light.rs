//! Lighting commands: NCS/NCT, NCCS/NCCT, NCDS/NCDT, CC and CDP (docs/hardware/gte.md §8).

use crate::Gte;
use crate::commands::matrix::widen;

impl Gte {
    /// The normal-colour steps for vertex Vi: IR = LLM * Vi, then IR = BK + LCM * IR.
    #[inline(always)]
    fn normal_light(&mut self, index: usize, shift: u32, lm: bool) {
        let llm = widen(&self.regs.llm());
        let v = self.regs.v(index).map(i64::from);
        self.multiply_add(&llm, v, [0; 3], shift, lm);
        self.background_light(shift, lm);
    }

    /// IR = BK + LCM * IR.
    #[inline(always)]
    fn background_light(&mut self, shift: u32, lm: bool) {
        let lcm = widen(&self.regs.lcm());
        let ir = self.ir_vector();
        let bk = self.regs.bk().map(i64::from);
        self.multiply_add(&lcm, ir, bk, shift, lm);
    }

    /// (Cn * IRn) << 4 with Cn the RGBC colour bytes.
    #[inline(always)]
    pub(crate) fn color_times_ir(&self) -> [i64; 3] {
        let c = self.regs.rgbc();
        let ir = self.ir_vector();
        [
            ((c & 0xFF) as i64 * ir[0]) << 4,
            (((c >> 8) & 0xFF) as i64 * ir[1]) << 4,
            (((c >> 16) & 0xFF) as i64 * ir[2]) << 4,
        ]
    }

    /// MACn = ((Cn * IRn) << 4) SAR sf, IRn by lm (the NCCS/CC colour step).
    #[inline(always)]
    fn color_step(&mut self, shift: u32, lm: bool) {
        let products = self.color_times_ir();
        for (n, p) in products.into_iter().enumerate() {
            let sum = self.accumulate(n + 1, 0, &[p]);
            self.set_mac_ir(n + 1, sum, shift, lm);
        }
    }

    fn ncs_vertex(&mut self, index: usize, shift: u32, lm: bool) {
        self.normal_light(index, shift, lm);
        self.push_color();
    }

    fn nccs_vertex(&mut self, index: usize, shift: u32, lm: bool) {
        self.normal_light(index, shift, lm);
        self.color_step(shift, lm);
        self.push_color();
    }

    fn ncds_vertex(&mut self, index: usize, shift: u32, lm: bool) {
        self.normal_light(index, shift, lm);
        let input = self.color_times_ir();
        self.depth_cue_interpolate(input, shift, lm);
        self.push_color();
    }

    /// NCS: light V0.
    pub(crate) fn ncs(&mut self, shift: u32, lm: bool) {
        self.ncs_vertex(0, shift, lm);
    }

    /// NCT: light V0, V1, V2.
    pub(crate) fn nct(&mut self, shift: u32, lm: bool) {
        for i in 0..3 {
            self.ncs_vertex(i, shift, lm);
        }
    }

    /// NCCS: light V0 and multiply by RGBC.
    pub(crate) fn nccs(&mut self, shift: u32, lm: bool) {
        self.nccs_vertex(0, shift, lm);
    }

    /// NCCT: NCCS for V0, V1, V2.
    pub(crate) fn ncct(&mut self, shift: u32, lm: bool) {
        for i in 0..3 {
            self.nccs_vertex(i, shift, lm);
        }
    }

    /// NCDS: light V0, multiply by RGBC, depth-cue towards FC.
    pub(crate) fn ncds(&mut self, shift: u32, lm: bool) {
        self.ncds_vertex(0, shift, lm);
    }

    /// NCDT: NCDS for V0, V1, V2.
    pub(crate) fn ncdt(&mut self, shift: u32, lm: bool) {
        for i in 0..3 {
            self.ncds_vertex(i, shift, lm);
        }
    }

    /// CC: IR = BK + LCM * IR, multiply by RGBC.
    pub(crate) fn cc(&mut self, shift: u32, lm: bool) {
        self.background_light(shift, lm);
        self.color_step(shift, lm);
        self.push_color();
    }

    /// CDP: IR = BK + LCM * IR, multiply by RGBC, depth-cue towards FC.
    pub(crate) fn cdp(&mut self, shift: u32, lm: bool) {
        self.background_light(shift, lm);
        let input = self.color_times_ir();
        self.depth_cue_interpolate(input, shift, lm);
        self.push_color();
    }
}
