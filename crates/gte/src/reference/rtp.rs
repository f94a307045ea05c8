//! RTPS and RTPT as docs/hardware/gte.md §5 states them, steps 5.1-5.7.

use super::arithmetic::{self, Row, Step, bit, flag, saturate, store};
use super::divide::divide;
use crate::{DivideMode, Flag, Registers};

/// What RTPS/RTPT compute for one vertex, steps 5.1-5.6 of docs/hardware/gte.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ProjectedVertex {
    /// Steps 5.1-5.3: the rotated and translated vertex (camera space) in MAC1-3 and IR1-3.
    /// IR3's flag is tested on [`ProjectedVertex::depth`], not on MAC3 (§5.3).
    pub camera: Step,
    /// acc_3 SAR 12 from the 44-bit accumulator, whatever sf is: the depth before SZ3's
    /// saturation (§5.3-5.4).
    pub depth: i64,
    /// SZ3: `depth` saturated to 0..=FFFFh (FLAG bit 18).
    pub sz3: u16,
    /// The divide H / SZ3 (§5.5, §6), 16.16.
    pub quotient: u32,
    /// quotient × IR1 + OFX and quotient × IR2 + OFY (16.16), the screen position before the
    /// SAR 16 and the saturation (§5.6).
    pub screen: [i64; 2],
    /// SX2 and SY2: `screen` SAR 16 saturated to -400h..=3FFh (FLAG bits 14, 13).
    pub sxy: [i16; 2],
    /// The FLAG bits steps 5.1-5.6 set for this vertex (the camera step's, SZ3, divide,
    /// MAC0 of either screen value, SX2, SY2).
    pub flag: Flag,
}

/// Step 5.7, the depth cue of the last vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct DepthCue {
    /// D = quotient × DQA + DQB, exact.
    pub exact: i64,
    /// MAC0: the low 32 bits of D.
    pub mac0: i32,
    /// IR0: D SAR 12 saturated to 0..=1000h (FLAG bit 12).
    pub ir0: i16,
    /// The FLAG bits the depth cue set (MAC0 16/15, IR0 12).
    pub flag: Flag,
}

/// RTPS: one vertex and its depth cue.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rtps {
    /// V0 projected.
    pub vertex: ProjectedVertex,
    /// The depth cue from V0's quotient.
    pub depth_cue: DepthCue,
    /// FLAG after the command.
    pub flag: Flag,
}

/// RTPT: three vertices, the depth cue of the last.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rtpt {
    /// V0, V1, V2 projected, in that order.
    pub vertices: [ProjectedVertex; 3],
    /// The depth cue from V2's quotient alone (§5.7).
    pub depth_cue: DepthCue,
    /// FLAG after the command: the three vertices' bits and the depth cue's.
    pub flag: Flag,
}

