//! Command decoding for debuggers and inspectors: what a GP0/GP1 command is, its fields,
//! the primitives it hands the rasterizer and what the rasterizer does with each (drawn,
//! or dropped and why), and the VRAM it may write.
//!
//! Decoding uses the command table ([`crate::command`]), field decoders and primitive
//! builders that GP0 itself runs (docs/hardware/gpu.md §2), and the drop tests are the
//! rasterizer's own (the rasterizer's `classify_triangle` and friends), so a decoded command
//! describes exactly what [`Gpu::gp0`] does with it. Decoding never changes the GPU.
//!
//! ```
//! use gpu::command;
//! use gpu::decode::Kind;
//! let mut gpu = gpu::Gpu::new();
//! gpu.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
//! let words = [0x2000_00FF, 0x0000_0000, 0x0000_0040, 0x0040_0000];
//! let decoded = gpu.decode_gp0(&words);
//! assert!(matches!(decoded.kind, Kind::Gp0(command::Kind::Polygon(_))));
//! assert_eq!(decoded.name, "F3 polygon");
//! assert!(decoded.primitives[0].coverage().dropped().is_none());
//! ```
#![deny(missing_docs)]

use alloc::vec::Vec;

use crate::command::{self, Command, LineOp, MAX_PACKET, PolygonOp, RectangleOp, Tail};
use crate::command_stream::{Port, StreamCommand};
use crate::gp0::{self, Polyline, PolylineStep, line_packet, polygon_packet, rectangle_packet};
use crate::gp1::Gp1;
/// The primitives a decoded command carries, as the rasterizer receives them.
pub use crate::primitive::{Line, Rectangle, Texture, Triangle, Vertex};
/// What a primitive covers, or why the hardware drops it.
pub use crate::rasterizer::{Coverage, DropReason, PixelBounds};
use crate::rasterizer::{classify_line, classify_rectangle, classify_triangle};
use crate::state::{BlendMode, DrawState, TextureDepth};
use crate::transfer::{FillRect, TransferRect};
use crate::{Gpu, VRAM_HEIGHT, VRAM_WIDTH};

/// What a traced command is (docs/hardware/gpu.md §2, §9).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// A GP0 command, as its row of the command table gives it.
    Gp0(command::Kind),
    /// A GP1 (display control) command (§9).
    Gp1,
    /// GP0 words that continue a packet begun before (the GPU was not at a packet start).
    Continuation,
}

/// The broad class of a command, for filtering.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Class {
    /// Polygons, lines and rectangles.
    Draw,
    /// Fills, copies and transfers between VRAM and the CPU.
    Transfer,
    /// The drawing environment, GP0(E1h)-(E6h).
    Environment,
    /// GP1 display control.
    Display,
    /// Everything else: no operation, CLUT cache, IRQ, continuations.
    Other,
}

impl Kind {
    /// The command's class.
    pub fn class(self) -> Class {
        use command::Kind as Gp0;
        match self {
            Kind::Gp0(Gp0::Polygon(_) | Gp0::Line(_) | Gp0::Rectangle(_)) => Class::Draw,
            Kind::Gp0(Gp0::Fill | Gp0::VramCopy | Gp0::CpuToVram | Gp0::VramToCpu) => {
                Class::Transfer
            }
            Kind::Gp0(
                Gp0::DrawMode
                | Gp0::TextureWindow
                | Gp0::AreaTopLeft
                | Gp0::AreaBottomRight
                | Gp0::DrawingOffset
                | Gp0::MaskBits,
            ) => Class::Environment,
            Kind::Gp1 => Class::Display,
            Kind::Gp0(Gp0::Nop | Gp0::ClearCache | Gp0::Irq) | Kind::Continuation => Class::Other,
        }
    }
}

/// One primitive a command hands the rasterizer, with the rasterizer's verdict.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// A triangle (a quad gives two, docs/hardware/gpu.md §3.1).
    Triangle(Triangle, Coverage),
    /// A line segment (a polyline gives one per vertex after the first, docs/hardware/gpu.md §4).
    Line(Line, Coverage),
    /// A rectangle (docs/hardware/gpu.md §5).
    Rectangle(Rectangle, Coverage),
}

impl Primitive {
    /// Drawn (with bounds) or dropped (with the reason).
    pub fn coverage(&self) -> Coverage {
        match self {
            Primitive::Triangle(_, c) | Primitive::Line(_, c) | Primitive::Rectangle(_, c) => *c,
        }
    }

    /// The outline in drawing coordinates (offset added, before the 11-bit wrap): three
    /// corners, two endpoints, or a rectangle's four corners (exclusive bottom-right).
    pub fn outline(&self) -> Vec<(i32, i32)> {
        match self {
            Primitive::Triangle(t, _) => t.vertices.iter().map(|v| (v.x, v.y)).collect(),
            Primitive::Line(l, _) => l.vertices.iter().map(|v| (v.x, v.y)).collect(),
            Primitive::Rectangle(r, _) => {
                let (x, y) = (r.origin.x, r.origin.y);
                let (w, h) = (i32::from(r.width), i32::from(r.height));
                alloc::vec![(x, y), (x + w, y), (x + w, y + h), (x, y + h)]
            }
        }
    }

