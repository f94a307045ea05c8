//! The GP0 command set: one row per command byte 00h-FFh giving the command's kind, its
//! packet's length, what follows the packet, whether its word takes FIFO space, and its
//! name; and where each word sits in the render packets (docs/hardware/gpu.md §2, §8).
//! Packet assembly, execution, decoding and the packet encoder all read them here.
//!
//! ```
//! use gpu::command::{Command, Kind, Tail};
//! let gt4 = Command::of(0x3C80_8080);
//! assert_eq!((gt4.words, gt4.name), (12, "GT4 polygon"));
//! let Kind::Polygon(op) = gt4.kind else { unreachable!() };
//! assert_eq!(op.uv_word(1), 5); // vertex 1's texture word carries the texpage attribute
//! assert_eq!(Command::of(0xA000_0000).tail, Tail::PixelData);
//! ```

use crate::state::sext11;

/// What a GP0 command does (docs/hardware/gpu.md §2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// 00h, 03h-1Eh, E0h, E7h-FFh: no operation.
    Nop,
    /// 01h: invalidate the CLUT cache.
    ClearCache,
    /// 02h: fill a rectangle (§8).
    Fill,
    /// 1Fh: raise the GPU IRQ.
    Irq,
    /// 20h-3Fh: a triangle or a quad (§3).
    Polygon(PolygonOp),
    /// 40h-5Fh: a line, or a polyline (§4).
    Line(LineOp),
    /// 60h-7Fh: a rectangle (sprite) (§5).
    Rectangle(RectangleOp),
    /// 80h-9Fh: VRAM-to-VRAM copy (§8).
    VramCopy,
    /// A0h-BFh: CPU-to-VRAM transfer; its pixel data follows the packet (§8).
    CpuToVram,
    /// C0h-DFh: VRAM-to-CPU transfer (§8).
    VramToCpu,
    /// E1h: draw mode.
    DrawMode,
    /// E2h: texture window.
    TextureWindow,
    /// E3h: drawing area top-left corner.
    AreaTopLeft,
    /// E4h: drawing area bottom-right corner.
    AreaBottomRight,
    /// E5h: drawing offset.
    DrawingOffset,
    /// E6h: mask bit settings (§6).
    MaskBits,
}

/// What follows a command's packet (docs/hardware/gpu.md §2, §8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tail {
    /// Nothing: the packet is the whole command.
    None,
    /// GP0(A0h): the pixel data, two pixels a word, `ceil(width * height / 2)` words of the
    /// size word's rectangle.
    PixelData,
    /// A polyline: further vertices, each its colour word (Gouraud) and its position word,
    /// up to a terminator word where a vertex's first word would be ([`is_terminator`]).
    PolylineVertices,
}

/// One row of the GP0 command table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Command {
    /// The command byte: bits 24-31 of the command word.
    pub op: u8,
    /// What the command does.
    pub kind: Kind,
    /// Words in its packet, the command word included.
    pub words: usize,
    /// What follows the packet.
    pub tail: Tail,
    /// The command word occupies a slot of the 16-word FIFO. psx-spx ("GPU Other Commands")
    /// lists GP0(00h), its mirrors 04h-1Eh, E0h and E7h-EFh, and E3h-E5h as taking none.
    pub takes_fifo_space: bool,
    /// Short name, e.g. `GT4 polygon`, `F2 line`, `16x16 textured sprite`, `draw mode`.
    pub name: &'static str,
}

impl Command {
    /// The row of the command that `word` starts.
    #[inline(always)]
    pub fn of(word: u32) -> &'static Command {
        &GP0_COMMANDS[(word >> 24) as usize]
    }
}

/// The GP0 command table, indexed by command byte.
pub static GP0_COMMANDS: [Command; 256] = TABLE;

const TABLE: [Command; 256] = {
    let mut t = [row(0); 256];
    let mut op = 0;
    while op < 256 {
        t[op] = row(op as u8);
        op += 1;
    }
    t
};

/// The longest packet of the table: a Gouraud-shaded textured quad's 12 words.
pub(crate) const MAX_PACKET: usize = {
    let mut max = 0;
    let mut op = 0;
    while op < 256 {
        if TABLE[op].words > max {
            max = TABLE[op].words;
        }
        op += 1;
    }
    max
};

