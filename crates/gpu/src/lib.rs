//! PlayStation GPU: GP0/GP1 command processing into a 1024x512 16-bit VRAM, pixel-exact with
//! a real console. Facts are those of the GPU fact sheet (`gpu.md`, cited by section); the
//! choices made where it is silent are listed in `docs/gpu.md`.
//!
//! Route the console's GP0/GP1 port writes (or DMA blocks) into [`Gpu`]; read pixels from
//! [`Gpu::vram`]. Commands may arrive split at any word boundary.
#![cfg_attr(not(feature = "std"), no_std)]

extern crate alloc;

pub mod color;
pub mod command_stream;
pub mod decode;
mod display;
mod dma;
mod drawing;
mod gp0;
pub mod ordering_table;
pub mod primitive;
pub mod rasterizer;
pub mod state;
pub mod texture;
mod transfer;

use alloc::boxed::Box;
use alloc::vec;

pub use display::{DisplayArea, DisplayState};
pub use dma::{
    DmaError, LINKED_LIST_WORD_BUDGET, LinkedListReport, ListEnd, RAM_MASK, RAM_SIZE,
    dma_clear_ordering_table,
};
use state::DrawState;
use texture::ClutCache;

/// VRAM width in halfwords.
pub const VRAM_WIDTH: usize = 1024;
/// VRAM height in lines.
pub const VRAM_HEIGHT: usize = 512;
/// VRAM size in halfwords.
pub const VRAM_LEN: usize = VRAM_WIDTH * VRAM_HEIGHT;

/// 1024x512 halfwords of 1555 MBGR pixels, row-major (`y * 1024 + x`) (gpu.md §1).
#[derive(Clone, PartialEq, Eq)]
pub struct Vram {
    pixels: Box<[u16]>,
}

impl Vram {
    /// All-zero VRAM.
    pub fn new() -> Self {
        Self {
            pixels: vec![0u16; VRAM_LEN].into_boxed_slice(),
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
    /// The pixel at (x, y), coordinates wrapped to the VRAM.
    pub fn pixel(&self, x: usize, y: usize) -> u16 {
        self.pixels
            .get((y & 511) * VRAM_WIDTH + (x & 1023))
            .copied()
            .unwrap_or(0)
    }
    /// Set the pixel at (x, y), coordinates wrapped to the VRAM.
    pub fn set_pixel(&mut self, x: usize, y: usize, value: u16) {
        if let Some(p) = self.pixels.get_mut((y & 511) * VRAM_WIDTH + (x & 1023)) {
            *p = value;
        }
    }
}

impl Default for Vram {
    fn default() -> Self {
        Self::new()
    }
}

impl core::fmt::Debug for Vram {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Vram").finish_non_exhaustive()
    }
}

/// The GPU: GP0 (rendering, VRAM transfers) and GP1 (display control) ports over a [`Vram`].
#[derive(Clone, Debug)]
pub struct Gpu {
    vram: Vram,
    draw: DrawState,
    clut: ClutCache,
    gp0: gp0::Gp0State,
    read: transfer::ReadTransfer,
    display: DisplayState,
    gpuread_latch: u32,
    irq: bool,
    /// GP0(1Fh) raised the IRQ and `run` has not reported it yet.
    irq_event: bool,
    texture_disable_allowed: bool,
    drawing: drawing::Drawing,
    /// CPU-to-GPU clock conversion remainder (GPU cycles * 33 868 800).
    clock_remainder: u64,
}

/// What happened during one [`Gpu::run`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Events {
    /// GP0(1Fh) raised the GPU IRQ since the previous run.
    pub gpu_irq: bool,
    /// The GPU went from busy (drawing, or commands waiting in the FIFO) to idle.
    pub drawing_done: bool,
}

/// CPU clock in Hz (44100 * 768).
const CPU_HZ: u64 = 33_868_800;
/// NTSC GPU clock in Hz.
const GPU_HZ: u64 = 53_693_175;

impl Gpu {
    /// A GPU in its reset state with all-zero VRAM.
    pub fn new() -> Self {
        Self {
            vram: Vram::new(),
            draw: DrawState::default(),
            clut: ClutCache::default(),
            gp0: gp0::Gp0State::default(),
            read: transfer::ReadTransfer::default(),
            display: DisplayState::default(),
            gpuread_latch: 0,
            irq: false,
            irq_event: false,
            texture_disable_allowed: false,
            drawing: drawing::Drawing::default(),
            clock_remainder: 0,
        }
    }

    /// Advance time by `cpu_cycles` CPU cycles and report what happened.
    pub fn run(&mut self, cpu_cycles: u32) -> Events {
        let total = cpu_cycles as u64 * GPU_HZ + self.clock_remainder;
        let gpu_cycles = u32::try_from(total / CPU_HZ).unwrap_or(u32::MAX);
        self.clock_remainder = total % CPU_HZ;
        let (gpu_irq, drawing_done) = self.advance_drawing(gpu_cycles);
        Events {
            gpu_irq,
            drawing_done,
        }
    }

    /// CPU cycles until [`Gpu::run`] would report an event (rounded up, so running exactly
    /// this many reaches it); 0 when one awaits delivery; `u32::MAX` when none comes.
    pub fn cycles_until_next_event(&self) -> u32 {
        match self.drawing_cycles_until_event() {
            None => u32::MAX,
            Some(gpu) => {
                let need = (gpu as u64 * CPU_HZ).saturating_sub(self.clock_remainder);
                u32::try_from(need.div_ceil(GPU_HZ)).unwrap_or(u32::MAX)
            }
        }
    }

    /// A block of GP0 words, as DMA2 delivers them.
    pub fn gp0_words(&mut self, words: &[u32]) {
        for &w in words {
            self.gp0(w);
        }
    }

    /// GPUREAD: the next two pixels of a VRAM-to-CPU transfer (GP0 C0h), or the latched
    /// value of the last GP1(10h) info read.
    pub fn gpuread(&mut self) -> u32 {
        if self.read.active() {
            let word = self.read.next_word(&self.vram);
            self.gpuread_latch = word;
        }
        self.gpuread_latch
    }

    /// The GPU interrupt line, GPUSTAT.24: set by GP0(1Fh), cleared by GP1(02h) (psx-spx
    /// "GPU Other Commands").
    pub fn irq_pending(&self) -> bool {
        self.irq
    }

    /// VRAM.
    pub fn vram(&self) -> &Vram {
        &self.vram
    }

    /// VRAM, mutable (for loading state or tests).
    pub fn vram_mut(&mut self) -> &mut Vram {
        &mut self.vram
    }

    /// The drawing environment set by E1-E6.
    pub fn draw_state(&self) -> &DrawState {
        &self.draw
    }

    /// The display state set by GP1.
    pub fn display_state(&self) -> &DisplayState {
        &self.display
    }

    /// The display area the current GP1 state selects (gpu.md §9).
    pub fn display_area(&self) -> DisplayArea {
        self.display.area()
    }
}

impl Default for Gpu {
    fn default() -> Self {
        Self::new()
    }
}