    /// The texture the primitive samples, if textured.
    pub fn texture(&self) -> Option<Texture> {
        match self {
            Primitive::Triangle(t, _) => t.texture,
            Primitive::Line(..) => None,
            Primitive::Rectangle(r, _) => r.texture,
        }
    }

    /// The texture coordinates the primitive spans, as inclusive `(u_min, v_min, u_max,
    /// v_max)` before the texture window (docs/hardware/gpu.md §7): the vertices' range for a triangle;
    /// for a rectangle the `width` x `height` texels from its origin, the whole 0-255 range
    /// on an axis where they wrap at 256 (docs/hardware/gpu.md §5). `None` when untextured.
    pub fn uv_bounds(&self) -> Option<(u8, u8, u8, u8)> {
        self.texture()?;
        match self {
            Primitive::Triangle(t, _) => {
                let us = t.vertices.map(|v| v.u);
                let vs = t.vertices.map(|v| v.v);
                let (u0, u1) = (us.iter().min()?, us.iter().max()?);
                let (v0, v1) = (vs.iter().min()?, vs.iter().max()?);
                Some((*u0, *v0, *u1, *v1))
            }
            Primitive::Rectangle(r, _) => {
                let span = |start: u8, len: u16, flip: bool| -> (u8, u8) {
                    let len = u32::from(len).max(1);
                    if len >= 256 {
                        return (0, 255);
                    }
                    let s = u32::from(start);
                    let (lo, hi) = if flip {
                        (s as i64 - (len as i64 - 1), s as i64)
                    } else {
                        (s as i64, s as i64 + len as i64 - 1)
                    };
                    if lo < 0 || hi > 255 {
                        (0, 255)
                    } else {
                        (lo as u8, hi as u8)
                    }
                };
                let (u0, u1) = span(r.origin.u, r.width, r.flip_x);
                let (v0, v1) = span(r.origin.v, r.height, r.flip_y);
                Some((u0, v0, u1, v1))
            }
            Primitive::Line(..) => None,
        }
    }
}

/// A field of a decoded command: what it is and its value. Positions of primitives are
/// after the drawing offset; everything else is as the command's words and the drawing
/// state give it (docs/hardware/gpu.md §2, §8, §9).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Field {
    /// The colour of a polygon's or line's vertex (vertex 0's is the command word's).
    VertexColor {
        /// Vertex index in packet order.
        vertex: u8,
        /// 8-bit R, G, B.
        rgb: [u8; 3],
    },
    /// A polygon's or line's vertex.
    Vertex {
        /// Vertex index in packet order.
        vertex: u8,
        /// X after the drawing offset.
        x: i32,
        /// Y after the drawing offset.
        y: i32,
        /// Texture coordinate (U, V), when the command is textured.
        uv: Option<(u8, u8)>,
    },
    /// The colour of a fill or a rectangle.
    Color([u8; 3]),
    /// The top-left corner of a fill (in VRAM) or a rectangle (after the drawing offset).
    Position {
        /// Left edge.
        x: i32,
        /// Top line.
        y: i32,
        /// A textured rectangle's first texel (U, V).
        uv: Option<(u8, u8)>,
    },
    /// The width and height of a fill, a rectangle or a transfer.
    Size {
        /// Width in pixels.
        width: u32,
        /// Height in lines.
        height: u32,
    },
    /// The texture a primitive samples: page, depth, CLUT, raw (unmodulated).
    Texture(Texture),
    /// Textured by its command, but GP0(E1h) bit 11 disabled texturing.
    TextureDisabled,
    /// The semi-transparency mode of a semi-transparent primitive.
    Blend(BlendMode),
    /// What applies to a primitive's pixels.
    Flags(Flags),
    /// The segments of a polyline.
    Segments(usize),
    /// The source corner of a VRAM copy or a VRAM-to-CPU transfer.
    Source {
        /// Left edge.
        x: u16,
        /// Top line.
        y: u16,
    },
    /// The destination corner of a VRAM copy or a CPU-to-VRAM transfer.
    Destination {
        /// Left edge.
        x: u16,
        /// Top line.
        y: u16,
    },
    /// The data words of a CPU-to-VRAM transfer.
    DataWords(usize),
    /// GP0(E1h) bits 0-4 and 7-8: the texture page and depth.
    Texpage {
        /// Page left edge in halfwords.
        x: u16,
        /// Page top line.
        y: u16,
        /// Texture depth.
        depth: TextureDepth,
    },
    /// GP0(E1h) bit 9: dithering.
    Dither(bool),
    /// GP0(E1h) bit 10: drawing to the displayed area allowed.
    DrawToDisplay(bool),
    /// GP0(E1h) bit 11: texture disable (as GP1(09h) lets it apply).
    TextureDisable(bool),
    /// GP0(E1h) bit 12: rectangle X flip.
    FlipX(bool),
    /// GP0(E1h) bit 13: rectangle Y flip.
    FlipY(bool),
    /// GP0(E2h) mask, in units of 8 texels.
    WindowMask {
        /// Mask X.
        x: u8,
        /// Mask Y.
        y: u8,
    },
    /// GP0(E2h) offset, in units of 8 texels.
    WindowOffset {
        /// Offset X.
        x: u8,
        /// Offset Y.
        y: u8,
    },
    /// GP0(E3h): the drawing area's top-left corner.
    AreaTopLeft {
        /// Left edge.
        x: u16,
        /// Top line.
        y: u16,
    },
    /// GP0(E4h): the drawing area's bottom-right corner (inclusive).
    AreaBottomRight {
        /// Right edge.
        x: u16,
        /// Bottom line.
        y: u16,
    },
    /// GP0(E5h): the drawing offset.
    DrawingOffset {
        /// X offset.
        x: i16,
        /// Y offset.
        y: i16,
    },
    /// GP0(E6h) bit 0: bit 15 set on every pixel drawn.
    SetMask(bool),
    /// GP0(E6h) bit 1: pixels whose bit 15 is set are not drawn over.
    CheckMask(bool),
    /// The words of a continuation.
    Words(usize),
    /// A GP1 command that carries fields (03h-09h, 10h-1Fh), as [`Gp1`] reads them.
    Gp1(Gp1),
}

