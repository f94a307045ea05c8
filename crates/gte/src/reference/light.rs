//! The lighting commands NCS/NCT, NCCS/NCCT, NCDS/NCDT, CC and CDP as docs/hardware/gte.md
//! §8 states them: each step's MAC1-3 and IR1-3 are stored before the next step reads IR.

use super::arithmetic::{self, Color, Step, ir_vector, push_color, step, store, union};
use super::depth_cue::{Interpolation, color_times_ir, interpolate};
use crate::{Flag, Registers};

/// What a lighting command computes for one vertex (or for CC/CDP, for IR1-3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Lit {
    /// NCS/NCT/NCCS/NCCT/NCDS/NCDT: (LLM × V) SAR (sf × 12); `None` for CC and CDP.
    pub light: Option<Step>,
    /// (BK << 12 + LCM × IR) SAR (sf × 12).
    pub background: Step,
    /// NCCS/NCCT/CC: ((Cn × IRn) << 4) SAR (sf × 12), Cn the RGBC colour bytes.
    pub color: Option<Step>,
    /// NCDS/NCDT/CDP: (Cn × IRn) << 4 depth-cued towards FC by IR0.
    pub depth_cue: Option<Interpolation>,
    /// The colour pushed from the last step's MAC1-3.
    pub push: Color,
    /// The FLAG bits set (for a single-vertex command, FLAG after it).
    pub flag: Flag,
}

/// NCT's, NCCT's or NCDT's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LitTriple {
    /// V0, V1, V2, in order.
    pub vertices: [Lit; 3],
    /// FLAG after the command.
    pub flag: Flag,
}

/// What follows the background step.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Finish {
    /// NCS/NCT: nothing.
    Light,
    /// NCCS/NCCT/CC: times RGBC.
    Color,
    /// NCDS/NCDT/CDP: times RGBC, depth-cued.
    DepthCue,
}

fn shift_of(sf: bool) -> u32 {
    if sf { 12 } else { 0 }
}

/// MAC/IR = (start + m × v) SAR (sf × 12), IR by lm, stored.
fn matrix_step(
    regs: &mut Registers,
    m: [[i16; 3]; 3],
    v: [i64; 3],
    start: [i64; 3],
    sf: bool,
    lm: bool,
) -> Step {
    let p = arithmetic::products(m, v);
    let s = step(start, [&p[0], &p[1], &p[2]], shift_of(sf), lm);
    store(regs, &s);
    s
}

/// The steps after the light step (if any): background, then colour or depth cue, then the
/// push.
fn finish(regs: &mut Registers, light: Option<Step>, how: Finish, sf: bool, lm: bool) -> Lit {
    let bk = regs.bk.map(|b| (b as i64) << 12);
    let background = matrix_step(regs, regs.lcm, ir_vector(regs), bk, sf, lm);
    let (mut color, mut depth_cue) = (None, None);
    match how {
        Finish::Light => {}
        Finish::Color => {
            let p = color_times_ir(regs).map(|x| [x]);
            let s = step([0; 3], [&p[0], &p[1], &p[2]], shift_of(sf), lm);
            store(regs, &s);
            color = Some(s);
        }
        Finish::DepthCue => depth_cue = Some(interpolate(regs, color_times_ir(regs), sf, lm)),
    }
    let push = push_color(regs);
    let mut flags = [Flag::EMPTY; 6];
    flags[0] = light.map_or(Flag::EMPTY, |s| s.flag);
    flags[1] = background.flag;
    flags[2] = color.map_or(Flag::EMPTY, |s| s.flag);
    if let Some(d) = depth_cue {
        (flags[3], flags[4]) = (d.far.flag, d.near.flag);
    }
    flags[5] = push.flag;
    Lit {
        light,
        background,
        color,
        depth_cue,
        push,
        flag: union(&flags),
    }
}

/// One vertex of a normal-colour command: the light step from V`index`, then the rest.
fn vertex(regs: &mut Registers, index: usize, how: Finish, sf: bool, lm: bool) -> Lit {
    let v = regs.v[index].map(i64::from);
    let light = matrix_step(regs, regs.llm, v, [0; 3], sf, lm);
    finish(regs, Some(light), how, sf, lm)
}

fn single(regs: &mut Registers, how: Finish, sf: bool, lm: bool) -> Lit {
    let lit = vertex(regs, 0, how, sf, lm);
    regs.flag = lit.flag;
    lit
}

fn triple(regs: &mut Registers, how: Finish, sf: bool, lm: bool) -> LitTriple {
    let vertices = [0, 1, 2].map(|i| vertex(regs, i, how, sf, lm));
    let flag = union(&vertices.map(|v| v.flag));
    regs.flag = flag;
    LitTriple { vertices, flag }
}

/// NCS: V0 lit (LLM, then BK + LCM). Updates `regs`, FLAG included.
pub fn ncs(regs: &mut Registers, sf: bool, lm: bool) -> Lit {
    single(regs, Finish::Light, sf, lm)
}

/// NCT: NCS for V0, V1, V2.
pub fn nct(regs: &mut Registers, sf: bool, lm: bool) -> LitTriple {
    triple(regs, Finish::Light, sf, lm)
}

/// NCCS: NCS times the RGBC colour.
pub fn nccs(regs: &mut Registers, sf: bool, lm: bool) -> Lit {
    single(regs, Finish::Color, sf, lm)
}

/// NCCT: NCCS for V0, V1, V2.
pub fn ncct(regs: &mut Registers, sf: bool, lm: bool) -> LitTriple {
    triple(regs, Finish::Color, sf, lm)
}

/// NCDS: NCS times the RGBC colour, depth-cued towards FC by IR0.
pub fn ncds(regs: &mut Registers, sf: bool, lm: bool) -> Lit {
    single(regs, Finish::DepthCue, sf, lm)
}

/// NCDT: NCDS for V0, V1, V2.
pub fn ncdt(regs: &mut Registers, sf: bool, lm: bool) -> LitTriple {
    triple(regs, Finish::DepthCue, sf, lm)
}

/// CC: IR1-3 through BK + LCM, times the RGBC colour.
pub fn cc(regs: &mut Registers, sf: bool, lm: bool) -> Lit {
    let lit = finish(regs, None, Finish::Color, sf, lm);
    regs.flag = lit.flag;
    lit
}

/// CDP: IR1-3 through BK + LCM, times the RGBC colour, depth-cued towards FC by IR0.
pub fn cdp(regs: &mut Registers, sf: bool, lm: bool) -> Lit {
    let lit = finish(regs, None, Finish::DepthCue, sf, lm);
    regs.flag = lit.flag;
    lit
}
