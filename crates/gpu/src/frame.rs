//! The displayed picture: the VRAM rectangle the GP1 display registers select, decoded to
//! 8-bit RGB (psx-spx "GP1(05h)".."GP1(08h)", "GPU Video Memory (VRAM)" Framebuffer), as a
//! whole frame or line by line as the beam scans it out (docs/hardware/timing.md §6, §7).

use crate::display::DisplayArea;
use crate::{Events, Gpu, VRAM_WIDTH, Vram};

/// Byte layout of a decoded frame.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PixelFormat {
    /// R, G, B: 3 bytes per pixel.
    #[default]
    Rgb888,
    /// R, G, B, A with A = 255: 4 bytes per pixel.
    Rgba8888,
}

impl PixelFormat {
    /// Bytes per pixel.
    pub const fn bytes_per_pixel(self) -> usize {
        match self {
            PixelFormat::Rgb888 => 3,
            PixelFormat::Rgba8888 => 4,
        }
    }
}

/// How a 5-bit channel of a 15-bit pixel becomes 8 bits.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ChannelExpand {
    /// `c << 3 | c >> 2`: 0 maps to 0 and 31 to 255.
    #[default]
    Replicate,
    /// `c << 3`: 31 maps to 248, as console capture tools write it.
    Shift,
}

impl ChannelExpand {
    /// One 5-bit channel (the low 5 bits of `c`) to 8 bits.
    pub const fn channel(self, c: u16) -> u8 {
        let c = (c & 31) as u8;
        match self {
            ChannelExpand::Replicate => (c << 3) | (c >> 2),
            ChannelExpand::Shift => c << 3,
        }
    }

    /// A 1555 pixel to R, G, B.
    pub const fn pixel(self, p: u16) -> [u8; 3] {
        [self.channel(p), self.channel(p >> 5), self.channel(p >> 10)]
    }
}

/// Width and height of a decoded frame, in pixels.
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FrameSize {
    /// Pixels per line.
    pub width: u32,
    /// Lines.
    pub height: u32,
}

impl FrameSize {
    /// Bytes a frame of this size takes in `format`.
    pub const fn bytes(&self, format: PixelFormat) -> usize {
        self.width as usize * self.height as usize * format.bytes_per_pixel()
    }
}

/// Why a frame could not be decoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// The output buffer is shorter than the frame.
    BufferTooSmall {
        /// Bytes the frame needs.
        needed: usize,
        /// Bytes given.
        got: usize,
    },
}

impl core::fmt::Display for FrameError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FrameError::BufferTooSmall { needed, got } => {
                write!(f, "frame needs {needed} bytes, buffer has {got}")
            }
        }
    }
}

impl core::error::Error for FrameError {}

fn halfword(vram: &[u16], x: usize, y: usize) -> u16 {
    vram.get((y & 511) * VRAM_WIDTH + (x & 1023))
        .copied()
        .unwrap_or(0)
}

impl DisplayArea {
    /// The size [`DisplayArea::decode`] produces.
    pub const fn frame_size(&self) -> FrameSize {
        FrameSize {
            width: self.width as u32,
            height: self.height as u32,
        }
    }

    /// Decode the area of `vram` (1024x512 halfwords, row-major; a shorter slice reads 0
    /// past its end) into `out`, row-major from the top-left pixel. Coordinates wrap at the
    /// VRAM edges. 15-bit: one halfword per pixel, channels widened by `expand`. 24-bit:
    /// three bytes R, G, B per pixel packed in consecutive halfwords of the line, low byte
    /// first (psx-spx "Framebuffer"). The rows are consecutive VRAM lines, so a 480i area
    /// shows both fields woven. Only the first `frame_size().bytes(format)` bytes of `out`
    /// are written.
    pub fn decode(
        &self,
        vram: &[u16],
        out: &mut [u8],
        format: PixelFormat,
        expand: ChannelExpand,
    ) -> Result<FrameSize, FrameError> {
        let size = self.frame_size();
        let needed = size.bytes(format);
        let got = out.len();
        let Some(out) = out.get_mut(..needed) else {
            return Err(FrameError::BufferTooSmall { needed, got });
        };
        let width = self.width as usize;
        if width == 0 {
            return Ok(size);
        }
        let bpp = format.bytes_per_pixel();
        for (row, line) in out.chunks_exact_mut(width * bpp).enumerate() {
            self.decode_row(vram, self.y as usize + row, line, bpp, expand);
        }
        Ok(size)
    }