/// What applies to a primitive's pixels, from its command and the drawing state
/// (docs/hardware/gpu.md §2, §6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Flags {
    /// Colours interpolated.
    pub gouraud: bool,
    /// Texture sampled.
    pub textured: bool,
    /// Semi-transparent.
    pub semi_transparent: bool,
    /// Dithered.
    pub dithered: bool,
    /// A textured rectangle mirrored in U (GP0(E1h) bit 12).
    pub flip_x: bool,
    /// A textured rectangle mirrored in V (GP0(E1h) bit 13).
    pub flip_y: bool,
    /// GP0(E6h) bit 0.
    pub mask_set: bool,
    /// GP0(E6h) bit 1.
    pub mask_check: bool,
}

/// A command cut short: the stream ended (or a GP1 write came) before its last word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Truncation {
    /// Words the command has.
    pub have: usize,
    /// Words it needs; `None` for a polyline that never reached its terminator.
    pub need: Option<usize>,
}

/// A decoded command.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Decoded {
    /// The command's kind.
    pub kind: Kind,
    /// Short name, e.g. `GT4 polygon`, `F2 line`, `16x16 sprite`, `draw mode` (a GP0
    /// command's from the command table).
    pub name: &'static str,
    /// Fields, in packet order.
    pub fields: Vec<Field>,
    /// Primitives handed to the rasterizer, each with its verdict. Empty for a truncated
    /// polygon, line or rectangle packet (the GPU still waits for its last words).
    pub primitives: Vec<Primitive>,
    /// Every VRAM pixel the command may write lies in this rectangle (primitives,
    /// fills, copies, CPU-to-VRAM transfers); `None` when it writes nothing.
    pub writes: Option<PixelBounds>,
    /// The command lacks words.
    pub truncated: Option<Truncation>,
}

impl Decoded {
    fn new(kind: Kind, name: &'static str) -> Self {
        Self {
            kind,
            name,
            fields: Vec::new(),
            primitives: Vec::new(),
            writes: None,
            truncated: None,
        }
    }

    fn field(&mut self, field: Field) {
        self.fields.push(field);
    }

    /// Whether every primitive was dropped (false for commands without primitives).
    pub fn all_dropped(&self) -> bool {
        !self.primitives.is_empty()
            && self
                .primitives
                .iter()
                .all(|p| p.coverage().dropped().is_some())
    }
}

/// How many words a GP0 command starting at `words[0]` consumes (docs/hardware/gpu.md §2, §8): the
/// packet, plus what follows it ([`Tail`]): a CPU-to-VRAM transfer's data words, a
/// polyline's further vertices and terminator. `Err` carries the count needed (`None` for
/// an unterminated polyline) when `words` ends first.
pub fn command_len(words: &[u32]) -> Result<usize, Option<usize>> {
    let Some(&cmd) = words.first() else {
        return Err(Some(1));
    };
    let row = Command::of(cmd);
    let len = row.words;
    if words.len() < len {
        return Err(Some(len));
    }
    match row.tail {
        Tail::PixelData => {
            let total = len + pixel_data_words(words);
            if words.len() < total {
                Err(Some(total))
            } else {
                Ok(total)
            }
        }
        Tail::PolylineVertices => {
            let per_vertex = LineOp::from_op(row.op).words_per_vertex();
            let mut i = len;
            loop {
                let &w = words.get(i).ok_or(None)?;
                if command::is_terminator(w) {
                    return Ok(i + 1);
                }
                i += per_vertex;
            }
        }
        Tail::None => Ok(len),
    }
}