/// GP0(00h): no operation.
pub const NOP: u8 = 0x00;
/// GP0(01h): invalidate the CLUT cache.
pub const CLEAR_CACHE: u8 = 0x01;
/// GP0(02h): fill a rectangle.
pub const FILL: u8 = 0x02;
/// GP0(1Fh): raise the GPU IRQ.
pub const IRQ: u8 = 0x1F;
/// GP0(80h), the first of 80h-9Fh: VRAM-to-VRAM copy.
pub const VRAM_COPY: u8 = 0x80;
/// GP0(A0h), the first of A0h-BFh: CPU-to-VRAM transfer.
pub const CPU_TO_VRAM: u8 = 0xA0;
/// GP0(C0h), the first of C0h-DFh: VRAM-to-CPU transfer.
pub const VRAM_TO_CPU: u8 = 0xC0;
/// GP0(E1h): draw mode.
pub const DRAW_MODE: u8 = 0xE1;
/// GP0(E2h): texture window.
pub const TEXTURE_WINDOW: u8 = 0xE2;
/// GP0(E3h): drawing area top-left corner.
pub const AREA_TOP_LEFT: u8 = 0xE3;
/// GP0(E4h): drawing area bottom-right corner.
pub const AREA_BOTTOM_RIGHT: u8 = 0xE4;
/// GP0(E5h): drawing offset.
pub const DRAWING_OFFSET: u8 = 0xE5;
/// GP0(E6h): mask bit settings.
pub const MASK_BITS: u8 = 0xE6;

/// The row of command byte `op`: bits 29-31 give the class, 1 polygon, 2 line, 3
/// rectangle, 4 VRAM copy, 5 CPU to VRAM, 6 VRAM to CPU (docs/hardware/gpu.md §2, §8;
/// psx-spx "GPU Command Summary", "GPU Other Commands").
const fn row(op: u8) -> Command {
    let (kind, words, tail, name) = match op >> 5 {
        1 => {
            let p = PolygonOp::from_op(op);
            (Kind::Polygon(p), p.words(), Tail::None, p.name())
        }
        2 => {
            let l = LineOp::from_op(op);
            let tail = if l.polyline {
                Tail::PolylineVertices
            } else {
                Tail::None
            };
            (Kind::Line(l), l.words(), tail, l.name())
        }
        3 => {
            let r = RectangleOp::from_op(op);
            (Kind::Rectangle(r), r.words(), Tail::None, r.name())
        }
        4 => (Kind::VramCopy, 4, Tail::None, "VRAM copy"),
        5 => (Kind::CpuToVram, 3, Tail::PixelData, "CPU to VRAM"),
        6 => (Kind::VramToCpu, 3, Tail::None, "VRAM to CPU"),
        _ => match op {
            CLEAR_CACHE => (Kind::ClearCache, 1, Tail::None, "clear cache"),
            FILL => (Kind::Fill, 3, Tail::None, "fill"),
            IRQ => (Kind::Irq, 1, Tail::None, "IRQ"),
            DRAW_MODE => (Kind::DrawMode, 1, Tail::None, "draw mode"),
            TEXTURE_WINDOW => (Kind::TextureWindow, 1, Tail::None, "texture window"),
            AREA_TOP_LEFT => (Kind::AreaTopLeft, 1, Tail::None, "drawing area top-left"),
            AREA_BOTTOM_RIGHT => (
                Kind::AreaBottomRight,
                1,
                Tail::None,
                "drawing area bottom-right",
            ),
            DRAWING_OFFSET => (Kind::DrawingOffset, 1, Tail::None, "drawing offset"),
            MASK_BITS => (Kind::MaskBits, 1, Tail::None, "mask bits"),
            _ => (Kind::Nop, 1, Tail::None, "NOP"),
        },
    };
    Command {
        op,
        kind,
        words,
        tail,
        takes_fifo_space: !matches!(op, NOP | 0x04..=0x1E | 0xE0 | 0xE3..=0xE5 | 0xE7..=0xEF),
        name,
    }
}

/// Render command bit 24: raw texture, no colour modulation (docs/hardware/gpu.md §2).
const RAW: u8 = 1 << 0;
/// Render command bit 25: semi-transparent.
const SEMI: u8 = 1 << 1;
/// Render command bit 26: textured.
const TEXTURED: u8 = 1 << 2;
/// Render command bit 27: a polygon's fourth vertex, a line's further vertices.
const MORE: u8 = 1 << 3;
/// Render command bit 28: Gouraud shading.
const GOURAUD: u8 = 1 << 4;
/// Render command bits 29-31 of the three classes.
const POLYGON: u8 = 0x20;
const LINE: u8 = 0x40;
const RECTANGLE: u8 = 0x60;

