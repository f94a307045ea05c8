//! The ordering-table stage: each projected polygon becomes a GP0 packet (flat or Gouraud,
//! textured or not, semi-transparent or not) linked into the ordering table at its depth
//! (docs/hardware/gpu.md §2, §6).

use super::gte_stage::ProjectedFace;
use super::{FrameStats, Renderer};

/// Ordering-table entries.
pub const OT_DEPTH: usize = 2048;
/// OTZ to OT index: OTZ (the mean SZ) >> this.
pub const OT_SHIFT: u32 = 3;

/// Most polygons one frame can draw: sizes the scratch list and the primitive buffer (13
/// words a polygon, 6.8 MB, inside the console's 8 MB address range the OT links can reach).
pub const MAX_POLYGONS: usize = 1 << 17;

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

impl Renderer {
    pub(super) fn ot_stage(&mut self, stats: &mut FrameStats) {
        let dither = self.options.dither.unwrap_or(self.scene.screen.dither);
        self.ot.clear();
        let mut packet = [0u32; 12];
        if self.options.precise() {
            // The precise path links each polygon's index instead of a GP0 packet: the same
            // depth order, drawn by the non-hardware rasterizer in `gpu_stage`.
            for (i, f) in self.scratch.iter().enumerate() {
                if self.ot.insert(f.ot_index as usize, &[i as u32]).is_ok() {
                    stats.drawn += 1;
                }
            }
            return;
        }
        for (k, f) in self.scratch.iter().enumerate() {
            if let Some(t) = self.trace.as_deref_mut()
                && let Some(&record) = t.scratch_face.get(k)
            {
                // The packet's node goes where the primitive buffer's free space starts.
                t.node_face
                    .push((self.ot.depth() + self.ot.used_words(), record));
            }
            let len = f.packet(&mut packet);
            if self.ot.insert(f.ot_index as usize, &packet[..len]).is_ok() {
                stats.drawn += 1;
            }
            // A draw-mode packet linked after the polygon at the same entry comes out just
            // before it. A full primitive buffer leaves the polygon in the default mode.
            if let Some(e1) = f.blend_e1(dither) {
                let _ = self.ot.insert(f.ot_index as usize, &[e1]);
            }
        }
    }
}
