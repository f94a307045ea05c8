//! The GP1 port's commands (docs/hardware/gpu.md §9): the command byte in bits 24-31 and the
//! fields each command reads from bits 0-23, read from a word ([`Gp1::from_word`]) and laid
//! out as one ([`Gp1::word`]). [`crate::Gpu::gp1`] executes them, [`crate::decode`] describes
//! them, and a program that drives the display builds its words here.
//!
//! ```
//! use gpu::gp1::Gp1;
//! let mut gpu = gpu::Gpu::new();
//! gpu.gp1(Gp1::DisplayStart { x: 0, y: 256 }.word());
//! gpu.gp1(Gp1::DisplayEnabled(true).word());
//! assert_eq!(gpu.display_state().start_y, 256);
//! assert!(!gpu.display_state().disabled);
//! ```

/// One GP1 command with its fields. Each field keeps the bits the GPU reads; [`Gp1::word`]
/// cuts a wider value to them, as the GPU would.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Gp1 {
    /// 00h: reset the GPU (command buffer, IRQ, display and drawing state, caches).
    Reset,
    /// 01h: reset the command buffer (the FIFO and any partial packet or transfer).
    ResetCommandBuffer,
    /// 02h: acknowledge the GPU interrupt (GPUSTAT.24).
    AcknowledgeIrq,
    /// 03h: display on (`true`: bit 0 clear) or off (bit 0 set).
    DisplayEnabled(bool),
    /// 04h: DMA direction, bits 0-1 (0 off, 1 FIFO, 2 CPU to GP0, 3 GPUREAD to CPU).
    DmaDirection(u8),
    /// 05h: the display area's top-left corner in VRAM: X bits 0-9 (halfwords), Y bits 10-18.
    DisplayStart {
        /// Left edge, halfwords (10 bits).
        x: u16,
        /// Top line (9 bits).
        y: u16,
    },
    /// 06h: horizontal display range in video clock ticks: X1 bits 0-11, X2 bits 12-23.
    HorizontalRange {
        /// First tick shown (12 bits).
        x1: u16,
        /// Tick after the last shown (12 bits).
        x2: u16,
    },
    /// 07h: vertical display range in scanlines: Y1 bits 0-9, Y2 bits 10-19.
    VerticalRange {
        /// First line shown (10 bits).
        y1: u16,
        /// Line after the last shown (10 bits).
        y2: u16,
    },
    /// 08h: display mode bits 0-7: horizontal resolution (bits 0-1, bit 6 for 368), 480
    /// lines (2), PAL (3), 24-bit colour (4), interlace (5), bit 7 (docs/hardware/timing.md
    /// §4-§7).
    DisplayMode(u8),
    /// 09h: bit 0, whether GP0(E1h) bit 11 may disable textures.
    AllowTextureDisable(bool),
    /// 10h-1Fh: latch internal register bits 0-2 into GPUREAD (2 texture window, 3 and 4 the
    /// drawing area corners, 5 the drawing offset, 7 the GPU version).
    GetInfo(u8),
    /// Any other command byte (0Ah-0Fh, 20h-FFh): no effect on this GPU; the byte is kept.
    Unused(u8),
}

impl Gp1 {
    /// The command `word` holds, its fields cut to the bits the GPU reads.
    pub const fn from_word(word: u32) -> Gp1 {
        match (word >> 24) as u8 {
            0x00 => Gp1::Reset,
            0x01 => Gp1::ResetCommandBuffer,
            0x02 => Gp1::AcknowledgeIrq,
            0x03 => Gp1::DisplayEnabled(word & 1 == 0),
            0x04 => Gp1::DmaDirection((word & 3) as u8),
            0x05 => Gp1::DisplayStart {
                x: bits(word, 0, 10),
                y: bits(word, 10, 9),
            },
            0x06 => Gp1::HorizontalRange {
                x1: bits(word, 0, 12),
                x2: bits(word, 12, 12),
            },
            0x07 => Gp1::VerticalRange {
                y1: bits(word, 0, 10),
                y2: bits(word, 10, 10),
            },
            0x08 => Gp1::DisplayMode(word as u8),
            0x09 => Gp1::AllowTextureDisable(word & 1 != 0),
            0x10..=0x1F => Gp1::GetInfo((word & 7) as u8),
            op => Gp1::Unused(op),
        }
    }

    /// The command byte: the unused byte kept, 10h for [`Gp1::GetInfo`].
    pub const fn op(self) -> u8 {
        match self {
            Gp1::Reset => 0x00,
            Gp1::ResetCommandBuffer => 0x01,
            Gp1::AcknowledgeIrq => 0x02,
            Gp1::DisplayEnabled(_) => 0x03,
            Gp1::DmaDirection(_) => 0x04,
            Gp1::DisplayStart { .. } => 0x05,
            Gp1::HorizontalRange { .. } => 0x06,
            Gp1::VerticalRange { .. } => 0x07,
            Gp1::DisplayMode(_) => 0x08,
            Gp1::AllowTextureDisable(_) => 0x09,
            Gp1::GetInfo(_) => 0x10,
            Gp1::Unused(op) => op,
        }
    }

    /// The GP1 word: the command byte in bits 24-31, each field in its bits, cut to them.
    pub const fn word(self) -> u32 {
        let parameter = match self {
            Gp1::Reset | Gp1::ResetCommandBuffer | Gp1::AcknowledgeIrq | Gp1::Unused(_) => 0,
            Gp1::DisplayEnabled(enabled) => !enabled as u32,
            Gp1::DmaDirection(direction) => direction as u32 & 3,
            Gp1::DisplayStart { x, y } => field(x, 0, 10) | field(y, 10, 9),
            Gp1::HorizontalRange { x1, x2 } => field(x1, 0, 12) | field(x2, 12, 12),
            Gp1::VerticalRange { y1, y2 } => field(y1, 0, 10) | field(y2, 10, 10),
            Gp1::DisplayMode(mode) => mode as u32,
            Gp1::AllowTextureDisable(allow) => allow as u32,
            Gp1::GetInfo(register) => register as u32 & 7,
        };
        (self.op() as u32) << 24 | parameter
    }
}

/// Bits `shift..shift + width` of `word`.
const fn bits(word: u32, shift: u32, width: u32) -> u16 {
    ((word >> shift) & ((1 << width) - 1)) as u16
}

/// `value` cut to `width` bits, placed at bit `shift`.
const fn field(value: u16, shift: u32, width: u32) -> u32 {
    (value as u32 & ((1 << width) - 1)) << shift
}
