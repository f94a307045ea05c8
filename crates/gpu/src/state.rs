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

impl TextureDepth {
    /// Decode the 2-bit depth field (E1h or texpage attribute bits 7-8, given here shifted
    /// down to bits 0-1; higher bits are ignored): 0 4-bit, 1 8-bit, 2 15-bit, 3 reserved,
    /// read as 15-bit (docs/hardware/gpu.md §2).
    pub const fn from_bits(bits: u32) -> TextureDepth {
        match bits & 3 {
            0 => TextureDepth::Clut4,
            1 => TextureDepth::Clut8,
            _ => TextureDepth::Direct15,
        }
    }

    /// The 2-bit depth field, 0-2 (docs/hardware/gpu.md §2).
    pub const fn bits(self) -> u32 {
        match self {
            TextureDepth::Clut4 => 0,
            TextureDepth::Clut8 => 1,
            TextureDepth::Direct15 => 2,
        }
    }

    /// Entries of the CLUT a texture of this depth indexes: 16, 256, or 0 for direct colour
    /// (docs/hardware/gpu.md §7).
    pub const fn clut_len(self) -> usize {
        match self {
            TextureDepth::Clut4 => 16,
            TextureDepth::Clut8 => 256,
            TextureDepth::Direct15 => 0,
        }
    }

    /// Texels stored in one VRAM halfword: 4, 2 or 1 (docs/hardware/gpu.md §7).
    pub const fn texels_per_halfword(self) -> usize {
        match self {
            TextureDepth::Clut4 => 4,
            TextureDepth::Clut8 => 2,
            TextureDepth::Direct15 => 1,
        }
    }
}

impl BlendMode {
    /// Decode the 2-bit semi-transparency field (E1h or texpage attribute bits 5-6, given
    /// here shifted down to bits 0-1; higher bits are ignored) (docs/hardware/gpu.md §2, §6).
    pub const fn from_bits(bits: u32) -> BlendMode {
        match bits & 3 {
            0 => BlendMode::Average,
            1 => BlendMode::Add,
            2 => BlendMode::Subtract,
            _ => BlendMode::AddQuarter,
        }
    }

    /// The 2-bit semi-transparency field, 0-3 (docs/hardware/gpu.md §2).
    pub const fn bits(self) -> u32 {
        match self {
            BlendMode::Average => 0,
            BlendMode::Add => 1,
            BlendMode::Subtract => 2,
            BlendMode::AddQuarter => 3,
        }
    }
}

/// A textured polygon's texture-page attribute, the upper half of vertex 1's texture word:
/// bits 0-3 page X / 64, 4 page Y / 256, 5-6 semi-transparency, 7-8 depth, 11 texture
/// disable; the same layout as E1h bits 0-8 and 11 (docs/hardware/gpu.md §2).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Texpage {
    /// Page left edge in halfwords, a multiple of 64 (0-960).
    pub page_x: u16,
    /// Page top line, 0 or 256.
    pub page_y: u16,
    /// Semi-transparency mode.
    pub blend: BlendMode,
    /// Texture depth (3, reserved, decodes as 15-bit; see [`Texpage::depth_reserved`]).
    pub depth: TextureDepth,
    /// The depth field was 3.
    pub depth_reserved: bool,
    /// Texture disable (bit 11).
    pub texture_disable: bool,
}

impl Texpage {
    /// Decode the attribute's bits 0-8 and 11; the others are ignored (docs/hardware/gpu.md §2).
    pub const fn from_bits(bits: u32) -> Texpage {
        Texpage {
            page_x: ((bits & 0xF) * 64) as u16,
            page_y: ((bits >> 4 & 1) * 256) as u16,
            blend: BlendMode::from_bits(bits >> 5),
            depth: TextureDepth::from_bits(bits >> 7),
            depth_reserved: bits >> 7 & 3 == 3,
            texture_disable: bits & (1 << 11) != 0,
        }
    }

    /// Encode bits 0-8 and 11 (docs/hardware/gpu.md §2). `page_x` / 64 and `page_y` / 256
    /// are taken modulo the field widths (16 pages, 2 rows); a reserved depth encodes as 3.
    pub const fn bits(self) -> u32 {
        let depth = if self.depth_reserved {
            3
        } else {
            self.depth.bits()
        };
        ((self.page_x as u32 / 64) & 0xF)
            | ((self.page_y as u32 / 256) & 1) << 4
            | self.blend.bits() << 5
            | depth << 7
            | (self.texture_disable as u32) << 11
    }
}

