//! Texture preparation: RGBA images to 4-bit or 8-bit CLUT textures, or 15-bit direct ones,
//! in the GPU's 1555 format (gpu.md §1, §7).
//!
//! An image that already has few enough colours keeps them exactly (after the 8-to-5-bit
//! reduction); otherwise the palette is chosen by NeuQuant from the `color_quant` crate
//! (maintained by the image-rs project, no dependencies, good palettes for photographic
//! input at small sizes; it also is what `image`'s GIF encoder uses).

use std::fmt;
use std::path::Path;

/// Texture colour depth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Deserialize, serde::Serialize)]
#[serde(try_from = "u8", into = "u8")]
pub enum Depth {
    /// 4-bit indices into a 16-entry CLUT.
    Clut4,
    /// 8-bit indices into a 256-entry CLUT.
    Clut8,
    /// 15-bit direct colour.
    Direct15,
}

impl TryFrom<u8> for Depth {
    type Error = String;
    fn try_from(v: u8) -> Result<Self, String> {
        match v {
            4 => Ok(Depth::Clut4),
            8 => Ok(Depth::Clut8),
            15 | 16 => Ok(Depth::Direct15),
            _ => Err(format!("texture depth must be 4, 8 or 15, got {v}")),
        }
    }
}

impl From<Depth> for u8 {
    fn from(d: Depth) -> u8 {
        match d {
            Depth::Clut4 => 4,
            Depth::Clut8 => 8,
            Depth::Direct15 => 15,
        }
    }
}

impl Depth {
    /// CLUT entries (0 for direct colour).
    pub fn clut_len(self) -> usize {
        match self {
            Depth::Clut4 => 16,
            Depth::Clut8 => 256,
            Depth::Direct15 => 0,
        }
    }

    /// Texels per VRAM halfword.
    pub fn texels_per_halfword(self) -> usize {
        match self {
            Depth::Clut4 => 4,
            Depth::Clut8 => 2,
            Depth::Direct15 => 1,
        }
    }

    /// E1/texpage depth bits.
    pub fn bits(self) -> u32 {
        match self {
            Depth::Clut4 => 0,
            Depth::Clut8 => 1,
            Depth::Direct15 => 2,
        }
    }
}

/// A texture ready for VRAM: texels as CLUT indices or 15-bit colours, and its CLUT.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texture {
    /// Width in texels (1..=256).
    pub width: u16,
    /// Height in texels (1..=256).
    pub height: u16,
    /// Depth.
    pub depth: Depth,
    /// Row-major texels: CLUT indices, or 1555 colours for direct textures.
    pub texels: Vec<u16>,
    /// CLUT entries (16 or 256; empty for direct textures).
    pub clut: Vec<u16>,
}

/// Why a texture could not be prepared.
#[derive(Debug)]
pub struct TextureError {
    /// The file or built-in name.
    pub source: String,
    /// What went wrong.
    pub message: String,
}

impl fmt::Display for TextureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.source, self.message)
    }
}

impl std::error::Error for TextureError {}

/// 8-bit RGBA to a 1555 texel: alpha below 128 is transparent (0000h); pure black becomes
/// 8000h, which the GPU draws as opaque black (0000h would be transparent).
pub fn to_1555(rgba: [u8; 4]) -> u16 {
    if rgba[3] < 128 {
        return 0;
    }
    let c = (rgba[0] >> 3) as u16 | ((rgba[1] >> 3) as u16) << 5 | ((rgba[2] >> 3) as u16) << 10;
    if c == 0 { 0x8000 } else { c }
}

impl Texture {
    /// Largest texture side: one texture page is 256x256 texels.
    pub const MAX_SIDE: u32 = 256;