/// Steps 5.1-5.6 for vertex `index`, pushing the SZ and SXY FIFOs; returns the vertex.
fn project(
    regs: &mut Registers,
    index: usize,
    sf: bool,
    lm: bool,
    mode: DivideMode,
) -> ProjectedVertex {
    let shift = if sf { 12 } else { 0 };
    let v = regs.v[index].map(i64::from);
    let products = arithmetic::products(regs.rt, v);
    let start = regs.tr.map(|t| (t as i64) << 12);
    // 5.1: the three sums; MACn from them.
    let mut bits = 0;
    let mut rows = [Row::default(); 3];
    for n in 0..3 {
        let (exact, acc, overflow) = arithmetic::sum(n + 1, start[n], &products[n]);
        bits |= overflow;
        rows[n] = Row {
            exact,
            acc,
            mac: arithmetic::mac_of(acc, shift),
            ir: 0,
        };
    }
    // 5.2: IR1 and IR2 by lm.
    for (n, row) in rows.iter_mut().enumerate().take(2) {
        let (ir, saturated) = saturate(row.mac as i64, arithmetic::ir_min(lm), 0x7FFF);
        row.ir = ir as i16;
        if saturated {
            bits |= bit::ir(n + 1);
        }
    }
    // 5.3: IR3's value from MAC3 by lm, its flag from acc_3 SAR 12 against -8000h..=7FFFh.
    let depth = rows[2].acc >> 12;
    rows[2].ir = saturate(rows[2].mac as i64, arithmetic::ir_min(lm), 0x7FFF).0 as i16;
    if saturate(depth, -0x8000, 0x7FFF).1 {
        bits |= bit::ir(3);
    }
    let camera = Step {
        rows,
        flag: flag(bits),
    };
    store(regs, &camera);
    // 5.4: SZ3 from the same depth, pushed.
    let (sz3, saturated) = saturate(depth, 0, 0xFFFF);
    if saturated {
        bits |= bit::SZ3_OTZ;
    }
    let sz3 = sz3 as u16;
    regs.sz = [regs.sz[1], regs.sz[2], regs.sz[3], sz3];
    // 5.5: the divide.
    let q = divide(mode, regs.h, sz3);
    if q.overflow {
        bits |= bit::DIVIDE;
    }
    // 5.6: the screen position in 64 bits, MAC0's flags on each value, SX/SY from the full
    // values, saturated, pushed.
    let screen = [
        q.value as i64 * rows[0].ir as i64 + regs.ofx as i64,
        q.value as i64 * rows[1].ir as i64 + regs.ofy as i64,
    ];
    let mut sxy = [0i16; 2];
    for k in 0..2 {
        bits |= arithmetic::mac0_bits(screen[k]);
        let (s, saturated) = saturate(screen[k] >> 16, -0x400, 0x3FF);
        sxy[k] = s as i16;
        if saturated {
            bits |= [bit::SX2, bit::SY2][k];
        }
    }
    regs.sxy = [
        regs.sxy[1],
        regs.sxy[2],
        sxy[0] as u16 as u32 | (sxy[1] as u16 as u32) << 16,
    ];
    ProjectedVertex {
        camera,
        depth,
        sz3,
        quotient: q.value,
        screen,
        sxy,
        flag: flag(bits),
    }
}

/// Step 5.7 from `quotient`: MAC0 and IR0.
fn depth_cue(regs: &mut Registers, quotient: u32) -> DepthCue {
    let exact = quotient as i64 * regs.dqa as i64 + regs.dqb as i64;
    let mut bits = arithmetic::mac0_bits(exact);
    let (ir0, saturated) = saturate(exact >> 12, 0, 0x1000);
    if saturated {
        bits |= bit::IR0;
    }
    regs.mac[0] = exact as i32;
    regs.ir[0] = ir0 as i16;
    DepthCue {
        exact,
        mac0: exact as i32,
        ir0: ir0 as i16,
        flag: flag(bits),
    }
}

/// RTPS (docs/hardware/gte.md §5): V0 projected, then the depth cue. Updates `regs`, FLAG
/// included.
pub fn rtps(regs: &mut Registers, sf: bool, lm: bool, mode: DivideMode) -> Rtps {
    let vertex = project(regs, 0, sf, lm, mode);
    let depth_cue = depth_cue(regs, vertex.quotient);
    let flag = arithmetic::union(&[vertex.flag, depth_cue.flag]);
    regs.flag = flag;
    Rtps {
        vertex,
        depth_cue,
        flag,
    }
}

/// RTPT (docs/hardware/gte.md §5): V0, V1, V2 projected in order, then the depth cue of V2
/// alone. Updates `regs`, FLAG included.
pub fn rtpt(regs: &mut Registers, sf: bool, lm: bool, mode: DivideMode) -> Rtpt {
    let vertices = [0, 1, 2].map(|i| project(regs, i, sf, lm, mode));
    let depth_cue = depth_cue(regs, vertices[2].quotient);
    let flag = arithmetic::union(&[
        vertices[0].flag,
        vertices[1].flag,
        vertices[2].flag,
        depth_cue.flag,
    ]);
    regs.flag = flag;
    Rtpt {
        vertices,
        depth_cue,
        flag,
    }
}
