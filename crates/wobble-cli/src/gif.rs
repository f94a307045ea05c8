//! Animated GIF output of 15-bit frames without dithering: each frame gets its own palette
//! built from its exact colours. A frame of at most 256 colours is written exactly; a frame
//! with more keeps its 256 most used colours and maps every other colour to the nearest of
//! them (squared RGB distance, ties to the more used), so no noise is added on top of the
//! GPU's own dither pattern.

use std::io::Write;

/// Colours a GIF palette holds.
const PALETTE: usize = 256;

/// A 15-bit colour (5 bits a channel, red lowest) from 8-bit RGB (the top 5 bits, which is
/// exact for frames read out of VRAM, whose channels are 5-bit values replicated).
pub fn rgb15(p: [u8; 3]) -> u16 {
    u16::from(p[0] >> 3) | u16::from(p[1] >> 3) << 5 | u16::from(p[2] >> 3) << 10
}

/// The 8-bit RGB of a 15-bit colour, channels replicated (c << 3 | c >> 2), as VRAM reads
/// out.
pub fn rgb8(c: u16) -> [u8; 3] {
    let e = |v: u16| {
        let v = (v & 31) as u8;
        v << 3 | v >> 2
    };
    [e(c), e(c >> 5), e(c >> 10)]
}

/// A frame's palette (15-bit colours, most used first) and its pixels as palette indices.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Indexed {
    /// Palette colours, at most 256.
    pub palette: Vec<u16>,
    /// One index per pixel.
    pub indices: Vec<u8>,
}

/// Index a frame of 15-bit colours: exact when it has at most 256 colours, else the 256
/// most used colours (ties to the lower colour value) with nearest-colour mapping.
pub fn index_frame(pixels: &[u16]) -> Indexed {
    let mut counts = vec![0u32; 1 << 15];
    for &p in pixels {
        if let Some(c) = counts.get_mut(usize::from(p & 0x7FFF)) {
            *c = c.saturating_add(1);
        }
    }
    let mut used: Vec<(u32, u16)> = (0u16..1 << 15)
        .zip(&counts)
        .filter(|(_, n)| **n > 0)
        .map(|(c, &n)| (n, c))
        .collect();
    used.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
    let palette: Vec<u16> = used.iter().take(PALETTE).map(|&(_, c)| c).collect();
    let mut map = vec![0u8; 1 << 15];
    for &(_, c) in &used {
        let nearest = palette
            .iter()
            .enumerate()
            .min_by_key(|(_, p)| distance(**p, c))
            .map_or(0, |(i, _)| i);
        if let Some(m) = map.get_mut(usize::from(c)) {
            *m = u8::try_from(nearest).unwrap_or(u8::MAX);
        }
    }
    let indices = pixels
        .iter()
        .map(|&p| map.get(usize::from(p & 0x7FFF)).copied().unwrap_or(0))
        .collect();
    Indexed { palette, indices }
}

/// Squared distance between two 15-bit colours in 5-bit units.
fn distance(a: u16, b: u16) -> u32 {
    (0..3)
        .map(|k| {
            let (x, y) = (
                i32::from((a >> (5 * k)) & 31),
                i32::from((b >> (5 * k)) & 31),
            );
            ((x - y) * (x - y)) as u32
        })
        .sum()
}

/// GIF frame delay in hundredths of a second for `fps` frames a second, rounded, at least 2
/// (viewers show shorter delays as 10).
pub fn delay_centiseconds(fps: u32) -> u16 {
    let fps = fps.max(1);
    u16::try_from((100 + fps / 2) / fps)
        .unwrap_or(u16::MAX)
        .max(2)
}

/// An animated GIF being written, looping forever.
pub struct GifWriter<W: Write> {
    encoder: gif::Encoder<W>,
    width: u16,
    height: u16,
    delay: u16,
}