const fn bit(op: u8, b: u8) -> bool {
    op & b != 0
}

const fn bit_if(on: bool, b: u8) -> u8 {
    if on { b } else { 0 }
}

/// The index of vertex `n`'s position word in a polygon or line packet: each vertex is its
/// colour word (Gouraud, not the first vertex), its position word, and its texture word
/// (textured) (docs/hardware/gpu.md §2).
const fn position_word(gouraud: bool, textured: bool, n: usize) -> usize {
    let (g, t) = (gouraud as usize, textured as usize);
    if n == 0 {
        1
    } else {
        // The command word, vertex 0's position and texture words, the vertices between,
        // then this vertex's colour word.
        1 + (1 + t) + (n - 1) * (g + 1 + t) + g
    }
}

/// The index of vertex `n`'s colour word: the command word for the first vertex and for
/// every vertex of a flat primitive, else the word before the position (docs/hardware/gpu.md §2).
const fn color_word(gouraud: bool, textured: bool, n: usize) -> usize {
    if n == 0 || !gouraud {
        0
    } else {
        position_word(gouraud, textured, n) - 1
    }
}

/// A polygon command byte 20h-3Fh, decoded (docs/hardware/gpu.md §2, §3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct PolygonOp {
    /// Bit 28: colours interpolated between the vertices.
    pub gouraud: bool,
    /// Bit 27: four vertices (two triangles) instead of three.
    pub quad: bool,
    /// Bit 26: each vertex has a texture word.
    pub textured: bool,
    /// Bit 25: semi-transparent.
    pub semi_transparent: bool,
    /// Bit 24: raw texture, no colour modulation.
    pub raw: bool,
}

impl PolygonOp {
    /// Decode a command byte's bits 24-28 (bits 29-31 are the class).
    pub const fn from_op(op: u8) -> Self {
        Self {
            gouraud: bit(op, GOURAUD),
            quad: bit(op, MORE),
            textured: bit(op, TEXTURED),
            semi_transparent: bit(op, SEMI),
            raw: bit(op, RAW),
        }
    }

    /// The command byte.
    pub const fn op(self) -> u8 {
        POLYGON
            | bit_if(self.gouraud, GOURAUD)
            | bit_if(self.quad, MORE)
            | bit_if(self.textured, TEXTURED)
            | bit_if(self.semi_transparent, SEMI)
            | bit_if(self.raw, RAW)
    }

    /// Vertices: 3, or 4 for a quad.
    pub const fn vertices(self) -> usize {
        if self.quad { 4 } else { 3 }
    }

    /// Words in the packet: F3 4, F4 5, G3 6, G4 8, FT3 7, FT4 9, GT3 9, GT4 12.
    pub const fn words(self) -> usize {
        position_word(self.gouraud, self.textured, self.vertices() - 1) + 1 + self.textured as usize
    }

    /// The index of vertex `n`'s position word.
    pub const fn position_word(self, n: usize) -> usize {
        position_word(self.gouraud, self.textured, n)
    }

    /// The index of vertex `n`'s colour word (0, the command word, for vertex 0 and for
    /// every vertex of a flat polygon).
    pub const fn color_word(self, n: usize) -> usize {
        color_word(self.gouraud, self.textured, n)
    }

    /// The index of vertex `n`'s texture word (U bits 0-7, V bits 8-15; the CLUT attribute
    /// in vertex 0's upper half, the texpage attribute in vertex 1's). Meaningful when
    /// [`PolygonOp::textured`].
    pub const fn uv_word(self, n: usize) -> usize {
        self.position_word(n) + 1
    }

    const fn name(self) -> &'static str {
        match (self.gouraud, self.textured, self.quad) {
            (false, false, false) => "F3 polygon",
            (false, false, true) => "F4 polygon",
            (false, true, false) => "FT3 polygon",
            (false, true, true) => "FT4 polygon",
            (true, false, false) => "G3 polygon",
            (true, false, true) => "G4 polygon",
            (true, true, false) => "GT3 polygon",
            (true, true, true) => "GT4 polygon",
        }
    }
}

