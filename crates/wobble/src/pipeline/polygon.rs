//! A polygon between the GTE stage and the ordering table: its screen positions, vertex
//! colours, texture coordinates and attributes and its ordering-table entry, and the GP0
//! packet that draws it (docs/hardware/gpu.md §2, §6).
//!
//! Why this shape: a polygon keeps its vertex colours as GP0 colour words from the lighting to
//! its packet, and equal colours make a flat packet, which the GPU draws without colour
//! interpolation: the flat-only sphere's GPU stage costs half the textured sphere's
//! (docs/pipeline.md, "Benchmarks").

/// A polygon after the GTE stage, waiting for its packet.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ProjectedFace {
    pub(super) xy: [(i16, i16); 4],
    /// Vertex colours as GP0 colour words: R in bits 0-7, G 8-15, B 16-23.
    pub(super) color: [u32; 4],
    pub(super) uv: [(u8, u8); 4],
    pub(super) quad: bool,
    pub(super) ot_index: u16,
    /// The CLUT and texpage attributes of a textured polygon.
    pub(super) texture: Option<(u32, u32)>,
    /// The semi-transparency mode of a semi-transparent polygon.
    pub(super) blend: Option<u8>,
}

/// An 8-bit RGB colour as a GP0 colour word (R in bits 0-7, G 8-15, B 16-23).
pub(super) fn rgb_word([r, g, b]: [u8; 3]) -> u32 {
    u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16
}

impl ProjectedFace {
    /// The GP0 polygon packet of this face, written to the start of `out`; returns its
    /// length. Gouraud (G3/G4/GT3/GT4) only when the vertex colours differ; otherwise the
    /// flat packet, which the GPU draws without colour interpolation.
    pub(super) fn packet(&self, out: &mut [u32; 12]) -> usize {
        let n = if self.quad { 4 } else { 3 };
        let gouraud = self.color[1..n].iter().any(|c| *c != self.color[0]);
        let mut op = 0x20u32 | if self.quad { 0x08 } else { 0 };
        if gouraud {
            op |= 0x10;
        }
        if self.texture.is_some() {
            op |= 0x04;
        }
        if self.blend.is_some() {
            op |= 0x02;
        }
        let mut len = 0;
        for i in 0..n {
            let rgb = self.color[i];
            if i == 0 {
                out[len] = op << 24 | rgb;
                len += 1;
            } else if gouraud {
                out[len] = rgb;
                len += 1;
            }
            let (x, y) = self.xy[i];
            out[len] = (x as u16 as u32 & 0x7FF) | (y as u16 as u32 & 0x7FF) << 16;
            len += 1;
            if let Some((clut, tpage)) = self.texture {
                let (u, v) = self.uv[i];
                let attr = match i {
                    0 => clut,
                    1 => tpage,
                    _ => 0,
                };
                out[len] = u as u32 | (v as u32) << 8 | attr << 16;
                len += 1;
            }
        }
        len
    }

    /// An untextured polygon has no texpage attribute to carry its blend mode: the draw-mode
    /// word (E1h) that must reach GP0 just before it (docs/hardware/gpu.md §2, §6).
    pub(super) fn blend_e1(&self, dither: bool) -> Option<u32> {
        match (self.texture, self.blend) {
            (None, Some(mode)) => {
                let blend = gpu::Texpage {
                    blend: gpu::BlendMode::from_bits(u32::from(mode)),
                    ..gpu::Texpage::default()
                };
                Some(0xE100_0000 | (dither as u32) << 9 | blend.bits())
            }
            _ => None,
        }
    }
}
