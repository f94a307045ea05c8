//! GP0 packets from typed values: polygons, rectangles, lines and polylines, fills, copies,
//! CPU-to-VRAM and VRAM-to-CPU headers and the environment words E1h-E6h, each word laid out
//! as the command table ([`crate::command`]) and the attribute encoders ([`Texpage`],
//! [`ClutAttr`], [`DrawMode`], ...) say (docs/hardware/gpu.md §2, §8). Decoding a packet
//! built here gives back what went in.
//!
//! ```
//! use gpu::encode::{self, Polygon, Vertex};
//! let mut gpu = gpu::Gpu::new();
//! gpu.gp0_words(&encode::environment(&gpu::DrawState {
//!     area: gpu::DrawingArea { left: 0, top: 0, right: 1023, bottom: 511 },
//!     ..Default::default()
//! }));
//! let red = |x, y| Vertex { x, y, color: [255, 0, 0], ..Vertex::default() };
//! let triangle = Polygon::triangle([red(0, 0), red(64, 0), red(0, 64)]);
//! gpu.gp0_words(&triangle.packet());
//! assert_eq!(gpu.vram().pixel(1, 1), 0x001F);
//! ```

use core::ops::Deref;

pub use crate::command::SpriteSize;

use crate::command::{
    self, AREA_BOTTOM_RIGHT, AREA_TOP_LEFT, CLEAR_CACHE, CPU_TO_VRAM, DRAW_MODE, DRAWING_OFFSET,
    FILL, IRQ, LineOp, MASK_BITS, MAX_PACKET, PolygonOp, RectangleOp, TEXTURE_WINDOW, VRAM_COPY,
    VRAM_TO_CPU,
};
use crate::state::{
    ClutAttr, DrawMode, DrawState, DrawingArea, MaskSettings, Texpage, TextureWindow,
};

/// A packet of at most 12 words, built by this module.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Packet {
    words: [u32; MAX_PACKET],
    len: usize,
}

impl Packet {
    /// `len` words of zero.
    fn zeroed(len: usize) -> Self {
        Packet {
            words: [0; MAX_PACKET],
            len,
        }
    }

    /// OR `w` into word `i` (a word past the buffer is not written).
    fn put(&mut self, i: usize, w: u32) {
        if let Some(slot) = self.words.get_mut(i) {
            *slot |= w;
        }
    }

    /// The packet's words.
    pub fn words(&self) -> &[u32] {
        self.words.get(..self.len).unwrap_or(&self.words)
    }
}

impl Deref for Packet {
    type Target = [u32];
    fn deref(&self) -> &[u32] {
        self.words()
    }
}

/// A command word: the command byte and its 24-bit parameter.
const fn word(op: u8, parameter: u32) -> u32 {
    (op as u32) << 24 | (parameter & 0xFF_FFFF)
}

/// A colour word's parameter: R bits 0-7, G 8-15, B 16-23 (docs/hardware/gpu.md §2).
const fn rgb(c: [u8; 3]) -> u32 {
    c[0] as u32 | (c[1] as u32) << 8 | (c[2] as u32) << 16
}

/// A halfword pair: `x` in bits 0-15, `y` in 16-31 (positions and sizes of fills and
/// transfers, docs/hardware/gpu.md §8).
const fn pair(x: u16, y: u16) -> u32 {
    x as u32 | (y as u32) << 16
}

/// A texture word: U bits 0-7, V bits 8-15, an attribute in bits 16-31 (docs/hardware/gpu.md §2).
const fn uv_word(u: u8, v: u8, attribute: u32) -> u32 {
    u as u32 | (v as u32) << 8 | attribute << 16
}

/// A vertex as a polygon or line packet carries it: its position before the drawing
/// offset (the low 11 bits of each are sent), its colour and its texture coordinate.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Vertex {
    /// X, signed 11-bit (-1024..=1023).
    pub x: i16,
    /// Y, signed 11-bit.
    pub y: i16,
    /// 8-bit R, G, B; a flat primitive sends vertex 0's only.
    pub color: [u8; 3],
    /// Texture U, sent when textured.
    pub u: u8,
    /// Texture V, sent when textured.
    pub v: u8,
}

impl Vertex {
    fn position(&self) -> u32 {
        command::position_bits(self.x.into(), self.y.into())
    }
}

/// What a textured polygon samples: the CLUT attribute (vertex 0's texture word), the
/// texture page attribute (vertex 1's, which also sets the draw mode's page, depth,
/// semi-transparency mode and texture disable), and raw texturing (command bit 24).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PolygonTexture {
    /// CLUT position (4/8-bit textures).
    pub clut: ClutAttr,
    /// Texture page and its attributes.
    pub page: Texpage,
    /// Texels written unmodulated.
    pub raw: bool,
}

