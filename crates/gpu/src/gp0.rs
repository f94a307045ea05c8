//! GP0: packet assembly (words arrive one at a time, split anywhere), decoding of render
//! commands into primitives, environment commands E1h-E6h, and the transfer commands
//! (docs/hardware/gpu.md §2, §8).

use crate::drawing::{Cost, units_to_gpu};
use crate::primitive::{Line, Rectangle, Texture, Triangle, Vertex, dither_applies};
use crate::rasterizer::{
    DrawCount, Rows, draw_flat_line, draw_flat_triangle_rows, draw_gouraud_triangle_rows,
    draw_line_rows, draw_rectangle_rows, draw_tiled_quad, draw_triangle_rows,
};
use crate::state::{ClutAttr, DrawMode, DrawState, Texpage};
use crate::transfer::{self, ReadTransfer, TransferRect, WriteTransfer};
use crate::{Gpu, color};

/// `$self.$f::<GOURAUD, QUAD, UV>($args)` with the polygon command word `$cmd`'s bits 28,
/// 27 and 26 as the const arguments (docs/hardware/gpu.md §2).
macro_rules! by_polygon_shape {
    ($cmd:expr, $self:ident . $f:ident ($($arg:expr),*)) => {
        match ($cmd >> 26) & 7 {
            0 => $self.$f::<false, false, false>($($arg),*),
            1 => $self.$f::<false, false, true>($($arg),*),
            2 => $self.$f::<false, true, false>($($arg),*),
            3 => $self.$f::<false, true, true>($($arg),*),
            4 => $self.$f::<true, false, false>($($arg),*),
            5 => $self.$f::<true, false, true>($($arg),*),
            6 => $self.$f::<true, true, false>($($arg),*),
            _ => $self.$f::<true, true, true>($($arg),*),
        }
    };
}

/// The longest fixed-size packet: a Gouraud textured quad, 12 words.
pub(crate) const MAX_PACKET: usize = 12;

/// What incoming GP0 words mean right now.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Mode {
    /// Collecting a command packet.
    #[default]
    Command,
    /// Receiving CPU-to-VRAM pixel data.
    Write(WriteTransfer),
    /// Receiving polyline vertices until the terminator.
    Polyline(Polyline),
}

/// A polyline in progress (docs/hardware/gpu.md §2, §4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Polyline {
    pub(crate) line: Line,
    /// Gouraud: the colour word of the next vertex has been read.
    pending_color: Option<[u8; 3]>,
}

/// What one word after a polyline's first segment does (docs/hardware/gpu.md §2, §4).
pub(crate) enum PolylineStep {
    /// The terminator: the polyline ends.
    End,
    /// A Gouraud colour word: the vertex position follows.
    Color(Polyline),
    /// A vertex: the segment from the previous vertex is drawn.
    Segment(Polyline),
}

impl Polyline {
    /// Vertex coordinates are an 11-bit signed position plus an 11-bit signed drawing
    /// offset: -2048..=2046 (docs/hardware/gpu.md §2).
    #[cfg(feature = "serde")]
    fn check(&self) -> Result<(), &'static str> {
        let in_range = |c: i32| (-2048..=2046).contains(&c);
        if self
            .line
            .vertices
            .iter()
            .all(|v| in_range(v.x) && in_range(v.y))
        {
            Ok(())
        } else {
            Err("polyline vertex outside the 11-bit position plus offset range")
        }
    }

    /// A polyline continuing after its first segment.
    pub(crate) fn new(line: Line) -> Self {
        Self {
            line,
            pending_color: None,
        }
    }

    /// Consume the next word (docs/hardware/gpu.md §2: the terminator is tested where the next vertex's
    /// first word would be).
    pub(crate) fn step(mut self, draw: &DrawState, word: u32) -> PolylineStep {
        let expecting_first_word = !self.line.gouraud || self.pending_color.is_none();
        if expecting_first_word && is_terminator(word) {
            return PolylineStep::End;
        }
        if self.line.gouraud && self.pending_color.is_none() {
            self.pending_color = Some(color::unpack888(word));
            return PolylineStep::Color(self);
        }
        let last = self.line.vertices[1];
        let mut next = Gpu::vertex(draw, word, 0);
        next.color = self.pending_color.unwrap_or(last.color);
        self.line.vertices = [last, next];
        self.pending_color = None;
        PolylineStep::Segment(self)
    }
}

/// A polygon packet decoded against the drawing state it meets (docs/hardware/gpu.md §2, §3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct PolygonPacket {
    /// The first triangle (v0, v1, v2).
    pub(crate) first: Triangle,
    /// A quad's second triangle (v1, v2, v3).
    pub(crate) second: Option<Triangle>,
    /// The draw mode after the packet: a textured polygon's texpage attribute rewrites it.
    pub(crate) mode: DrawMode,
    /// The command carries texture coordinates (bit 26), even if texturing is disabled.
    pub(crate) has_uv: bool,
}

