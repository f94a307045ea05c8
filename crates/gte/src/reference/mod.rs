//! A reference model of the GTE (feature `reference`): every command as
//! docs/hardware/gte.md states it, written from that page alone and kept apart from the
//! engine, with the exact values the hardware computes before any wrap or saturation.
//!
//! Each command function takes the register file ([`Registers`], as [`Gte::registers`]
//! returns it), updates it as the command does, FLAG included, and returns what each step
//! computed: the exact 64-bit sums beside the 44-bit accumulators and the 32-bit MACs, the
//! unsaturated IR, depth, screen, OTZ and colour values, the divide's quotient, and the FLAG
//! bits of each step. [`execute`] runs a whole 25-bit command word. [`read()`] and [`write()`]
//! are MFC2/CFC2 and MTC2/CTC2 with the rules of docs/hardware/gte.md §2.
//!
//! The model favours being plainly checkable against the page over speed: it computes in
//! `i64`, stores each step's MAC1-3 and IR1-3 before the next step reads IR, and builds FLAG
//! from named conditions. The crate's own tests hold it to the 1,150 console-recorded
//! vectors and the engine to it on every command. `no_std`, no allocation, no panics.
//!
//! ```
//! use gte::reference::{self, Trace};
//! use gte::{Gte, Opcode};
//!
//! let mut gte = Gte::new();
//! gte.write_data(12, 0x7FFF_7FFF); // SXY0 = (7FFFh, 7FFFh)
//! gte.write_data(13, 0x7FFF_8000); // SXY1 = (-8000h, 7FFFh)
//! gte.write_data(14, 0x8000_7FFF); // SXY2 = (7FFFh, -8000h)
//! let mut regs = gte.registers();
//! let trace = reference::execute(&mut regs, Opcode::Nclip.bits());
//! gte.execute(Opcode::Nclip.bits());
//! assert_eq!(gte.registers(), regs);
//! let Trace::Nclip(n) = trace else { unreachable!() };
//! // Twice the area, FFFFh², does not fit MAC0: it wraps, with FLAG bit 16 (and 31).
//! assert_eq!(n.exact, 0xFFFF * 0xFFFF);
//! assert_eq!(n.mac0, 0xFFFE_0001_u32 as i32);
//! assert_eq!(n.flag.bits(), 0x8001_0000);
//! ```
//!
//! [`Gte::registers`]: crate::Gte::registers

mod arithmetic;
mod depth_cue;
mod divide;
mod light;
mod registers;
mod rtp;
mod screen;
mod vector;

pub use arithmetic::{Color, Row, Step};
pub use depth_cue::{
    DepthCued, DepthCuedTriple, General, Interpolation, dcpl, dpcs, dpct, gpf, gpl, intpl,
};
pub use divide::{QUOTIENT_LIMIT, Quotient, SEEDS, divide, unr};
pub use light::{Lit, LitTriple, cc, cdp, nccs, ncct, ncds, ncdt, ncs, nct};
pub use registers::{read, write};
pub use rtp::{DepthCue, ProjectedVertex, Rtps, Rtpt, rtps, rtpt};
pub use screen::{AverageZ, Nclip, avsz3, avsz4, nclip};
pub use vector::{Mvmva, Vector, mvmva, op, sqr};

use crate::{Command, DivideMode, Flag, Opcode, Registers};

/// What one command computed, by command.
// The variants' sizes differ (a triple lighting command's three vertices against nothing for
// an undefined opcode); boxing would need an allocator, which the model does without.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Trace {
    /// RTPS.
    Rtps(Rtps),
    /// RTPT.
    Rtpt(Rtpt),
    /// NCLIP.
    Nclip(Nclip),
    /// AVSZ3 or AVSZ4.
    AverageZ(AverageZ),
    /// MVMVA.
    Mvmva(Mvmva),
    /// SQR or OP.
    Vector(Vector),
    /// NCS, NCCS, NCDS, CC or CDP.
    Lit(Lit),
    /// NCT, NCCT or NCDT.
    LitTriple(LitTriple),
    /// DPCS, DCPL or INTPL.
    DepthCued(DepthCued),
    /// DPCT.
    DepthCuedTriple(DepthCuedTriple),
    /// GPF or GPL.
    General(General),
    /// An undefined opcode: FLAG cleared, nothing else changed (docs/gte.md, "Undefined
    /// opcodes").
    Undefined,
}