/// A line command byte 40h-5Fh, decoded (docs/hardware/gpu.md §2, §4). Bits 24 and 26 are
/// ignored: lines are never textured; [`LineOp::op`] leaves them clear.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct LineOp {
    /// Bit 28: colours interpolated along the line.
    pub gouraud: bool,
    /// Bit 27: a polyline, vertices up to a terminator word.
    pub polyline: bool,
    /// Bit 25: semi-transparent.
    pub semi_transparent: bool,
}

impl LineOp {
    /// Decode a command byte's bits 24-28.
    pub const fn from_op(op: u8) -> Self {
        Self {
            gouraud: bit(op, GOURAUD),
            polyline: bit(op, MORE),
            semi_transparent: bit(op, SEMI),
        }
    }

    /// The command byte.
    pub const fn op(self) -> u8 {
        LINE | bit_if(self.gouraud, GOURAUD)
            | bit_if(self.polyline, MORE)
            | bit_if(self.semi_transparent, SEMI)
    }

    /// Words in the packet up to the first segment's end: F2 3, G2 4 (a polyline's
    /// further vertices follow, [`Tail::PolylineVertices`]).
    pub const fn words(self) -> usize {
        position_word(self.gouraud, false, 1) + 1
    }

    /// The index of vertex `n`'s (0 or 1) position word.
    pub const fn position_word(self, n: usize) -> usize {
        position_word(self.gouraud, false, n)
    }

    /// The index of vertex `n`'s (0 or 1) colour word (0, the command word, for vertex 0
    /// and for a flat line).
    pub const fn color_word(self, n: usize) -> usize {
        color_word(self.gouraud, false, n)
    }

    /// Words of each further polyline vertex: its colour (Gouraud) and its position.
    pub const fn words_per_vertex(self) -> usize {
        1 + self.gouraud as usize
    }

    const fn name(self) -> &'static str {
        match (self.gouraud, self.polyline) {
            (false, false) => "F2 line",
            (true, false) => "G2 line",
            (false, true) => "F polyline",
            (true, true) => "G polyline",
        }
    }
}

/// A rectangle's size, command bits 27-28 (docs/hardware/gpu.md §2, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SpriteSize {
    /// 0: the size word gives it, W & 3FFh by H & 1FFh.
    #[default]
    Variable,
    /// 1: one pixel.
    One,
    /// 2: 8x8.
    Eight,
    /// 3: 16x16.
    Sixteen,
}

impl SpriteSize {
    /// Decode the two-bit field.
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 3 {
            0 => SpriteSize::Variable,
            1 => SpriteSize::One,
            2 => SpriteSize::Eight,
            _ => SpriteSize::Sixteen,
        }
    }

    /// The two-bit field.
    pub const fn bits(self) -> u8 {
        match self {
            SpriteSize::Variable => 0,
            SpriteSize::One => 1,
            SpriteSize::Eight => 2,
            SpriteSize::Sixteen => 3,
        }
    }

    /// Width and height of a fixed size; `None` for [`SpriteSize::Variable`].
    pub const fn fixed(self) -> Option<(u16, u16)> {
        match self {
            SpriteSize::Variable => None,
            SpriteSize::One => Some((1, 1)),
            SpriteSize::Eight => Some((8, 8)),
            SpriteSize::Sixteen => Some((16, 16)),
        }
    }
}

/// A rectangle command byte 60h-7Fh, decoded (docs/hardware/gpu.md §2, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct RectangleOp {
    /// Bits 27-28.
    pub size: SpriteSize,
    /// Bit 26: a texture word follows the position.
    pub textured: bool,
    /// Bit 25: semi-transparent.
    pub semi_transparent: bool,
    /// Bit 24: raw texture, no colour modulation.
    pub raw: bool,
}

impl RectangleOp {
    /// Decode a command byte's bits 24-28.
    pub const fn from_op(op: u8) -> Self {
        Self {
            size: SpriteSize::from_bits(op >> 3),
            textured: bit(op, TEXTURED),
            semi_transparent: bit(op, SEMI),
            raw: bit(op, RAW),
        }
    }

    /// The command byte.
    pub const fn op(self) -> u8 {
        RECTANGLE
            | self.size.bits() << 3
            | bit_if(self.textured, TEXTURED)
            | bit_if(self.semi_transparent, SEMI)
            | bit_if(self.raw, RAW)
    }

    /// The index of the position word (the top-left corner).
    pub const fn position_word(self) -> usize {
        1
    }

    /// The index of the texture word (U, V and the CLUT attribute); meaningful when
    /// [`RectangleOp::textured`].
    pub const fn uv_word(self) -> usize {
        2
    }