/// The data words of the CPU-to-VRAM transfer whose packet starts `words` (at least its
/// three words): two pixels a word (docs/hardware/gpu.md §8).
fn pixel_data_words(words: &[u32]) -> usize {
    let word = |i: usize| words.get(i).copied().unwrap_or(0);
    (TransferRect::decode(word(1), word(2)).pixels() as usize).div_ceil(2)
}

/// A VRAM rectangle that may wrap at the edges, as the bounds of all pixels it touches.
fn wrapped_bounds(x: usize, y: usize, w: usize, h: usize) -> Option<PixelBounds> {
    if w == 0 || h == 0 {
        return None;
    }
    let (left, right) = if x + w > VRAM_WIDTH {
        (0, VRAM_WIDTH - 1)
    } else {
        (x, x + w - 1)
    };
    let (top, bottom) = if y + h > VRAM_HEIGHT {
        (0, VRAM_HEIGHT - 1)
    } else {
        (y, y + h - 1)
    };
    Some(PixelBounds {
        left: left as u16,
        top: top as u16,
        right: right as u16,
        bottom: bottom as u16,
    })
}

fn union(a: Option<PixelBounds>, b: PixelBounds) -> PixelBounds {
    match a {
        None => b,
        Some(a) => PixelBounds {
            left: a.left.min(b.left),
            top: a.top.min(b.top),
            right: a.right.max(b.right),
            bottom: a.bottom.max(b.bottom),
        },
    }
}

impl Decoded {
    fn push_primitive(&mut self, p: Primitive) {
        if let Coverage::Drawn(b) = p.coverage() {
            self.writes = Some(union(self.writes, b));
        }
        self.primitives.push(p);
    }
}

fn size(width: impl Into<u32>, height: impl Into<u32>) -> Field {
    Field::Size {
        width: width.into(),
        height: height.into(),
    }
}

/// A vertex's texture coordinate.
fn uv(v: &Vertex) -> (u8, u8) {
    (v.u, v.v)
}

impl Gpu {
    /// The GPU is at a GP0 packet boundary: no packet, polyline or CPU-to-VRAM transfer is
    /// in progress, so the next GP0 word starts a command.
    pub fn gp0_idle(&self) -> bool {
        self.gp0.idle()
    }

    /// Decode a GP0 command starting at `words[0]` against the current drawing state,
    /// as [`Gpu::gp0`] would execute it now. `words` may hold the whole command (see
    /// [`command_len`]) or fewer words (the result is then marked truncated). Only
    /// meaningful when [`Gpu::gp0_idle`].
    pub fn decode_gp0(&self, words: &[u32]) -> Decoded {
        decode_gp0(words, &self.draw, self.texture_disable_allowed)
    }

    /// Decode a GP1 command (docs/hardware/gpu.md §9).
    pub fn decode_gp1(&self, word: u32) -> Decoded {
        decode_gp1(word)
    }
}

fn decode_gp0(words: &[u32], draw: &DrawState, texture_disable_allowed: bool) -> Decoded {
    use command::Kind as Gp0;
    let cmd = words.first().copied().unwrap_or(0);
    let row = Command::of(cmd);
    let len = row.words;
    let mut packet = [0u32; MAX_PACKET];
    for (slot, w) in packet.iter_mut().zip(words) {
        *slot = *w;
    }
    let complete = words.len() >= len;
    let mut d = Decoded::new(Kind::Gp0(row.kind), row.name);
    match row.kind {
        Gp0::Fill => {
            let r = FillRect::decode(packet[1], packet[2]);
            let (x, y, w, h) = (r.x as usize, r.y as usize, r.w as usize, r.h as usize);
            d.field(Field::Color(crate::color::unpack888(cmd)));
            d.field(Field::Position {
                x: r.x.into(),
                y: r.y.into(),
                uv: None,
            });
            d.field(size(r.w, r.h));
            if complete {
                d.writes = wrapped_bounds(x, y, w, h);
            }
        }
        Gp0::Polygon(op) => polygon(&mut d, op, &packet, draw, texture_disable_allowed, complete),
        Gp0::Line(op) => line(&mut d, op, words, &packet, draw, complete),
        Gp0::Rectangle(op) => {
            rectangle(&mut d, op, &packet, draw, texture_disable_allowed, complete)
        }
        Gp0::VramCopy => {
            let src = TransferRect::decode(packet[1], packet[3]);
            let dst = TransferRect::decode(packet[2], packet[3]);
            d.field(Field::Source { x: src.x, y: src.y });
            d.field(Field::Destination { x: dst.x, y: dst.y });
            d.field(size(dst.w, dst.h));
            if complete {
                d.writes = wrapped_bounds(dst.x.into(), dst.y.into(), dst.w.into(), dst.h.into());
            }
        }
        Gp0::CpuToVram => {
            let r = TransferRect::decode(packet[1], packet[2]);
            d.field(Field::Destination { x: r.x, y: r.y });
            d.field(size(r.w, r.h));
            let data = pixel_data_words(&packet);
            d.field(Field::DataWords(data));
            if complete {
                // Data words already received are written even if the rest never comes.
                let got = words.len().saturating_sub(len).min(data) * 2;
                let rows = got.div_ceil(r.w.into()).min(r.h.into());
                d.writes = wrapped_bounds(r.x.into(), r.y.into(), r.w.into(), rows);
                if words.len() < len + data {
                    d.truncated = Some(Truncation {
                        have: words.len(),
                        need: Some(len + data),
                    });
                }
            }
        }
        Gp0::VramToCpu => {
            let r = TransferRect::decode(packet[1], packet[2]);
            d.field(Field::Source { x: r.x, y: r.y });
            d.field(size(r.w, r.h));
        }
        Gp0::DrawMode
        | Gp0::TextureWindow
        | Gp0::AreaTopLeft
        | Gp0::AreaBottomRight
        | Gp0::DrawingOffset
        | Gp0::MaskBits => environment(&mut d, row.kind, cmd, draw, texture_disable_allowed),
        Gp0::Nop | Gp0::ClearCache | Gp0::Irq => {}
    }
    if !complete && d.truncated.is_none() {
        d.truncated = Some(Truncation {
            have: words.len(),
            need: Some(len),
        });
    }
    d
}