    /// Decode the area's `width` pixels of VRAM line `y` (wrapped) into `line`, `bpp` bytes
    /// a pixel (the alpha byte of RGBA is 255).
    fn decode_row(&self, vram: &[u16], y: usize, line: &mut [u8], bpp: usize, e: ChannelExpand) {
        let x0 = self.x as usize;
        // 15-bit pixels of a line that does not wrap at the VRAM's right edge: one slice.
        let start = (y & 511) * VRAM_WIDTH + x0;
        let width = line.len() / bpp;
        let src = vram
            .get(start..start + width)
            .filter(|_| x0 + width <= VRAM_WIDTH);
        if let (false, Some(src)) = (self.color_24bit, src) {
            match bpp {
                3 => put::<3>(line, src, e),
                _ => put::<4>(line, src, e),
            }
            return;
        }
        for (col, px) in line.chunks_exact_mut(bpp).enumerate() {
            let rgb = if self.color_24bit {
                let byte = |k: usize| {
                    let h = halfword(vram, x0 + k / 2, y);
                    if k.is_multiple_of(2) {
                        h as u8
                    } else {
                        (h >> 8) as u8
                    }
                };
                [byte(3 * col), byte(3 * col + 1), byte(3 * col + 2)]
            } else {
                e.pixel(halfword(vram, x0 + col, y))
            };
            px[..3].copy_from_slice(&rgb);
            if let Some(a) = px.get_mut(3) {
                *a = 255;
            }
        }
    }
}

/// 15-bit pixels `src` into `line` as `N`-byte RGB (3) or RGBA (4, alpha 255) pixels.
fn put<const N: usize>(line: &mut [u8], src: &[u16], e: ChannelExpand) {
    for (px, &p) in line.chunks_exact_mut(N).zip(src) {
        let [r, g, b] = e.pixel(p);
        let mut out = [255u8; N];
        out[0] = r;
        out[1] = g;
        out[2] = b;
        px.copy_from_slice(&out);
    }
}

/// Fill `out` with black pixels of `format` (alpha 255).
fn black(out: &mut [u8], format: PixelFormat) {
    for px in out.chunks_exact_mut(format.bytes_per_pixel()) {
        px.fill(0);
        if let Some(a) = px.get_mut(3) {
            *a = 255;
        }
    }
}

/// One displayed line as the beam scans it out: which scanline and field it is, where it goes
/// in the picture, the VRAM line it shows and the display settings of that moment
/// ([`Gpu::run_lines`], [`Gpu::beam_line`]). [`DisplayLine::decode`] reads its pixels from
/// VRAM as it is while the line is alive, so a GP1(05h)-(08h) change or a VRAM write between
/// two lines shows from the next line on.
#[derive(Clone, Copy, Debug)]
pub struct DisplayLine<'a> {
    /// The interlace field, 0 or 1 (0 without interlace).
    pub field: u8,
    /// The scanline of the field, counted from the vertical sync ([`crate::Beam::line`]).
    pub scanline: u32,
    /// The line's row in its field's picture: scanlines since GP1(07h) Y1.
    pub field_row: u32,
    /// The line's row in the whole frame: `field_row`, or in 480i (GP1(08h) bits 2 and 5)
    /// `2 * field_row + field`, the rows of the two fields woven as [`Gpu::display_frame`]
    /// shows them.
    pub row: u32,
    /// The VRAM line shown: the GP1(05h) start line plus `row`, wrapped at 512.
    pub vram_y: u16,
    /// The display area of that moment: GP1(05h) start X, width in pixels, colour depth;
    /// `height` is the frame's ([`DisplayArea::height`]).
    pub area: DisplayArea,
    /// GP1(03h) disables the display: the line is black.
    pub blanked: bool,
    vram: &'a Vram,
}

impl DisplayLine<'_> {
    /// Bytes the line takes in `format`: `area.width` pixels.
    pub const fn bytes(&self, format: PixelFormat) -> usize {
        self.area.width as usize * format.bytes_per_pixel()
    }

    /// The line's pixels as [`DisplayArea::decode`] decodes a frame's row (15- or 24-bit,
    /// 15-bit channels widened as [`ChannelExpand::Replicate`]); black when `blanked`. Writes
    /// the first [`DisplayLine::bytes`] bytes of `out` and returns the pixel count; errors,
    /// writing nothing, when `out` is shorter.
    ///
    /// ```
    /// use gpu::PixelFormat;
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp1(0x0300_0000); // display on, 256 wide, lines 16..256 (GP1(00h) ranges)
    /// gpu.vram_mut().set_pixel(0, 0, 0x001F); // red at the start of VRAM line 0
    /// let mut rows = vec![];
    /// gpu.run_lines(600_000, |line| {
    ///     let mut rgb = vec![0u8; line.bytes(PixelFormat::Rgb888)];
    ///     line.decode(&mut rgb, PixelFormat::Rgb888).unwrap();
    ///     rows.push((line.row, line.vram_y, rgb));
    /// });
    /// assert_eq!(rows.len(), 240); // one frame's lines, each as the beam left it
    /// assert_eq!((rows[0].0, rows[0].1), (0, 0));
    /// assert_eq!(&rows[0].2[..6], &[255, 0, 0, 0, 0, 0]);
    /// ```
    pub fn decode(&self, out: &mut [u8], format: PixelFormat) -> Result<u32, FrameError> {
        let needed = self.bytes(format);
        let got = out.len();
        let Some(out) = out.get_mut(..needed) else {
            return Err(FrameError::BufferTooSmall { needed, got });
        };
        if self.blanked {
            black(out, format);
        } else {
            let (bpp, y) = (format.bytes_per_pixel(), self.vram_y as usize);
            let expand = ChannelExpand::Replicate;
            self.area
                .decode_row(self.vram.as_slice(), y, out, bpp, expand);
        }
        Ok(self.area.width as u32)
    }
}

