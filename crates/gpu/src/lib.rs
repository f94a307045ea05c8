//! PlayStation GPU: GP0/GP1 command processing into a 1024x512 16-bit VRAM.
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

pub mod command_stream;
pub mod ordering_table;
pub mod primitive;
pub mod rasterizer;
pub mod state;
pub mod texture;

use alloc::boxed::Box;
use alloc::vec;

/// VRAM width in halfwords.
pub const VRAM_WIDTH: usize = 1024;
/// VRAM height in lines.
pub const VRAM_HEIGHT: usize = 512;

/// 1024x512 halfwords of 1555 MBGR pixels, row-major (`y * 1024 + x`).
#[derive(Clone)]
pub struct Vram {
    pixels: Box<[u16]>,
}

impl Vram {
    /// All-zero VRAM.
    pub fn new() -> Self {
        Self {
            pixels: vec![0u16; VRAM_WIDTH * VRAM_HEIGHT].into_boxed_slice(),
        }
    }
    /// The whole VRAM, `VRAM_WIDTH * VRAM_HEIGHT` halfwords.
    pub fn as_slice(&self) -> &[u16] {
        &self.pixels
    }
    /// The whole VRAM, mutable.
    pub fn as_mut_slice(&mut self) -> &mut [u16] {
        &mut self.pixels
    }
}

impl Default for Vram {
    fn default() -> Self {
        Self::new()
    }
}

/// The part of VRAM the display shows, from GP1(05h) and GP1(08h).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DisplayArea {
    /// Left edge in VRAM halfwords.
    pub x: u16,
    /// Top line.
    pub y: u16,
    /// Width in display pixels (256, 320, 368, 512 or 640).
    pub width: u16,
    /// Height in lines (240, or 480 when interlaced at 480 lines).
    pub height: u16,
    /// 24-bit colour display: each pixel spans 1.5 halfwords.
    pub color_24bit: bool,
}

/// The GPU: GP0 (rendering, VRAM transfers) and GP1 (display control) ports over a [`Vram`].
pub struct Gpu {
    vram: Vram,
}

impl Gpu {
    /// A GPU in its reset state with all-zero VRAM.
    pub fn new() -> Self {
        Self { vram: Vram::new() }
    }
    /// One word written to the GP0 port.
    pub fn gp0(&mut self, word: u32) {
        let _ = word;
    }
    /// A block of GP0 words, as DMA2 delivers them.
    pub fn gp0_words(&mut self, words: &[u32]) {
        for &w in words {
            self.gp0(w);
        }
    }
    /// One word written to the GP1 port.
    pub fn gp1(&mut self, word: u32) {
        let _ = word;
    }
    /// GPUREAD.
    pub fn gpuread(&mut self) -> u32 {
        0
    }
    /// GPUSTAT.
    pub fn gpustat(&self) -> u32 {
        0
    }
    /// VRAM.
    pub fn vram(&self) -> &Vram {
        &self.vram
    }
    /// VRAM, mutable (for loading state or tests).
    pub fn vram_mut(&mut self) -> &mut Vram {
        &mut self.vram
    }
    /// The display area the current GP1 state selects.
    pub fn display_area(&self) -> DisplayArea {
        DisplayArea {
            x: 0,
            y: 0,
            width: 320,
            height: 240,
            color_24bit: false,
        }
    }
}

impl Default for Gpu {
    fn default() -> Self {
        Self::new()
    }
}
