//! PlayStation GTE (COP2): the geometry transformation engine, bit-exact in fixed point.
//!
//! Two faces: [`Gte`], the register-level engine an emulator drives (MTC2/MFC2/CTC2/CFC2 and
//! the COP2 command word), and [`typed`], a fixed-point API for transforming and projecting
//! vertices the PS1 way.
#![cfg_attr(not(feature = "std"), no_std)]

pub mod flag;
pub mod typed;

pub use flag::Flag;

/// The GTE register file and command engine.
#[derive(Clone, Debug, Default)]
pub struct Gte {}

impl Gte {
    /// A GTE with every register zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// MTC2/LWC2: write data register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn write_data(&mut self, reg: usize, value: u32) {
        let _ = (reg, value);
    }

    /// MFC2/SWC2: read data register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn read_data(&self, reg: usize) -> u32 {
        let _ = reg;
        0
    }

    /// CTC2: write control register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn write_control(&mut self, reg: usize, value: u32) {
        let _ = (reg, value);
    }

    /// CFC2: read control register `reg` (0..=31; higher bits of `reg` are ignored).
    pub fn read_control(&self, reg: usize) -> u32 {
        let _ = reg;
        0
    }

    /// Run the 25-bit COP2 command word (bits above 24 are ignored).
    pub fn execute(&mut self, command: u32) {
        let _ = command;
    }
}
