//! A per-pixel model of the colour and texture pipeline (docs/hardware/gpu.md §1, §6, §7),
//! written from the fact sheet for the fast-path property tests (`fast_paths.rs`). Each
//! function is one rule of the sheet applied to one pixel, with no tables and no packed
//! channels, so it shares nothing with the rasterizer's specialised routines.

use super::model;
use gpu::Vram;

/// A texture as a primitive selects it: page, depth, CLUT and the E2h window.
#[derive(Clone, Copy, Debug)]
pub struct Texture {
    /// Page base X / 64 (E1h / texpage bits 0-3).
    pub page_x: u32,
    /// Page base Y / 256 (bit 4).
    pub page_y: u32,
    /// 0 4-bit, 1 8-bit, 2 15-bit, 3 reserved (read as 15-bit) (bits 7-8, §2).
    pub depth: u32,
    /// The CLUT attribute: X / 16 in bits 0-5, Y in bits 6-14 (§7).
    pub clut: u32,
    /// E2h: mask X, mask Y, offset X, offset Y, each 5 bits in units of 8 texels (§2).
    pub window: [u32; 4],
}

impl Texture {
    /// The E2h word selecting this texture window (§2).
    pub fn e2(&self) -> u32 {
        let [mask_x, mask_y, offset_x, offset_y] = self.window.map(|f| f as u8);
        gpu::encode::texture_window(gpu::TextureWindow {
            mask_x,
            mask_y,
            offset_x,
            offset_y,
        })
    }

    /// Texpage bits 0-4 and 7-8 (page and depth) as E1h and the polygon attribute hold them.
    pub fn page_bits(&self) -> u32 {
        self.page_x | self.page_y << 4 | self.depth << 7
    }

    /// The texel (a 16-bit VRAM value, 0000h = transparent) sampled at 8-bit (u, v):
    /// texture window (§7), then the 4/8/15-bit address and, for 4/8-bit, the CLUT entry.
    pub fn texel(&self, vram: &Vram, u: u32, v: u32) -> u16 {
        let [mx, my, ox, oy] = self.window;
        // §7: u' = (u & ~(maskX * 8)) | ((offX & maskX) * 8), likewise for v.
        let u = ((u & 0xFF) & !(mx * 8)) | ((ox & mx) * 8);
        let v = ((v & 0xFF) & !(my * 8)) | ((oy & my) * 8);
        let (px, py) = (64 * self.page_x as usize, 256 * self.page_y as usize);
        let (u, row) = (u as usize, py + v as usize);
        let clut_x = (self.clut & 0x3F) as usize * 16;
        let clut_y = ((self.clut >> 6) & 0x1FF) as usize;
        let entry = |i: usize| vram.pixel((clut_x + i) & 1023, clut_y);
        match self.depth {
            0 => {
                let word = vram.pixel((px + (u >> 2)) & 1023, row);
                entry(((word >> ((u & 3) * 4)) & 0xF) as usize)
            }
            1 => {
                let word = vram.pixel((px + (u >> 1)) & 1023, row);
                entry(((word >> ((u & 1) * 8)) & 0xFF) as usize)
            }
            _ => vram.pixel((px + u) & 1023, row),
        }
    }
}

/// The 5-bit channel `i` (0 red, 1 green, 2 blue) of a 15-bit pixel (§1).
fn ch(p: u16, i: u32) -> u32 {
    ((p >> (5 * i)) & 31) as u32
}

/// An 8-bit RGB colour as a flat untextured primitive writes it: c8 >> 3 per channel, never
/// dithered (§6 "When dithering applies": flat untextured polygons no, rectangles no).
pub fn flat(rgb: [u32; 3]) -> u16 {
    (rgb[0] >> 3 | (rgb[1] >> 3) << 5 | (rgb[2] >> 3) << 10) as u16
}

/// Texel modulated by the 8-bit colour (§6 "Modulation", v2 GPU): per channel
/// idx = (t5 * c8) >> 4, then clamp(idx + dither, 0, 255) >> 3; bits 0-14 only.
pub fn modulate(texel: u16, rgb: [u32; 3], x: i64, y: i64, dither: bool) -> u16 {
    (0..3)
        .map(|i| model::channel((ch(texel, i) * rgb[i as usize]) >> 4, x, y, dither) << (5 * i))
        .sum()
}

/// Semi-transparency mode 0-3 on 5-bit channels, B the VRAM pixel, F the new one (§6).
pub fn blend(b: u16, f: u16, mode: u32) -> u16 {
    (0..3)
        .map(|i| {
            let (b, f) = (ch(b, i) as i32, ch(f, i) as i32);
            let c = match mode {
                0 => (b + f) >> 1,
                1 => (b + f).min(31),
                2 => (b - f).max(0),
                _ => (b + (f >> 2)).min(31),
            };
            (c as u16) << (5 * i)
        })
        .sum()
}

/// The E6h mask settings (§2, §6).
#[derive(Clone, Copy, Debug)]
pub struct Mask {
    /// E6h bit 0: every pixel written gets bit 15.
    pub set: bool,
    /// E6h bit 1: destination pixels with bit 15 are left alone.
    pub check: bool,
}

impl Mask {
    /// The E6h word.
    pub fn e6(&self) -> u32 {
        gpu::encode::mask_bits(gpu::MaskSettings {
            set: self.set,
            check: self.check,
        })
    }
}

/// Write one pixel (§6 "Mask bit", "Semi-transparency"): `color` is the 15-bit colour,
/// `bit15` the texel's bit 15 (false when untextured), `blend` the mode when this pixel
/// blends. With the mask check a destination with bit 15 is kept, whatever the blending.
pub fn plot(
    vram: &mut Vram,
    (x, y): (i64, i64),
    color: u16,
    bit15: bool,
    blend_mode: Option<u32>,
    mask: Mask,
) {
    let (x, y) = (x as usize, y as usize);
    let dest = vram.pixel(x, y);
    if mask.check && dest & 0x8000 != 0 {
        return;
    }
    let color = match blend_mode {
        Some(mode) => blend(dest, color, mode),
        None => color & 0x7FFF,
    };
    let top = if bit15 || mask.set { 0x8000 } else { 0 };
    vram.set_pixel(x, y, color | top);
}