impl<W: Write> GifWriter<W> {
    /// Start a `width` x `height` GIF shown at `fps` frames a second.
    pub fn new(writer: W, width: u16, height: u16, fps: u32) -> Result<Self, String> {
        let mut encoder =
            gif::Encoder::new(writer, width, height, &[]).map_err(|e| e.to_string())?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        Ok(GifWriter {
            encoder,
            width,
            height,
            delay: delay_centiseconds(fps),
        })
    }

    /// Add a frame of 15-bit colours, row-major, `width * height` of them.
    pub fn frame(&mut self, pixels: &[u16]) -> Result<(), String> {
        if pixels.len() != usize::from(self.width) * usize::from(self.height) {
            return Err(format!(
                "GIF frame of {} pixels for a {}x{} animation",
                pixels.len(),
                self.width,
                self.height
            ));
        }
        let indexed = index_frame(pixels);
        let mut palette: Vec<u8> = indexed.palette.iter().flat_map(|&c| rgb8(c)).collect();
        // A GIF colour table holds a power of two entries, at least 2.
        let entries = indexed.palette.len().max(2).next_power_of_two();
        palette.resize(entries * 3, 0);
        let mut frame =
            gif::Frame::from_indexed_pixels(self.width, self.height, indexed.indices, None);
        frame.palette = Some(palette);
        frame.delay = self.delay;
        self.encoder.write_frame(&frame).map_err(|e| e.to_string())
    }

    /// Finish the file (the trailer) and hand back the writer.
    pub fn finish(self) -> Result<W, String> {
        self.encoder.into_inner().map_err(|e| e.to_string())
    }
}

/// An RGB image read out of VRAM as 15-bit colours.
pub fn image_rgb15(img: &image::RgbImage) -> Vec<u16> {
    img.pixels().map(|p| rgb15(p.0)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At most 256 colours: every pixel decodes to its own colour.
    #[test]
    fn few_colours_are_exact() {
        let pixels: Vec<u16> = (0..1000u32)
            .map(|i| ((i * 97) % 256) as u16 * 113)
            .collect();
        let x = index_frame(&pixels);
        assert!(x.palette.len() <= 256);
        for (p, i) in pixels.iter().zip(&x.indices) {
            assert_eq!(x.palette[usize::from(*i)], *p);
        }
    }

    /// 300 colours: the 256 most used are exact, the 44 rarest go to their nearest kept
    /// colour. Colours are grey levels g * 0x421 (g = 0..31 in every channel) plus reds; a
    /// colour used once maps to a kept colour one step away.
    #[test]
    fn many_colours_keep_the_most_used_and_map_to_nearest() {
        let mut pixels = Vec::new();
        // 256 colours used 3 times each: red r, green g for r in 0..16, g in 0..16.
        for r in 0..16u16 {
            for g in 0..16u16 {
                pixels.extend([r | g << 5; 3]);
            }
        }
        // 44 colours used once: blue 1 on top of some of them.
        for k in 0..44u16 {
            pixels.push((k % 16) | (k / 16) << 5 | 1 << 10);
        }
        let x = index_frame(&pixels);
        assert_eq!(x.palette.len(), 256);
        for (p, i) in pixels.iter().zip(&x.indices) {
            let kept = x.palette[usize::from(*i)];
            // Exact, or the same colour without its blue unit.
            assert_eq!(kept, p & 0x3FF, "{p:#x}");
        }
    }

    #[test]
    fn delays_follow_the_frame_rate() {
        assert_eq!(delay_centiseconds(30), 3);
        assert_eq!(delay_centiseconds(25), 4);
        assert_eq!(delay_centiseconds(20), 5);
        assert_eq!(delay_centiseconds(60), 2);
        assert_eq!(delay_centiseconds(0), 100);
    }

    #[test]
    fn rgb_round_trip() {
        for c in [0u16, 0x7FFF, 0x1234, 0x4210] {
            assert_eq!(rgb15(rgb8(c)), c);
        }
    }
}