/// GP0 packet assembly state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Gp0State {
    buf: [u32; MAX_PACKET],
    len: usize,
    mode: Mode,
}

/// GP0 input that has started but not finished: what a stream that stops here leaves
/// behind (docs/hardware/gpu.md §2, §8).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PendingInput {
    /// A command packet with fewer words than its command needs.
    Packet {
        /// The packet's first (command) word.
        command: u32,
        /// Words received, the command word included.
        received: usize,
        /// Words the command needs.
        expected: usize,
    },
    /// A CPU-to-VRAM transfer (GP0 A0h) still waiting for data words.
    Transfer {
        /// Data words still expected (two pixels a word).
        remaining_words: u32,
    },
    /// A polyline (GP0 48h-5Fh with bit 27) not yet ended by its terminator word.
    Polyline,
}

impl Gp0State {
    /// No packet or transfer is in progress.
    pub(crate) fn idle(&self) -> bool {
        self.len == 0 && self.mode == Mode::Command
    }

    /// The packet buffer holds fewer words than its command needs (a complete packet is
    /// executed the moment its last word arrives), and a transfer or polyline in progress is
    /// one the GPU could have reached.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        if self.len > MAX_PACKET {
            return Err("GP0 packet buffer longer than 12 words");
        }
        match self.mode {
            Mode::Command => match self.buf.first() {
                Some(&cmd) if self.len > 0 && self.len >= packet_len(cmd) => {
                    Err("complete GP0 packet left unexecuted")
                }
                _ => Ok(()),
            },
            Mode::Write(t) if self.len == 0 => t.check(),
            Mode::Polyline(p) if self.len == 0 => p.check(),
            _ => Err("GP0 packet words during a transfer or polyline"),
        }
    }

    /// A polygon or line packet is being received: psx-spx ("GPU Status Register", "Ready
    /// Bits") has GPUSTAT.28 clear from its command word on.
    pub(crate) fn receiving_vertices(&self) -> bool {
        match self.mode {
            Mode::Polyline(_) => true,
            Mode::Command => self.len != 0 && matches!(self.buf[0] >> 24, 0x20..=0x5F),
            Mode::Write(_) => false,
        }
    }
}

/// Whether a command word occupies FIFO space: psx-spx ("GPU Other Commands") lists GP0(00h),
/// its mirrors 04h-1Eh, E0h, E7h-EFh, and E3h-E5h as taking none.
fn takes_fifo_space(cmd: u32) -> bool {
    !matches!(cmd >> 24, 0x00 | 0x04..=0x1E | 0xE0 | 0xE3..=0xE5 | 0xE7..=0xEF)
}

/// Words in the packet a command word starts (docs/hardware/gpu.md §2): a function of the
/// command byte alone, looked up.
#[inline(always)]
pub(crate) fn packet_len(cmd: u32) -> usize {
    usize::from(PACKET_LEN[(cmd >> 24) as usize])
}

/// The fact sheet's word counts of the polygon packets, F3, F4, G3, G4, FT3, FT4, GT3 and GT4
/// (docs/hardware/gpu.md §2), by command byte.
#[cfg(test)]
pub(crate) const POLYGON_WORDS: [(u32, usize); 8] = [
    (0x20, 4),
    (0x28, 5),
    (0x30, 6),
    (0x38, 8),
    (0x24, 7),
    (0x2C, 9),
    (0x34, 9),
    (0x3C, 12),
];

/// [`packet_len`] of each command byte.
static PACKET_LEN: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut op = 0;
    while op < 256 {
        t[op] = packet_len_of(op as u32);
        op += 1;
    }
    t
};

/// Words in the packet command byte `op` starts (docs/hardware/gpu.md §2).
const fn packet_len_of(op: u32) -> u8 {
    let cmd = op << 24;
    match op {
        0x02 => 3,
        0x20..=0x3F => {
            let verts = if cmd & (1 << 27) != 0 { 4 } else { 3 };
            let per_vertex = 1 + (cmd >> 26 & 1);
            let colors = if cmd & (1 << 28) != 0 { verts - 1 } else { 0 };
            (1 + verts * per_vertex + colors) as u8
        }
        0x40..=0x5F => {
            if cmd & (1 << 28) != 0 {
                4
            } else {
                3
            }
        }
        0x60..=0x7F => {
            let textured = cmd >> 26 & 1;
            let variable = ((cmd >> 27) & 3 == 0) as u32;
            (2 + textured + variable) as u8
        }
        0x80..=0x9F => 4,
        0xA0..=0xDF => 3,
        _ => 1,
    }
}