    /// The index of the size word (height << 16 | width); meaningful for
    /// [`SpriteSize::Variable`].
    pub const fn size_word(self) -> usize {
        2 + self.textured as usize
    }

    /// Words in the packet: the command and position words, the texture word when
    /// textured, the size word when variable.
    pub const fn words(self) -> usize {
        self.size_word() + matches!(self.size, SpriteSize::Variable) as usize
    }

    const fn name(self) -> &'static str {
        match (self.size, self.textured) {
            (SpriteSize::Variable, false) => "variable sprite",
            (SpriteSize::Variable, true) => "variable textured sprite",
            (SpriteSize::One, false) => "1x1 sprite",
            (SpriteSize::One, true) => "1x1 textured sprite",
            (SpriteSize::Eight, false) => "8x8 sprite",
            (SpriteSize::Eight, true) => "8x8 textured sprite",
            (SpriteSize::Sixteen, false) => "16x16 sprite",
            (SpriteSize::Sixteen, true) => "16x16 textured sprite",
        }
    }
}

/// The polyline terminator: a word with `(w & F000F000h) == 50005000h` where the next
/// vertex's first word would be (docs/hardware/gpu.md §2).
pub const fn is_terminator(word: u32) -> bool {
    word & 0xF000_F000 == 0x5000_5000
}

/// A vertex position word, X in bits 0-10 and Y in bits 16-26, each signed 11-bit; the
/// other bits are ignored (docs/hardware/gpu.md §2).
pub const fn position(word: u32) -> (i32, i32) {
    (sext11(word), sext11(word >> 16))
}

