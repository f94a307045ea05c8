//! Texture sampling: texture window, 4/8/15-bit texel fetch, CLUT lookup and the CLUT cache
//! (gpu.md §7).

/// The latched CLUT (gpu.md §7, "CLUT cache").
#[derive(Clone, Debug, Default)]
pub struct ClutCache {}

impl ClutCache {
    /// GP0(01h): forget the latched CLUT so the next 4/8-bit primitive reloads it.
    pub fn invalidate(&mut self) {}
}