/// Sign-extend the 11-bit field (docs/hardware/gpu.md §2).
pub(crate) const fn sext11(v: u32) -> i32 {
    ((v << 21) as i32) >> 21
}

/// The polyline terminator, tested where the next vertex's first word would be (docs/hardware/gpu.md §2).
pub(crate) const fn is_terminator(word: u32) -> bool {
    word & 0xF000_F000 == 0x5000_5000
}

impl DrawMode {
    /// GP0(E1h) bits 0-13 (docs/hardware/gpu.md §2).
    pub fn from_e1(word: u32) -> Self {
        let mut m = DrawMode::default();
        m.set_texpage(word);
        m.dither = word & (1 << 9) != 0;
        m.draw_to_display = word & (1 << 10) != 0;
        m.flip_x = word & (1 << 12) != 0;
        m.flip_y = word & (1 << 13) != 0;
        m
    }

    /// The bits a polygon's texpage attribute rewrites: 0-8 and 11, never 9-10 (docs/hardware/gpu.md §2).
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

/// GP0(E1h)-(E6h): update the drawing environment (docs/hardware/gpu.md §2).
pub(crate) fn apply_environment(draw: &mut DrawState, cmd: u32, texture_disable_allowed: bool) {
    match cmd >> 24 {
        0xE1 => {
            let texture_disable = cmd & (1 << 11) != 0 && texture_disable_allowed;
            draw.mode = DrawMode::from_e1(cmd);
            draw.mode.texture_disable = texture_disable;
        }
        0xE2 => {
            let w = &mut draw.window;
            w.mask_x = (cmd & 0x1F) as u8;
            w.mask_y = (cmd >> 5 & 0x1F) as u8;
            w.offset_x = (cmd >> 10 & 0x1F) as u8;
            w.offset_y = (cmd >> 15 & 0x1F) as u8;
        }
        // X bits 0-9, Y bits 10-19 on the v2 GPU (docs/hardware/gpu.md §2; docs/gpu.md
        // "Modelled GPU version").
        0xE3 => {
            draw.area.left = (cmd & 0x3FF) as u16;
            draw.area.top = (cmd >> 10 & 0x3FF) as u16;
        }
        0xE4 => {
            draw.area.right = (cmd & 0x3FF) as u16;
            draw.area.bottom = (cmd >> 10 & 0x3FF) as u16;
        }
        0xE5 => {
            draw.offset_x = sext11(cmd & 0x7FF) as i16;
            draw.offset_y = sext11(cmd >> 11 & 0x7FF) as i16;
        }
        0xE6 => {
            draw.mask.set = cmd & 1 != 0;
            draw.mask.check = cmd & 2 != 0;
        }
        _ => {}
    }
}

/// Textures apply unless E1.11 disabled them after GP1(09h) allowed it (docs/hardware/gpu.md §2).
fn textures_enabled(mode: &DrawMode, texture_disable_allowed: bool) -> bool {
    !(mode.texture_disable && texture_disable_allowed)
}

/// The texture of a primitive: the page and depth of `mode`, the CLUT attribute given.
fn texture(mode: &DrawMode, clut_attr: u32, raw: bool) -> Texture {
    let clut = ClutAttr::from_bits(clut_attr);
    Texture {
        page_x: mode.page_x,
        page_y: mode.page_y,
        depth: mode.depth,
        clut_x: clut.x,
        clut_y: clut.y,
        raw,
    }
}

/// A quad's second triangle: vertices 1, 2 and 3 of the packet, drawn as the first is
/// (docs/hardware/gpu.md §3).
#[inline(always)]
fn second_triangle(first: &Triangle, fourth: Vertex) -> Triangle {
    Triangle {
        vertices: [first.vertices[1], first.vertices[2], fourth],
        ..*first
    }
}

/// Decode a polygon packet (docs/hardware/gpu.md §2, §3).
pub(crate) fn polygon_packet(
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
) -> PolygonPacket {
    let cmd = p[0];
    let gouraud = cmd & (1 << 28) != 0;
    let quad = cmd & (1 << 27) != 0;
    let has_uv = cmd & (1 << 26) != 0;
    let semi = cmd & (1 << 25) != 0;
    let raw = cmd & (1 << 24) != 0;
    let count = if quad { 4 } else { 3 };
    let mut mode = draw.mode;
    let mut verts = [Vertex::default(); 4];
    let mut clut_attr = 0;
    let mut i = 1;
    for (n, v) in verts.iter_mut().take(count).enumerate() {
        let rgb = if n > 0 && gouraud {
            i += 1;
            p.get(i - 1).copied().unwrap_or(0)
        } else {
            cmd
        };
        *v = Gpu::vertex(draw, p.get(i).copied().unwrap_or(0), rgb);
        i += 1;
        if has_uv {
            let uv = p.get(i).copied().unwrap_or(0);
            i += 1;
            v.u = uv as u8;
            v.v = (uv >> 8) as u8;
            match n {
                0 => clut_attr = uv >> 16,
                1 => mode.set_texpage(uv >> 16),
                _ => {}
            }
        }
    }
    if has_uv && !texture_disable_allowed {
        mode.texture_disable = false;
    }
    let textured = has_uv && textures_enabled(&mode, texture_disable_allowed);
    let first = Triangle {
        vertices: [verts[0], verts[1], verts[2]],
        gouraud,
        texture: textured.then(|| texture(&mode, clut_attr, raw)),
        blend: semi.then_some(mode.blend),
        dither: mode.dither && dither_applies(gouraud, textured, raw),
    };
    let second = quad.then(|| second_triangle(&first, verts[3]));
    PolygonPacket {
        first,
        second,
        mode,
        has_uv,
    }
}

/// Decode a line packet's first segment (docs/hardware/gpu.md §2, §4).
pub(crate) fn line_packet(p: &[u32; MAX_PACKET], draw: &DrawState) -> Line {
    let cmd = p[0];
    let gouraud = cmd & (1 << 28) != 0;
    let semi = cmd & (1 << 25) != 0;
    let v0 = Gpu::vertex(draw, p[1], cmd);
    let v1 = if gouraud {
        Gpu::vertex(draw, p[3], p[2])
    } else {
        Gpu::vertex(draw, p[2], cmd)
    };
    Line {
        vertices: [v0, v1],
        gouraud,
        blend: semi.then_some(draw.mode.blend),
        dither: draw.mode.dither,
    }
}

/// Decode a rectangle packet (docs/hardware/gpu.md §2, §5).
pub(crate) fn rectangle_packet(
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
) -> Rectangle {
    let cmd = p[0];
    let textured = cmd & (1 << 26) != 0 && textures_enabled(&draw.mode, texture_disable_allowed);
    let has_uv = cmd & (1 << 26) != 0;
    let semi = cmd & (1 << 25) != 0;
    let raw = cmd & (1 << 24) != 0;
    let mut origin = Gpu::vertex(draw, p[1], cmd);
    let mut i = 2;
    let mut clut_attr = 0;
    if has_uv {
        origin.u = p[2] as u8;
        origin.v = (p[2] >> 8) as u8;
        clut_attr = p[2] >> 16;
        i = 3;
    }
    let (width, height) = match (cmd >> 27) & 3 {
        0 => {
            let wh = p.get(i).copied().unwrap_or(0);
            ((wh & 0x3FF) as u16, (wh >> 16 & 0x1FF) as u16)
        }
        1 => (1, 1),
        2 => (8, 8),
        _ => (16, 16),
    };
    Rectangle {
        origin,
        width,
        height,
        texture: textured.then(|| texture(&draw.mode, clut_attr, raw)),
        blend: semi.then_some(draw.mode.blend),
        flip_x: draw.mode.flip_x,
        flip_y: draw.mode.flip_y,
    }
}

impl Gpu {
    /// One word written to the GP0 port.
    ///
    /// Packets may arrive one word at a time, as CPU writes to 1F801810h do:
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// for w in [0x0200_00FF, 0x0000_0000, 0x0001_0010] {
    ///     gpu.gp0(w); // GP0(02h): fill 16x1 at (0, 0) with red
    /// }
    /// assert_eq!(gpu.vram().pixel(15, 0), 0x001F);
    /// assert_eq!(gpu.vram().pixel(16, 0), 0);
    /// ```
    pub fn gp0(&mut self, word: u32) {
        let units = match self.gp0.mode {
            Mode::Write(mut t) => {
                self.drawing.receive(true);
                let more = t.push(&mut self.vram, word, self.draw.mask);
                self.gp0.mode = if more { Mode::Write(t) } else { Mode::Command };
                Some(Cost::WRITE_WORD)
            }
            Mode::Polyline(p) => {
                self.drawing.receive(true);
                self.polyline_word(p, word)
            }
            Mode::Command => {
                let len = self.gp0.len;
                let head = if len == 0 { word } else { self.gp0.buf[0] };
                self.drawing.receive(takes_fifo_space(head));
                if let Some(slot) = self.gp0.buf.get_mut(len) {
                    *slot = word;
                }
                self.gp0.len = len + 1;
                if self.gp0.len >= packet_len(self.gp0.buf[0]) {
                    let packet = self.gp0.buf;
                    self.gp0.len = 0;
                    Some(self.execute(&packet))
                } else {
                    None
                }
            }
        };
        if let Some(units) = units {
            self.drawing.complete(units_to_gpu(units as u64));
        }
    }

