//! Textures: RGBA images prepared as 4-bit or 8-bit CLUT textures, or 15-bit direct ones,
//! in the GPU's 1555 format (docs/hardware/gpu.md §1, §7); the palette choice is in `quantize`,
//! the conversion of one pixel in `texel`.

use super::quantize;
use super::texel::to_1555;
use gpu::TextureDepth;
use std::fmt;
use std::path::{Path, PathBuf};

/// A scene file's texture depth in bits per texel (4, 8, or 15; 16 is taken as 15) as the
/// GPU's texture depth (docs/hardware/gpu.md §7).
pub fn depth_from_bits_per_texel(bits: u8) -> Result<TextureDepth, DepthError> {
    match bits {
        4 => Ok(TextureDepth::Clut4),
        8 => Ok(TextureDepth::Clut8),
        15 | 16 => Ok(TextureDepth::Direct15),
        _ => Err(DepthError(bits)),
    }
}

/// Bits per texel of a texture depth: 4, 8 or 15 (docs/hardware/gpu.md §7).
pub fn bits_per_texel(depth: TextureDepth) -> u8 {
    match depth {
        TextureDepth::Clut4 => 4,
        TextureDepth::Clut8 => 8,
        TextureDepth::Direct15 => 15,
    }
}

/// A texture depth other than 4, 8 or 15 (16 is taken as 15).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DepthError(pub u8);

impl fmt::Display for DepthError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "texture depth must be 4, 8 or 15, got {}", self.0)
    }
}

impl std::error::Error for DepthError {}

/// A texture ready for VRAM: texels as CLUT indices or 15-bit colours, and its CLUT.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texture {
    /// Width in texels (1..=256).
    pub width: u16,
    /// Height in texels (1..=256).
    pub height: u16,
    /// TextureDepth.
    pub depth: TextureDepth,
    /// Row-major texels: CLUT indices, or 1555 colours for direct textures.
    pub texels: Vec<u16>,
    /// CLUT entries (16 or 256; empty for direct textures).
    pub clut: Vec<u16>,
}

/// Why texture fields or pixels do not make a valid texture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum InvalidTexture {
    /// Pixels given for a size outside 1..=256 a side, or not `width * height` of them.
    Pixels {
        /// Width asked for.
        width: u16,
        /// Height asked for.
        height: u16,
        /// Pixels given.
        pixels: usize,
    },
    /// A side outside 1..=256: larger than a texture page.
    Size {
        /// Width.
        width: usize,
        /// Height.
        height: usize,
    },
    /// The texel count is not `width * height`.
    Texels {
        /// Width.
        width: usize,
        /// Height.
        height: usize,
        /// Texels present.
        texels: usize,
    },
    /// The CLUT length does not match the depth.
    ClutLength {
        /// The depth in bits (4, 8 or 15).
        bits: u8,
        /// Entries the depth needs.
        needed: usize,
        /// Entries present.
        has: usize,
    },
    /// A texel indexes past the end of the CLUT.
    IndexBeyondClut {
        /// CLUT entries.
        limit: usize,
    },
}

impl fmt::Display for InvalidTexture {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InvalidTexture::Pixels {
                width,
                height,
                pixels,
            } => write!(
                f,
                "{width}x{height} texture with {pixels} pixels is not a valid texture"
            ),
            InvalidTexture::Size { width, height } => {
                write!(f, "{width}x{height} does not fit a 256x256 texture page")
            }
            InvalidTexture::Texels {
                width,
                height,
                texels,
            } => write!(f, "{width}x{height} texture has {texels} texels"),
            InvalidTexture::ClutLength { bits, needed, has } => write!(
                f,
                "a {bits}-bit texture needs {needed} CLUT entries, has {has}"
            ),
            InvalidTexture::IndexBeyondClut { limit } => {
                write!(f, "texel index beyond the {limit}-entry CLUT")
            }
        }
    }
}

impl std::error::Error for InvalidTexture {}

/// Why a texture file could not be prepared; every variant names the file.
#[derive(Debug)]
pub enum TextureError {
    /// Opening the file or guessing its format failed.
    Io {
        /// The file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Decoding the image failed.
    Decode {
        /// The file.
        file: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
    /// The image is larger than a texture page.
    TooLarge {
        /// The file.
        file: PathBuf,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// The pixels do not make a valid texture.
    Invalid {
        /// The file.
        file: PathBuf,
        /// What is wrong.
        source: InvalidTexture,
    },
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TextureError::Io { file, source } => write!(
                f,
                "texture file {}: cannot read it: {source}",
                super::file_shown(file)
            ),
            TextureError::Decode { file, source } => write!(f, "{}: {source}", file.display()),
            TextureError::TooLarge {
                file,
                width,
                height,
            } => write!(
                f,
                "{}: {width}x{height} does not fit a 256x256 texture page; scale it down first",
                file.display()
            ),
            TextureError::Invalid { file, source } => write!(f, "{}: {source}", file.display()),
        }
    }
}

impl std::error::Error for TextureError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TextureError::Io { source, .. } => Some(source),
            TextureError::Decode { source, .. } => Some(source),
            TextureError::TooLarge { .. } => None,
            TextureError::Invalid { source, .. } => Some(source),
        }
    }
}

impl Texture {
    /// Largest texture side: one texture page is 256x256 texels.
    pub const MAX_SIDE: u32 = 256;

