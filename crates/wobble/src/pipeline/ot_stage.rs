//! The ordering-table stage: each projected polygon becomes a GP0 packet (flat or Gouraud,
//! textured or not, semi-transparent or not) linked into the ordering table at its depth
//! (docs/hardware/gpu.md §2, §6).

use super::{FrameStats, Renderer};

/// Ordering-table entries.
pub const OT_DEPTH: usize = 2048;
/// OTZ to OT index: OTZ (the mean SZ) >> this.
pub const OT_SHIFT: u32 = 3;

/// Most polygons one frame can draw: sizes the scratch list and the primitive buffer (13
/// words a polygon, 6.8 MB, inside the console's 8 MB address range the OT links can reach).
pub const MAX_POLYGONS: usize = 1 << 17;

/// The primitive buffer for `polygons` polygons: each takes at most 13 words, a GT4 packet
/// (12 words) and its node header, or an untextured polygon's packet (at most 8 words) and
/// its draw-mode word, each with a header; and 64 words to spare.
pub(super) fn primitive_words(polygons: usize) -> usize {
    polygons.saturating_mul(13).saturating_add(64)
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