    /// Take a whole packet from the front of `words` when a new command starts there and
    /// all its words are present: the same effect as passing them to [`Gpu::gp0`] one by
    /// one (each word received, then the packet executed), without the per-word buffering.
    /// Returns the number of words taken: 0 when the packet is not complete in `words` or
    /// GP0 is in the middle of other input.
    #[inline]
    pub(crate) fn gp0_packet(&mut self, words: &[u32]) -> usize {
        let (Mode::Command, 0, Some(&head)) = (self.gp0.mode, self.gp0.len, words.first()) else {
            return 0;
        };
        let n = packet_len(head);
        if words.len() < n {
            return 0;
        }
        // The buffer as `gp0` leaves it: the packet's words, then what it held before. The
        // packet executes from `words` itself while a whole buffer's length of them is
        // there (a command reads only its own words).
        let units = if let Some(block) = words.first_chunk::<MAX_PACKET>() {
            if let (Some(buf), Some(packet)) = (self.gp0.buf.get_mut(..n), block.get(..n)) {
                buf.copy_from_slice(packet);
            }
            self.execute(block)
        } else {
            if let (Some(buf), Some(packet)) = (self.gp0.buf.get_mut(..n), words.get(..n)) {
                buf.copy_from_slice(packet);
            }
            let packet = self.gp0.buf;
            self.execute(&packet)
        };
        // Executing a packet leaves the drawing side as it was: the words are received and
        // complete a unit together.
        let cycles = units_to_gpu(units as u64);
        self.drawing
            .receive_unit(takes_fifo_space(head), n as u32, cycles);
        n
    }