/// A GP0(20h-3Fh) polygon (docs/hardware/gpu.md §2, §3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Polygon {
    /// Vertices in packet order; the fourth only for a quad.
    pub vertices: [Vertex; 4],
    /// Four vertices (two triangles, v0 v1 v2 and v1 v2 v3).
    pub quad: bool,
    /// Colours interpolated (each vertex's colour sent).
    pub gouraud: bool,
    /// Semi-transparent.
    pub semi_transparent: bool,
    /// Texture coordinates and attributes, when textured.
    pub texture: Option<PolygonTexture>,
}

impl Polygon {
    /// A flat untextured opaque triangle of vertex 0's colour (Gouraud when the vertices'
    /// colours differ).
    pub fn triangle(vertices: [Vertex; 3]) -> Self {
        let [a, b, c] = vertices;
        Self {
            vertices: [a, b, c, Vertex::default()],
            gouraud: a.color != b.color || a.color != c.color,
            ..Self::default()
        }
    }

    /// A flat untextured opaque quad (Gouraud when the vertices' colours differ).
    pub fn quad(vertices: [Vertex; 4]) -> Self {
        let first = vertices[0].color;
        Self {
            vertices,
            quad: true,
            gouraud: vertices.iter().any(|v| v.color != first),
            ..Self::default()
        }
    }

    /// The command byte's parts.
    pub fn op(&self) -> PolygonOp {
        PolygonOp {
            gouraud: self.gouraud,
            quad: self.quad,
            textured: self.texture.is_some(),
            semi_transparent: self.semi_transparent,
            raw: self.texture.is_some_and(|t| t.raw),
        }
    }

    /// The packet: for each vertex its colour word (Gouraud, after the first), position
    /// word and texture word (textured), the first colour in the command word.
    pub fn packet(&self) -> Packet {
        let op = self.op();
        let mut p = Packet::zeroed(op.words());
        p.put(0, word(op.op(), 0));
        for (n, v) in self.vertices.iter().enumerate().take(op.vertices()) {
            if n == 0 || op.gouraud {
                p.put(op.color_word(n), rgb(v.color));
            }
            p.put(op.position_word(n), v.position());
            if let Some(t) = self.texture {
                let attribute = match n {
                    0 => t.clut.bits(),
                    1 => t.page.bits(),
                    _ => 0,
                };
                p.put(op.uv_word(n), uv_word(v.u, v.v, attribute));
            }
        }
        p
    }
}

/// A GP0(40h-5Fh) line of one segment (docs/hardware/gpu.md §2, §4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Line {
    /// Endpoints; `u` and `v` are not sent.
    pub vertices: [Vertex; 2],
    /// Colours interpolated (the second colour sent).
    pub gouraud: bool,
    /// Semi-transparent.
    pub semi_transparent: bool,
}

impl Line {
    /// The command byte's parts.
    pub fn op(&self) -> LineOp {
        LineOp {
            gouraud: self.gouraud,
            polyline: false,
            semi_transparent: self.semi_transparent,
        }
    }

    /// The packet: the command and first colour, the first position, the second colour
    /// (Gouraud), the second position.
    pub fn packet(&self) -> Packet {
        line_words(self.op(), &self.vertices)
    }
}

fn line_words(op: LineOp, vertices: &[Vertex; 2]) -> Packet {
    let mut p = Packet::zeroed(op.words());
    p.put(0, word(op.op(), 0));
    for (n, v) in vertices.iter().enumerate() {
        if n == 0 || op.gouraud {
            p.put(op.color_word(n), rgb(v.color));
        }
        p.put(op.position_word(n), v.position());
    }
    p
}

/// The word this module ends a polyline with: the pattern `(w & F000F000h) == 50005000h`
/// where a vertex's first word would be (docs/hardware/gpu.md §2).
pub const POLYLINE_END: u32 = 0x5555_5555;

/// A GP0(48h-5Fh) polyline: two vertices, any number more, and the terminator
/// (docs/hardware/gpu.md §2, §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Polyline<'a> {
    /// The first segment's endpoints.
    pub first: [Vertex; 2],
    /// The vertices after them, each drawn to from the one before.
    pub more: &'a [Vertex],
    /// Colours interpolated (every vertex's colour sent).
    pub gouraud: bool,
    /// Semi-transparent.
    pub semi_transparent: bool,
}

