//! MVMVA, SQR and OP as docs/hardware/gte.md §8 states them, with MVMVA's operands chosen as
//! §1 says.

use super::arithmetic::{self, Step, ir_vector, step, store, union};
use crate::{Command, Flag, MatrixSel, Registers, TranslationSel, VectorSel};

/// MVMVA's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Mvmva {
    /// MAC1-3 and IR1-3: (T << 12 + M × V) SAR (sf × 12), or with cv = 2 (FC) only
    /// (M_n2 × V2 + M_n3 × V3) SAR (sf × 12) (§8).
    pub step: Step,
    /// With cv = 2: per row, FC_n << 12 + M_n1 × V1, formed, tested (44-bit flags, and IR's
    /// flag with the lm = 0 range) and discarded; its `ir` values are never stored.
    pub discarded: Option<Step>,
    /// FLAG after the command.
    pub flag: Flag,
}

/// SQR's or OP's result.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vector {
    /// MAC1-3 and IR1-3.
    pub step: Step,
    /// FLAG after the command.
    pub flag: Flag,
}

/// The matrix MVMVA's `mx` selects; 3 gives [-(R << 4), R << 4, IR0], [RT13] × 3, [RT22] × 3
/// with R = RGBC bits 0-7 (§8).
pub(super) fn matrix(regs: &Registers, mx: MatrixSel) -> [[i16; 3]; 3] {
    match mx {
        MatrixSel::Rotation => regs.rt,
        MatrixSel::Light => regs.llm,
        MatrixSel::LightColor => regs.lcm,
        MatrixSel::Garbage => {
            let r = ((regs.rgbc & 0xFF) << 4) as i16;
            [[-r, r, regs.ir[0]], [regs.rt[0][2]; 3], [regs.rt[1][1]; 3]]
        }
    }
}

/// MVMVA (docs/hardware/gte.md §8) with the sf, lm, mx, v and cv of `command`. Updates
/// `regs`, FLAG included.
pub fn mvmva(regs: &mut Registers, command: Command) -> Mvmva {
    let shift = command.shift();
    let lm = command.lm();
    let m = matrix(regs, command.mx());
    let v = match command.v() {
        VectorSel::V0 => regs.v[0].map(i64::from),
        VectorSel::V1 => regs.v[1].map(i64::from),
        VectorSel::V2 => regs.v[2].map(i64::from),
        VectorSel::Ir => ir_vector(regs),
    };
    let p = arithmetic::products(m, v);
    let add = match command.cv() {
        TranslationSel::Translation => regs.tr,
        TranslationSel::Background => regs.bk,
        TranslationSel::FarColor => regs.fc,
        TranslationSel::None => [0; 3],
    };
    let start = add.map(|t| (t as i64) << 12);
    let (result, discarded) = if command.cv() == TranslationSel::FarColor {
        let discarded = step(start, [&p[0][..1], &p[1][..1], &p[2][..1]], shift, false);
        let result = step([0; 3], [&p[0][1..], &p[1][1..], &p[2][1..]], shift, lm);
        (result, Some(discarded))
    } else {
        (step(start, [&p[0], &p[1], &p[2]], shift, lm), None)
    };
    store(regs, &result);
    let flag = union(&[result.flag, discarded.map_or(Flag::EMPTY, |d| d.flag)]);
    regs.flag = flag;
    Mvmva {
        step: result,
        discarded,
        flag,
    }
}

/// SQR (docs/hardware/gte.md §8): MACn = IRn² SAR (sf × 12), IR by lm. Updates `regs`, FLAG
/// included.
pub fn sqr(regs: &mut Registers, sf: bool, lm: bool) -> Vector {
    let ir = ir_vector(regs);
    let p = ir.map(|x| [x * x]);
    products(regs, [&p[0], &p[1], &p[2]], sf, lm)
}

/// OP (docs/hardware/gte.md §8): the outer product of D = (RT11, RT22, RT33) and IR1-3,
/// MAC1 = IR3·D2 - IR2·D3, MAC2 = IR1·D3 - IR3·D1, MAC3 = IR2·D1 - IR1·D2, each SAR
/// (sf × 12), IR by lm. Updates `regs`, FLAG included.
pub fn op(regs: &mut Registers, sf: bool, lm: bool) -> Vector {
    let [i1, i2, i3] = ir_vector(regs);
    let [d1, d2, d3] = [regs.rt[0][0], regs.rt[1][1], regs.rt[2][2]].map(i64::from);
    let p = [
        [i3 * d2, -(i2 * d3)],
        [i1 * d3, -(i3 * d1)],
        [i2 * d1, -(i1 * d2)],
    ];
    products(regs, [&p[0], &p[1], &p[2]], sf, lm)
}

/// SQR's and OP's last step (§8): MACn = the sum of row n's products SAR (sf × 12), IR by
/// lm; MAC1-3, IR1-3 and FLAG stored.
fn products(regs: &mut Registers, p: [&[i64]; 3], sf: bool, lm: bool) -> Vector {
    let s = step([0; 3], p, if sf { 12 } else { 0 }, lm);
    store(regs, &s);
    regs.flag = s.flag;
    Vector {
        step: s,
        flag: s.flag,
    }
}