impl Gpu {
    /// The size of the frame [`Gpu::display_frame`] writes: the display area of GP1(05h)-(08h).
    pub fn frame_size(&self) -> FrameSize {
        self.display_area().frame_size()
    }

    /// The displayed frame as 8-bit pixels in `format` (15-bit channels widened as
    /// [`ChannelExpand::Replicate`]); black while GP1(03h) disables the display (psx-spx
    /// "GP1(03h)"). A whole-frame snapshot of VRAM as it is now, 480i fields woven; a picture
    /// that changes while the beam scans it comes line by line from [`Gpu::run_lines`].
    /// Errors, writing nothing, when `out` is shorter than `frame_size().bytes(format)`.
    pub fn display_frame(
        &self,
        out: &mut [u8],
        format: PixelFormat,
    ) -> Result<FrameSize, FrameError> {
        let area = self.display_area();
        if self.display.disabled {
            let size = area.frame_size();
            let needed = size.bytes(format);
            let got = out.len();
            let Some(out) = out.get_mut(..needed) else {
                return Err(FrameError::BufferTooSmall { needed, got });
            };
            black(out, format);
            return Ok(size);
        }
        area.decode(self.vram.as_slice(), out, format, ChannelExpand::Replicate)
    }

    /// [`Gpu::run`], calling `line` with each displayed line the beam finishes during that
    /// time, in order: the scanlines GP1(07h) Y1..Y2 select, as the beam reaches the end of
    /// each (docs/hardware/timing.md §6). Each line shows VRAM and the GP1(03h)/(05h)-(08h)
    /// settings as they are when it ends, so a display start, range or mode changed between
    /// two calls (a raster effect, a mid-frame buffer flip) shows from the next line the beam
    /// finishes. 480i fields come unwoven, one field's lines after the other, each with its
    /// [`DisplayLine::field`] and woven [`DisplayLine::row`]. The events are those of `run`
    /// over the same time.
    ///
    /// ```
    /// // Display start Y 0 for the top half of a frame, then 256 (GP1(05h)) for the rest.
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp1(0x0300_0000);
    /// let mut shown = vec![];
    /// gpu.run_lines(16 * 2172 + 120 * 2172, |l| shown.push(l.vram_y)); // lines 16..135
    /// gpu.gp1(0x0500_0000 | 256 << 10);
    /// gpu.run_lines(130 * 2172, |l| shown.push(l.vram_y));
    /// assert_eq!(shown.len(), 240);
    /// assert_eq!(&shown[118..122], &[118, 119, 256 + 120, 256 + 121]);
    /// ```
    pub fn run_lines(&mut self, cpu_cycles: u32, mut line: impl FnMut(DisplayLine<'_>)) -> Events {
        let vm = self.display.video_mode();
        let mut video = self.timing.convert(cpu_cycles);
        let total = video;
        let mut events = Events::default();
        while let Some((until, field, scanline)) = self.timing.next_shown_line_end(&vm) {
            if until > video {
                break;
            }
            events.merge(self.timing.advance(until, &vm));
            video -= until;
            line(self.display_line(field, scanline));
        }
        events.merge(self.timing.advance(video, &vm));
        let (gpu_irq, drawing_done) =
            self.advance_drawing(u32::try_from(total).unwrap_or(u32::MAX));
        events.gpu_irq = gpu_irq;
        events.drawing_done = drawing_done;
        events
    }

    /// The displayed line the beam is on now, with VRAM and the display settings as they are
    /// (see [`Gpu::run_lines`]); `None` while the beam is on a line GP1(07h) does not select.
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// assert!(gpu.beam_line().is_none()); // line 0: above Y1 = 16
    /// gpu.run(20 * 2172); // into line 20 (2171.9 CPU cycles a line)
    /// let line = gpu.beam_line().unwrap();
    /// assert_eq!((line.scanline, line.row, line.vram_y), (20, 4, 4));
    /// ```
    pub fn beam_line(&self) -> Option<DisplayLine<'_>> {
        let vm = self.display.video_mode();
        if !self.timing.on_shown_line(&vm) {
            return None;
        }
        let beam = self.timing.beam(&vm);
        Some(self.display_line(beam.field, beam.line))
    }

    /// Displayed scanline `scanline` of field `field` (one GP1(07h) selects).
    fn display_line(&self, field: u8, scanline: u32) -> DisplayLine<'_> {
        let d = &self.display;
        let field_row = scanline.saturating_sub(d.v_range.0 as u32);
        let row = if d.mode & 0x24 == 0x24 {
            2 * field_row + field as u32
        } else {
            field_row
        };
        DisplayLine {
            field,
            scanline,
            field_row,
            row,
            vram_y: ((d.start_y as u32 + row) & 511) as u16,
            area: d.area(),
            blanked: d.disabled,
            vram: &self.vram,
        }
    }
}
