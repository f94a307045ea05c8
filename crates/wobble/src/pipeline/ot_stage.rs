//! The ordering-table stage (docs/pipeline.md step 6): each projected polygon's GP0 packet
//! (flat or Gouraud, textured or not, semi-transparent or not) linked into the ordering
//! table at its depth, and an untextured semi-transparent polygon's draw-mode word after it
//! (docs/hardware/gpu.md §2, §6).
//!
//! Why this shape: one packet buffer for every polygon, and `OrderingTable::insert` inlined
//! into the loop (85 K fewer instructions per wall frame, docs/performance.md, "Pipeline
//! frames").

use super::polygon::ProjectedFace;
use super::trace::FrameRecorder;
use gpu::OrderingTable;

/// Ordering-table entries.
pub const OT_DEPTH: usize = 2048;
/// OTZ to OT index: OTZ (the mean SZ) >> this.
pub const OT_SHIFT: u32 = 3;

/// Most polygons one frame can draw: sizes the GTE stage's polygon list and the primitive
/// buffer (13 words a polygon, 6.8 MB, inside the console's 8 MB address range the OT
/// links can reach).
pub const MAX_POLYGONS: usize = 1 << 17;

/// The primitive buffer for `polygons` polygons: each takes at most 13 words, a GT4 packet
/// (12 words) and its node header, or an untextured polygon's packet (at most 8 words) and
/// its draw-mode word, each with a header; and 64 words to spare.
pub(super) fn primitive_words(polygons: usize) -> usize {
    polygons.saturating_mul(13).saturating_add(64)
}

/// The word index of entry `entry`'s first node: the packet linked there last.
fn first_node(ot: &OrderingTable, entry: usize) -> usize {
    ot.ram()
        .get(entry)
        .map_or(0, |&link| (link & 0xFF_FFFF) as usize / 4)
}

/// Clear the table (DMA6) and link every polygon of `faces` in order, each at its entry
/// (`dither`: the dither bit of the draw-mode words). Returns how many polygons were
/// linked. A draw-mode word that finds the primitive buffer full leaves its polygon in the
/// default mode.
pub(super) fn link(
    faces: &[ProjectedFace],
    dither: bool,
    ot: &mut OrderingTable,
    mut trace: Option<&mut FrameRecorder>,
) -> usize {
    ot.clear();
    let mut linked = 0;
    for (k, f) in faces.iter().enumerate() {
        let entry = usize::from(f.ot_index);
        if ot.insert(entry, &f.packet()).is_ok() {
            linked += 1;
            if let Some(t) = trace.as_deref_mut() {
                t.linked(first_node(ot, entry), k, false);
            }
        }
        // A draw-mode packet linked after the polygon at the same entry comes out just
        // before it.
        if let Some(e1) = f.blend_e1(dither)
            && ot.insert(entry, &[e1]).is_ok()
            && let Some(t) = trace.as_deref_mut()
        {
            t.linked(first_node(ot, entry), k, true);
        }
    }
    linked
}