fn polygon(
    d: &mut Decoded,
    op: PolygonOp,
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
    complete: bool,
) {
    let packet = polygon_packet(op, p, draw, texture_disable_allowed);
    let gouraud = op.gouraud;
    let tri = &packet.first;
    let mut verts: Vec<Vertex> = tri.vertices.to_vec();
    if let Some(second) = &packet.second {
        verts.push(second.vertices[2]);
    }
    vertex_fields(d, &verts, gouraud, op.textured);
    if let Some(t) = tri.texture {
        d.field(Field::Texture(t));
    } else if op.textured {
        d.field(Field::TextureDisabled);
    }
    if let Some(b) = tri.blend {
        d.field(Field::Blend(b));
    }
    d.field(Field::Flags(Flags {
        gouraud,
        textured: tri.texture.is_some(),
        semi_transparent: tri.blend.is_some(),
        dithered: tri.dither,
        mask_set: draw.mask.set,
        mask_check: draw.mask.check,
        ..Flags::default()
    }));
    if complete {
        d.push_primitive(Primitive::Triangle(
            *tri,
            classify_triangle(tri, &draw.area),
        ));
        if let Some(second) = &packet.second {
            d.push_primitive(Primitive::Triangle(
                *second,
                classify_triangle(second, &draw.area),
            ));
        }
    }
}

/// Each vertex's colour (the first only, unless Gouraud), position and, when `textured`,
/// texel.
fn vertex_fields(d: &mut Decoded, verts: &[Vertex], gouraud: bool, textured: bool) {
    for (i, v) in (0u8..).zip(verts) {
        if i == 0 || gouraud {
            d.field(Field::VertexColor {
                vertex: i,
                rgb: v.color,
            });
        }
        d.field(Field::Vertex {
            vertex: i,
            x: v.x,
            y: v.y,
            uv: textured.then(|| uv(v)),
        });
    }
}

fn line(
    d: &mut Decoded,
    op: LineOp,
    words: &[u32],
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    complete: bool,
) {
    let gouraud = op.gouraud;
    let first = line_packet(op, p, draw);
    vertex_fields(d, &first.vertices, gouraud, false);
    if let Some(b) = first.blend {
        d.field(Field::Blend(b));
    }
    d.field(Field::Flags(Flags {
        gouraud,
        semi_transparent: first.blend.is_some(),
        dithered: first.dither,
        mask_set: draw.mask.set,
        mask_check: draw.mask.check,
        ..Flags::default()
    }));
    if !complete {
        return;
    }
    d.push_primitive(Primitive::Line(first, classify_line(&first, &draw.area)));
    if op.polyline {
        let mut state = Polyline::new(first);
        let mut terminated = false;
        for &w in words.iter().skip(op.words()) {
            match state.step(draw, w) {
                PolylineStep::End => {
                    terminated = true;
                    break;
                }
                PolylineStep::Color(s) => state = s,
                PolylineStep::Segment(s) => {
                    state = s;
                    d.push_primitive(Primitive::Line(s.line, classify_line(&s.line, &draw.area)));
                }
            }
        }
        d.field(Field::Segments(d.primitives.len()));
        if !terminated {
            d.truncated = Some(Truncation {
                have: words.len(),
                need: None,
            });
        }
    }
}

fn rectangle(
    d: &mut Decoded,
    op: RectangleOp,
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
    complete: bool,
) {
    let rect = rectangle_packet(op, p, draw, texture_disable_allowed);
    let textured = op.textured;
    d.field(Field::Color(rect.origin.color));
    d.field(Field::Position {
        x: rect.origin.x,
        y: rect.origin.y,
        uv: textured.then(|| uv(&rect.origin)),
    });
    d.field(size(rect.width, rect.height));
    if let Some(t) = rect.texture {
        d.field(Field::Texture(t));
    } else if textured {
        d.field(Field::TextureDisabled);
    }
    if let Some(b) = rect.blend {
        d.field(Field::Blend(b));
    }
    let sampled = rect.texture.is_some();
    d.field(Field::Flags(Flags {
        textured: sampled,
        semi_transparent: rect.blend.is_some(),
        flip_x: sampled && rect.flip_x,
        flip_y: sampled && rect.flip_y,
        mask_set: draw.mask.set,
        mask_check: draw.mask.check,
        ..Flags::default()
    }));
    if complete {
        d.push_primitive(Primitive::Rectangle(
            rect,
            classify_rectangle(&rect, &draw.area),
        ));
    }
}

