//! VRAM to image conversions: the whole VRAM, the display area (15-bit or 24-bit), a texture
//! page seen through its CLUT, and the raw VRAM file format (docs/formats.md).

use gpu::{DisplayArea, VRAM_HEIGHT, VRAM_LEN, VRAM_WIDTH};
use image::{Rgb, RgbImage, Rgba, RgbaImage};
use std::fmt;
use std::path::{Path, PathBuf};

/// How a 5-bit channel becomes 8 bits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Expand {
    /// `c << 3 | c >> 2`: 31 maps to 255.
    #[default]
    Replicate,
    /// `c << 3`: what console capture tools wrote (31 maps to 248).
    Shift,
}

impl Expand {
    /// One 5-bit channel to 8 bits.
    pub fn channel(self, c: u16) -> u8 {
        let c = (c & 31) as u8;
        match self {
            Expand::Replicate => (c << 3) | (c >> 2),
            Expand::Shift => c << 3,
        }
    }

    /// A 1555 pixel to RGB.
    pub fn pixel(self, p: u16) -> [u8; 3] {
        [self.channel(p), self.channel(p >> 5), self.channel(p >> 10)]
    }
}

/// Errors of the raw VRAM format and image output.
#[derive(Debug)]
pub enum ImageError {
    /// A raw VRAM file is not exactly 1024 * 512 * 2 bytes.
    RawSize {
        /// File size found.
        size: usize,
    },
    /// Encoding or writing a PNG failed.
    Encode {
        /// The image file.
        file: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImageError::RawSize { size } => write!(
                f,
                "raw VRAM must be {} bytes (1024x512 little-endian u16), got {size}",
                VRAM_LEN * 2
            ),
            ImageError::Encode { file, source } => write!(f, "{}: {source}", file.display()),
        }
    }
}

impl std::error::Error for ImageError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ImageError::RawSize { .. } => None,
            ImageError::Encode { source, .. } => Some(source),
        }
    }
}

/// The whole VRAM as a 1024x512 RGB image.
pub fn vram_image(vram: &[u16], expand: Expand) -> RgbImage {
    RgbImage::from_fn(VRAM_WIDTH as u32, VRAM_HEIGHT as u32, |x, y| {
        let p = vram
            .get(y as usize * VRAM_WIDTH + x as usize)
            .copied()
            .unwrap_or(0);
        Rgb(expand.pixel(p))
    })
}

fn halfword(vram: &[u16], x: usize, y: usize) -> u16 {
    vram.get((y & 511) * VRAM_WIDTH + (x & 1023))
        .copied()
        .unwrap_or(0)
}

/// The display area as an image, decoded by the GPU crate ([`DisplayArea::decode`]: 15-bit
/// or 24-bit, coordinates wrapping at the VRAM edges).
pub fn display_image(vram: &[u16], area: DisplayArea, expand: Expand) -> RgbImage {
    let expand = match expand {
        Expand::Replicate => gpu::ChannelExpand::Replicate,
        Expand::Shift => gpu::ChannelExpand::Shift,
    };
    let size = area.frame_size();
    let mut bytes = vec![0u8; size.bytes(gpu::PixelFormat::Rgb888)];
    // The buffer is sized from the same area, so decoding cannot fail.
    let _ = area.decode(vram, &mut bytes, gpu::PixelFormat::Rgb888, expand);
    RgbImage::from_raw(size.width, size.height, bytes).unwrap_or_default()
}

/// A 256x256 texture page at (`page_x`, `page_y`) seen through the CLUT at (`clut_x`,
/// `clut_y`) as the GPU samples it (docs/hardware/gpu.md §7). Texels equal to 0000h are transparent and
/// written with alpha 0.
pub fn texture_page_image(
    vram: &[u16],
    page_x: usize,
    page_y: usize,
    depth: gpu::TextureDepth,
    clut: (usize, usize),
    expand: Expand,
) -> RgbaImage {
    RgbaImage::from_fn(256, 256, |u, v| {
        let (u, v) = (u as usize, v as usize);
        let y = page_y + v;
        let texel = match depth {
            gpu::TextureDepth::Clut4 => {
                let w = halfword(vram, page_x + u / 4, y);
                let i = (w >> ((u % 4) * 4)) & 0xF;
                halfword(vram, clut.0 + i as usize, clut.1)
            }
            gpu::TextureDepth::Clut8 => {
                let w = halfword(vram, page_x + u / 2, y);
                let i = (w >> ((u % 2) * 8)) & 0xFF;
                halfword(vram, clut.0 + i as usize, clut.1)
            }
            gpu::TextureDepth::Direct15 => halfword(vram, page_x + u, y),
        };
        let [r, g, b] = expand.pixel(texel);
        Rgba([r, g, b, if texel == 0 { 0 } else { 255 }])
    })
}

/// Decode a raw VRAM file: 1024 * 512 little-endian u16.
pub fn raw_from_bytes(bytes: &[u8]) -> Result<Vec<u16>, ImageError> {
    if bytes.len() != VRAM_LEN * 2 {
        return Err(ImageError::RawSize { size: bytes.len() });
    }
    Ok(bytes
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect())
}

/// Encode VRAM as the raw file format.
pub fn raw_to_bytes(vram: &[u16]) -> Vec<u8> {
    vram.iter().flat_map(|p| p.to_le_bytes()).collect()
}

/// Save an image as PNG, naming the path in errors.
pub fn save_png<P, C>(img: &image::ImageBuffer<P, C>, path: &Path) -> Result<(), ImageError>
where
    P: image::Pixel + image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    img.save_with_format(path, image::ImageFormat::Png)
        .map_err(|source| ImageError::Encode {
            file: path.to_path_buf(),
            source,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expand_modes() {
        assert_eq!(Expand::Replicate.channel(31), 255);
        assert_eq!(Expand::Shift.channel(31), 248);
        assert_eq!(Expand::Replicate.channel(16), 132);
    }

    #[test]
    fn display_24bit_decodes_bytes() {
        let mut vram = vec![0u16; VRAM_LEN];
        // Two 24-bit pixels (10,20,30) and (40,50,60) at (0,0): bytes 10,20,30,40,50,60.
        vram[0] = 20 << 8 | 10;
        vram[1] = 40 << 8 | 30;
        vram[2] = 60 << 8 | 50;
        let area = DisplayArea {
            x: 0,
            y: 0,
            width: 320,
            height: 240,
            color_24bit: true,
        };
        let img = display_image(&vram, area, Expand::Replicate);
        assert_eq!(img.get_pixel(0, 0).0, [10, 20, 30]);
        assert_eq!(img.get_pixel(1, 0).0, [40, 50, 60]);
    }

    #[test]
    fn raw_size_checked() {
        assert!(raw_from_bytes(&[0; 10]).is_err());
        let v = raw_from_bytes(&vec![0; VRAM_LEN * 2]).unwrap();
        assert_eq!(v.len(), VRAM_LEN);
    }
}
