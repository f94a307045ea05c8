//! PlayStation GTE (COP2): the geometry transformation engine, bit-exact in fixed point.
//!
//! Two faces: [`Gte`], the register-level engine an emulator drives (MTC2/MFC2/CTC2/CFC2 and
//! the COP2 command word), and `typed` (feature `typed`, default), a fixed-point API for
//! transforming and projecting vertices the PS1 way. The facts implemented are those of the
//! GTE hardware reference (`docs/hardware/gte.md`, cited by section); choices where hardware data is silent are
//! listed in `docs/gte.md`.
//!
//! Features: `typed` (default) the typed API and its `fixed` dependency; `divide-modes`
//! (default) the non-hardware divides [`DivideMode::Exact`] and [`DivideMode::F32`] in the
//! engine (without it [`Gte::set_divide_mode`] refuses them); `serde` serialization of
//! [`GteState`]; `reference` the reference model `gte::reference`, every command with the
//! exact values it computes, for property tests; `proptest` the proptest strategies
//! `gte::strategy`. The crate is `no_std` and allocates nothing, but for `proptest`, which
//! needs `std` (docs/typed-api.md).
#![no_std]
// One volatile load in `registers.rs` (`Words::whole`) is the crate's only unsafe code.
#![deny(unsafe_code)]
#![deny(missing_docs, rustdoc::broken_intra_doc_links)]

// proptest, behind the `proptest` feature, needs std.
#[cfg(feature = "proptest")]
extern crate std;

mod command;
mod commands;
mod flag;
mod mac;
#[cfg(feature = "reference")]
pub mod reference;
mod registers;
mod state;
#[cfg(feature = "proptest")]
pub mod strategy;
#[cfg(feature = "typed")]
pub mod typed;
pub mod unr;

pub use command::{Command, MatrixSel, Opcode, TranslationSel, VectorSel, cycles};
pub use flag::Flag;
pub use registers::{REGISTER_NAMES, Registers};

use registers::RegisterFile;
pub use state::{GteState, StateError};
pub use unr::{DivideMode, UnsupportedDivideMode};

/// The GTE: register file and command engine.
///
/// Register indices are `u32`, as a CPU decoder extracts the `rt`/`rd` fields; the data and
/// control accessors use the low 5 bits, the 64-register [`Gte::read`]/[`Gte::write`] the low
/// 6. Command words use their low 25 bits. No input panics.
///
/// An emulator's MTC2/CTC2, COP2 command and MFC2 for one RTPS (docs/hardware/gte.md §2, §5):
///
/// ```
/// let mut gte = gte::Gte::new();
/// gte.write_control(0, 0x1000);     // CTC2 RT11 = 1.0, RT12 = 0
/// gte.write_control(2, 0x1000);     // CTC2 RT22 = 1.0, RT23 = 0
/// gte.write_control(4, 0x1000);     // CTC2 RT33 = 1.0
/// gte.write_control(7, 1000);       // CTC2 TRZ = 1000
/// gte.write_control(24, 160 << 16); // CTC2 OFX = 160.0
/// gte.write_control(25, 120 << 16); // CTC2 OFY = 120.0
/// gte.write_control(26, 1000);      // CTC2 H = 1000
/// gte.write_data(0, (20 << 16) | 100); // MTC2 VXY0: X = 100, Y = 20
/// gte.write_data(1, 0);                // MTC2 VZ0 = 0
/// let cycles = gte.execute(0x0008_0001); // COP2 RTPS, sf = 1
/// assert_eq!(cycles, Some(15));
/// // SZ3 = 1000, quotient H / SZ3 = 1.0: screen X = 160 + 100, Y = 120 + 20.
/// assert_eq!(gte.read_data(19), 1000); // MFC2 SZ3
/// assert_eq!(gte.read_data(14), (140 << 16) | 260); // MFC2 SXY2
/// assert!(gte.flag().is_empty()); // CFC2 FLAG
/// ```
///
/// Two engines are equal when their architectural states are: the 64 registers as stored
/// (FLAG included) and the divide mode, what [`Gte::state`] returns.
#[derive(Clone, Debug, Default)]
pub struct Gte {
    regs: RegisterFile,
    divide_mode: DivideMode,
    /// FLAG bits collected while a command runs, for the commands that do not keep them in
    /// a local: cleared at the start of such a command's dispatch arm.
    flag_bits: u32,
}

