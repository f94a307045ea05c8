//! What the rasterizer does with a primitive before drawing any pixel: the size limit, the
//! zero-area test and the drawing-area clip, and the bounds of what it draws
//! (docs/hardware/gpu.md §3.2, §3.5, §4, §5). The draw routines and `decode` run the same
//! tests.
//!
//! Why this shape: the tests run once per primitive on wrapped integer corners, before any
//! set-up, so a dropped primitive costs no edge or gradient work; they are apart from the
//! draw routines so that `decode` reports exactly their verdicts.

use super::{rectangle, wrap11};
use crate::primitive::{Line, Rectangle, Triangle};
use crate::state::DrawingArea;

/// Why the rasterizer draws nothing of a primitive (docs/hardware/gpu.md §3-§5).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DropReason {
    /// A vertex pair is 1024 or more apart in X or 512 or more in Y, after the drawing
    /// offset and the 11-bit wrap: the whole triangle or line is dropped (docs/hardware/gpu.md §3.2, §4).
    SizeLimit,
    /// A triangle whose vertices are collinear (the gradient denominator is 0, docs/hardware/gpu.md §3.6),
    /// or a rectangle of width or height 0 (docs/hardware/gpu.md §5).
    ZeroArea,
    /// The primitive's bounding box lies entirely outside the drawing area (E3/E4), so no
    /// pixel survives the clip (docs/hardware/gpu.md §3.5, §4, §5).
    Clipped,
}

/// An inclusive VRAM rectangle: every pixel a primitive can write lies inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelBounds {
    /// Leftmost column.
    pub left: u16,
    /// Top line.
    pub top: u16,
    /// Rightmost column (inclusive).
    pub right: u16,
    /// Bottom line (inclusive).
    pub bottom: u16,
}

impl PixelBounds {
    /// Width in pixels.
    pub fn width(&self) -> usize {
        usize::from(self.right.saturating_sub(self.left)) + 1
    }
    /// Height in lines.
    pub fn height(&self) -> usize {
        usize::from(self.bottom.saturating_sub(self.top)) + 1
    }
}

/// What the rasterizer does with a primitive, decided before any pixel is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Coverage {
    /// Rasterized; no pixel outside these bounds is written (a thin triangle may still
    /// cover no pixel).
    Drawn(PixelBounds),
    /// Nothing drawn, for this reason.
    Dropped(DropReason),
}

impl Coverage {
    /// The drop reason, if the primitive is not drawn.
    pub fn dropped(&self) -> Option<DropReason> {
        match self {
            Coverage::Drawn(_) => None,
            Coverage::Dropped(r) => Some(*r),
        }
    }
}

/// The size-drop test on wrapped vertices (docs/hardware/gpu.md §3.2, §4).
#[inline(always)]
pub(super) fn exceeds_size_limit(a: (i32, i32), b: (i32, i32)) -> bool {
    (a.0 - b.0).abs() >= 1024 || (a.1 - b.1).abs() >= 512
}

/// Clip an inclusive box of wrapped coordinates to the drawing area.
#[inline(always)]
fn clip_box(x0: i32, x1: i32, y0: i32, y1: i32, area: &DrawingArea) -> Coverage {
    let left = x0.max(area.left as i32);
    let right = x1.min(area.right as i32);
    let top = y0.max(area.top as i32);
    let bottom = y1.min(area.bottom as i32);
    if left > right || top > bottom {
        return Coverage::Dropped(DropReason::Clipped);
    }
    // The area is at most 1023x511, so the clipped box fits u16.
    Coverage::Drawn(PixelBounds {
        left: left as u16,
        top: top as u16,
        right: right as u16,
        bottom: bottom as u16,
    })
}

/// The triangle tests on wrapped vertices: size drop, zero area, drawing-area clip. Rows
/// `[min y, max y)` and columns `[min x, max x)` bound the spans (docs/hardware/gpu.md §3.4-§3.5), so
/// the inclusive box of the vertices contains every drawn pixel.
#[inline(always)]
pub(super) fn triangle_coverage(p: [(i32, i32); 3], area: &DrawingArea) -> Coverage {
    let [a, b, c] = p;
    if exceeds_size_limit(a, b) || exceeds_size_limit(b, c) || exceeds_size_limit(a, c) {
        return Coverage::Dropped(DropReason::SizeLimit);
    }
    // Twice the signed area: the gradient denominator up to sign (docs/hardware/gpu.md §3.6).
    let cross = (b.0 - a.0) as i64 * (c.1 - b.1) as i64 - (c.0 - b.0) as i64 * (b.1 - a.1) as i64;
    if cross == 0 {
        return Coverage::Dropped(DropReason::ZeroArea);
    }
    clip_box(
        a.0.min(b.0).min(c.0),
        a.0.max(b.0).max(c.0),
        a.1.min(b.1).min(c.1),
        a.1.max(b.1).max(c.1),
        area,
    )
}

/// The line tests on wrapped endpoints: size drop, drawing-area clip (docs/hardware/gpu.md §4). Points
/// lie between the endpoints; negative positions wrap to 1024 and above (`& 2047`), past
/// any drawing area.
#[inline(always)]
pub(super) fn line_coverage(p: [(i32, i32); 2], area: &DrawingArea) -> Coverage {
    let [a, b] = p;
    if exceeds_size_limit(a, b) {
        return Coverage::Dropped(DropReason::SizeLimit);
    }
    clip_box(a.0.min(b.0), a.0.max(b.0), a.1.min(b.1), a.1.max(b.1), area)
}

/// What the rasterizer does with a triangle under a drawing area (docs/hardware/gpu.md §3): the same
/// tests the triangle drawing routines apply before drawing.
pub fn classify_triangle(tri: &Triangle, area: &DrawingArea) -> Coverage {
    let v = tri.vertices.map(|p| (wrap11(p.x), wrap11(p.y)));
    triangle_coverage(v, area)
}

/// What the rasterizer does with a line segment under a drawing area (docs/hardware/gpu.md §4): the
/// same tests the line routine applies before drawing.
pub fn classify_line(line: &Line, area: &DrawingArea) -> Coverage {
    let v = line.vertices.map(|p| (wrap11(p.x), wrap11(p.y)));
    line_coverage(v, area)
}

/// What the rasterizer does with a rectangle under a drawing area (docs/hardware/gpu.md §5): the same
/// clip the rectangle routine computes.
pub fn classify_rectangle(rect: &Rectangle, area: &DrawingArea) -> Coverage {
    if rect.width == 0 || rect.height == 0 {
        return Coverage::Dropped(DropReason::ZeroArea);
    }
    match rectangle::clip(rect, area) {
        Some((x_start, x_end, y_start, y_end)) => {
            clip_box(x_start, x_end - 1, y_start, y_end - 1, area)
        }
        None => Coverage::Dropped(DropReason::Clipped),
    }
}
