//! Whole-polygon clipping after projection: a polygon is dropped whole (a vertex behind or too
//! near the camera, a saturated screen position, a size the GPU would refuse), culled as a
//! back face, off screen, or drawn; no polygon is cut at the screen edge (the GPU clips
//! pixels to the drawing area).
//!
//! Why this shape: the verdict carries only the polygon's extent, its positions, screen Z and
//! IR0 staying with the projection rather than being copied through it (128 K fewer
//! instructions per wall frame, docs/performance.md, "Pipeline frames"), and each triangle's
//! bounding box is taken once (docs/pipeline.md, "Benchmarks").

use gte::Flag;

/// FLAG bits that discard a polygon whole: SZ3 saturated (a vertex behind the camera, SZ
/// clamped to 0), divide overflow (SZ3 <= H/2, too near), SX2/SY2 saturated (docs/hardware/gte.md §3,
/// §5 steps 4 and 6, §6).
const DROP_FLAGS: Flag = Flag::DIVIDE_OVERFLOW
    .union(Flag::SX2_SATURATED)
    .union(Flag::SY2_SATURATED)
    .union(Flag::SZ3_OTZ_SATURATED);

/// What the GTE stage decides for one polygon.
#[derive(Clone, Copy, Debug)]
pub(super) enum Verdict {
    /// Discarded whole: a vertex behind or too near the camera (SZ3 saturated, divide
    /// overflow), a saturated SX/SY, or a size the GPU would drop (docs/hardware/gpu.md §3).
    Drop(super::trace::DropCause),
    /// Back face: NCLIP <= 0, the first three vertices not clockwise on screen (docs/hardware/gte.md §7).
    Cull,
    /// Entirely outside the screen.
    Offscreen,
    /// To be drawn: the larger side of its bounding box.
    Draw { extent: i32 },
}

/// Screen bounding box (min x, max x, min y, max y) of three vertices.
#[inline(always)]
fn bounds3(p: [(i16, i16); 3]) -> (i32, i32, i32, i32) {
    let [a, b, c] = p.map(|(x, y)| (i32::from(x), i32::from(y)));
    (
        a.0.min(b.0).min(c.0),
        a.0.max(b.0).max(c.0),
        a.1.min(b.1).min(c.1),
        a.1.max(b.1).max(c.1),
    )
}

/// The GPU drops a triangle with any vertex pair |dx| >= 1024 or |dy| >= 512 (docs/hardware/gpu.md §3):
/// the extent of its bounding box.
#[inline(always)]
fn gpu_drops((x0, x1, y0, y1): (i32, i32, i32, i32)) -> bool {
    x1 - x0 >= 1024 || y1 - y0 >= 512
}

/// The verdict for a projected polygon: FLAG of its RTPT/RTPS, the NCLIP area of its
/// first three vertices and its screen positions (the fourth unused for a triangle), on a
/// `w` x `h` screen.
#[inline]
pub(super) fn classify(
    flag: Flag,
    area: i32,
    xy: [(i16, i16); 4],
    quad: bool,
    (w, h): (i32, i32),
) -> Verdict {
    if flag.intersects(DROP_FLAGS) {
        return Verdict::Drop(super::trace::DropCause::NearPlane);
    }
    if area <= 0 {
        return Verdict::Cull;
    }
    // A quad is drawn as the triangles v0 v1 v2 and v1 v2 v3 (docs/hardware/gpu.md §3).
    let first = bounds3([xy[0], xy[1], xy[2]]);
    let second = quad.then(|| bounds3([xy[1], xy[2], xy[3]]));
    let (x0, x1, y0, y1) = match second {
        Some(s) => (
            first.0.min(s.0),
            first.1.max(s.1),
            first.2.min(s.2),
            first.3.max(s.3),
        ),
        None => first,
    };
    if x1 < 0 || x0 >= w || y1 < 0 || y0 >= h {
        return Verdict::Offscreen;
    }
    if gpu_drops(first) || second.is_some_and(gpu_drops) {
        return Verdict::Drop(super::trace::DropCause::SizeLimit);
    }
    Verdict::Draw {
        extent: (x1 - x0).max(y1 - y0),
    }
}
