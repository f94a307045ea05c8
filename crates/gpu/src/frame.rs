//! The displayed frame: the VRAM rectangle the GP1 display registers select, decoded to
//! 8-bit RGB (psx-spx "GP1(05h)".."GP1(08h)", "GPU Video Memory (VRAM)" Framebuffer).

use crate::display::DisplayArea;
use crate::{Gpu, VRAM_WIDTH};

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
        let bpp = format.bytes_per_pixel();
        let width = self.width as usize;
        let (x0, y0) = (self.x as usize, self.y as usize);
        if width == 0 {
            return Ok(size);
        }
        for (row, line) in out.chunks_exact_mut(width * bpp).enumerate() {
            let y = y0 + row;
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
                    expand.pixel(halfword(vram, x0 + col, y))
                };
                px[..3].copy_from_slice(&rgb);
                if let Some(a) = px.get_mut(3) {
                    *a = 255;
                }
            }
        }
        Ok(size)
    }
}

impl Gpu {
    /// The size of the frame [`Gpu::display_frame`] writes: the display area of GP1(05h)-(08h).
    pub fn frame_size(&self) -> FrameSize {
        self.display_area().frame_size()
    }

    /// The displayed frame as 8-bit pixels in `format` (15-bit channels widened as
    /// [`ChannelExpand::Replicate`]); black while GP1(03h) disables the display (psx-spx
    /// "GP1(03h)"). Errors, writing nothing, when `out` is shorter than
    /// `frame_size().bytes(format)`.
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
            for px in out.chunks_exact_mut(format.bytes_per_pixel()) {
                px.fill(0);
                if let Some(a) = px.get_mut(3) {
                    *a = 255;
                }
            }
            return Ok(size);
        }
        area.decode(self.vram.as_slice(), out, format, ChannelExpand::Replicate)
    }
}