/// A CLUT attribute, the upper half of vertex 0's texture word (or a textured rectangle's):
/// x = (bits & 3Fh) × 16, y = (bits >> 6) & 1FFh (docs/hardware/gpu.md §7).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClutAttr {
    /// CLUT left edge in halfwords, a multiple of 16 (0-1008).
    pub x: u16,
    /// CLUT line (0-511).
    pub y: u16,
}

impl ClutAttr {
    /// Decode bits 0-14; bit 15 is ignored (docs/hardware/gpu.md §7).
    pub const fn from_bits(bits: u32) -> ClutAttr {
        ClutAttr {
            x: ((bits & 0x3F) * 16) as u16,
            y: (bits >> 6 & 0x1FF) as u16,
        }
    }

    /// Encode (docs/hardware/gpu.md §7): `x` / 16 and `y` are taken modulo the field widths
    /// (64 columns, 512 lines).
    pub const fn bits(self) -> u32 {
        ((self.x as u32 / 16) & 0x3F) | (self.y as u32 & 0x1FF) << 6
    }
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

impl DrawMode {
    /// Decode GP0(E1h) bits 0-13; the others are ignored (docs/hardware/gpu.md §2).
    pub const fn from_bits(word: u32) -> Self {
        let t = Texpage::from_bits(word);
        DrawMode {
            page_x: t.page_x,
            page_y: t.page_y,
            blend: t.blend,
            depth: t.depth,
            depth_reserved: t.depth_reserved,
            texture_disable: t.texture_disable,
            dither: word & (1 << 9) != 0,
            draw_to_display: word & (1 << 10) != 0,
            flip_x: word & (1 << 12) != 0,
            flip_y: word & (1 << 13) != 0,
        }
    }

    /// Encode GP0(E1h) bits 0-13 (docs/hardware/gpu.md §2).
    pub const fn bits(self) -> u32 {
        self.texpage().bits()
            | (self.dither as u32) << 9
            | (self.draw_to_display as u32) << 10
            | (self.flip_x as u32) << 12
            | (self.flip_y as u32) << 13
    }

    /// The fields a texpage attribute shares with the mode: bits 0-8 and 11.
    pub const fn texpage(self) -> Texpage {
        Texpage {
            page_x: self.page_x,
            page_y: self.page_y,
            blend: self.blend,
            depth: self.depth,
            depth_reserved: self.depth_reserved,
            texture_disable: self.texture_disable,
        }
    }

    /// Take a polygon's texpage attribute: it rewrites bits 0-8 and 11, never 9-10
    /// (docs/hardware/gpu.md §2).
    pub fn set_texpage(&mut self, attr: u32) {
        let t = Texpage::from_bits(attr);
        self.page_x = t.page_x;
        self.page_y = t.page_y;
        self.blend = t.blend;
        self.depth = t.depth;
        self.depth_reserved = t.depth_reserved;
        self.texture_disable = t.texture_disable;
    }
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

impl TextureWindow {
    /// Decode GP0(E2h) bits 0-19 (docs/hardware/gpu.md §2).
    pub const fn from_bits(word: u32) -> Self {
        TextureWindow {
            mask_x: (word & 0x1F) as u8,
            mask_y: (word >> 5 & 0x1F) as u8,
            offset_x: (word >> 10 & 0x1F) as u8,
            offset_y: (word >> 15 & 0x1F) as u8,
        }
    }

    /// Encode GP0(E2h) bits 0-19; each field is taken modulo 32 (docs/hardware/gpu.md §2).
    pub const fn bits(self) -> u32 {
        (self.mask_x as u32 & 0x1F)
            | (self.mask_y as u32 & 0x1F) << 5
            | (self.offset_x as u32 & 0x1F) << 10
            | (self.offset_y as u32 & 0x1F) << 15
    }
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

impl DrawingArea {
    /// Decode a GP0(E3h)/(E4h) corner: X bits 0-9, Y bits 10-19 on the v2 GPU
    /// (docs/hardware/gpu.md §2; docs/gpu.md "Modelled GPU version").
    pub const fn corner_from_bits(word: u32) -> (u16, u16) {
        ((word & 0x3FF) as u16, (word >> 10 & 0x3FF) as u16)
    }

    /// Encode a GP0(E3h)/(E4h) corner; X and Y are taken modulo 1024.
    pub const fn corner_bits(x: u16, y: u16) -> u32 {
        (x as u32 & 0x3FF) | (y as u32 & 0x3FF) << 10
    }
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

impl MaskSettings {
    /// Decode GP0(E6h) bits 0-1 (docs/hardware/gpu.md §2).
    pub const fn from_bits(word: u32) -> Self {
        MaskSettings {
            set: word & 1 != 0,
            check: word & 2 != 0,
        }
    }

