//! GP1 display control (docs/hardware/gpu.md §9) and the GPUSTAT register.

use crate::gp1::Gp1;
use crate::state::{BlendMode, TextureDepth};
use crate::{Beam, Gpu, drawing, timing};

/// The part of VRAM the display shows, from GP1(05h)-(08h).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DisplayArea {
    /// Left edge in VRAM halfwords.
    pub x: u16,
    /// Top line.
    pub y: u16,
    /// Width in display pixels: the GP1(06h) range in dots, rounded to a multiple of 4
    /// (320 for a 2560-cycle range at 8 cycles a dot).
    pub width: u16,
    /// Height in lines: the GP1(07h) range, doubled in 480i (240 for the reset range).
    pub height: u16,
    /// 24-bit colour display: each pixel spans 1.5 halfwords.
    pub color_24bit: bool,
}

/// State written through GP1 (docs/hardware/gpu.md §9).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DisplayState {
    /// GP1(03h): display disabled.
    pub disabled: bool,
    /// GP1(04h): DMA direction (0 off, 1 FIFO, 2 CPU to GP0, 3 GPUREAD to CPU).
    pub dma_direction: u8,
    /// GP1(05h): display area start X (halfwords).
    pub start_x: u16,
    /// GP1(05h): display area start Y.
    pub start_y: u16,
    /// GP1(06h): horizontal display range X1, X2 (GPU clock ticks).
    pub h_range: (u16, u16),
    /// GP1(07h): vertical display range Y1, Y2 (scanlines).
    pub v_range: (u16, u16),
    /// GP1(08h): display mode bits 0-7.
    pub mode: u8,
}

impl Default for DisplayState {
    fn default() -> Self {
        // GP1(00h) values (psx-spx "GP1(00h) Reset GPU").
        Self {
            disabled: true,
            dma_direction: 0,
            start_x: 0,
            start_y: 0,
            h_range: (0x200, 0x200 + 256 * 10),
            v_range: (0x10, 0x10 + 240),
            mode: 0,
        }
    }
}

impl DisplayState {
    /// The registers the video timing depends on: GP1(06h), GP1(07h), GP1(08h).
    pub(crate) fn video_mode(&self) -> timing::VideoMode {
        timing::VideoMode {
            mode: self.mode,
            h_range: self.h_range,
            v_range: self.v_range,
        }
    }

    /// Every field within the bits its GP1 command writes (docs/hardware/gpu.md §9).
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        let fits = self.dma_direction <= 3
            && self.start_x <= 0x3FF
            && self.start_y <= 0x1FF
            && self.h_range.0 <= 0xFFF
            && self.h_range.1 <= 0xFFF
            && self.v_range.0 <= 0x3FF
            && self.v_range.1 <= 0x3FF;
        if fits {
            Ok(())
        } else {
            Err("display register wider than its GP1 field")
        }
    }

    /// The displayed VRAM rectangle. Width: the GP1(06h) range X1..X2 (video cycles,
    /// clamped to the line) in dots of the GP1(08h) resolution, `((X2 - X1) / divider + 2)
    /// & !3` (docs/hardware/timing.md §5), 0 when X2 <= X1. Height: Y2 - Y1 of GP1(07h), clamped
    /// to the field, doubled when GP1(08h) bits 2 and 5 (480 lines, interlace) are both set
    /// (docs/hardware/timing.md §6, §7).
    pub fn area(&self) -> DisplayArea {
        let pal = self.mode & 0x08 != 0;
        let interlaced = self.mode & 0x20 != 0;
        let line = timing::cycles_per_line(pal);
        let x1 = (self.h_range.0 as u32).min(line);
        let x2 = (self.h_range.1 as u32).min(line);
        let width = if x2 > x1 {
            ((x2 - x1) / timing::dot_divider(self.mode) + 2) & !3
        } else {
            0
        };
        let lines = timing::lines_per_field(pal, interlaced, 0);
        let y1 = (self.v_range.0 as u32).min(lines);
        let y2 = (self.v_range.1 as u32).min(lines);
        let mut height = y2.saturating_sub(y1);
        if self.mode & 0x24 == 0x24 {
            height *= 2;
        }
        DisplayArea {
            x: self.start_x,
            y: self.start_y,
            width: width as u16,
            height: height as u16,
            color_24bit: self.mode & 0x10 != 0,
        }
    }
}