    /// The GP0 input in progress, if any: a partial packet, an unfinished CPU-to-VRAM
    /// transfer or an unterminated polyline. `None` when the next word starts a new command.
    pub fn pending_input(&self) -> Option<PendingInput> {
        match self.gp0.mode {
            Mode::Write(t) => Some(PendingInput::Transfer {
                remaining_words: t.remaining_pixels().div_ceil(2),
            }),
            Mode::Polyline(_) => Some(PendingInput::Polyline),
            Mode::Command if self.gp0.len > 0 => {
                let command = self.gp0.buf[0];
                Some(PendingInput::Packet {
                    command,
                    received: self.gp0.len,
                    expected: packet_len(command),
                })
            }
            Mode::Command => None,
        }
    }

    /// Execute a complete packet; returns its cost in draw units.
    fn execute(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        let cmd = p[0];
        match cmd >> 24 {
            0x01 => self.clut.invalidate(),
            0x02 => {
                let rows = self.draw_rows();
                let (w, h) = transfer::fill(&mut self.vram, cmd, p[1], p[2], rows);
                return Cost::fill(w, h);
            }
            0x1F => {
                if !self.irq {
                    self.irq_event = true;
                }
                self.irq = true;
            }
            0x20 | 0x21 if !self.draw.mask.check => return self.flat_triangle(p),
            0x30 | 0x31 if !self.draw.mask.check => return self.gouraud_triangle(p),
            0x20..=0x3F => return self.polygon(p),
            0x40..=0x5F => return self.line(p),
            0x60..=0x7F => return self.rectangle(p),
            0x80..=0x9F => {
                let pixels = transfer::copy(&mut self.vram, p[1], p[2], p[3], self.draw.mask);
                return Cost::copy(pixels);
            }
            0xA0..=0xBF => {
                let rect = TransferRect::decode(p[1], p[2]);
                self.gp0.mode = Mode::Write(WriteTransfer::new(rect));
            }
            0xC0..=0xDF => self.read = ReadTransfer::new(TransferRect::decode(p[1], p[2])),
            0xE1..=0xE6 => apply_environment(&mut self.draw, cmd, self.texture_disable_allowed),
            _ => {}
        }
        0
    }

    /// The lines drawing may write: in 480i (GP1(08h) bits 2 and 5) with GP0(E1h) bit 10
    /// clear, not those of the field being displayed, whose VRAM lines have bit 0 equal to
    /// that of the display start line plus the field (docs/hardware/gpu.md §8; psx-spx
    /// "GP1(08h)", "GPU Status Register" bit 31).
    fn draw_rows(&self) -> Rows {
        if self.display.mode & 0x24 == 0x24 && !self.draw.mode.draw_to_display {
            Rows::SkipParity(self.displayed_line_parity() as u8)
        } else {
            Rows::All
        }
    }