impl Polyline<'_> {
    /// The command byte's parts.
    pub fn op(&self) -> LineOp {
        LineOp {
            gouraud: self.gouraud,
            polyline: true,
            semi_transparent: self.semi_transparent,
        }
    }

    /// Every word: the first segment's packet, each further vertex's colour word (Gouraud)
    /// and position word, then [`POLYLINE_END`]. A vertex whose word matches the
    /// terminator's pattern would end the polyline early on the GPU, as it would on a console.
    pub fn words(&self) -> impl Iterator<Item = u32> + '_ {
        let op = self.op();
        let head = line_words(op, &self.first);
        let gouraud = op.gouraud;
        (0..head.len)
            .map(move |i| head.words[i])
            .chain(self.more.iter().flat_map(move |v| {
                let color = gouraud.then(|| rgb(v.color));
                color.into_iter().chain([v.position()])
            }))
            .chain([POLYLINE_END])
    }
}

/// What a textured rectangle samples: the CLUT attribute and first texel of its texture
/// word, and raw texturing (command bit 24). Its page is the draw mode's (GP0(E1h)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RectangleTexture {
    /// CLUT position (4/8-bit textures).
    pub clut: ClutAttr,
    /// Texel U of the top-left corner.
    pub u: u8,
    /// Texel V of the top-left corner.
    pub v: u8,
    /// Texels written unmodulated.
    pub raw: bool,
}

/// A GP0(60h-7Fh) rectangle (docs/hardware/gpu.md §2, §5).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rectangle {
    /// Left edge before the drawing offset (11 bits sent).
    pub x: i16,
    /// Top edge before the drawing offset.
    pub y: i16,
    /// 8-bit R, G, B.
    pub color: [u8; 3],
    /// A fixed size, or [`SpriteSize::Variable`] for `width` x `height`.
    pub size: SpriteSize,
    /// Width of a variable-size rectangle (W & 3FFh is drawn).
    pub width: u16,
    /// Height of a variable-size rectangle (H & 1FFh is drawn).
    pub height: u16,
    /// Semi-transparent.
    pub semi_transparent: bool,
    /// Texture word, when textured.
    pub texture: Option<RectangleTexture>,
}

impl Rectangle {
    /// The command byte's parts.
    pub fn op(&self) -> RectangleOp {
        RectangleOp {
            size: self.size,
            textured: self.texture.is_some(),
            semi_transparent: self.semi_transparent,
            raw: self.texture.is_some_and(|t| t.raw),
        }
    }

    /// The packet: command and colour, position, texture word (textured), size word
    /// (variable).
    pub fn packet(&self) -> Packet {
        let op = self.op();
        let mut p = Packet::zeroed(op.words());
        p.put(0, word(op.op(), rgb(self.color)));
        let position = command::position_bits(self.x.into(), self.y.into());
        p.put(op.position_word(), position);
        if let Some(t) = self.texture {
            p.put(op.uv_word(), uv_word(t.u, t.v, t.clut.bits()));
        }
        if op.size == SpriteSize::Variable {
            p.put(op.size_word(), pair(self.width, self.height));
        }
        p
    }
}

/// GP0(02h): fill `width` x `height` at VRAM (`x`, `y`) with `color` (docs/hardware/gpu.md §8:
/// the GPU takes x & 3F0h, the width rounded up to 16, y and the height & 1FFh).
pub const fn fill(color: [u8; 3], x: u16, y: u16, width: u16, height: u16) -> [u32; 3] {
    [word(FILL, rgb(color)), pair(x, y), pair(width, height)]
}

/// GP0(80h): copy `width` x `height` from VRAM `source` to `destination` (docs/hardware/gpu.md §8).
pub const fn copy(
    source: (u16, u16),
    destination: (u16, u16),
    width: u16,
    height: u16,
) -> [u32; 4] {
    [
        word(VRAM_COPY, 0),
        pair(source.0, source.1),
        pair(destination.0, destination.1),
        pair(width, height),
    ]
}

/// GP0(A0h): the header of a CPU-to-VRAM transfer of `width` x `height` to (`x`, `y`); the
/// pixel data follows ([`pixel_words`]) (docs/hardware/gpu.md §8).
pub const fn cpu_to_vram(x: u16, y: u16, width: u16, height: u16) -> [u32; 3] {
    [word(CPU_TO_VRAM, 0), pair(x, y), pair(width, height)]
}

/// A CPU-to-VRAM transfer's data words: two pixels a word, the first in the low half; an
/// odd count leaves the last word's upper half 0 (docs/hardware/gpu.md §8).
pub fn pixel_words(pixels: &[u16]) -> impl Iterator<Item = u32> + '_ {
    pixels.chunks(2).map(|pair| {
        let lo = u32::from(pair.first().copied().unwrap_or(0));
        let hi = u32::from(pair.get(1).copied().unwrap_or(0));
        hi << 16 | lo
    })
}

