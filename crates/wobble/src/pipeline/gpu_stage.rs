//! GPU submission: the drawing environment and background fill for the back buffer, the
//! ordering-table walk into the GPU (or, with the non-hardware knobs, the precise
//! rasterizer in the same order), the display flip, and texture uploads (GP0 A0h).

use super::Renderer;
#[cfg(feature = "accuracy-knobs")]
use super::polygon::ProjectedFace;
#[cfg(feature = "accuracy-knobs")]
use super::precise::SubpixelVertex;
use gpu::Gpu;

/// Draw one polygon through the GPU's non-hardware precise path: the same GP0 packet (and
/// blend-mode word) the ordering table would carry, at sub-pixel positions.
#[cfg(feature = "accuracy-knobs")]
fn draw_precise(
    gpu: &mut Gpu,
    f: &ProjectedFace,
    at: &[SubpixelVertex; 4],
    dither: bool,
    perspective: bool,
) {
    if let Some(e1) = f.blend_e1(dither) {
        gpu.gp0(e1);
    }
    let mut packet = [0u32; 12];
    let len = f.packet(&mut packet);
    let n = if f.quad { 4 } else { 3 };
    let at = at.map(|v| gpu::precise::PreciseVertex {
        x: v.x,
        y: v.y,
        inv_z: v.inv_z,
    });
    // The packet and positions are built together here, so their lengths agree.
    let _ = gpu.draw_polygon_precise(&packet[..len], &at[..n], perspective);
}

impl Renderer {
    pub(super) fn gpu_stage(&mut self, frame: u32) {
        let screen = self.scene.screen;
        let buffer_y = (frame % 2) * screen.height as u32;
        let dither = self.options.dither.unwrap_or(screen.dither);
        let gpu = &mut self.gpu;
        gpu.gp0_words(&frame_environment(&screen, buffer_y, dither));
        // Bad links cannot occur in a table this renderer built; a walk error leaves the
        // frame partly drawn rather than stopping the renderer.
        if self.options.precise() {
            #[cfg(feature = "accuracy-knobs")]
            {
                let (scratch, at, perspective) = (
                    &self.scratch,
                    &self.precise_vertices,
                    self.options.perspective_uv,
                );
                let _ = self.ot.walk(|words| {
                    let i = words.first().map_or(usize::MAX, |&i| i as usize);
                    if let (Some(f), Some(at)) = (scratch.get(i), at.get(i)) {
                        draw_precise(gpu, f, at, dither, perspective);
                    }
                });
            }
        } else {
            let _ = self.ot.walk_into(gpu);
        }
        gpu.gp1(display_word(buffer_y));
        self.display = gpu.display_area();
        self.display.width = screen.width;
        self.display.height = screen.height;
    }
}

/// Upload halfwords into a `width`-halfword-wide VRAM rectangle at (x, y) with GP0(A0h).
pub(super) fn upload(gpu: &mut Gpu, x: u16, y: u16, width: usize, halfwords: &[u16]) {
    if width == 0 || halfwords.is_empty() {
        return;
    }
    let height = halfwords.len() / width;
    gpu.gp0_words(&[
        0xA000_0000,
        (y as u32) << 16 | x as u32,
        (height as u32) << 16 | width as u32,
    ]);
    for pair in halfwords.chunks(2) {
        let lo = pair[0] as u32;
        let hi = pair.get(1).copied().unwrap_or(0) as u32;
        gpu.gp0(hi << 16 | lo);
    }
}

/// The GP0 words that start a frame in the back buffer at line `buffer_y`: draw mode,
/// texture window, drawing area, offset, mask, and a fill with the background colour.
pub(super) fn frame_environment(
    screen: &crate::scene::Screen,
    buffer_y: u32,
    dither: bool,
) -> [u32; 9] {
    let (w, h) = (screen.width as u32, screen.height as u32);
    let [r, g, b] = screen.background;
    [
        0xE100_0000 | (dither as u32) << 9,
        0xE200_0000,
        0xE300_0000 | buffer_y << 10,
        0xE400_0000 | (buffer_y + h - 1) << 10 | (w - 1),
        0xE500_0000 | (buffer_y & 0x7FF) << 11,
        0xE600_0000,
        0x0200_0000 | r as u32 | (g as u32) << 8 | (b as u32) << 16,
        buffer_y << 16,
        h << 16 | w,
    ]
}

/// GP1(05h): display the buffer at line `buffer_y`.
pub(super) fn display_word(buffer_y: u32) -> u32 {
    0x0500_0000 | buffer_y << 10
}
