//! The non-hardware precise path (`PipelineOptions::precise`, docs/pipeline.md): polygons
//! drawn by the GPU crate's precise rasterizer at sub-pixel positions with 1/Z per vertex,
//! fed the same GP0 packets. No code of it runs on the hardware path.

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