fn environment(
    d: &mut Decoded,
    kind: command::Kind,
    cmd: u32,
    draw: &DrawState,
    texture_disable_allowed: bool,
) {
    use command::Kind as Gp0;
    let mut after = *draw;
    gp0::apply_environment(&mut after, cmd, texture_disable_allowed);
    match kind {
        Gp0::DrawMode => {
            let m = after.mode;
            d.field(Field::Texpage {
                x: m.page_x,
                y: m.page_y,
                depth: m.depth,
            });
            d.field(Field::Blend(m.blend));
            d.field(Field::Dither(m.dither));
            d.field(Field::DrawToDisplay(m.draw_to_display));
            d.field(Field::TextureDisable(m.texture_disable));
            d.field(Field::FlipX(m.flip_x));
            d.field(Field::FlipY(m.flip_y));
        }
        Gp0::TextureWindow => {
            let w = after.window;
            d.field(Field::WindowMask {
                x: w.mask_x,
                y: w.mask_y,
            });
            d.field(Field::WindowOffset {
                x: w.offset_x,
                y: w.offset_y,
            });
        }
        Gp0::AreaTopLeft => d.field(Field::AreaTopLeft {
            x: after.area.left,
            y: after.area.top,
        }),
        Gp0::AreaBottomRight => d.field(Field::AreaBottomRight {
            x: after.area.right,
            y: after.area.bottom,
        }),
        Gp0::DrawingOffset => d.field(Field::DrawingOffset {
            x: after.offset_x,
            y: after.offset_y,
        }),
        Gp0::MaskBits => {
            d.field(Field::SetMask(after.mask.set));
            d.field(Field::CheckMask(after.mask.check));
        }
        _ => {}
    }
}

fn decode_gp1(word: u32) -> Decoded {
    let command = Gp1::from_word(word);
    let name = match command {
        Gp1::Reset => "GP1 reset",
        Gp1::ResetCommandBuffer => "GP1 reset command buffer",
        Gp1::AcknowledgeIrq => "GP1 acknowledge IRQ",
        Gp1::DisplayEnabled(_) => "GP1 display enable",
        Gp1::DmaDirection(_) => "GP1 DMA direction",
        Gp1::DisplayStart { .. } => "GP1 display start",
        Gp1::HorizontalRange { .. } => "GP1 horizontal display range",
        Gp1::VerticalRange { .. } => "GP1 vertical display range",
        Gp1::DisplayMode(_) => "GP1 display mode",
        Gp1::AllowTextureDisable(_) => "GP1 allow texture disable",
        Gp1::GetInfo(_) => "GP1 get GPU info",
        Gp1::Unused(_) => "GP1 unused GP1",
    };
    let mut d = Decoded::new(Kind::Gp1, name);
    match command {
        Gp1::Reset | Gp1::ResetCommandBuffer | Gp1::AcknowledgeIrq | Gp1::Unused(_) => {}
        fields => d.field(Field::Gp1(fields)),
    }
    d
}

/// Whether `words` (non-empty, grown one word at a time) hold a whole command: the test
/// [`command_len`] makes, in constant time for the last word.
fn complete(words: &[u32]) -> bool {
    let (Some(&cmd), n) = (words.first(), words.len()) else {
        return false;
    };
    let row = Command::of(cmd);
    let len = row.words;
    if n < len {
        return false;
    }
    match row.tail {
        Tail::PixelData => n >= len + pixel_data_words(words),
        Tail::PolylineVertices => {
            let per_vertex = LineOp::from_op(row.op).words_per_vertex();
            n > len
                && (n - 1 - len).is_multiple_of(per_vertex)
                && words.last().is_some_and(|&w| command::is_terminator(w))
        }
        Tail::None => true,
    }
}

/// One command of a stream as the GPU receives it: its words (possibly spread over
/// several stream lines) and their decoding.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TracedCommand {
    /// Stream line of the first word (1-based).
    pub line: usize,
    /// Stream line of the last word.
    pub last_line: usize,
    /// Port written.
    pub port: Port,
    /// The words, in order.
    pub words: Vec<u32>,
    /// Their decoding against the state the GPU had before them.
    pub decoded: Decoded,
}

/// Splits a parsed command stream into GPU commands, one at a time, each decoded against
/// the GPU's state just before it. Run each command's words yourself (or with
/// [`Tracer::execute`]) before asking for the next, so decoding sees the state it needs.
#[derive(Clone, Debug)]
pub struct Tracer<'a> {
    commands: &'a [StreamCommand],
    line: usize,
    word: usize,
}