/// GP0(C0h): a VRAM-to-CPU transfer of `width` x `height` from (`x`, `y`), read through
/// GPUREAD (docs/hardware/gpu.md §8).
pub const fn vram_to_cpu(x: u16, y: u16, width: u16, height: u16) -> [u32; 3] {
    [word(VRAM_TO_CPU, 0), pair(x, y), pair(width, height)]
}

/// GP0(01h): invalidate the CLUT cache.
pub const fn clear_cache() -> u32 {
    word(CLEAR_CACHE, 0)
}

/// GP0(1Fh): raise the GPU IRQ.
pub const fn irq() -> u32 {
    word(IRQ, 0)
}

/// GP0(E1h): the draw mode (docs/hardware/gpu.md §2).
pub const fn draw_mode(mode: DrawMode) -> u32 {
    word(DRAW_MODE, mode.bits())
}

/// GP0(E2h): the texture window.
pub const fn texture_window(window: TextureWindow) -> u32 {
    word(TEXTURE_WINDOW, window.bits())
}

/// GP0(E3h): the drawing area's top-left corner.
pub const fn area_top_left(x: u16, y: u16) -> u32 {
    word(AREA_TOP_LEFT, DrawingArea::corner_bits(x, y))
}

/// GP0(E4h): the drawing area's bottom-right corner (inclusive).
pub const fn area_bottom_right(x: u16, y: u16) -> u32 {
    word(AREA_BOTTOM_RIGHT, DrawingArea::corner_bits(x, y))
}

/// GP0(E5h): the drawing offset, signed 11-bit.
pub const fn drawing_offset(x: i16, y: i16) -> u32 {
    word(DRAWING_OFFSET, DrawState::offset_bits(x, y))
}

/// GP0(E6h): the mask bit settings.
pub const fn mask_bits(mask: MaskSettings) -> u32 {
    word(MASK_BITS, mask.bits())
}

/// The words of [`environment`]: one for each of E1h-E6h.
pub const ENVIRONMENT_WORDS: usize = 6;

