//! PlayStation GTE (COP2): the geometry transformation engine, bit-exact in fixed point.
//!
//! Two faces: [`Gte`], the register-level engine an emulator drives (MTC2/MFC2/CTC2/CFC2 and
//! the COP2 command word), and [`typed`], a fixed-point API for transforming and projecting
//! vertices the PS1 way. The facts implemented are those of the GTE fact sheet (`gte.md`,
//! cited by section); choices where hardware data is silent are listed in `docs/gte.md`.
#![cfg_attr(not(feature = "std"), no_std)]

pub mod command;
mod commands;
pub mod flag;
pub mod mac;
pub mod registers;
pub mod typed;
pub mod unr;

pub use command::{Command, Opcode, cycles};
pub use flag::Flag;
pub use registers::{REGISTER_NAMES, Registers};
pub use unr::DivideMode;

/// The GTE: register file and command engine.
///
/// Register indices use their low 5 bits; command words their low 25 bits. No input panics.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Gte {
    regs: Registers,
    divide_mode: DivideMode,
    /// FLAG bits collected while a command runs.
    flag_bits: u32,
}

impl Gte {
    /// A GTE with every register zero and the hardware divide.
    pub fn new() -> Self {
        Self::default()
    }

    /// MTC2/LWC2: write data register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn write_data(&mut self, reg: usize, value: u32) {
        self.regs.write_data(reg, value);
    }

    /// MFC2/SWC2: read data register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn read_data(&self, reg: usize) -> u32 {
        self.regs.read_data(reg)
    }

    /// CTC2: write control register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn write_control(&mut self, reg: usize, value: u32) {
        self.regs.write_control(reg, value);
    }

    /// CFC2: read control register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn read_control(&self, reg: usize) -> u32 {
        self.regs.read_control(reg)
    }

    /// Read register `index` of the 64 (0..=31 data, 32..=63 control; higher bits ignored).
    pub fn read(&self, index: usize) -> u32 {
        if index & 32 == 0 {
            self.read_data(index)
        } else {
            self.read_control(index)
        }
    }

    /// Write register `index` of the 64 (0..=31 data via MTC2, 32..=63 control via CTC2).
    pub fn write(&mut self, index: usize, value: u32) {
        if index & 32 == 0 {
            self.write_data(index, value);
        } else {
            self.write_control(index, value);
        }
    }

    /// The FLAG register as a typed set.
    pub fn flag(&self) -> Flag {
        self.regs.flag
    }

    /// The register file, for inspection.
    pub fn registers(&self) -> &Registers {
        &self.regs
    }

    /// How RTPS/RTPT divide; [`DivideMode::Unr`] (the default) is the hardware.
    pub fn divide_mode(&self) -> DivideMode {
        self.divide_mode
    }

    /// Select a divide; anything but [`DivideMode::Unr`] departs from the hardware.
    pub fn set_divide_mode(&mut self, mode: DivideMode) {
        self.divide_mode = mode;
    }

    /// Run the 25-bit COP2 command word (bits above 24 are ignored). FLAG is cleared first
    /// and its bit 31 set from the error sources at the end (gte.md §3). Undefined opcodes
    /// clear FLAG and change nothing else (docs/gte.md, "Undefined opcodes").
    ///
    /// Returns the command's cycle count (gte.md §1), or `None` for an undefined opcode.
    pub fn execute(&mut self, command: u32) -> Option<u32> {
        let command = Command::new(command);
        self.flag_bits = 0;
        let opcode = command.opcode();
        if let Some(op) = opcode {
            self.run(op, command);
        }
        self.regs.flag = Flag::from_bits(self.flag_bits);
        opcode.map(Opcode::cycles)
    }

    fn run(&mut self, op: Opcode, c: Command) {
        let (shift, lm) = (c.shift(), c.lm());
        match op {
            Opcode::Rtps => self.rtps(shift, lm),
            Opcode::Rtpt => self.rtpt(shift, lm),
            Opcode::Nclip => self.nclip(),
            Opcode::Avsz3 => self.avsz3(),
            Opcode::Avsz4 => self.avsz4(),
            Opcode::Mvmva => self.mvmva(c, shift, lm),
            Opcode::Sqr => self.sqr(shift, lm),
            Opcode::Op => self.op(shift, lm),
            Opcode::Ncs => self.ncs(shift, lm),
            Opcode::Nct => self.nct(shift, lm),
            Opcode::Nccs => self.nccs(shift, lm),
            Opcode::Ncct => self.ncct(shift, lm),
            Opcode::Ncds => self.ncds(shift, lm),
            Opcode::Ncdt => self.ncdt(shift, lm),
            Opcode::Cc => self.cc(shift, lm),
            Opcode::Cdp => self.cdp(shift, lm),
            Opcode::Dpcs => self.dpcs(shift, lm),
            Opcode::Dpct => self.dpct(shift, lm),
            Opcode::Dcpl => self.dcpl(shift, lm),
            Opcode::Intpl => self.intpl(shift, lm),
            Opcode::Gpf => self.gpf(shift, lm),
            Opcode::Gpl => self.gpl(shift, lm),
        }
    }
}