impl<'a> Tracer<'a> {
    /// Start at the first word of `commands`.
    pub fn new(commands: &'a [StreamCommand]) -> Self {
        Self {
            commands,
            line: 0,
            word: 0,
        }
    }

    /// Send a traced command's words to the GPU.
    pub fn execute(gpu: &mut Gpu, command: &TracedCommand) {
        match command.port {
            Port::Gp0 => gpu.gp0_words(&command.words),
            Port::Gp1 => {
                for &w in &command.words {
                    gpu.gp1(w);
                }
            }
        }
    }

    /// The next command, decoded against `gpu` as it is now; `None` at the end. A GP0
    /// command ends at its last word or where a GP1 line interrupts it (then it is marked
    /// truncated); words arriving while the GPU is mid-packet are a
    /// [`Kind::Continuation`].
    pub fn next_command(&mut self, gpu: &Gpu) -> Option<TracedCommand> {
        let first = self.commands.get(self.line)?;
        let start_line = first.line;
        if first.port == Port::Gp1 {
            let word = first.words.get(self.word).copied().unwrap_or(0);
            self.advance(1);
            return Some(TracedCommand {
                line: start_line,
                last_line: start_line,
                port: Port::Gp1,
                words: alloc::vec![word],
                decoded: gpu.decode_gp1(word),
            });
        }
        if !gpu.gp0_idle() {
            let words: Vec<u32> = first.words.get(self.word..).unwrap_or(&[]).to_vec();
            self.line += 1;
            self.word = 0;
            let mut decoded = Decoded::new(Kind::Continuation, "continuation");
            decoded.field(Field::Words(words.len()));
            return Some(TracedCommand {
                line: start_line,
                last_line: start_line,
                port: Port::Gp0,
                words,
                decoded,
            });
        }
        // Gather words across GP0 lines until the command is complete.
        let mut words = Vec::new();
        let mut last_line = start_line;
        while let Some(c) = self.commands.get(self.line) {
            if c.port != Port::Gp0 {
                break;
            }
            let rest = c.words.get(self.word..).unwrap_or(&[]);
            let mut taken = 0;
            let mut done = false;
            for &w in rest {
                words.push(w);
                taken += 1;
                if complete(&words) {
                    done = true;
                    break;
                }
            }
            last_line = c.line;
            self.advance(taken.max(1));
            if done {
                break;
            }
        }
        let decoded = gpu.decode_gp0(&words);
        Some(TracedCommand {
            line: start_line,
            last_line,
            port: Port::Gp0,
            words,
            decoded,
        })
    }