    /// Encode GP0(E6h) bits 0-1.
    pub const fn bits(self) -> u32 {
        self.set as u32 | (self.check as u32) << 1
    }
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
    /// Decode a GP0(E5h) drawing offset: X bits 0-10, Y bits 11-21, each signed 11-bit
    /// (docs/hardware/gpu.md §2).
    pub const fn offset_from_bits(word: u32) -> (i16, i16) {
        (sext11(word) as i16, sext11(word >> 11) as i16)
    }

    /// Encode a GP0(E5h) drawing offset: the low 11 bits of X and Y.
    pub const fn offset_bits(x: i16, y: i16) -> u32 {
        (x as u32 & 0x7FF) | (y as u32 & 0x7FF) << 11
    }

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

/// Sign-extend the low 11 bits (docs/hardware/gpu.md §2).
pub(crate) const fn sext11(v: u32) -> i32 {
    ((v << 21) as i32) >> 21
}

#[cfg(test)]
mod field_tests {
    use super::*;

    /// E1h bits 7-8 (docs/hardware/gpu.md §2): 0 4-bit, 1 8-bit, 2 15-bit, 3 read as 15-bit.
    #[test]
    fn texture_depth_field() {
        let table = [
            (0, TextureDepth::Clut4),
            (1, TextureDepth::Clut8),
            (2, TextureDepth::Direct15),
            (3, TextureDepth::Direct15),
        ];
        for (bits, depth) in table {
            assert_eq!(TextureDepth::from_bits(bits), depth);
            assert_eq!(
                TextureDepth::from_bits(bits | 0xFFFF_FFFC),
                depth,
                "high bits ignored"
            );
        }
        for (bits, depth) in &table[..3] {
            assert_eq!(depth.bits(), *bits);
        }
        let sizes = [(TextureDepth::Clut4, 16, 4), (TextureDepth::Clut8, 256, 2)];
        for (d, clut, per) in sizes {
            assert_eq!((d.clut_len(), d.texels_per_halfword()), (clut, per));
        }
        assert_eq!(TextureDepth::Direct15.clut_len(), 0);
        assert_eq!(TextureDepth::Direct15.texels_per_halfword(), 1);
    }

    /// E1h bits 5-6 (docs/hardware/gpu.md §2, §6): 0 average, 1 add, 2 subtract, 3 add a quarter.
    #[test]
    fn blend_mode_field() {
        let table = [
            (0, BlendMode::Average),
            (1, BlendMode::Add),
            (2, BlendMode::Subtract),
            (3, BlendMode::AddQuarter),
        ];
        for (bits, mode) in table {
            assert_eq!(BlendMode::from_bits(bits), mode);
            assert_eq!(BlendMode::from_bits(bits | 4), mode);
            assert_eq!(mode.bits(), bits);
        }
    }

    /// Texpage attribute, written out from the fact sheet's layout: page X 3 (192), page Y 1
    /// (256), blend 2, depth 1, texture disable: 3 | 1<<4 | 2<<5 | 1<<7 | 1<<11 = 8D3h.
    #[test]
    fn texpage_layout() {
        let t = Texpage {
            page_x: 192,
            page_y: 256,
            blend: BlendMode::Subtract,
            depth: TextureDepth::Clut8,
            depth_reserved: false,
            texture_disable: true,
        };
        assert_eq!(t.bits(), 0x8D3);
        assert_eq!(Texpage::from_bits(0x8D3), t);
        // Bits 9-10 (dither, draw to display) and 12 up are not part of the attribute.
        assert_eq!(Texpage::from_bits(0x8D3 | 0x600 | 0xF000), t);
        // Depth 3 reads as 15-bit and is kept as reserved.
        let r = Texpage::from_bits(3 << 7);
        assert_eq!((r.depth, r.depth_reserved), (TextureDepth::Direct15, true));
        assert_eq!(r.bits(), 3 << 7);
        assert_eq!(Texpage::from_bits(0xF).page_x, 960);
    }

    /// CLUT attribute (docs/hardware/gpu.md §7): x = (a & 3Fh) * 16, y = (a >> 6) & 1FFh.
    /// x 1008 (3Fh), y 511 (1FFh): 3Fh | 1FFh << 6 = 7FFFh.
    #[test]
    fn clut_layout() {
        let c = ClutAttr { x: 1008, y: 511 };
        assert_eq!(c.bits(), 0x7FFF);
        assert_eq!(ClutAttr::from_bits(0x7FFF), c);
        assert_eq!(ClutAttr::from_bits(0xFFFF), c, "bit 15 ignored");
        assert_eq!(
            ClutAttr::from_bits(5 | 300 << 6),
            ClutAttr { x: 80, y: 300 }
        );
        assert_eq!(ClutAttr { x: 80, y: 300 }.bits(), 5 | 300 << 6);
    }
}