/// The architectural state only: the FLAG bits a command collects while it runs are scratch,
/// copied into FLAG when it ends.
impl PartialEq for Gte {
    fn eq(&self, other: &Self) -> bool {
        self.regs == other.regs && self.divide_mode == other.divide_mode
    }
}

impl Eq for Gte {}

/// Bits 0-5 of each defined command, as the patterns of [`Gte::execute`]'s dispatch: a match
/// on the bits themselves compiles to one jump table over the 64 values, undefined ones
/// included, with no lookup of the opcode first.
mod opcode_bits {
    use crate::Opcode;
    pub(crate) const RTPS: u32 = Opcode::Rtps.bits();
    pub(crate) const NCLIP: u32 = Opcode::Nclip.bits();
    pub(crate) const OP: u32 = Opcode::Op.bits();
    pub(crate) const DPCS: u32 = Opcode::Dpcs.bits();
    pub(crate) const INTPL: u32 = Opcode::Intpl.bits();
    pub(crate) const MVMVA: u32 = Opcode::Mvmva.bits();
    pub(crate) const NCDS: u32 = Opcode::Ncds.bits();
    pub(crate) const CDP: u32 = Opcode::Cdp.bits();
    pub(crate) const NCDT: u32 = Opcode::Ncdt.bits();
    pub(crate) const NCCS: u32 = Opcode::Nccs.bits();
    pub(crate) const CC: u32 = Opcode::Cc.bits();
    pub(crate) const NCS: u32 = Opcode::Ncs.bits();
    pub(crate) const NCT: u32 = Opcode::Nct.bits();
    pub(crate) const SQR: u32 = Opcode::Sqr.bits();
    pub(crate) const DCPL: u32 = Opcode::Dcpl.bits();
    pub(crate) const DPCT: u32 = Opcode::Dpct.bits();
    pub(crate) const AVSZ3: u32 = Opcode::Avsz3.bits();
    pub(crate) const AVSZ4: u32 = Opcode::Avsz4.bits();
    pub(crate) const RTPT: u32 = Opcode::Rtpt.bits();
    pub(crate) const GPF: u32 = Opcode::Gpf.bits();
    pub(crate) const GPL: u32 = Opcode::Gpl.bits();
    pub(crate) const NCCT: u32 = Opcode::Ncct.bits();
}

impl Gte {
    /// A GTE with every register zero and the hardware divide.
    pub fn new() -> Self {
        Self::default()
    }

    /// MTC2/LWC2: write data register `reg & 31` with its write rules (docs/hardware/gte.md §2).
    #[inline]
    pub fn write_data(&mut self, reg: u32, value: u32) {
        self.regs.write_data(reg, value);
    }

    /// MFC2/SWC2: read data register `reg & 31` with its read rules (docs/hardware/gte.md §2).
    #[inline]
    pub fn read_data(&self, reg: u32) -> u32 {
        self.regs.read_data(reg)
    }