    /// A vertex from a position word plus the drawing offset (docs/hardware/gpu.md §2).
    pub(crate) fn vertex(draw: &DrawState, pos: u32, rgb: u32) -> Vertex {
        Vertex {
            x: sext11(pos & 0x7FF) + draw.offset_x as i32,
            y: sext11(pos >> 16 & 0x7FF) + draw.offset_y as i32,
            color: color::unpack888(rgb),
            u: 0,
            v: 0,
        }
    }

    /// [`polygon_packet`] for the packet being executed: the texpage attribute's bits are
    /// written into the draw mode in place (docs/hardware/gpu.md §2), and the vertices are
    /// decoded from fixed word positions. Returns the first triangle and a quad's fourth
    /// vertex; [`second_triangle`] makes the quad's second triangle from them.
    /// `GOURAUD`, `QUAD` and `UV` are the command's bits 28, 27 and 26, so that each
    /// word's position is a constant.
    #[inline(always)]
    fn decode_polygon<const GOURAUD: bool, const QUAD: bool, const UV: bool>(
        &mut self,
        p: &[u32; MAX_PACKET],
    ) -> (Triangle, Option<Vertex>) {
        let cmd = p[0];
        let (gouraud, quad, has_uv) = (GOURAUD, QUAD, UV);
        let semi = cmd & (1 << 25) != 0;
        let raw = cmd & (1 << 24) != 0;
        // Vertex n > 0 starts with its colour word when Gouraud; position, then UV word.
        let per_vertex = 1 + usize::from(has_uv) + usize::from(gouraud);
        let at = |n: usize| -> (u32, u32, u32) {
            let start = if n == 0 {
                0
            } else {
                1 + usize::from(has_uv) + (n - 1) * per_vertex
            };
            let word = |i: usize| p.get(i).copied().unwrap_or(0);
            let rgb = if n > 0 && gouraud {
                word(start + 1)
            } else {
                cmd
            };
            let pos = start + 1 + usize::from(n > 0 && gouraud);
            (rgb, word(pos), if has_uv { word(pos + 1) } else { 0 })
        };
        let draw = &self.draw;
        let vertex = |(rgb, pos, uv): (u32, u32, u32)| {
            let mut v = Gpu::vertex(draw, pos, rgb);
            v.u = uv as u8;
            v.v = (uv >> 8) as u8;
            v
        };
        let (w0, w1, w2) = (at(0), at(1), at(2));
        let verts = [vertex(w0), vertex(w1), vertex(w2)];
        let fourth = quad.then(|| vertex(at(3)));
        if has_uv {
            self.draw.mode.set_texpage(w1.2 >> 16);
            if !self.texture_disable_allowed {
                self.draw.mode.texture_disable = false;
            }
        }
        let mode = &self.draw.mode;
        let textured = has_uv && textures_enabled(mode, self.texture_disable_allowed);
        let first = Triangle {
            vertices: verts,
            gouraud,
            texture: textured.then(|| texture(mode, w0.2 >> 16, raw)),
            blend: semi.then_some(mode.blend),
            dither: mode.dither && dither_applies(gouraud, textured, raw),
        };
        (first, fourth)
    }

    /// [`Gpu::decode_polygon`] for any polygon command: the packet's shape from its bits
    /// 26-28.
    #[cfg(test)]
    fn decode_any_polygon(&mut self, p: &[u32; MAX_PACKET]) -> (Triangle, Option<Vertex>) {
        by_polygon_shape!(p[0], self.decode_polygon(p))
    }

    /// Execute a polygon packet; returns its cost in draw units. The packet's shape
    /// (Gouraud, quad, textured: bits 28, 27, 26) chooses one copy of the routine.
    fn polygon(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        by_polygon_shape!(p[0], self.polygon_as(p))
    }

    /// [`Gpu::polygon`] for a packet of the shape the const parameters give.
    fn polygon_as<const GOURAUD: bool, const QUAD: bool, const UV: bool>(
        &mut self,
        p: &[u32; MAX_PACKET],
    ) -> u32 {
        let cmd = p[0];
        let gouraud = GOURAUD;
        let semi = cmd & (1 << 25) != 0;
        let (tri, fourth) = self.decode_polygon::<GOURAUD, QUAD, UV>(p);
        let textured = tri.texture.is_some();
        let clut_units = tri
            .texture
            .map_or(0, |t| Cost::clut_load(self.clut.load_size(&t)));
        let read_back = semi || self.draw.mask.check;
        let rows = self.draw_rows();
        let second = match fourth {
            None => None,
            Some(d) => {
                let second = second_triangle(&tri, d);
                if let Some(drawn) =
                    draw_tiled_quad(&mut self.vram, &self.draw, &tri, &second, rows)
                {
                    // Both triangles' set-up; the pixels, each drawn by one of them, once.
                    return Cost::triangle(false, false, false, false, drawn).saturating_add(
                        Cost::triangle(true, false, false, false, DrawCount::default()),
                    );
                }
                Some(second)
            }
        };
        let drawn = draw_triangle_rows(&mut self.vram, &self.draw, &mut self.clut, &tri, rows);
        let mut units =
            clut_units.saturating_add(Cost::triangle(false, gouraud, textured, read_back, drawn));
        if let Some(second) = &second {
            let drawn =
                draw_triangle_rows(&mut self.vram, &self.draw, &mut self.clut, second, rows);
            units = units.saturating_add(Cost::triangle(true, gouraud, textured, read_back, drawn));
        }
        units
    }

