//! A GPU for tests that time the drawing side.

use gpu::Gpu;

/// A GPU with a zero-width display and a vertical range past the last line: no vblank edge
/// (docs/hardware/timing.md §6), an hblank on every line (docs/gpu.md, "Video timing"). Tests
/// that time the drawing side read its end from `cycles_until(EventKind::DrawingDone)`, which
/// no video event comes before.
pub fn quiet() -> Gpu {
    let mut g = Gpu::new();
    g.gp1(0x0600_0000);
    g.gp1(0x07FF_FFFF);
    g
}
