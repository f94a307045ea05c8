//! The non-hardware precise path (`PipelineOptions::precise`, docs/pipeline.md): polygons
//! drawn by the GPU crate's precise rasterizer at sub-pixel positions with 1/Z per vertex,
//! fed the same GP0 packets, in the order the ordering table would give them (far entries
//! first, and within an entry the polygon linked last first, docs/hardware/gpu.md §2). No
//! code of it runs on the hardware path.

use super::polygon::ProjectedFace;

/// Fractional bits of the sub-pixel screen positions the precise path draws at (1/16 pixel,
/// the GPU's `precise::SUBPIXEL_BITS`).
pub(super) const SUBPIXEL_BITS: u32 = 4;
#[cfg(feature = "accuracy-knobs")]
const _: () = assert!(SUBPIXEL_BITS == gpu::precise::SUBPIXEL_BITS);

/// A vertex for the precise path: position in 1/16 pixel relative to the drawing offset,
/// and 1/Z scaled by 2^24 for perspective-correct texture coordinates. Without the knobs
/// nothing draws them (`PipelineOptions::precise` is always false).
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(not(feature = "accuracy-knobs"), allow(dead_code))]
pub(super) struct SubpixelVertex {
    pub(super) x: i32,
    pub(super) y: i32,
    pub(super) inv_z: u32,
}

/// A polygon's vertices for the precise path: its whole-pixel positions, or the sub-pixel
/// ones (`fine`) where the GTE stage kept them, and 1/SZ of each.
pub(super) fn subpixel_vertices(
    xy: [(i16, i16); 4],
    sz: [u16; 4],
    fine: Option<[(i32, i32); 4]>,
    quad: bool,
) -> [SubpixelVertex; 4] {
    let whole = xy.map(|(x, y)| (i32::from(x) << SUBPIXEL_BITS, i32::from(y) << SUBPIXEL_BITS));
    let positions = fine.unwrap_or(whole);
    let n = if quad { 4 } else { 3 };
    let mut precise = [SubpixelVertex::default(); 4];
    for k in 0..n {
        precise[k] = SubpixelVertex {
            x: positions[k].0,
            y: positions[k].1,
            inv_z: (1u32 << 24) / u32::from(sz[k]).max(1),
        };
    }
    precise
}

/// The indices of `faces` in the order the ordering table's walk would draw them, into
/// `order` (cleared first): far entries first (the highest index), and within one entry the
/// face linked last first, as a packet linked at an entry becomes its first node
/// (docs/hardware/gpu.md §2). Returns how many faces there are.
pub(super) fn depth_order(faces: &[ProjectedFace], order: &mut Vec<u32>) -> usize {
    order.clear();
    order.extend(0..faces.len() as u32);
    order.sort_unstable_by_key(|&i| {
        let entry = faces.get(i as usize).map_or(0, |f| f.ot_index);
        std::cmp::Reverse((entry, i))
    });
    order.len()
}

/// Draw `faces` in `order` through the GPU's precise path, each with the packet (and the
/// blend-mode word before it) the ordering table would carry, at the positions in
/// `vertices` (one entry per face).
#[cfg(feature = "accuracy-knobs")]
pub(super) fn draw(
    gpu: &mut gpu::Gpu,
    (faces, vertices): (&[ProjectedFace], &[[SubpixelVertex; 4]]),
    order: &[u32],
    dither: bool,
    perspective: bool,
) {
    for &i in order {
        let (Some(f), Some(at)) = (faces.get(i as usize), vertices.get(i as usize)) else {
            continue;
        };
        if let Some(e1) = f.blend_e1(dither) {
            gpu.gp0(e1);
        }
        let packet = f.packet();
        let n = if f.quad { 4 } else { 3 };
        let at = at.map(|v| gpu::precise::PreciseVertex {
            x: v.x,
            y: v.y,
            inv_z: v.inv_z,
        });
        // The packet and positions are built together here, so their lengths agree.
        let _ = gpu.draw_polygon_precise(&packet, &at[..n], perspective);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gpu::OrderingTable;

    /// The order is the ordering table's own: faces linked into a table (each as a one-word
    /// packet holding its index) come out of its walk in the order `depth_order` gives,
    /// for faces spread over few entries (many sharing one) and over many.
    #[test]
    fn depth_order_is_the_walk_order() {
        for (count, entries) in [(0usize, 4u16), (1, 4), (50, 3), (400, 2048), (300, 1)] {
            let faces: Vec<ProjectedFace> = (0..count)
                .map(|i| ProjectedFace {
                    ot_index: ((i * 7919) % usize::from(entries)) as u16,
                    ..ProjectedFace::default()
                })
                .collect();
            let mut ot = OrderingTable::new(2048, 2 * count + 2).expect("table");
            for (i, f) in faces.iter().enumerate() {
                ot.insert(usize::from(f.ot_index), &[i as u32])
                    .expect("room");
            }
            let mut walked = Vec::new();
            ot.walk(|words| walked.extend_from_slice(words))
                .expect("walk");
            let mut order = Vec::new();
            assert_eq!(depth_order(&faces, &mut order), count);
            assert_eq!(order, walked, "{count} faces over {entries} entries");
        }
    }
}