    /// CTC2: write control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub fn write_control(&mut self, reg: u32, value: u32) {
        self.regs.write_control(reg, value);
    }

    /// CFC2: read control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub fn read_control(&self, reg: u32) -> u32 {
        self.regs.read_control(reg)
    }

    /// Read register `index & 63` of the 64 (0..=31 data via MFC2, 32..=63 control via CFC2).
    #[inline]
    pub fn read(&self, index: u32) -> u32 {
        if index & 32 == 0 {
            self.read_data(index)
        } else {
            self.read_control(index)
        }
    }

    /// Write register `index & 63` of the 64 (0..=31 data via MTC2, 32..=63 control via CTC2).
    #[inline]
    pub fn write(&mut self, index: u32, value: u32) {
        if index & 32 == 0 {
            self.write_data(index, value);
        } else {
            self.write_control(index, value);
        }
    }

    /// The FLAG register as a typed set.
    #[inline]
    pub fn flag(&self) -> Flag {
        self.regs.flag()
    }

    /// The register file field by field, as stored, for inspection.
    pub fn registers(&self) -> Registers {
        self.regs.snapshot()
    }

    /// The whole engine state (registers as stored and the divide mode), read without any
    /// register read rule; [`Gte::load_state`] restores it exactly.
    pub fn state(&self) -> GteState {
        GteState {
            version: GteState::VERSION,
            registers: self.regs.snapshot(),
            divide_mode: self.divide_mode,
        }
    }

    /// Restore a state from [`Gte::state`]: every register takes the stored value, without the
    /// side effects of MTC2/CTC2 (IRGB, SXYP, LZCS). FLAG keeps only what the hardware can hold
    /// (bits 12-30 and their summary bit 31, as [`Flag::from_bits`]).
    ///
    /// Fails, changing nothing, for a version outside [`GteState::OLDEST_VERSION`] to
    /// [`GteState::VERSION`] (versions differ only in how they serialize) or a divide mode
    /// this build cannot run.
    pub fn load_state(&mut self, state: &GteState) -> Result<(), StateError> {
        if !(GteState::OLDEST_VERSION..=GteState::VERSION).contains(&state.version) {
            return Err(StateError::Version {
                found: state.version,
                expected: GteState::VERSION,
            });
        }
        if !state.divide_mode.is_supported() {
            return Err(StateError::DivideMode(UnsupportedDivideMode(
                state.divide_mode,
            )));
        }
        self.regs = RegisterFile::from_snapshot(&state.registers);
        self.divide_mode = state.divide_mode;
        Ok(())
    }

    /// How RTPS/RTPT divide; [`DivideMode::Unr`] (the default) is the hardware.
    pub fn divide_mode(&self) -> DivideMode {
        self.divide_mode
    }

    /// Select a divide; anything but [`DivideMode::Unr`] departs from the hardware. Without
    /// the `divide-modes` feature the other modes are refused and the mode stays as it was.
    pub fn set_divide_mode(&mut self, mode: DivideMode) -> Result<(), UnsupportedDivideMode> {
        if !mode.is_supported() {
            return Err(UnsupportedDivideMode(mode));
        }
        self.divide_mode = mode;
        Ok(())
    }

    /// Run the 25-bit COP2 command word (bits above 24 are ignored). FLAG is cleared first
    /// and its bit 31 set from the error sources at the end (docs/hardware/gte.md §3). Undefined opcodes
    /// clear FLAG and change nothing else (docs/gte.md, "Undefined opcodes").
    ///
    /// Returns the command's cycle count (docs/hardware/gte.md §1), or `None` for an undefined opcode.
    ///
    /// The opcode dispatch, RTPS and the short commands compile into the caller (an
    /// emulator's COP2 handler); the long ones (RTPT, the lighting commands) stay calls. Each
    /// dispatch arm extracts the sf and lm bits it uses and writes FLAG itself. Wrapped in a
    /// function the compiler may not inline (`#[inline(never)]`, a foreign-function layer),
    /// every call pays for that function's entry and exit: in one measurement the short
    /// commands went from 2.2-3.2x Mednafen's speed to 1.3-1.8x (docs/performance.md, "What
    /// the comparison assumes").
    #[inline(always)]
    pub fn execute(&mut self, command: u32) -> Option<u32> {
        let c = Command::new(command);
        // One dispatch on bits 0-5 runs the command and yields its cycle count.
        match command & 0x3F {
            opcode_bits::RTPS => {
                self.flag_bits = 0;
                self.rtps(c.shift(), c.lm());
                self.finish(Opcode::Rtps)
            }
            opcode_bits::NCLIP => {
                let flags = self.nclip();
                self.finish_with(Opcode::Nclip, flags)
            }
            opcode_bits::OP => {
                self.flag_bits = 0;
                self.op(c.shift(), c.lm());
                self.finish(Opcode::Op)
            }
            opcode_bits::DPCS => {
                self.flag_bits = 0;
                self.dpcs(c.shift(), c.lm());
                self.finish(Opcode::Dpcs)
            }
            opcode_bits::INTPL => {
                self.flag_bits = 0;
                self.intpl(c.shift(), c.lm());
                self.finish(Opcode::Intpl)
            }
            opcode_bits::MVMVA => {
                let flags = self.mvmva(c, c.shift(), c.lm());
                self.finish_with(Opcode::Mvmva, flags)
            }
            opcode_bits::NCDS => {
                let flags = self.ncds(c.shift(), c.lm());
                self.finish_with(Opcode::Ncds, flags)
            }
            opcode_bits::CDP => {
                let flags = self.cdp(c.shift(), c.lm());
                self.finish_with(Opcode::Cdp, flags)
            }
            opcode_bits::NCDT => {
                let flags = self.ncdt(c.shift(), c.lm());
                self.finish_with(Opcode::Ncdt, flags)
            }
            opcode_bits::NCCS => {
                let flags = self.nccs(c.shift(), c.lm());
                self.finish_with(Opcode::Nccs, flags)
            }
            opcode_bits::CC => {
                let flags = self.cc(c.shift(), c.lm());
                self.finish_with(Opcode::Cc, flags)
            }
            opcode_bits::NCS => {
                let flags = self.ncs(c.shift(), c.lm());
                self.finish_with(Opcode::Ncs, flags)
            }
            opcode_bits::NCT => {
                let flags = self.nct(c.shift(), c.lm());
                self.finish_with(Opcode::Nct, flags)
            }
            opcode_bits::SQR => {
                let flags = self.sqr(c.shift());
                self.finish_with(Opcode::Sqr, flags)
            }
            opcode_bits::DCPL => {
                self.flag_bits = 0;
                self.dcpl(c.shift(), c.lm());
                self.finish(Opcode::Dcpl)
            }
            opcode_bits::DPCT => {
                self.flag_bits = 0;
                self.dpct(c.shift(), c.lm());
                self.finish(Opcode::Dpct)
            }
            opcode_bits::AVSZ3 => {
                let flags = self.avsz3();
                self.finish_with(Opcode::Avsz3, flags)
            }
            opcode_bits::AVSZ4 => {
                let flags = self.avsz4();
                self.finish_with(Opcode::Avsz4, flags)
            }
            opcode_bits::RTPT => {
                self.flag_bits = 0;
                self.rtpt(c.shift(), c.lm());
                self.finish(Opcode::Rtpt)
            }
            opcode_bits::GPF => {
                let flags = self.gpf(c.shift(), c.lm());
                self.finish_with(Opcode::Gpf, flags)
            }
            opcode_bits::GPL => {
                let flags = self.gpl(c.shift(), c.lm());
                self.finish_with(Opcode::Gpl, flags)
            }
            opcode_bits::NCCT => {
                let flags = self.ncct(c.shift(), c.lm());
                self.finish_with(Opcode::Ncct, flags)
            }
            // The undefined opcodes one by one (docs/hardware/gte.md §1): with all 64 values
            // of bits 0-5 named, the jump table needs no range check.
            #[rustfmt::skip]
            0x00 | 0x02 | 0x03 | 0x04 | 0x05 | 0x07 | 0x08 | 0x09 | 0x0A | 0x0B | 0x0D | 0x0E
            | 0x0F | 0x15 | 0x17 | 0x18 | 0x19 | 0x1A | 0x1D | 0x1F | 0x21 | 0x22 | 0x23 | 0x24
            | 0x25 | 0x26 | 0x27 | 0x2B | 0x2C | 0x2F | 0x31 | 0x32 | 0x33 | 0x34 | 0x35 | 0x36
            | 0x37 | 0x38 | 0x39 | 0x3A | 0x3B | 0x3C | 0x40.. => {
                self.regs.set_flag(Flag::EMPTY);
                None
            }
        }
    }

    /// The end of a command that collects its FLAG bits in `flag_bits` (cleared at the
    /// start of its dispatch arm): FLAG is those bits.
    #[inline(always)]
    fn finish(&mut self, op: Opcode) -> Option<u32> {
        self.finish_with(op, self.flag_bits)
    }

    /// The end of a command: FLAG is the bits its steps set, `bits`, an error source having
    /// brought bit 31 with it (docs/hardware/gte.md §3), and its cycle count. In each
    /// dispatch arm, so that the compiler sees which bits the command can set. The short
    /// commands and the lighting commands collect their bits in a local and pass them here,
    /// so that their arms touch no scratch field (docs/performance.md, "The plain loop",
    /// "The plain loop: short paths").
    #[inline(always)]
    fn finish_with(&mut self, op: Opcode, bits: u32) -> Option<u32> {
        self.regs.set_flag(Flag::from_register(bits));
        Some(op.cycles())
    }
}
