//! The depth-cue interpolation towards FC and the commands built on it alone (DPCS, DPCT,
//! DCPL, INTPL), and GPF/GPL, as docs/hardware/gte.md §8 states them.

use super::arithmetic::{Color, Step, ir_vector, push_color, step, store, union};
use crate::{Flag, Registers};

/// The depth-cue interpolation of an input towards the far colour FC by IR0
/// (docs/hardware/gte.md §8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Interpolation {
    /// in_n: (Cn × IRn) << 4 for NCDS/NCDT/CDP/DCPL, Cn << 16 for DPCS/DPCT, IRn << 12 for
    /// INTPL.
    pub input: [i64; 3],
    /// (a) MACn = ((FCn << 12) - in_n) SAR (sf × 12), IRn saturated to -8000h..=7FFFh
    /// whatever lm is.
    pub far: Step,
    /// (b) MACn = (IRn × IR0 + in_n) SAR (sf × 12), IRn by lm, with IRn from (a).
    pub near: Step,
}

/// A depth cue and the colour it pushed: DPCS, DCPL, INTPL, or one of DPCT's three.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct DepthCued {
    /// The interpolation.
    pub interpolation: Interpolation,
    /// The colour pushed from the interpolation's MAC1-3.
    pub push: Color,
    /// The FLAG bits set (for DPCS, DCPL and INTPL, FLAG after the command).
    pub flag: Flag,
}

/// DPCT's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct DepthCuedTriple {
    /// The three depth cues, in order.
    pub entries: [DepthCued; 3],
    /// FLAG after the command.
    pub flag: Flag,
}

/// GPF's or GPL's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct General {
    /// MAC1-3 and IR1-3.
    pub step: Step,
    /// The colour pushed.
    pub push: Color,
    /// FLAG after the command.
    pub flag: Flag,
}

fn shift_of(sf: bool) -> u32 {
    if sf { 12 } else { 0 }
}

/// Steps (a) and (b) of the interpolation of `input`, MAC1-3 and IR1-3 stored after each.
pub(super) fn interpolate(
    regs: &mut Registers,
    input: [i64; 3],
    sf: bool,
    lm: bool,
) -> Interpolation {
    let shift = shift_of(sf);
    let fc = regs.fc.map(|f| (f as i64) << 12);
    let minus = input.map(|i| [-i]);
    let far = step(fc, [&minus[0], &minus[1], &minus[2]], shift, false);
    store(regs, &far);
    let ir0 = regs.ir[0] as i64;
    let p = ir_vector(regs).map(|ir| [ir * ir0]);
    let near = step(input, [&p[0], &p[1], &p[2]], shift, lm);
    store(regs, &near);
    Interpolation { input, far, near }
}

/// The colour bytes R, G, B of a word, each shifted left 16.
fn color_input(word: u32) -> [i64; 3] {
    [0, 8, 16].map(|s| (((word >> s) & 0xFF) as i64) << 16)
}

/// (Cn × IRn) << 4 with Cn the RGBC colour bytes and IRn the registers.
pub(super) fn color_times_ir(regs: &Registers) -> [i64; 3] {
    let ir = ir_vector(regs);
    [0, 1, 2].map(|n| (((regs.rgbc >> (8 * n)) & 0xFF) as i64 * ir[n]) << 4)
}

fn depth_cued(regs: &mut Registers, input: [i64; 3], sf: bool, lm: bool) -> DepthCued {
    let interpolation = interpolate(regs, input, sf, lm);
    let push = push_color(regs);
    let flag = union(&[interpolation.far.flag, interpolation.near.flag, push.flag]);
    DepthCued {
        interpolation,
        push,
        flag,
    }
}

fn single(regs: &mut Registers, input: [i64; 3], sf: bool, lm: bool) -> DepthCued {
    let d = depth_cued(regs, input, sf, lm);
    regs.flag = d.flag;
    d
}

/// DPCS (docs/hardware/gte.md §8): RGBC's colour depth-cued. Updates `regs`, FLAG included.
pub fn dpcs(regs: &mut Registers, sf: bool, lm: bool) -> DepthCued {
    single(regs, color_input(regs.rgbc), sf, lm)
}

/// DPCT (docs/hardware/gte.md §8): DPCS three times on RGB0, the bottom of the colour FIFO,
/// read again after each push (CODE still from RGBC). Updates `regs`, FLAG included.
pub fn dpct(regs: &mut Registers, sf: bool, lm: bool) -> DepthCuedTriple {
    let entries = [(); 3].map(|_| depth_cued(regs, color_input(regs.rgb[0]), sf, lm));
    let flag = union(&entries.map(|e| e.flag));
    regs.flag = flag;
    DepthCuedTriple { entries, flag }
}

/// DCPL (docs/hardware/gte.md §8): (RGBC × IR) << 4 depth-cued. Updates `regs`, FLAG
/// included.
pub fn dcpl(regs: &mut Registers, sf: bool, lm: bool) -> DepthCued {
    single(regs, color_times_ir(regs), sf, lm)
}

/// INTPL (docs/hardware/gte.md §8): IR << 12 interpolated towards FC. Updates `regs`, FLAG
/// included.
pub fn intpl(regs: &mut Registers, sf: bool, lm: bool) -> DepthCued {
    single(regs, ir_vector(regs).map(|ir| ir << 12), sf, lm)
}

fn general(regs: &mut Registers, start: [i64; 3], sf: bool, lm: bool) -> General {
    let ir0 = regs.ir[0] as i64;
    let p = ir_vector(regs).map(|ir| [ir * ir0]);
    let s = step(start, [&p[0], &p[1], &p[2]], shift_of(sf), lm);
    store(regs, &s);
    let push = push_color(regs);
    let flag = union(&[s.flag, push.flag]);
    regs.flag = flag;
    General {
        step: s,
        push,
        flag,
    }
}

/// GPF (docs/hardware/gte.md §8): MACn = (IRn × IR0) SAR (sf × 12), IR by lm, a colour
/// pushed. Updates `regs`, FLAG included.
pub fn gpf(regs: &mut Registers, sf: bool, lm: bool) -> General {
    general(regs, [0; 3], sf, lm)
}

/// GPL (docs/hardware/gte.md §8): MACn = ((MACn << (sf × 12)) + IRn × IR0) SAR (sf × 12), IR
/// by lm, a colour pushed. Updates `regs`, FLAG included.
pub fn gpl(regs: &mut Registers, sf: bool, lm: bool) -> General {
    let start = [1, 2, 3].map(|n| (regs.mac[n] as i64) << shift_of(sf));
    general(regs, start, sf, lm)
}