/// The position word of (x, y): their low 11 bits (docs/hardware/gpu.md §2).
pub const fn position_bits(x: i32, y: i32) -> u32 {
    (x as u32 & 0x7FF) | (y as u32 & 0x7FF) << 16
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every command byte's packet length, what follows it and its kind, from psx-spx: "GPU
    /// Render Polygon Commands" (F3 4, F4 5, G3 6, G4 8, FT3 7, FT4 9, GT3 9, GT4 12 words),
    /// "GPU Render Line Commands" (F2 3, G2 4; a polyline's vertices up to the terminator),
    /// "GPU Render Rectangle Commands" (the command and position words, plus the texture
    /// word when textured, plus the size word when variable), "GPU Memory Transfer Commands"
    /// and "GPU Command Summary" (fill 3, VRAM copy 4, CPU transfers 3, A0h's pixel data
    /// after them), every other command one word: the counts of docs/hardware/gpu.md §2,
    /// written out here by command byte.
    #[test]
    fn every_command_matches_the_psx_spx_table() {
        for op in 0..=0xFFu8 {
            let low = op & 0x03; // semi-transparency and raw never change the length
            let (words, tail) = match op {
                0x02 => (3, Tail::None),
                0x20..=0x3F => match op & !0x03 {
                    0x20 => (4, Tail::None), // F3
                    0x28 => (5, Tail::None), // F4
                    0x30 => (6, Tail::None), // G3
                    0x38 => (8, Tail::None), // G4
                    0x24 => (7, Tail::None), // FT3
                    0x2C => (9, Tail::None), // FT4
                    0x34 => (9, Tail::None), // GT3
                    _ => (12, Tail::None),   // GT4
                },
                0x40..=0x5F => match op & 0x18 {
                    0x00 => (3, Tail::None),             // F2
                    0x10 => (4, Tail::None),             // G2
                    0x08 => (3, Tail::PolylineVertices), // F polyline
                    _ => (4, Tail::PolylineVertices),    // G polyline
                },
                0x60..=0x7F => match op & 0x1C {
                    0x00 => (3, Tail::None), // variable
                    0x04 => (4, Tail::None), // variable, textured
                    0x08 | 0x10 | 0x18 => (2, Tail::None),
                    _ => (3, Tail::None), // fixed size, textured
                },
                0x80..=0x9F => (4, Tail::None),
                0xA0..=0xBF => (3, Tail::PixelData),
                0xC0..=0xDF => (3, Tail::None),
                _ => (1, Tail::None),
            };
            let c = Command::of(u32::from(op) << 24 | 0xFF_FFFF);
            assert_eq!(
                (c.op, c.words, c.tail),
                (op, words, tail),
                "{op:02X}h ({low})"
            );
            let class = match c.kind {
                Kind::Polygon(_) => 1,
                Kind::Line(_) => 2,
                Kind::Rectangle(_) => 3,
                Kind::VramCopy => 4,
                Kind::CpuToVram => 5,
                Kind::VramToCpu => 6,
                Kind::DrawMode
                | Kind::TextureWindow
                | Kind::AreaTopLeft
                | Kind::AreaBottomRight
                | Kind::DrawingOffset
                | Kind::MaskBits => 7,
                Kind::Nop | Kind::ClearCache | Kind::Fill | Kind::Irq => 0,
            };
            let expected_class = match op {
                0xE7..=0xFF | 0xE0 => 0, // no operation
                _ => op >> 5,
            };
            assert_eq!(class, expected_class, "{op:02X}h");
        }
        assert_eq!(MAX_PACKET, 12);
    }

    /// psx-spx "GPU Other Commands": GP0(00h), 04h-1Eh, E0h, E7h-EFh and E3h-E5h take no
    /// FIFO space; GP0(03h) does on the v2 GPU modelled; every other command does.
    #[test]
    fn fifo_space() {
        let none = [
            (0x00, 0x00),
            (0x04, 0x1E),
            (0xE0, 0xE0),
            (0xE3, 0xE5),
            (0xE7, 0xEF),
        ];
        for op in 0..=0xFFu8 {
            let expected = !none.iter().any(|&(lo, hi)| (lo..=hi).contains(&op));
            assert_eq!(
                Command::of(u32::from(op) << 24).takes_fifo_space,
                expected,
                "{op:02X}h"
            );
        }
    }

    /// Word positions of the polygon packets written out from the docs/hardware/gpu.md §2
    /// word order ([colour] [position] [texture word] per vertex): GT4's 12 words are
    /// command+colour0, xy0, uv0+clut, colour1, xy1, uv1+page, colour2, xy2, uv2, colour3,
    /// xy3, uv3.
    #[test]
    fn polygon_word_positions() {
        let gt4 = PolygonOp::from_op(0x3C);
        let at = |n| (gt4.color_word(n), gt4.position_word(n), gt4.uv_word(n));
        assert_eq!(
            [at(0), at(1), at(2), at(3)],
            [(0, 1, 2), (3, 4, 5), (6, 7, 8), (9, 10, 11)]
        );
        let ft3 = PolygonOp::from_op(0x24);
        let at = |n| (ft3.color_word(n), ft3.position_word(n), ft3.uv_word(n));
        assert_eq!([at(0), at(1), at(2)], [(0, 1, 2), (0, 3, 4), (0, 5, 6)]);
        let g4 = PolygonOp::from_op(0x38);
        let at = |n| (g4.color_word(n), g4.position_word(n));
        assert_eq!(
            [at(0), at(1), at(2), at(3)],
            [(0, 1), (2, 3), (4, 5), (6, 7)]
        );
        let f4 = PolygonOp::from_op(0x28);
        assert_eq!([0, 1, 2, 3].map(|n| f4.position_word(n)), [1, 2, 3, 4]);
        let g2 = LineOp::from_op(0x50);
        assert_eq!([g2.color_word(1), g2.position_word(1)], [2, 3]);
        let ft = RectangleOp::from_op(0x64);
        assert_eq!(
            [ft.position_word(), ft.uv_word(), ft.size_word()],
            [1, 2, 3]
        );
        assert_eq!(RectangleOp::from_op(0x60).size_word(), 2);
    }

    /// Every render command byte decodes to its parts and encodes back.
    #[test]
    fn render_ops_round_trip() {
        for op in 0x20..=0x3Fu8 {
            assert_eq!(PolygonOp::from_op(op).op(), op);
        }
        for op in 0x40..=0x5Fu8 {
            assert_eq!(LineOp::from_op(op).op(), op & !(RAW | TEXTURED));
        }
        for op in 0x60..=0x7Fu8 {
            assert_eq!(RectangleOp::from_op(op).op(), op);
        }
    }

    #[test]
    fn positions_are_signed_11_bit() {
        assert_eq!(position(0x0400_03FF), (1023, 1024 - 2048));
        assert_eq!(position(0xF800_F800), (0, 0));
        assert_eq!(position_bits(-1, 5), 0x0005_07FF);
        assert!(is_terminator(0x5555_5555) && is_terminator(0x5000_5000));
        assert!(!is_terminator(0x5000_4000));
    }
}