    /// Load a PNG and prepare it at `depth`.
    pub fn load_png(path: &Path, depth: Depth) -> Result<Texture, TextureError> {
        let err = |message: String| TextureError {
            source: path.display().to_string(),
            message,
        };
        let reader = image::ImageReader::open(path)
            .map_err(|e| err(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| err(e.to_string()))?;
        let (w, h) = reader.into_dimensions().map_err(|e| err(e.to_string()))?;
        if w == 0 || h == 0 || w > Self::MAX_SIDE || h > Self::MAX_SIDE {
            return Err(err(format!(
                "{w}x{h} does not fit a 256x256 texture page; scale it down first"
            )));
        }
        let img = image::open(path)
            .map_err(|e| err(e.to_string()))?
            .to_rgba8();
        let pixels: Vec<[u8; 4]> = img.pixels().map(|p| p.0).collect();
        Self::from_rgba(w as u16, h as u16, &pixels, depth).map_err(err)
    }

    /// Prepare RGBA pixels (row-major, `width * height` of them) at `depth`.
    pub fn from_rgba(
        width: u16,
        height: u16,
        pixels: &[[u8; 4]],
        depth: Depth,
    ) -> Result<Texture, String> {
        let (w, h) = (width as usize, height as usize);
        if w == 0 || h == 0 || w > 256 || h > 256 || pixels.len() != w * h {
            return Err(format!(
                "{width}x{height} texture with {} pixels is not a valid texture",
                pixels.len()
            ));
        }
        let colors: Vec<u16> = pixels.iter().map(|&p| to_1555(p)).collect();
        if depth == Depth::Direct15 {
            return Ok(Texture {
                width,
                height,
                depth,
                texels: colors,
                clut: Vec::new(),
            });
        }
        let size = depth.clut_len();
        let mut distinct: Vec<u16> = colors.clone();
        distinct.sort_unstable();
        distinct.dedup();
        let (clut, texels) = if distinct.len() <= size {
            let texels = colors
                .iter()
                .map(|c| distinct.binary_search(c).unwrap_or(0) as u16)
                .collect();
            (distinct, texels)
        } else {
            Self::neuquant(pixels, &colors, size)
        };
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

    /// NeuQuant palette for the opaque pixels; transparent pixels keep entry 0 = 0000h.
    fn neuquant(pixels: &[[u8; 4]], colors: &[u16], size: usize) -> (Vec<u16>, Vec<u16>) {
        let has_transparent = colors.contains(&0);
        let slots = if has_transparent { size - 1 } else { size };
        let rgba: Vec<u8> = pixels
            .iter()
            .filter(|p| p[3] >= 128)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        let nq = color_quant::NeuQuant::new(10, slots, &rgba);
        let offset = usize::from(has_transparent);
        let mut clut = vec![0u16; offset];
        for chunk in nq.color_map_rgba().chunks_exact(4) {
            clut.push(to_1555([chunk[0], chunk[1], chunk[2], 255]));
        }
        let texels = pixels
            .iter()
            .map(|p| {
                if p[3] < 128 {
                    0
                } else {
                    (nq.index_of(&[p[0], p[1], p[2], 255]) + offset) as u16
                }
            })
            .collect();
        (clut, texels)
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
        Self::from_rgba(size, size, &pixels, Depth::Clut4).unwrap_or_else(|_| Texture {
            width: 1,
            height: 1,
            depth: Depth::Direct15,
            texels: vec![0x7FFF],
            clut: Vec::new(),
        })
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
        for y in 0..self.height as usize {
            for x in 0..self.width as usize {
                let t = self
                    .texels
                    .get(y * self.width as usize + x)
                    .copied()
                    .unwrap_or(0);
                if let Some(slot) = out.get_mut(y * row + x / per) {
                    *slot |= t << ((x % per) * bits);
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
    fn black_and_transparent() {
        assert_eq!(to_1555([0, 0, 0, 255]), 0x8000);
        assert_eq!(to_1555([255, 255, 255, 0]), 0);
        assert_eq!(to_1555([255, 8, 0, 255]), 31 | 1 << 5);
    }

    #[test]
    fn packs_4bit_low_nibble_first() {
        let t = Texture {
            width: 4,
            height: 1,
            depth: Depth::Clut4,
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
        let t = Texture::from_rgba(64, 64, &pixels, Depth::Clut4).unwrap();
        assert_eq!(t.clut.len(), 16);
        assert!(t.texels.iter().all(|&i| i < 16));
    }
}
