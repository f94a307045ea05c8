//! Lighting commands: NCS/NCT, NCCS/NCCT, NCDS/NCDT, CC and CDP (docs/hardware/gte.md §8).
//!
//! A command reads its operands once, carries the MAC1-3 and IR1-3 values of each step to the
//! next, and stores the last step's MAC1-3 and IR1-3 and the colours it pushes at the end: the
//! registers then hold what the hardware's step-by-step writes leave. Its FLAG bits are
//! collected in a local and returned to the dispatch.
//!
//! Why this shape: the IRs of the second step, the colour step and the depth cue are tested
//! together, one compare each, with the clamps out of line when one fires: NCDS 370 → 316
//! instructions a call, 0.855 of its time (docs/performance.md, "Saturation tests"). The light
//! step keeps a test per IR, as light from behind a surface saturates it often. The three
//! colour bytes are one test too (NCDS 240 → 233 instructions in the plain loop, "The plain
//! loop: short paths").

use crate::Gte;
use crate::commands::depth_cue::interpolate;
use crate::mac::{Step, color_entry_rare as color, ir_test, matrix_products, step, step_with};
use crate::registers::RegisterFile;

/// The operands of a lighting command that its first step reads, read once per command, and
/// the register file for LCM, BK, FC and IR0, read at their use: loaded up front for the
/// three vertices, they did not fit the registers and went through the stack (NCDT 547 →
/// 537 instructions a call in the plain loop, docs/performance.md, "The plain loop: short
/// paths").
struct Lighting<'r> {
    regs: &'r RegisterFile,
    /// Light matrix LLM, widened.
    llm: [[i64; 3]; 3],
    /// RGBC colour bytes R, G, B.
    color: [i64; 3],
    /// RGBC's CODE byte, in place.
    code: u32,
    /// 0 or 12 (sf).
    shift: u32,
    lm: bool,
}

impl<'r> Lighting<'r> {
    #[inline(always)]
    fn read(regs: &'r RegisterFile, shift: u32, lm: bool) -> Self {
        let rgbc = regs.rgbc();
        Lighting {
            regs,
            llm: regs.llm_wide(),
            color: [0, 8, 16].map(|s| ((rgbc >> s) & 0xFF) as i64),
            code: rgbc & 0xFF00_0000,
            shift,
            lm,
        }
    }

    /// Light colour matrix LCM, widened.
    #[inline(always)]
    fn lcm(&self) -> [[i64; 3]; 3] {
        self.regs.lcm_wide()
    }

    /// Background colour BK << 12, the start of the second step.
    #[inline(always)]
    fn bk(&self) -> [i64; 3] {
        self.regs.bk().map(|b| (b as i64) << 12)
    }

    /// Far colour FC << 12, the start of the depth cue's first step.
    #[inline(always)]
    fn fc(&self) -> [i64; 3] {
        self.regs.fc().map(|f| (f as i64) << 12)
    }

    /// MACn = (start_n + row n of `m` * `v`) SAR sf, IRn by lm.
    #[inline(always)]
    fn matrix_step(
        &self,
        flags: &mut u32,
        m: &[[i64; 3]; 3],
        v: [i64; 3],
        start: [i64; 3],
        plain: bool,
    ) -> Step {
        let products = matrix_products(m, v);
        step(flags, start, products, plain, self.shift, self.lm)
    }

    /// A vertex of a normal-colour command: its last step and its colour.
    #[inline(always)]
    fn vertex<const PLAIN: bool>(&self, flags: &mut u32, v: [i16; 3], how: Finish) -> (Step, u32) {
        let lit = self.normal_light::<PLAIN>(flags, v);
        let last = match how {
            Finish::Light => lit,
            Finish::Color => self.color_step(flags, lit.ir),
            Finish::DepthCue => self.depth_cue::<PLAIN>(flags, lit.ir),
        };
        (last, color(flags, last.mac, self.code))
    }

    /// IR = LLM * V, then IR = BK + LCM * IR (the normal-colour steps). The first step's IRs
    /// saturate whenever the normal faces away from a light (at 0 with lm), so they are
    /// tested one by one ([`step_with`]).
    #[inline(always)]
    fn normal_light<const PLAIN: bool>(&self, flags: &mut u32, v: [i16; 3]) -> Step {
        let products = matrix_products(&self.llm, v.map(i64::from));
        let light =
            step_with::<3, { ir_test::EACH }>(flags, [0; 3], products, true, self.shift, self.lm);
        self.background_light::<PLAIN>(flags, light.ir)
    }

    /// IR = BK + LCM * IR.
    #[inline(always)]
    fn background_light<const PLAIN: bool>(&self, flags: &mut u32, ir: [i64; 3]) -> Step {
        self.matrix_step(flags, &self.lcm(), ir, self.bk(), PLAIN)
    }

    /// (Cn * IRn) << 4 with Cn the RGBC colour bytes.
    #[inline(always)]
    fn color_times(&self, ir: [i64; 3]) -> [i64; 3] {
        [0, 1, 2].map(|n| (self.color[n] * ir[n]) << 4)
    }

    /// MACn = ((Cn * IRn) << 4) SAR sf, IRn by lm (the NCCS/CC colour step).
    #[inline(always)]
    fn color_step(&self, flags: &mut u32, ir: [i64; 3]) -> Step {
        let products = self.color_times(ir).map(|p| [p]);
        step(flags, [0; 3], products, true, self.shift, self.lm)
    }

