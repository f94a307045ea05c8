//! Drawing environment set by GP0(E1h..E6h): draw mode, texture window, drawing area,
//! drawing offset and mask settings (docs/hardware/gpu.md §2).

/// Texture colour depth, E1 bits 7-8 (docs/hardware/gpu.md §2, §7). Value 3 behaves as 15-bit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum TextureDepth {
    /// 4-bit CLUT indices, four texels per halfword.
    #[default]
    Clut4,
    /// 8-bit CLUT indices, two texels per halfword.
    Clut8,
    /// 15-bit direct colour, one texel per halfword.
    Direct15,
}

/// Semi-transparency mode, E1 bits 5-6 (docs/hardware/gpu.md §6). B = VRAM pixel, F = new pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BlendMode {
    /// 0: (B + F) >> 1.
    #[default]
    Average,
    /// 1: min(31, B + F).
    Add,
    /// 2: max(0, B - F).
    Subtract,
    /// 3: min(31, B + F/4).
    AddQuarter,
}

/// GP0(E1h) draw mode (docs/hardware/gpu.md §2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DrawMode {
    /// Texture page left edge in halfwords (multiple of 64).
    pub page_x: u16,
    /// Texture page top line (0 or 256).
    pub page_y: u16,
    /// Semi-transparency mode.
    pub blend: BlendMode,
    /// Texture depth.
    pub depth: TextureDepth,
    /// E1 bits 7-8 were 3 ("reserved"): textures read as 15-bit, GPUSTAT bits 7-8 read back
    /// 3 (ps1-tests gpu/gp0-e1).
    pub depth_reserved: bool,
    /// Dithering enabled (E1 bit 9).
    pub dither: bool,
    /// Drawing to the displayed area allowed (E1 bit 10).
    pub draw_to_display: bool,
    /// Texture disable (E1 bit 11; effective only when GP1(09h) allows it).
    pub texture_disable: bool,
    /// Rectangle X flip (E1 bit 12).
    pub flip_x: bool,
    /// Rectangle Y flip (E1 bit 13).
    pub flip_y: bool,
}

/// GP0(E2h) texture window, each field in 8-texel units (5 bits) (docs/hardware/gpu.md §2, §7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TextureWindow {
    /// Mask X (bits 0-4).
    pub mask_x: u8,
    /// Mask Y (bits 5-9).
    pub mask_y: u8,
    /// Offset X (bits 10-14).
    pub offset_x: u8,
    /// Offset Y (bits 15-19).
    pub offset_y: u8,
}

/// GP0(E3h)/(E4h) drawing area, inclusive bounds (docs/hardware/gpu.md §2). X is 10 bits; Y is 10 bits
/// (0-1023) on the modelled v2 GPU, compared with the unwrapped pixel Y, while rows are written
/// at `y & 511`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DrawingArea {
    /// Leftmost drawable column (0-1023).
    pub left: u16,
    /// Topmost drawable line (0-1023).
    pub top: u16,
    /// Rightmost drawable column, inclusive (0-1023).
    pub right: u16,
    /// Bottom drawable line, inclusive (0-1023).
    pub bottom: u16,
}

/// GP0(E6h) mask bit settings (docs/hardware/gpu.md §6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MaskSettings {
    /// Force bit 15 on every written pixel (E6 bit 0).
    pub set: bool,
    /// Skip destination pixels whose bit 15 is set (E6 bit 1).
    pub check: bool,
}

/// The whole drawing environment a primitive is drawn with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct DrawState {
    /// E1.
    pub mode: DrawMode,
    /// E2.
    pub window: TextureWindow,
    /// E3/E4.
    pub area: DrawingArea,
    /// E5 X offset (signed 11-bit).
    pub offset_x: i16,
    /// E5 Y offset (signed 11-bit).
    pub offset_y: i16,
    /// E6.
    pub mask: MaskSettings,
}

impl DrawState {
    /// Every field within what E1-E6 and texpage attributes can set (docs/hardware/gpu.md §2):
    /// page X a multiple of 64 up to 960, page Y 0 or 256, window fields 5 bits, area corners
    /// 10 bits, offsets signed 11 bits, the reserved depth read as 15-bit.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        let m = &self.mode;
        let w = &self.window;
        let a = &self.area;
        let offset = -1024..=1023;
        if !m.page_x.is_multiple_of(64) || m.page_x > 960 || !matches!(m.page_y, 0 | 256) {
            Err("texture page outside the texpage field")
        } else if m.depth_reserved && m.depth != TextureDepth::Direct15 {
            Err("reserved texture depth not read as 15-bit")
        } else if [w.mask_x, w.mask_y, w.offset_x, w.offset_y]
            .iter()
            .any(|&f| f > 0x1F)
        {
            Err("texture window field wider than 5 bits")
        } else if [a.left, a.top, a.right, a.bottom]
            .iter()
            .any(|&c| c > 0x3FF)
        {
            Err("drawing area corner wider than 10 bits")
        } else if !offset.contains(&self.offset_x) || !offset.contains(&self.offset_y) {
            Err("drawing offset outside signed 11 bits")
        } else {
            Ok(())
        }
    }
}
