//! GP0: packet assembly (words arrive one at a time, split anywhere), decoding of render
//! commands into primitives, environment commands E1h-E6h, and the transfer commands
//! (docs/hardware/gpu.md §2, §8). What each command byte is and where its words sit comes
//! from the command table ([`crate::command`]).
//!
//! Why this shape: a packet whose words are all at hand executes from the caller's words
//! (`gp0_packet`), not from the command buffer it would be written to and read back from (a
//! store-forwarding stall: flat triangles 98 to 66 µs, lines 62 to 34 µs per 1,000); a
//! polygon is decoded by one copy per shape, each word at a fixed position (about 75
//! instructions a primitive); flat and Gouraud untextured triangles and flat lines go to
//! their rasterizer straight from the packet (docs/performance.md, "What each change bought").

use crate::command::{self, Command, Kind, LineOp, MAX_PACKET, PolygonOp, RectangleOp, SpriteSize};
use crate::drawing::{Cost, FIFO_WORDS};
use crate::primitive::{Line, Rectangle, Texture, Triangle, Vertex, dither_applies};
use crate::rasterizer::{
    DrawCount, draw_flat_line, draw_flat_triangle_rows, draw_gouraud_triangle_rows, draw_line_rows,
    draw_rectangle_rows, draw_tiled_quad, draw_triangle_rows,
};
use crate::rows::Rows;
use crate::state::{ClutAttr, DrawMode, DrawState, DrawingArea, MaskSettings, TextureWindow};
use crate::texture_cache::WriteRegion;
use crate::transfer::{self, FillRect, ReadTransfer, TransferRect, WriteTransfer};
use crate::{Gpu, color};

/// `$f::<GOURAUD, QUAD, UV>($args)` (`$f` a function or `self.method`) with the polygon
/// command `$op`'s Gouraud, quad and textured bits (28, 27, 26) as the const arguments
/// (docs/hardware/gpu.md §2).
macro_rules! by_polygon_shape {
    ($op:expr, $($f:ident).+ ($($arg:expr),*)) => {{
        let op: PolygonOp = $op;
        match (op.gouraud, op.quad, op.textured) {
            (false, false, false) => $($f).+::<false, false, false>($($arg),*),
            (false, false, true) => $($f).+::<false, false, true>($($arg),*),
            (false, true, false) => $($f).+::<false, true, false>($($arg),*),
            (false, true, true) => $($f).+::<false, true, true>($($arg),*),
            (true, false, false) => $($f).+::<true, false, false>($($arg),*),
            (true, false, true) => $($f).+::<true, false, true>($($arg),*),
            (true, true, false) => $($f).+::<true, true, false>($($arg),*),
            (true, true, true) => $($f).+::<true, true, true>($($arg),*),
        }
    }};
}

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
        if expecting_first_word && command::is_terminator(word) {
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
                Some(&cmd) if self.len > 0 && self.len >= Command::of(cmd).words => {
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
            Mode::Command => {
                self.len != 0
                    && matches!(
                        Command::of(self.buf[0]).kind,
                        Kind::Polygon(_) | Kind::Line(_)
                    )
            }
            Mode::Write(_) => false,
        }
    }
}