    /// The depth cue of (Cn * IRn) << 4 towards FC by IR0 (docs/hardware/gte.md §8): MACn =
    /// ((FCn << 12) - in_n) SAR sf with IRn saturated to the lm=0 range, then MACn =
    /// (IRn * IR0 + in_n) SAR sf with IRn by lm. The second sum starts below 2^27 in
    /// magnitude, so it is plain addition.
    #[inline(always)]
    fn depth_cue<const PLAIN: bool>(&self, flags: &mut u32, ir: [i64; 3]) -> Step {
        let input = self.color_times(ir);
        let ir0 = self.regs.ir(0) as i64;
        interpolate::<{ ir_test::GROUPED }>(
            flags,
            input,
            self.fc(),
            ir0,
            PLAIN,
            self.shift,
            self.lm,
        )
    }
}

/// What a lighting command does after the normal-colour steps.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Finish {
    /// NCS/NCT: the colour from BK + LCM * IR.
    Light,
    /// NCCS/NCCT: times RGBC.
    Color,
    /// NCDS/NCDT: times RGBC, depth-cued towards FC.
    DepthCue,
}

impl Gte {
    /// The normal-colour commands on `COUNT` vertices from V0 (1 or 3), with BK and FC sums
    /// plain or not by `PLAIN`; returns the FLAG bits.
    #[inline(always)]
    fn normal_color<const COUNT: usize, const PLAIN: bool>(
        &mut self,
        shift: u32,
        lm: bool,
        how: Finish,
    ) -> u32 {
        let l = Lighting::read(&self.regs, shift, lm);
        let mut flags = 0;
        let mut colors = [0; COUNT];
        let (mut last, c) = l.vertex::<PLAIN>(&mut flags, self.regs.v(0), how);
        colors[0] = c;
        if COUNT == 3 {
            (_, colors[1]) = l.vertex::<PLAIN>(&mut flags, self.regs.v(1), how);
            (last, colors[2]) = l.vertex::<PLAIN>(&mut flags, self.regs.v(2), how);
        }
        self.step_result(last, &colors);
        flags
    }

    #[inline(always)]
    fn normal_color_command<const COUNT: usize>(
        &mut self,
        shift: u32,
        lm: bool,
        how: Finish,
    ) -> u32 {
        with_constant_sf_lm!(shift, lm, {
            // Every sum from BK (three products) and from FC (one product) plain addition
            // (docs/hardware/gte.md §4), for every vertex alike.
            if self.regs.bk_plain() && self.regs.fc_plain() {
                self.normal_color::<COUNT, true>(shift, lm, how)
            } else {
                self.normal_color::<COUNT, false>(shift, lm, how)
            }
        })
    }

    /// NCS: light V0. Returns the FLAG bits.
    pub(crate) fn ncs(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<1>(shift, lm, Finish::Light)
    }

    /// NCT: light V0, V1, V2. Returns the FLAG bits.
    pub(crate) fn nct(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<3>(shift, lm, Finish::Light)
    }

    /// NCCS: light V0 and multiply by RGBC. Returns the FLAG bits.
    pub(crate) fn nccs(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<1>(shift, lm, Finish::Color)
    }

    /// NCCT: NCCS for V0, V1, V2. Returns the FLAG bits.
    pub(crate) fn ncct(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<3>(shift, lm, Finish::Color)
    }

    /// NCDS: light V0, multiply by RGBC, depth-cue towards FC. Returns the FLAG bits.
    pub(crate) fn ncds(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<1>(shift, lm, Finish::DepthCue)
    }

    /// NCDT: NCDS for V0, V1, V2. Returns the FLAG bits.
    pub(crate) fn ncdt(&mut self, shift: u32, lm: bool) -> u32 {
        self.normal_color_command::<3>(shift, lm, Finish::DepthCue)
    }

    /// CC and CDP: IR = BK + LCM * IR, then times RGBC (and depth-cued towards FC).
    #[inline(always)]
    fn color_color(&mut self, shift: u32, lm: bool, how: Finish) -> u32 {
        let ir = self.ir_vector();
        let l = Lighting::read(&self.regs, shift, lm);
        let plain = self.regs.bk_plain() && self.regs.fc_plain();
        let mut flags = 0;
        let lit = l.matrix_step(&mut flags, &l.lcm(), ir, l.bk(), plain);
        let last = if how == Finish::DepthCue {
            if plain {
                l.depth_cue::<true>(&mut flags, lit.ir)
            } else {
                l.depth_cue::<false>(&mut flags, lit.ir)
            }
        } else {
            l.color_step(&mut flags, lit.ir)
        };
        let c = color(&mut flags, last.mac, l.code);
        self.step_result(last, &[c]);
        flags
    }

    /// CC: IR = BK + LCM * IR, multiply by RGBC. Returns the FLAG bits.
    pub(crate) fn cc(&mut self, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.color_color(shift, lm, Finish::Color))
    }

    /// CDP: IR = BK + LCM * IR, multiply by RGBC, depth-cue towards FC. Returns the FLAG
    /// bits.
    pub(crate) fn cdp(&mut self, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.color_color(shift, lm, Finish::DepthCue))
    }

    /// (Cn * IRn) << 4 with Cn the RGBC colour bytes and IRn the registers.
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
}
