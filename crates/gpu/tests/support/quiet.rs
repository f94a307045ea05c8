//! A GPU without video timing events, for tests that time the drawing side.

use gpu::Gpu;

/// A GPU whose video timing reports no events (a zero-width horizontal range is an endless
/// hblank, a vertical range past the last line has no vblank edge; docs/hardware/timing.md
/// §5, §6), so the next event is the drawing side's.
pub fn quiet() -> Gpu {
    let mut g = Gpu::new();
    g.gp1(0x0600_0000);
    g.gp1(0x07FF_FFFF);
    g
}
