//! A polygon between the GTE stage and the ordering table: its screen positions, vertex
//! colours, texture coordinates and attributes and its ordering-table entry, and the GP0
//! packet that draws it (docs/hardware/gpu.md §2, §6).
//!
//! Why this shape: a polygon keeps its vertex colours as GP0 colour words from the lighting to
//! its packet, and equal colours make a flat packet, which the GPU draws without colour
//! interpolation: the flat-only sphere's GPU stage costs half the textured sphere's
//! (docs/pipeline.md, "Benchmarks").

use gpu::encode::{self, Packet, Polygon, PolygonTexture, Vertex};

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
    pub(super) texture: Option<(gpu::ClutAttr, gpu::Texpage)>,
    /// The semi-transparency mode of a semi-transparent polygon.
    pub(super) blend: Option<u8>,
}

/// An 8-bit RGB colour as a GP0 colour word (R in bits 0-7, G 8-15, B 16-23).
pub(super) fn rgb_word([r, g, b]: [u8; 3]) -> u32 {
    u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16
}

impl ProjectedFace {
    /// The GP0 polygon packet of this face. Gouraud (G3/G4/GT3/GT4) only when the vertex
    /// colours differ; otherwise the flat packet, which the GPU draws without colour
    /// interpolation.
    pub(super) fn packet(&self) -> Packet {
        let n = if self.quad { 4 } else { 3 };
        let vertex = |i: usize| {
            let ((x, y), (u, v)) = (self.xy[i], self.uv[i]);
            let [r, g, b, _] = self.color[i].to_le_bytes();
            let color = [r, g, b];
            Vertex { x, y, color, u, v }
        };
        Polygon {
            vertices: [vertex(0), vertex(1), vertex(2), vertex(3)],
            quad: self.quad,
            gouraud: self.color[1..n].iter().any(|c| *c != self.color[0]),
            semi_transparent: self.blend.is_some(),
            texture: self.texture.map(|(clut, page)| PolygonTexture {
                clut,
                page,
                raw: false,
            }),
        }
        .packet()
    }

    /// An untextured polygon has no texpage attribute to carry its blend mode: the draw-mode
    /// word (E1h) that must reach GP0 just before it (docs/hardware/gpu.md §2, §6).
    pub(super) fn blend_e1(&self, dither: bool) -> Option<u32> {
        match (self.texture, self.blend) {
            (None, Some(mode)) => Some(encode::draw_mode(gpu::DrawMode {
                blend: gpu::BlendMode::from_bits(u32::from(mode)),
                dither,
                ..gpu::DrawMode::default()
            })),
            _ => None,
        }
    }
}