/// GP0(E1h)-(E6h): update the drawing environment (docs/hardware/gpu.md §2).
pub(crate) fn apply_environment(draw: &mut DrawState, cmd: u32, texture_disable_allowed: bool) {
    match Command::of(cmd).kind {
        Kind::DrawMode => {
            draw.mode = DrawMode::from_bits(cmd);
            draw.mode.texture_disable &= texture_disable_allowed;
        }
        Kind::TextureWindow => draw.window = TextureWindow::from_bits(cmd),
        Kind::AreaTopLeft => (draw.area.left, draw.area.top) = DrawingArea::corner_from_bits(cmd),
        Kind::AreaBottomRight => {
            (draw.area.right, draw.area.bottom) = DrawingArea::corner_from_bits(cmd);
        }
        Kind::DrawingOffset => (draw.offset_x, draw.offset_y) = DrawState::offset_from_bits(cmd),
        Kind::MaskBits => draw.mask = MaskSettings::from_bits(cmd),
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

/// Decode a polygon packet of command `op` and shape `GOURAUD`, `QUAD`, `UV` (`op`'s bits
/// 28, 27 and 26, so that each word's position is a constant) against `draw`, writing a textured
/// polygon's texpage attribute into `draw.mode` (docs/hardware/gpu.md §2, §3). Returns the
/// first triangle and a quad's fourth vertex; [`second_triangle`] makes the quad's second
/// triangle from them.
#[inline(always)]
fn decode_polygon<const GOURAUD: bool, const QUAD: bool, const UV: bool>(
    op: PolygonOp,
    p: &[u32; MAX_PACKET],
    draw: &mut DrawState,
    texture_disable_allowed: bool,
) -> (Triangle, Option<Vertex>) {
    let (semi_transparent, raw) = (op.semi_transparent, op.raw);
    let shape = PolygonOp {
        gouraud: GOURAUD,
        quad: QUAD,
        textured: UV,
        ..PolygonOp::default()
    };
    let word = |i: usize| p.get(i).copied().unwrap_or(0);
    // (colour, position, texture word) of vertex n.
    let at = |n: usize| -> (u32, u32, u32) {
        let uv = if UV { word(shape.uv_word(n)) } else { 0 };
        (word(shape.color_word(n)), word(shape.position_word(n)), uv)
    };
    let vertex = |draw: &DrawState, (rgb, pos, uv): (u32, u32, u32)| {
        let mut v = Gpu::vertex(draw, pos, rgb);
        v.u = uv as u8;
        v.v = (uv >> 8) as u8;
        v
    };
    let (w0, w1, w2) = (at(0), at(1), at(2));
    let verts = [vertex(draw, w0), vertex(draw, w1), vertex(draw, w2)];
    let fourth = QUAD.then(|| vertex(draw, at(3)));
    if UV {
        draw.mode.set_texpage(w1.2 >> 16);
        if !texture_disable_allowed {
            draw.mode.texture_disable = false;
        }
    }
    let mode = &draw.mode;
    let textured = UV && textures_enabled(mode, texture_disable_allowed);
    let first = Triangle {
        vertices: verts,
        gouraud: GOURAUD,
        texture: textured.then(|| texture(mode, w0.2 >> 16, raw)),
        blend: semi_transparent.then_some(mode.blend),
        dither: mode.dither && dither_applies(GOURAUD, textured, raw),
    };
    (first, fourth)
}

/// Decode a polygon packet against the drawing state it meets, which it leaves unchanged
/// (docs/hardware/gpu.md §2, §3).
pub(crate) fn polygon_packet(
    op: PolygonOp,
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
) -> PolygonPacket {
    let mut after = *draw;
    let (first, fourth) = by_polygon_shape!(
        op,
        decode_polygon(op, p, &mut after, texture_disable_allowed)
    );
    PolygonPacket {
        first,
        second: fourth.map(|d| second_triangle(&first, d)),
        mode: after.mode,
    }
}

/// Decode a line packet's first segment (docs/hardware/gpu.md §2, §4).
pub(crate) fn line_packet(op: LineOp, p: &[u32; MAX_PACKET], draw: &DrawState) -> Line {
    let word = |i: usize| p.get(i).copied().unwrap_or(0);
    let vertex = |n| Gpu::vertex(draw, word(op.position_word(n)), word(op.color_word(n)));
    Line {
        vertices: [vertex(0), vertex(1)],
        gouraud: op.gouraud,
        blend: op.semi_transparent.then_some(draw.mode.blend),
        dither: draw.mode.dither,
    }
}

/// Decode a rectangle packet (docs/hardware/gpu.md §2, §5).
pub(crate) fn rectangle_packet(
    op: RectangleOp,
    p: &[u32; MAX_PACKET],
    draw: &DrawState,
    texture_disable_allowed: bool,
) -> Rectangle {
    let word = |i: usize| p.get(i).copied().unwrap_or(0);
    let textured = op.textured && textures_enabled(&draw.mode, texture_disable_allowed);
    let mut origin = Gpu::vertex(draw, word(op.position_word()), p[0]);
    let mut clut_attr = 0;
    if op.textured {
        let uv = word(op.uv_word());
        origin.u = uv as u8;
        origin.v = (uv >> 8) as u8;
        clut_attr = uv >> 16;
    }
    let (width, height) = match op.size {
        SpriteSize::Variable => {
            let wh = word(op.size_word());
            ((wh & 0x3FF) as u16, (wh >> 16 & 0x1FF) as u16)
        }
        fixed => fixed.fixed().unwrap_or((0, 0)),
    };
    Rectangle {
        origin,
        width,
        height,
        texture: textured.then(|| texture(&draw.mode, clut_attr, op.raw)),
        blend: op.semi_transparent.then_some(draw.mode.blend),
        flip_x: draw.mode.flip_x,
        flip_y: draw.mode.flip_y,
    }
}

impl Gpu {
    /// One word written to the GP0 port by a CPU store; returns the CPU cycles the store
    /// waited.
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
    ///
    /// A store into a full FIFO waits until the GPU takes the next command and there is
    /// room (docs/emulator.md, "The FIFO and GPUSTAT bits 25-28"): the drawing side runs
    /// ahead through the wait and the CPU cycles it took are returned (0 when there was
    /// room). The CPU is stalled for them: add them to its time and pass them to
    /// [`Gpu::run`] as usual; they are not counted twice.
    pub fn gp0(&mut self, word: u32) -> u32 {
        let wait = self.wait_for_room(word);
        self.gp0_word(word);
        self.gpu_to_cpu_cycles(wait)
    }

    /// Whether `word`, arriving now, takes a place in the FIFO (psx-spx "GPU Other
    /// Commands": GP0(00h), 04h-1Eh, E0h, E3h-E5h and E7h-EFh take none).
    fn word_takes_space(&self, word: u32) -> bool {
        match self.gp0.mode {
            Mode::Write(_) | Mode::Polyline(_) => true,
            Mode::Command if self.gp0.len == 0 => Command::of(word).takes_fifo_space,
            Mode::Command => Command::of(self.gp0.buf[0]).takes_fifo_space,
        }
    }

    /// If `word` needs a FIFO place and the FIFO is full, run the drawing side until the GPU
    /// has taken enough to make room; returns the GPU cycles waited.
    pub(crate) fn wait_for_room(&mut self, word: u32) -> u32 {
        if self.drawing.fifo_words() < FIFO_WORDS || !self.word_takes_space(word) {
            return 0;
        }
        let wait = self.drawing.cycles_until_room();
        self.drawing.run_ahead(wait);
        wait
    }

    /// One GP0 word, whatever the FIFO holds.
    pub(crate) fn gp0_word(&mut self, word: u32) {
        // `fetch`: the unit is a VRAM-to-CPU transfer's fetch.
        let (fetch, units) = match self.gp0.mode {
            Mode::Write(mut t) => {
                self.drawing.receive(true);
                let more = t.push(&mut self.vram, word, self.draw.mask);
                self.gp0.mode = if more { Mode::Write(t) } else { Mode::Command };
                (false, Some(Cost::WRITE_WORD))
            }
            Mode::Polyline(p) => {
                self.drawing.receive(true);
                (false, self.polyline_word(p, word))
            }
            Mode::Command => {
                let len = self.gp0.len;
                let head = Command::of(if len == 0 { word } else { self.gp0.buf[0] });
                self.drawing.receive(head.takes_fifo_space);
                if let Some(slot) = self.gp0.buf.get_mut(len) {
                    *slot = word;
                }
                self.gp0.len = len + 1;
                let fetch = matches!(head.kind, Kind::VramToCpu);
                if self.gp0.len >= head.words {
                    let packet = self.gp0.buf;
                    self.gp0.len = 0;
                    (fetch, Some(self.execute(&packet)))
                } else {
                    (fetch, None)
                }
            }
        };
        if let Some(units) = units {
            let cycles = self.drawing.complete(units, self.timing.standard());
            self.read.unit_queued(fetch, cycles);
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
        let head = Command::of(head);
        let n = head.words;
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
        let cycles = self.drawing.receive_unit(
            head.takes_fifo_space,
            n as u32,
            units,
            self.timing.standard(),
        );
        self.read
            .unit_queued(matches!(head.kind, Kind::VramToCpu), cycles);
        n
    }

    /// GP0 input is cut short (GP1(01h), GP1(00h)). A quad is drawn as two triangles, the
    /// first as soon as its words are in and the GPU reaches it (docs/gpu.md, "A quad cut
    /// short"): when the words of a quad's first triangle have all arrived and nothing before
    /// them is still drawing or queued, that triangle is drawn now, its texpage attribute
    /// applied, and its time spent; the rest of the packet is dropped with the input.
    pub(crate) fn cut_gp0_input(&mut self) {
        let cmd = self.gp0.buf[0];
        let first_triangle = cmd & !(1 << 27);
        if let (Mode::Command, Kind::Polygon(op)) = (self.gp0.mode, Command::of(cmd).kind)
            && op.quad
            && self.gp0.len >= Command::of(first_triangle).words
            && self.drawing.idle()
        {
            let mut packet = self.gp0.buf;
            packet[0] = first_triangle;
            let units = self.polygon(PolygonOp { quad: false, ..op }, &packet);
            self.drawing.complete(units, self.timing.standard());
        }
        self.gp0 = Gp0State::default();
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
                    expected: Command::of(command).words,
                })
            }
            Mode::Command => None,
        }
    }

    /// Execute a complete packet; returns its cost in draw units.
    fn execute(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        let cmd = p[0];
        match Command::of(cmd).kind {
            Kind::ClearCache => {
                self.clut.invalidate();
                self.texture_cache.invalidate();
            }
            Kind::Fill => {
                let rect = FillRect::decode(p[1], p[2]);
                self.texture_cache
                    .prepare(self.vram.as_array(), None, WriteRegion::fill(&rect));
                let rows = self.draw_rows();
                let (w, h) = transfer::fill(&mut self.vram, cmd, rect, rows);
                return Cost::fill(w, h);
            }
            Kind::Irq => {
                if !self.irq {
                    self.irq_event = true;
                }
                self.irq = true;
            }
            // An untextured opaque triangle without the E6h mask check.
            Kind::Polygon(op) if !(op.quad || op.textured || op.semi_transparent) => {
                if self.draw.mask.check {
                    return self.polygon(op, p);
                }
                return if op.gouraud {
                    self.gouraud_triangle(p)
                } else {
                    self.flat_triangle(p)
                };
            }
            Kind::Polygon(op) => return self.polygon(op, p),
            Kind::Line(op) => return self.line(op, p),
            Kind::Rectangle(op) => return self.rectangle(op, p),
            Kind::VramCopy => {
                self.texture_cache.invalidate();
                let pixels = transfer::copy(&mut self.vram, p[1], p[2], p[3], self.draw.mask);
                return Cost::copy(pixels);
            }
            Kind::CpuToVram => {
                self.texture_cache.invalidate();
                let rect = TransferRect::decode(p[1], p[2]);
                self.gp0.mode = Mode::Write(WriteTransfer::new(rect));
            }
            Kind::VramToCpu => {
                self.texture_cache.invalidate();
                let rect = TransferRect::decode(p[1], p[2]);
                self.read = ReadTransfer::new(rect);
                return rect.pixels().div_ceil(2).saturating_mul(Cost::READ_WORD);
            }
            Kind::DrawMode
            | Kind::TextureWindow
            | Kind::AreaTopLeft
            | Kind::AreaBottomRight
            | Kind::DrawingOffset
            | Kind::MaskBits => {
                let old = self.draw.mode;
                apply_environment(&mut self.draw, cmd, self.texture_disable_allowed);
                self.texture_cache.texpage_change(&old, &self.draw.mode);
            }
            Kind::Nop => {}
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
        let (x, y) = command::position(pos);
        Vertex {
            x: x + draw.offset_x as i32,
            y: y + draw.offset_y as i32,
            color: color::unpack888(rgb),
            u: 0,
            v: 0,
        }
    }

    /// Execute a polygon packet; returns its cost in draw units. The packet's shape
    /// (Gouraud, quad, textured: bits 28, 27, 26) chooses one copy of [`Gpu::polygon_as`].
    fn polygon(&mut self, op: PolygonOp, p: &[u32; MAX_PACKET]) -> u32 {
        by_polygon_shape!(op, self.polygon_as(op, p))
    }

    /// [`Gpu::polygon`] for a packet of the shape the const parameters give.
    fn polygon_as<const GOURAUD: bool, const QUAD: bool, const UV: bool>(
        &mut self,
        op: PolygonOp,
        p: &[u32; MAX_PACKET],
    ) -> u32 {
        let semi = op.semi_transparent;
        let old = self.draw.mode;
        let (tri, fourth) = decode_polygon::<GOURAUD, QUAD, UV>(
            op,
            p,
            &mut self.draw,
            self.texture_disable_allowed,
        );
        if UV {
            self.texture_cache.texpage_change(&old, &self.draw.mode);
        }
        self.prepare_texture_cache(tri.texture.as_ref());
        let gouraud = GOURAUD;
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
        let cache = &mut self.texture_cache;
        let drawn = draw_triangle_rows(
            &mut self.vram,
            &self.draw,
            &mut self.clut,
            cache,
            &tri,
            (rows, self.host),
        );
        let mut units =
            clut_units.saturating_add(Cost::triangle(false, gouraud, textured, read_back, drawn));
        if let Some(second) = &second {
            let drawn = draw_triangle_rows(
                &mut self.vram,
                &self.draw,
                &mut self.clut,
                cache,
                second,
                (rows, self.host),
            );
            units = units.saturating_add(Cost::triangle(true, gouraud, textured, read_back, drawn));
        }
        units.saturating_add(Cost::texture_misses(self.texture_cache.take_misses()))
    }

    /// GP0(20h), a flat untextured opaque triangle (21h: the raw bit, which only textured
    /// polygons read), without the E6h mask check: what [`Gpu::polygon`] does for it. The
    /// draw mode is unchanged (no texpage attribute), no CLUT is loaded, nothing is read back
    /// (docs/hardware/gpu.md §2, §3).
    fn flat_triangle(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        self.prepare_texture_cache(None);
        const F3: PolygonOp = PolygonOp::from_op(0x20);
        let at = |n: usize| {
            let v = Gpu::vertex(&self.draw, p[F3.position_word(n)], 0);
            (v.x, v.y)
        };
        let [a, b, c] = [at(0), at(1), at(2)];
        let rows = self.draw_rows();
        let rgb = color::unpack888(p[F3.color_word(0)]);
        let drawn = draw_flat_triangle_rows(&mut self.vram, &self.draw, [a, b, c], rgb, rows);
        Cost::triangle(false, false, false, false, drawn)
    }

    /// GP0(30h), a Gouraud-shaded untextured opaque triangle (31h: the raw bit, which only
    /// textured polygons read), without the E6h mask check: what [`Gpu::polygon`] does for
    /// it. Dithered under E1h bit 9; the draw mode is unchanged (no texpage attribute), no
    /// CLUT is loaded, nothing is read back (docs/hardware/gpu.md §2, §3, §6).
    fn gouraud_triangle(&mut self, p: &[u32; MAX_PACKET]) -> u32 {
        self.prepare_texture_cache(None);
        const G3: PolygonOp = PolygonOp::from_op(0x30);
        let vertex = |n| Gpu::vertex(&self.draw, p[G3.position_word(n)], p[G3.color_word(n)]);
        let tri = Triangle {
            vertices: [vertex(0), vertex(1), vertex(2)],
            gouraud: true,
            texture: None,
            blend: None,
            dither: self.draw.mode.dither,
        };
        let rows = self.draw_rows();
        let drawn = draw_gouraud_triangle_rows(
            &mut self.vram,
            &self.draw,
            &mut self.texture_cache,
            &tri,
            rows,
        );
        Cost::triangle(false, true, false, false, drawn)
    }

    fn line(&mut self, op: LineOp, p: &[u32; MAX_PACKET]) -> u32 {
        self.prepare_texture_cache(None);
        // One flat opaque segment (no Gouraud, semi-transparency or polyline bit),
        // undithered, without mask check, on every row: two positions and a colour, without
        // the decoded line, when it lies inside the drawing area (docs/hardware/gpu.md §2, §4).
        let plain = !(op.gouraud || op.polyline || op.semi_transparent);
        if plain && !self.draw.mode.dither && !self.draw.mask.check && self.draw_rows() == Rows::All
        {
            const F2: LineOp = LineOp::from_op(0x40);
            let at = |n: usize| {
                let v = Gpu::vertex(&self.draw, p[F2.position_word(n)], 0);
                (v.x, v.y)
            };
            let v = [at(0), at(1)];
            let rgb = color::unpack888(p[F2.color_word(0)]);
            if let Some(drawn) = draw_flat_line(&mut self.vram, &self.draw, v, rgb) {
                return Cost::line(drawn);
            }
        }
        let line = line_packet(op, p, &self.draw);
        let rows = self.draw_rows();
        let cache = &mut self.texture_cache;
        let drawn = draw_line_rows(&mut self.vram, &self.draw, cache, &line, rows);
        if op.polyline {
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
                self.prepare_texture_cache(None);
                let rows = self.draw_rows();
                let cache = &mut self.texture_cache;
                let drawn = draw_line_rows(&mut self.vram, &self.draw, cache, &p.line, rows);
                self.gp0.mode = Mode::Polyline(p);
                Some(Cost::line(drawn))
            }
        }
    }

    fn rectangle(&mut self, op: RectangleOp, p: &[u32; MAX_PACKET]) -> u32 {
        let rect = rectangle_packet(op, p, &self.draw, self.texture_disable_allowed);
        self.prepare_texture_cache(rect.texture.as_ref());
        let clut_units = rect
            .texture
            .map_or(0, |t| Cost::clut_load(self.clut.load_size(&t)));
        let rows = self.draw_rows();
        let cache = &mut self.texture_cache;
        let drawn = draw_rectangle_rows(
            &mut self.vram,
            &self.draw,
            &mut self.clut,
            cache,
            &rect,
            rows,
        );
        clut_units
            .saturating_add(Cost::rectangle(
                op.semi_transparent || self.draw.mask.check,
                drawn,
            ))
            .saturating_add(Cost::texture_misses(self.texture_cache.take_misses()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The polygon word order of docs/hardware/gpu.md §2 read word by word: for each vertex in
    /// turn its colour word (Gouraud, not the first vertex), its position word and its
    /// texture word (textured); vertex 0's texture word carries the CLUT attribute, vertex
    /// 1's the texpage attribute, which rewrites the draw mode's bits 0-8 and 11.
    fn fact_sheet_polygon(p: &[u32; MAX_PACKET], draw: &DrawState, allowed: bool) -> PolygonPacket {
        let cmd = p[0];
        let gouraud = cmd & (1 << 28) != 0;
        let quad = cmd & (1 << 27) != 0;
        let has_uv = cmd & (1 << 26) != 0;
        let semi = cmd & (1 << 25) != 0;
        let raw = cmd & (1 << 24) != 0;
        let mut mode = draw.mode;
        let mut verts = [Vertex::default(); 4];
        let mut clut_attr = 0;
        let mut words = p[1..].iter().copied();
        for (n, v) in verts.iter_mut().take(if quad { 4 } else { 3 }).enumerate() {
            let rgb = if n > 0 && gouraud {
                words.next().unwrap_or(0)
            } else {
                cmd
            };
            *v = Gpu::vertex(draw, words.next().unwrap_or(0), rgb);
            if has_uv {
                let uv = words.next().unwrap_or(0);
                (v.u, v.v) = (uv as u8, (uv >> 8) as u8);
                match n {
                    0 => clut_attr = uv >> 16,
                    1 => mode.set_texpage(uv >> 16),
                    _ => {}
                }
            }
        }
        if has_uv && !allowed {
            mode.texture_disable = false;
        }
        let textured = has_uv && textures_enabled(&mode, allowed);
        let first = Triangle {
            vertices: [verts[0], verts[1], verts[2]],
            gouraud,
            texture: textured.then(|| texture(&mode, clut_attr, raw)),
            blend: semi.then_some(mode.blend),
            dither: mode.dither && dither_applies(gouraud, textured, raw),
        };
        let second = quad.then(|| Triangle {
            vertices: [verts[1], verts[2], verts[3]],
            ..first
        });
        PolygonPacket {
            first,
            second,
            mode,
        }
    }

    proptest! {
        /// Every polygon command decodes as the fact sheet's word order reads, for random
        /// words and any draw mode, offset and GP1(09h) setting.
        #[test]
        fn polygon_decode_follows_the_word_order(
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
            let expected = fact_sheet_polygon(&p, &g.draw, allowed);
            let decoded = polygon_packet(PolygonOp::from_op(op as u8), &p, &g.draw, allowed);
            prop_assert_eq!(decoded, expected);
        }
    }

    /// A flat quad's drawing cost is both triangles' set-up (41 + 23 CPU cycles), each
    /// triangle's rows and the pixels drawn (docs/emulator.md, "Drawing time": 615 and 136
    /// 256ths of a cycle), whether its triangles tile a rectangle (drawn one span per line)
    /// or not.
    #[test]
    fn flat_quad_cost() {
        let quad = |g: &mut Gpu, v: [(u32, u32); 4]| {
            let mut p = [0u32; MAX_PACKET];
            p[0] = 0x2800_7F7F;
            for (k, (x, y)) in v.into_iter().enumerate() {
                p[k + 1] = x | y << 16;
            }
            g.polygon(PolygonOp::from_op(0x28), &p)
        };
        let units = |rows: u32, pixels: u32| (41 + 23) * 256 + rows * 615 + pixels * 136;
        let mut g = Gpu::new();
        g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
        // Tiling orders: 10 x 20 and 320 x 240; each triangle spans every row.
        assert_eq!(
            quad(&mut g, [(0, 0), (10, 0), (0, 20), (10, 20)]),
            units(2 * 20, 200)
        );
        assert_eq!(
            quad(&mut g, [(10, 0), (10, 20), (0, 0), (0, 20)]),
            units(2 * 20, 200)
        );
        assert_eq!(
            quad(&mut g, [(5, 5), (325, 5), (5, 245), (325, 245)]),
            units(2 * 240, 320 * 240)
        );
        // Not a tiling (a kite, drawn on its own): the first triangle spans rows 0-9, the
        // second rows 10-19.
        let mut k = Gpu::new();
        k.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
        let kite = quad(&mut k, [(10, 0), (0, 10), (20, 10), (10, 20)]);
        let drawn = k.vram().as_slice().iter().filter(|&&p| p != 0).count() as u32;
        assert_eq!(kite, units(10 + 10, drawn));
        // Clipped by the drawing area (0..=99, 0..=49): 100 x 50 of 320 x 240 drawn, 50 rows
        // each.
        g.gp0_words(&[0xE300_0000, 0xE400_0000 | 99 | 49 << 10]);
        assert_eq!(
            quad(&mut g, [(0, 0), (320, 0), (0, 240), (320, 240)]),
            units(2 * 50, 100 * 50)
        );
    }
}
