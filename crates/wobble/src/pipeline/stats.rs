//! What one frame did: the polygons examined and each one's end (drawn, culled, off screen,
//! dropped), frames that reached the per-frame cap, and the time in each stage.

use super::ot_stage::MAX_POLYGONS;
use std::time::Duration;

/// What one frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Polygons examined after splitting: each ends drawn, culled, off screen or dropped.
    pub polygons: usize,
    /// Polygons linked into the ordering table and drawn.
    pub drawn: usize,
    /// Back faces removed by NCLIP.
    pub culled: usize,
    /// Polygons entirely off screen.
    pub offscreen: usize,
    /// Polygons dropped whole: a vertex behind the near plane (SZ3 or divide overflow flag),
    /// a saturated SX/SY, or an extent the GPU would drop; also polygons past the
    /// per-frame cap ([`MAX_POLYGONS`]), see `capped`.
    pub dropped: usize,
    /// Frames that filled the polygon list to [`MAX_POLYGONS`]: further polygons in them
    /// were dropped (counted in `dropped`). 0 or 1 for one frame, summed by `accumulate`.
    pub capped: usize,
    /// Time in GTE work (transform, project, cull, light, AVSZ).
    pub gte: Duration,
    /// Time building packets and linking them into the ordering table.
    pub ot: Duration,
    /// Time in the GPU (environment, OT walk, rasterization).
    pub gpu: Duration,
}

impl FrameStats {
    /// Add another frame's counts and times.
    pub fn accumulate(&mut self, other: &FrameStats) {
        self.polygons += other.polygons;
        self.drawn += other.drawn;
        self.culled += other.culled;
        self.offscreen += other.offscreen;
        self.dropped += other.dropped;
        self.capped += other.capped;
        self.gte += other.gte;
        self.ot += other.ot;
        self.gpu += other.gpu;
    }
}

/// What to say when frames reached [`MAX_POLYGONS`]: the cap, why it is there, and how to
/// stay under it. `None` when no frame did.
pub fn cap_message(stats: &FrameStats) -> Option<String> {
    (stats.capped > 0).then(|| {
        format!(
            "{} reached the per-frame cap of {MAX_POLYGONS} polygons (the primitive \
             buffer must fit the console's RAM): polygons past it were dropped. To draw them \
             all, lower the mesh's face count or the tessellation level (`--tessellation 0`, \
             or `tessellation` in the scene), or split the model across frames; the cap \
             itself is `MAX_POLYGONS` in crates/wobble/src/pipeline/ot_stage.rs",
            if stats.capped == 1 {
                "1 frame".to_string()
            } else {
                format!("{} frames", stats.capped)
            }
        )
    })
}