impl Trace {
    /// FLAG as the command left it.
    pub fn flag(&self) -> Flag {
        match self {
            Trace::Rtps(t) => t.flag,
            Trace::Rtpt(t) => t.flag,
            Trace::Nclip(t) => t.flag,
            Trace::AverageZ(t) => t.flag,
            Trace::Mvmva(t) => t.flag,
            Trace::Vector(t) => t.flag,
            Trace::Lit(t) => t.flag,
            Trace::LitTriple(t) => t.flag,
            Trace::DepthCued(t) => t.flag,
            Trace::DepthCuedTriple(t) => t.flag,
            Trace::General(t) => t.flag,
            Trace::Undefined => Flag::EMPTY,
        }
    }
}

/// Run the COP2 command word `command` (its low 25 bits) on `regs` with the hardware divide.
pub fn execute(regs: &mut Registers, command: u32) -> Trace {
    execute_with(regs, command, DivideMode::Unr)
}

/// [`execute`] with RTPS/RTPT dividing by `mode` ([`DivideMode::Unr`] is the hardware; the
/// others are the engine's accuracy knobs).
pub fn execute_with(regs: &mut Registers, command: u32, mode: DivideMode) -> Trace {
    let c = Command::new(command);
    let (sf, lm) = (c.shift() != 0, c.lm());
    let Some(opcode) = c.opcode() else {
        regs.flag = Flag::EMPTY;
        return Trace::Undefined;
    };
    match opcode {
        Opcode::Rtps => Trace::Rtps(rtps(regs, sf, lm, mode)),
        Opcode::Rtpt => Trace::Rtpt(rtpt(regs, sf, lm, mode)),
        Opcode::Nclip => Trace::Nclip(nclip(regs)),
        Opcode::Avsz3 => Trace::AverageZ(avsz3(regs)),
        Opcode::Avsz4 => Trace::AverageZ(avsz4(regs)),
        Opcode::Mvmva => Trace::Mvmva(mvmva(regs, c)),
        Opcode::Sqr => Trace::Vector(sqr(regs, sf, lm)),
        Opcode::Op => Trace::Vector(op(regs, sf, lm)),
        Opcode::Ncs => Trace::Lit(ncs(regs, sf, lm)),
        Opcode::Nccs => Trace::Lit(nccs(regs, sf, lm)),
        Opcode::Ncds => Trace::Lit(ncds(regs, sf, lm)),
        Opcode::Cc => Trace::Lit(cc(regs, sf, lm)),
        Opcode::Cdp => Trace::Lit(cdp(regs, sf, lm)),
        Opcode::Nct => Trace::LitTriple(nct(regs, sf, lm)),
        Opcode::Ncct => Trace::LitTriple(ncct(regs, sf, lm)),
        Opcode::Ncdt => Trace::LitTriple(ncdt(regs, sf, lm)),
        Opcode::Dpcs => Trace::DepthCued(dpcs(regs, sf, lm)),
        Opcode::Dcpl => Trace::DepthCued(dcpl(regs, sf, lm)),
        Opcode::Intpl => Trace::DepthCued(intpl(regs, sf, lm)),
        Opcode::Dpct => Trace::DepthCuedTriple(dpct(regs, sf, lm)),
        Opcode::Gpf => Trace::General(gpf(regs, sf, lm)),
        Opcode::Gpl => Trace::General(gpl(regs, sf, lm)),
    }
}