/// The six words E1h-E6h that set the whole drawing environment `state`, in command order.
/// GP1(09h) decides whether the draw mode's texture disable applies.
pub const fn environment(state: &DrawState) -> [u32; ENVIRONMENT_WORDS] {
    let a = state.area;
    [
        draw_mode(state.mode),
        texture_window(state.window),
        area_top_left(a.left, a.top),
        area_bottom_right(a.right, a.bottom),
        drawing_offset(state.offset_x, state.offset_y),
        mask_bits(state.mask),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::{BlendMode, TextureDepth};
    use alloc::vec::Vec;

    /// Packets written out from the word layouts of docs/hardware/gpu.md §2 and §8.
    #[test]
    fn words_follow_the_fact_sheet() {
        let v = |x, y, c: u8, u, v| Vertex {
            x,
            y,
            color: [c, c + 1, c + 2],
            u,
            v,
        };
        let gt4 = Polygon {
            vertices: [
                v(1, 2, 0x10, 3, 4),
                v(-1, 5, 0x20, 6, 7),
                v(8, -9, 0x30, 10, 11),
                v(12, 13, 0x40, 14, 15),
            ],
            quad: true,
            gouraud: true,
            semi_transparent: true,
            texture: Some(PolygonTexture {
                clut: ClutAttr { x: 32, y: 500 },
                page: Texpage {
                    page_x: 640,
                    page_y: 256,
                    blend: BlendMode::Add,
                    depth: TextureDepth::Clut8,
                    ..Texpage::default()
                },
                raw: true,
            }),
        };
        // Command 3Fh; CLUT 32/16 | 500 << 6; page 10 | 1 << 4 | 1 << 5 | 1 << 7.
        assert_eq!(
            *gt4.packet(),
            [
                0x3F12_1110,
                0x0002_0001,
                0x7D02_0403,
                0x0022_2120,
                0x0005_07FF,
                0x00BA_0706,
                0x0032_3130,
                0x07F7_0008,
                0x0000_0B0A,
                0x0042_4140,
                0x000D_000C,
                0x0000_0F0E,
            ]
        );
        let red = |x, y| Vertex {
            x,
            y,
            color: [0xFF, 0, 0],
            ..Vertex::default()
        };
        let f3 = Polygon::triangle([red(0, 0), red(64, 0), red(0, 64)]);
        assert_eq!(*f3.packet(), [0x2000_00FF, 0, 64, 64 << 16]);
        let g2 = Line {
            vertices: [v(1, 2, 0x10, 0, 0), v(3, 4, 0x20, 0, 0)],
            gouraud: true,
            semi_transparent: false,
        };
        assert_eq!(
            *g2.packet(),
            [0x5012_1110, 0x0002_0001, 0x0022_2120, 0x0004_0003]
        );
        let poly = Polyline {
            first: [v(1, 2, 0x10, 0, 0), v(3, 4, 0x20, 0, 0)],
            more: &[v(5, 6, 0x30, 0, 0)],
            gouraud: false,
            semi_transparent: true,
        };
        assert_eq!(
            poly.words().collect::<Vec<_>>(),
            [
                0x4A12_1110,
                0x0002_0001,
                0x0004_0003,
                0x0006_0005,
                0x5555_5555
            ]
        );
        let sprite = Rectangle {
            x: 16,
            y: 32,
            color: [0x80, 0x80, 0x80],
            size: SpriteSize::Variable,
            width: 24,
            height: 8,
            semi_transparent: false,
            texture: Some(RectangleTexture {
                clut: ClutAttr { x: 0, y: 480 },
                u: 5,
                v: 6,
                raw: false,
            }),
        };
        assert_eq!(
            *sprite.packet(),
            [0x6480_8080, 0x0020_0010, 0x7800_0605, 0x0008_0018]
        );
        let tile = Rectangle {
            size: SpriteSize::Sixteen,
            texture: None,
            ..sprite
        };
        assert_eq!(*tile.packet(), [0x7880_8080, 0x0020_0010]);
        assert_eq!(
            fill([1, 2, 3], 16, 8, 32, 4),
            [0x0203_0201, 0x0008_0010, 0x0004_0020]
        );
        assert_eq!(
            copy((1, 2), (3, 4), 5, 6),
            [0x8000_0000, 0x0002_0001, 0x0004_0003, 0x0006_0005]
        );
        assert_eq!(
            cpu_to_vram(640, 0, 64, 256),
            [0xA000_0000, 640, 256 << 16 | 64]
        );
        assert_eq!(
            vram_to_cpu(1, 2, 3, 4),
            [0xC000_0000, 0x0002_0001, 0x0004_0003]
        );
        assert_eq!(
            pixel_words(&[1, 2, 3]).collect::<Vec<_>>(),
            [0x0002_0001, 3]
        );
        assert_eq!([clear_cache(), irq()], [0x0100_0000, 0x1F00_0000]);
    }

    /// E1h-E6h from the bit layouts of docs/hardware/gpu.md §2.
    #[test]
    fn environment_words_follow_the_fact_sheet() {
        let state = DrawState {
            mode: DrawMode {
                page_x: 320,
                page_y: 256,
                blend: BlendMode::Subtract,
                depth: TextureDepth::Direct15,
                dither: true,
                flip_y: true,
                ..DrawMode::default()
            },
            window: TextureWindow {
                mask_x: 1,
                mask_y: 2,
                offset_x: 3,
                offset_y: 4,
            },
            area: DrawingArea {
                left: 5,
                top: 6,
                right: 1023,
                bottom: 511,
            },
            offset_x: -1,
            offset_y: 240,
            mask: MaskSettings {
                set: false,
                check: true,
            },
        };
        // E1: page 5 | 1 << 4, blend 2 << 5, depth 2 << 7, dither 1 << 9, flip Y 1 << 13.
        assert_eq!(
            environment(&state),
            [
                0xE100_2355,
                0xE202_0C41,
                0xE300_1805,
                0xE407_FFFF,
                0xE507_87FF,
                0xE600_0002,
            ]
        );
    }

    /// What a packet built here decodes to is what went in.
    #[test]
    fn environment_round_trips() {
        let mut g = crate::Gpu::new();
        let state = DrawState {
            mode: DrawMode {
                page_x: 960,
                blend: BlendMode::AddQuarter,
                depth: TextureDepth::Clut8,
                draw_to_display: true,
                flip_x: true,
                ..DrawMode::default()
            },
            window: TextureWindow {
                mask_x: 31,
                mask_y: 0,
                offset_x: 17,
                offset_y: 31,
            },
            area: DrawingArea {
                left: 1,
                top: 1023,
                right: 2,
                bottom: 3,
            },
            offset_x: -1024,
            offset_y: 1023,
            mask: MaskSettings {
                set: true,
                check: false,
            },
        };
        g.gp0_words(&environment(&state));
        assert_eq!(g.draw_state(), &state);
    }
}