    /// Load a PNG and prepare it at `depth`.
    pub fn load_png(path: &Path, depth: TextureDepth) -> Result<Texture, TextureError> {
        let file = || path.to_path_buf();
        let io = |source| TextureError::Io {
            file: file(),
            source,
        };
        let decode = |source| TextureError::Decode {
            file: file(),
            source,
        };
        let reader = image::ImageReader::open(path)
            .map_err(io)?
            .with_guessed_format()
            .map_err(io)?;
        let (w, h) = reader.into_dimensions().map_err(decode)?;
        if w == 0 || h == 0 || w > Self::MAX_SIDE || h > Self::MAX_SIDE {
            return Err(TextureError::TooLarge {
                file: file(),
                width: w,
                height: h,
            });
        }
        let img = image::open(path).map_err(decode)?.to_rgba8();
        let pixels: Vec<[u8; 4]> = img.pixels().map(|p| p.0).collect();
        Self::from_rgba(w as u16, h as u16, &pixels, depth).map_err(|source| {
            TextureError::Invalid {
                file: file(),
                source,
            }
        })
    }

    /// Prepare RGBA pixels (row-major, `width * height` of them) at `depth`.
    pub fn from_rgba(
        width: u16,
        height: u16,
        pixels: &[[u8; 4]],
        depth: TextureDepth,
    ) -> Result<Texture, InvalidTexture> {
        let (w, h) = (width as usize, height as usize);
        if w == 0 || h == 0 || w > 256 || h > 256 || pixels.len() != w * h {
            return Err(InvalidTexture::Pixels {
                width,
                height,
                pixels: pixels.len(),
            });
        }
        let colors: Vec<u16> = pixels.iter().map(|&p| to_1555(p)).collect();
        if depth == TextureDepth::Direct15 {
            return Ok(Texture {
                width,
                height,
                depth,
                texels: colors,
                clut: Vec::new(),
            });
        }
        let size = depth.clut_len();
        let (clut, texels) = quantize::palette(pixels, &colors, size);
        let mut clut = clut;
        clut.resize(size, 0);
        Ok(Texture {
            width,
            height,
            depth,
            texels,
            clut,
        })
    }

    /// A checkerboard of `size` x `size` texels with `cells` squares a side in two colours,
    /// as a 4-bit texture.
    pub fn checker(size: u16, cells: u16, a: [u8; 3], b: [u8; 3]) -> Texture {
        let size = size.clamp(1, 256);
        let cell = (size / cells.max(1)).max(1);
        let pixels: Vec<[u8; 4]> = (0..size as usize * size as usize)
            .map(|i| {
                let (x, y) = ((i % size as usize) as u16, (i / size as usize) as u16);
                let c = if ((x / cell) + (y / cell)).is_multiple_of(2) {
                    a
                } else {
                    b
                };
                [c[0], c[1], c[2], 255]
            })
            .collect();
        // Two colours always fit a 16-entry CLUT exactly.
        Self::from_rgba(size, size, &pixels, TextureDepth::Clut4).unwrap_or_else(|_| Texture {
            width: 1,
            height: 1,
            depth: TextureDepth::Direct15,
            texels: vec![0x7FFF],
            clut: Vec::new(),
        })
    }

    /// Check the fields agree: sides 1..=256, one texel per pixel, texel values within the
    /// depth, a CLUT of 16 or 256 entries for CLUT depths and none for direct colour.
    pub fn check(&self) -> Result<(), InvalidTexture> {
        let (w, h) = (self.width as usize, self.height as usize);
        if w == 0 || h == 0 || w > 256 || h > 256 {
            return Err(InvalidTexture::Size {
                width: w,
                height: h,
            });
        }
        if self.texels.len() != w * h {
            return Err(InvalidTexture::Texels {
                width: w,
                height: h,
                texels: self.texels.len(),
            });
        }
        if self.clut.len() != self.depth.clut_len() {
            return Err(InvalidTexture::ClutLength {
                bits: bits_per_texel(self.depth),
                needed: self.depth.clut_len(),
                has: self.clut.len(),
            });
        }
        let limit = self.depth.clut_len();
        if limit > 0 && self.texels.iter().any(|&t| t as usize >= limit) {
            return Err(InvalidTexture::IndexBeyondClut { limit });
        }
        Ok(())
    }

    /// VRAM halfwords per texture row.
    pub fn row_halfwords(&self) -> usize {
        (self.width as usize).div_ceil(self.depth.texels_per_halfword())
    }

    /// The texture rows packed as VRAM halfwords (4-bit: low nibble first).
    pub fn halfwords(&self) -> Vec<u16> {
        let per = self.depth.texels_per_halfword();
        let bits = 16 / per;
        let row = self.row_halfwords();
        let mut out = vec![0u16; row * self.height as usize];
        let mask = if bits == 16 {
            0xFFFF
        } else {
            (1u16 << bits) - 1
        };
        let width = self.width as usize;
        for (y, texels) in self.texels.chunks(width.max(1)).enumerate() {
            for (x, &t) in texels.iter().enumerate() {
                if let Some(slot) = out.get_mut(y * row + x / per) {
                    *slot |= (t & mask) << ((x % per) * bits);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packs_4bit_low_nibble_first() {
        let t = Texture {
            width: 4,
            height: 1,
            depth: TextureDepth::Clut4,
            texels: vec![1, 2, 3, 4],
            clut: vec![0; 16],
        };
        assert_eq!(t.halfwords(), vec![0x4321]);
    }

    #[test]
    fn many_colours_use_neuquant() {
        let pixels: Vec<[u8; 4]> = (0..64 * 64)
            .map(|i| [(i % 64 * 4) as u8, (i / 64 * 4) as u8, 128, 255])
            .collect();
        let t = Texture::from_rgba(64, 64, &pixels, TextureDepth::Clut4).unwrap();
        assert_eq!(t.clut.len(), 16);
        assert!(t.texels.iter().all(|&i| i < 16));
    }
}