impl Gpu {
    /// One word written to the GP1 port (docs/hardware/gpu.md §9); [`crate::gp1::Gp1`] reads
    /// and builds the words.
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp1(0x0300_0000); // GP1(03h): display enable
    /// assert_eq!(gpu.gpustat() & 1 << 23, 0);
    /// gpu.gp1(0x0800_0009); // GP1(08h): 320 wide, PAL
    /// assert_eq!(gpu.gpustat() >> 20 & 1, 1); // GPUSTAT bit 20: PAL
    /// ```
    pub fn gp1(&mut self, word: u32) {
        match Gp1::from_word(word) {
            Gp1::Reset => self.reset(),
            Gp1::ResetCommandBuffer => self.reset_command_buffer(),
            Gp1::AcknowledgeIrq => self.irq = false,
            Gp1::DisplayEnabled(enabled) => self.display.disabled = !enabled,
            Gp1::DmaDirection(direction) => self.display.dma_direction = direction,
            Gp1::DisplayStart { x, y } => (self.display.start_x, self.display.start_y) = (x, y),
            Gp1::HorizontalRange { x1, x2 } => self.display.h_range = (x1, x2),
            Gp1::VerticalRange { y1, y2 } => self.display.v_range = (y1, y2),
            Gp1::DisplayMode(mode) => self.display.mode = mode,
            Gp1::AllowTextureDisable(allow) => self.texture_disable_allowed = allow,
            Gp1::GetInfo(register) => self.info(register),
            Gp1::Unused(_) => {}
        }
    }

    /// GP1(09h) bit 0: whether GP0(E1h) bit 11 may disable textures (docs/hardware/gpu.md §2).
    pub fn texture_disable_allowed(&self) -> bool {
        self.texture_disable_allowed
    }

    /// GP1(00h): reset the command buffer, IRQ, display and drawing state, and empty the CLUT
    /// and texture caches (docs/hardware/gpu.md §10); VRAM is kept.
    /// Drawing in progress is abandoned (docs/emulator.md, "Drawing time, FIFO and DMA").
    fn reset(&mut self) {
        self.reset_command_buffer();
        if !self.drawing.idle() {
            self.drawing = Default::default();
            self.drawing.set_done();
        }
        self.irq = false;
        self.display = DisplayState::default();
        self.draw = Default::default();
        self.texture_disable_allowed = false;
        self.clut.invalidate();
        self.texture_cache.invalidate();
    }

    /// GP1(01h): drop any partial packet and transfer, and the FIFO's waiting words; the
    /// command executing finishes, and so does the first triangle of a quad the GPU has
    /// reached ([`Gpu::cut_gp0_input`]).
    fn reset_command_buffer(&mut self) {
        self.drawing.clear_fifo();
        self.cut_gp0_input();
        self.read = Default::default();
    }

    /// GP1(10h..1Fh): latch internal register `register` (bits 0-2) into GPUREAD: 2 texture window,
    /// 3/4 drawing area corners (X bits 0-9, Y bits 10-19 on the v2 GPU), 5 drawing offset,
    /// 7 GPU version (2); other indices keep the latch (psx-spx "GP1(10h) Get GPU Info").
    fn info(&mut self, register: u8) {
        let d = &self.draw;
        self.gpuread_latch = match register {
            2 => {
                let w = d.window;
                w.mask_x as u32
                    | (w.mask_y as u32) << 5
                    | (w.offset_x as u32) << 10
                    | (w.offset_y as u32) << 15
            }
            3 => d.area.left as u32 | (d.area.top as u32) << 10,
            4 => d.area.right as u32 | (d.area.bottom as u32) << 10,
            5 => (d.offset_x as u32 & 0x7FF) | (d.offset_y as u32 & 0x7FF) << 11,
            7 => 2,
            _ => self.gpuread_latch,
        };
    }