    /// GP0(20h), a flat untextured opaque triangle (21h: the raw bit, which only textured
    /// polygons read), without the E6h mask check: what [`Gpu::polygon`] does for it. The
    /// draw mode is unchanged (no texpage attribute), no CLUT is loaded, nothing is read back
    /// (docs/hardware/gpu.md §2, §3).
    fn flat_triangle(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        let [a, b, c] = [p[1], p[2], p[3]].map(|w| {
            let v = Gpu::vertex(&self.draw, w, 0);
            (v.x, v.y)
        });
        let rows = self.draw_rows();
        let rgb = color::unpack888(p[0]);
        let drawn = draw_flat_triangle_rows(&mut self.vram, &self.draw, [a, b, c], rgb, rows);
        Cost::triangle(false, false, false, false, drawn)
    }

    /// GP0(30h), a Gouraud-shaded untextured opaque triangle (31h: the raw bit, which only
    /// textured polygons read), without the E6h mask check: what [`Gpu::polygon`] does for
    /// it. Dithered under E1h bit 9; the draw mode is unchanged (no texpage attribute), no
    /// CLUT is loaded, nothing is read back (docs/hardware/gpu.md §2, §3, §6).
    fn gouraud_triangle(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        let tri = Triangle {
            vertices: [
                Gpu::vertex(&self.draw, p[1], p[0]),
                Gpu::vertex(&self.draw, p[3], p[2]),
                Gpu::vertex(&self.draw, p[5], p[4]),
            ],
            gouraud: true,
            texture: None,
            blend: None,
            dither: self.draw.mode.dither,
        };
        let rows = self.draw_rows();
        let drawn = draw_gouraud_triangle_rows(&mut self.vram, &self.draw, &tri, rows);
        Cost::triangle(false, true, false, false, drawn)
    }

    fn line(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        // One flat opaque segment (no Gouraud, semi-transparency or polyline bit),
        // undithered, without mask check, on every row: two positions and a colour, without
        // the decoded line, when it lies inside the drawing area (docs/hardware/gpu.md §2, §4).
        if p[0] & (1 << 28 | 1 << 27 | 1 << 25) == 0
            && !self.draw.mode.dither
            && !self.draw.mask.check
            && self.draw_rows() == Rows::All
        {
            let v = [p[1], p[2]].map(|w| {
                let v = Gpu::vertex(&self.draw, w, 0);
                (v.x, v.y)
            });
            let rgb = color::unpack888(p[0]);
            if let Some(drawn) = draw_flat_line(&mut self.vram, &self.draw, v, rgb) {
                return Cost::line(drawn);
            }
        }
        let line = line_packet(p, &self.draw);
        let rows = self.draw_rows();
        let drawn = draw_line_rows(&mut self.vram, &self.draw, &line, rows);
        if p[0] & (1 << 27) != 0 {
            self.gp0.mode = Mode::Polyline(Polyline::new(line));
        }
        Cost::line(drawn)
    }

    /// One polyline word; returns the cost of the unit it completes (a segment, or the
    /// terminator), in draw units.
    fn polyline_word(&mut self, p: Polyline, word: u32) -> Option<u32> {
        match p.step(&self.draw, word) {
            PolylineStep::End => {
                self.gp0.mode = Mode::Command;
                Some(0)
            }
            PolylineStep::Color(p) => {
                self.gp0.mode = Mode::Polyline(p);
                None
            }
            PolylineStep::Segment(p) => {
                let rows = self.draw_rows();
                let drawn = draw_line_rows(&mut self.vram, &self.draw, &p.line, rows);
                self.gp0.mode = Mode::Polyline(p);
                Some(Cost::line(drawn))
            }
        }
    }