    fn advance(&mut self, taken: usize) {
        self.word += taken;
        let len = self.commands.get(self.line).map_or(0, |c| c.words.len());
        if self.word >= len {
            self.line += 1;
            self.word = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command_stream::parse;
    use crate::rasterizer::DropReason;

    fn gpu_with_area() -> Gpu {
        let mut gpu = Gpu::new();
        gpu.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
        gpu
    }

    #[test]
    fn command_lengths_follow_the_word_counts_of_section_2() {
        // F3=4, F4=5, G3=6, G4=8, FT3=7, FT4=9, GT3=9, GT4=12 (docs/hardware/gpu.md §2).
        for (op, n) in [
            (0x20, 4),
            (0x28, 5),
            (0x30, 6),
            (0x38, 8),
            (0x24, 7),
            (0x2C, 9),
            (0x34, 9),
            (0x3C, 12),
        ] {
            let words = [op << 24; 12];
            assert_eq!(command_len(&words), Ok(n), "op {op:02x}");
        }
        // A0h 3x1: 3 pixels -> 2 data words.
        assert_eq!(command_len(&[0xA000_0000, 0, 0x0001_0003, 0, 0]), Ok(5));
        assert_eq!(command_len(&[0xA000_0000, 0, 0x0001_0003, 0]), Err(Some(5)));
        // Flat polyline: two vertices, one more, terminator.
        let poly = [0x4800_0000, 0, 0x0001_0001, 0x0002_0002, 0x5555_5555];
        assert_eq!(command_len(&poly), Ok(5));
        assert_eq!(command_len(&poly[..4]), Err(None));
        // Gouraud polyline: the terminator is tested at the colour word's place only, so
        // a position word with the pattern does not end it.
        let g = [0x5800_0000, 0, 0, 1, 0x00FF_0000, 0x5000_5000, 0x5555_5555];
        assert_eq!(command_len(&g), Ok(7));
    }

    #[test]
    fn polygon_fields_are_after_the_drawing_offset() {
        let mut gpu = gpu_with_area();
        gpu.gp0(0xE500_0000 | 5 | (7 << 11));
        let d = gpu.decode_gp0(&[0x2000_00FF, 0x0002_0001, 0x0000_0040, 0x0040_0000]);
        assert_eq!(d.name, "F3 polygon");
        let v0 = d.fields.iter().find_map(|f| match *f {
            Field::Vertex {
                vertex: 0, x, y, ..
            } => Some((x, y)),
            _ => None,
        });
        assert_eq!(v0, Some((6, 9)));
        assert_eq!(
            d.fields[0],
            Field::VertexColor {
                vertex: 0,
                rgb: [0xFF, 0, 0]
            }
        );
        match d.primitives[0].coverage() {
            Coverage::Drawn(b) => assert_eq!((b.left, b.top, b.right, b.bottom), (5, 7, 69, 71)),
            c => panic!("{c:?}"),
        }
    }

    #[test]
    fn drop_reasons() {
        let gpu = gpu_with_area();
        // 1024 wide: size limit (docs/hardware/gpu.md §3.2).
        let d = gpu.decode_gp0(&[0x2000_0000, 0, 0x0000_0400, 0x0010_0000]);
        assert_eq!(
            d.primitives[0].coverage(),
            Coverage::Dropped(DropReason::SizeLimit)
        );
        // Collinear.
        let d = gpu.decode_gp0(&[0x2000_0000, 0, 0x0001_0001, 0x0002_0002]);
        assert_eq!(
            d.primitives[0].coverage(),
            Coverage::Dropped(DropReason::ZeroArea)
        );
        // Outside a 16x16 area.
        let mut small = Gpu::new();
        small.gp0_words(&[0xE300_0000, 0xE400_3C0F]);
        let d = small.decode_gp0(&[0x2000_0000, 0x0020_0020, 0x0020_0030, 0x0030_0020]);
        assert_eq!(
            d.primitives[0].coverage(),
            Coverage::Dropped(DropReason::Clipped)
        );
        // Zero-size sprite.
        let d = gpu.decode_gp0(&[0x6000_0000, 0, 0]);
        assert_eq!(
            d.primitives[0].coverage(),
            Coverage::Dropped(DropReason::ZeroArea)
        );
        // A line 1024 wide.
        let d = gpu.decode_gp0(&[0x4000_0000, 0, 0x0000_0400]);
        assert_eq!(
            d.primitives[0].coverage(),
            Coverage::Dropped(DropReason::SizeLimit)
        );
    }

    #[test]
    fn dropped_primitives_write_nothing_and_drawn_ones_stay_in_bounds() {
        // Every pixel a command changes lies in `writes`; a command whose primitives are
        // all dropped changes none.
        let cases: [&[u32]; 6] = [
            &[0x2000_FFFF, 0, 0x0000_0400, 0x0010_0000],
            &[0x2000_FFFF, 0x0005_0003, 0x0000_0040, 0x0040_0000],
            &[
                0x3800_FFFF,
                0x0010_0010,
                0xFF,
                0x0010_0050,
                0xFF00,
                0x0050_0010,
                0xFF,
                0x0050_0050,
            ],
            &[0x4000_FFFF, 0x0003_0002, 0x0020_0100],
            &[0x6000_FFFF, 0x0010_0008, 0x0005_0007],
            &[0x0200_FFFF, 0x0010_03F8, 0x0008_0020],
        ];
        for words in cases {
            let mut gpu = gpu_with_area();
            let d = gpu.decode_gp0(words);
            let before = gpu.vram().clone();
            gpu.gp0_words(words);
            let mut changed = 0;
            for y in 0..VRAM_HEIGHT {
                for x in 0..VRAM_WIDTH {
                    if before.pixel(x, y) != gpu.vram().pixel(x, y) {
                        changed += 1;
                        let b = d.writes.expect("writes");
                        assert!(
                            (b.left as usize..=b.right as usize).contains(&x)
                                && (b.top as usize..=b.bottom as usize).contains(&y),
                            "{words:x?}: ({x}, {y}) outside {b:?}"
                        );
                    }
                }
            }
            assert_eq!(
                changed == 0,
                d.writes.is_none() || d.all_dropped(),
                "{words:x?}"
            );
        }
    }

    #[test]
    fn tracer_groups_words_split_over_lines() {
        let text = "gp1 00000000\ngp0 e3000000\ngp0 e407ffff\ngp0 02ff0000\ngp0 00000000\n\
                    gp0 00100010\ngp0 48ffffff 0 00100010\ngp0 00200000 55555555 e5000000\n\
                    gp0 20000000 0";
        let cmds = parse(text).unwrap();
        let mut gpu = Gpu::new();
        let mut tracer = Tracer::new(&cmds);
        let mut got = Vec::new();
        while let Some(c) = tracer.next_command(&gpu) {
            Tracer::execute(&mut gpu, &c);
            got.push((
                c.line,
                c.last_line,
                c.decoded.name,
                c.words.len(),
                c.decoded.truncated,
            ));
        }
        assert_eq!(
            got,
            [
                (1, 1, "GP1 reset", 1, None),
                (2, 2, "drawing area top-left", 1, None),
                (3, 3, "drawing area bottom-right", 1, None),
                (4, 6, "fill", 3, None),
                (7, 8, "F polyline", 5, None),
                (8, 8, "drawing offset", 1, None),
                (
                    9,
                    9,
                    "F3 polygon",
                    2,
                    Some(Truncation {
                        have: 2,
                        need: Some(4)
                    })
                ),
            ]
        );
    }
}