    /// GPUSTAT (psx-spx "GPU Status Register"): draw mode bits 0-10, mask bits 11-12, display
    /// mode bits 14, 16-22, display disable 23, IRQ 24, DMA direction 29-30; bits 13 and 31
    /// from the video timing ([`Gpu::interlace_field_bit`], [`Gpu::line_parity_bit`]). The
    /// ready bits follow the FIFO and the drawing time (docs/hardware/dma.md §8): 26 when
    /// nothing is being received, queued or drawn; 27 while a VRAM-to-CPU transfer has data;
    /// 28 unless a complete command waits in the FIFO, the FIFO is full, or a polygon or line
    /// is being received; 25 is 0, FIFO-not-full, bit 28 or bit 27 for DMA direction 0 to 3.
    ///
    /// ```
    /// // After reset: display disabled (23), ready for commands (26) and DMA blocks (28), and
    /// // bit 13 set outside interlace (docs/hardware/gpu.md §8): 14802000h.
    /// let gpu = gpu::Gpu::new();
    /// assert_eq!(gpu.gpustat() & 0x7FFF_FFFF, 0x1480_2000);
    /// ```
    pub fn gpustat(&self) -> u32 {
        let m = &self.draw.mode;
        let mut s = (m.page_x as u32 / 64) & 0xF;
        s |= ((m.page_y as u32 / 256) & 1) << 4;
        s |= (match m.blend {
            BlendMode::Average => 0,
            BlendMode::Add => 1,
            BlendMode::Subtract => 2,
            BlendMode::AddQuarter => 3,
        }) << 5;
        s |= (match m.depth {
            _ if m.depth_reserved => 3,
            TextureDepth::Clut4 => 0,
            TextureDepth::Clut8 => 1,
            TextureDepth::Direct15 => 2,
        }) << 7;
        s |= (m.dither as u32) << 9;
        s |= (m.draw_to_display as u32) << 10;
        s |= (self.draw.mask.set as u32) << 11;
        s |= (self.draw.mask.check as u32) << 12;
        let beam = self.beam();
        s |= (field_bit(self.display.mode, beam) as u32) << 13;
        let mode = self.display.mode as u32;
        s |= ((mode >> 7) & 1) << 14;
        s |= (m.texture_disable as u32) << 15;
        s |= ((mode >> 6) & 1) << 16;
        s |= (mode & 3) << 17;
        s |= ((mode >> 2) & 1) << 19;
        s |= ((mode >> 3) & 1) << 20;
        s |= ((mode >> 4) & 1) << 21;
        s |= ((mode >> 5) & 1) << 22;
        s |= (self.display.disabled as u32) << 23;
        s |= (self.irq as u32) << 24;
        let fifo_full = self.drawing.fifo_words() >= drawing::FIFO_WORDS;
        let ready_cmd = self.gp0.idle() && self.drawing.idle();
        let ready_read = self.read.active();
        let ready_dma = !self.drawing.unit_queued() && !fifo_full && !self.gp0.receiving_vertices();
        let dma_request = match self.display.dma_direction {
            0 => false,
            1 => !fifo_full,
            2 => ready_dma,
            _ => ready_read,
        };
        s |= (dma_request as u32) << 25;
        s |= (ready_cmd as u32) << 26;
        s |= (ready_read as u32) << 27;
        s |= (ready_dma as u32) << 28;
        s |= (self.display.dma_direction as u32) << 29;
        s |= (self.parity_bit(beam) as u32) << 31;
        s
    }

    /// GPUSTAT.13: 1 when GP1(08h) bit 5 (interlace) is clear, else the current field
    /// (docs/hardware/timing.md §7). Which field value the console reports first is not
    /// recorded; the model's field 0 (the one showing the display start line) reads 0.
    pub fn interlace_field_bit(&self) -> bool {
        field_bit(self.display.mode, self.beam())
    }

    /// GPUSTAT.31: 0 during vblank; otherwise bit 0 of the VRAM line being displayed, which
    /// changes every scanline in 240-line modes and every field in 480i (docs/hardware/timing.md §7; psx-spx "GPU Status
    /// Register": "0=Even or Vblank, 1=Odd").
    pub fn line_parity_bit(&self) -> bool {
        self.parity_bit(self.beam())
    }

    /// GPUSTAT.31 at beam position `beam`.
    fn parity_bit(&self, beam: Beam) -> bool {
        !beam.vblank && self.line_parity(beam) == 1
    }

    /// Bit 0 of the VRAM line the current field shows (480i) or the current scanline shows
    /// (other modes).
    pub(crate) fn displayed_line_parity(&self) -> u32 {
        self.line_parity(self.beam())
    }

    /// Bit 0 of the VRAM line shown at beam position `beam`: the display start line plus the
    /// field in 480i, plus the lines since GP1(07h) Y1 otherwise.
    fn line_parity(&self, beam: Beam) -> u32 {
        let start = self.display.start_y as u32;
        if self.display.mode & 0x24 == 0x24 {
            (start + beam.field as u32) & 1
        } else {
            (start + beam.line.saturating_sub(self.display.v_range.0 as u32)) & 1
        }
    }
}

/// GPUSTAT.13 for display mode `mode` at beam position `beam`.
fn field_bit(mode: u8, beam: Beam) -> bool {
    mode & 0x20 == 0 || beam.field == 1
}