    fn rectangle(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        let semi = p[0] & (1 << 25) != 0;
        let rect = rectangle_packet(p, &self.draw, self.texture_disable_allowed);
        let clut_units = rect
            .texture
            .map_or(0, |t| Cost::clut_load(self.clut.load_size(&t)));
        let rows = self.draw_rows();
        let drawn = draw_rectangle_rows(&mut self.vram, &self.draw, &mut self.clut, &rect, rows);
        clut_units.saturating_add(Cost::rectangle(semi || self.draw.mask.check, drawn))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// A polygon packet decoded in place (the draw mode rewritten by its texpage
        /// attribute) gives the triangles and draw mode [`polygon_packet`] gives, for every
        /// polygon command, random words and any draw mode, offset and GP1(09h) setting.
        #[test]
        fn in_place_decode_matches_polygon_packet(
            op in 0x20u32..0x40,
            words in proptest::array::uniform12(any::<u32>()),
            e1 in any::<u32>(),
            offset in any::<u32>(),
            allowed in any::<bool>(),
        ) {
            let mut g = Gpu::new();
            g.texture_disable_allowed = allowed;
            apply_environment(&mut g.draw, 0xE100_0000 | (e1 & 0xFF_FFFF), allowed);
            apply_environment(&mut g.draw, 0xE500_0000 | (offset & 0xFF_FFFF), allowed);
            let mut p = words;
            p[0] = op << 24 | (p[0] & 0xFF_FFFF);
            let expected = polygon_packet(&p, &g.draw, allowed);
            let (first, fourth) = g.decode_any_polygon(&p);
            prop_assert_eq!(first, expected.first);
            prop_assert_eq!(fourth.map(|d| second_triangle(&first, d)), expected.second);
            prop_assert_eq!(g.draw.mode, expected.mode);
        }
    }

    /// Packet lengths from the word layouts of docs/hardware/gpu.md §2: polygons F3=4, F4=5,
    /// G3=6, G4=8, FT3=7, FT4=9, GT3=9, GT4=12 whatever their semi-transparency and raw bits;
    /// lines F2=3, G2=4 (a polyline's first segment the same); rectangles the command and
    /// position words, plus the texture word when textured, plus the size word when variable;
    /// fill 3, VRAM copy 4, CPU transfers 3; every other command one word.
    #[test]
    fn packet_lengths_match_the_fact_sheet() {
        for low in 0..4u32 {
            for (op, len) in POLYGON_WORDS {
                assert_eq!(packet_len((op | low) << 24), len, "{:02X}h", op | low);
            }
            for (op, len) in [(0x40, 3), (0x48, 3), (0x50, 4), (0x58, 4)] {
                assert_eq!(packet_len((op | low) << 24), len, "{:02X}h", op | low);
            }
            let rectangles = [(0x60, 3), (0x64, 4), (0x68, 2), (0x6C, 3), (0x70, 2)];
            for (op, len) in rectangles
                .into_iter()
                .chain([(0x74, 3), (0x78, 2), (0x7C, 3)])
            {
                assert_eq!(packet_len((op | low) << 24), len, "{:02X}h", op | low);
            }
        }
        for op in 0..=0xFFu32 {
            let expected = match op {
                0x02 => 3,
                0x20..=0x7F => continue,
                0x80..=0x9F => 4,
                0xA0..=0xDF => 3,
                _ => 1,
            };
            // The low 24 bits are parameters and never change the length.
            assert_eq!(packet_len(op << 24 | 0xFF_FFFF), expected, "{op:02X}h");
        }
    }

    /// A flat quad's drawing cost is both triangles' set-up plus one unit per pixel drawn
    /// (docs/emulator.md, "Drawing time": 82 + 46 + pixels), whether its triangles tile a
    /// rectangle (drawn one span per line) or not.
    #[test]
    fn flat_quad_cost() {
        let quad = |g: &mut Gpu, v: [(u32, u32); 4]| {
            let mut p = [0u32; MAX_PACKET];
            p[0] = 0x2800_7F7F;
            for (k, (x, y)) in v.into_iter().enumerate() {
                p[k + 1] = x | y << 16;
            }
            g.polygon(&p)
        };
        let mut g = Gpu::new();
        g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
        // Tiling orders: 10 x 20 and 320 x 240.
        assert_eq!(
            quad(&mut g, [(0, 0), (10, 0), (0, 20), (10, 20)]),
            128 + 200
        );
        assert_eq!(
            quad(&mut g, [(10, 0), (10, 20), (0, 0), (0, 20)]),
            128 + 200
        );
        assert_eq!(
            quad(&mut g, [(5, 5), (325, 5), (5, 245), (325, 245)]),
            128 + 320 * 240
        );
        // Clipped by the drawing area (0..=99, 0..=49): 100 x 50 of 320 x 240 drawn.
        g.gp0_words(&[0xE300_0000, 0xE400_0000 | 99 | 49 << 10]);
        assert_eq!(
            quad(&mut g, [(0, 0), (320, 0), (0, 240), (320, 240)]),
            128 + 100 * 50
        );
    }
}
