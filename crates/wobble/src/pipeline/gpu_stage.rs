//! GPU submission: the drawing environment and background fill for the back buffer, the
//! ordering-table walk into the GPU (or, with the non-hardware knobs, the precise
//! rasterizer in the same order), the display flip, and texture uploads (GP0 A0h).

use super::Renderer;
#[cfg(feature = "accuracy-knobs")]
use super::polygon::ProjectedFace;
#[cfg(feature = "accuracy-knobs")]
use super::precise::SubpixelVertex;
use gpu::{DisplayArea, Gpu};

/// GP1(00h): reset the GPU.
pub(super) const GP1_RESET: u32 = 0x0000_0000;
/// GP1(03h) with bit 0 clear: display on.
const GP1_DISPLAY_ON: u32 = 0x0300_0000;

/// GP1(08h) for a screen `width` pixels wide: the width by bits 0-1 (256, 320, 512, 640)
/// or bit 6 (368, also taken for any other width, which `Scene::validate` refuses), 240
/// lines, NTSC, 15-bit colour, no interlace (docs/hardware/timing.md §4, §7).
fn gp1_display_mode(width: u16) -> u32 {
    let bits = match width {
        256 => 0,
        320 => 1,
        512 => 2,
        640 => 3,
        _ => 0x40,
    };
    0x0800_0000 | bits
}

/// Turn the display on for `screen`: its width's display mode, then display enable. The
/// display area the renderer reads out (`Renderer::image`), at the screen's size.
pub(super) fn start_display(gpu: &mut Gpu, screen: &crate::scene::Screen) -> DisplayArea {
    gpu.gp1(gp1_display_mode(screen.width));
    gpu.gp1(GP1_DISPLAY_ON);
    DisplayArea {
        x: 0,
        y: 0,
        width: screen.width,
        height: screen.height,
        color_24bit: false,
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// The display mode selects each width through GP1(08h) bits 0-1 and 6, which GPUSTAT
    /// mirrors in bits 17-18 and 16 (docs/hardware/timing.md §7).
    #[test]
    fn display_mode_selects_each_width() {
        for (width, bits_17_18, bit_16) in [
            (256, 0, 0),
            (320, 1, 0),
            (512, 2, 0),
            (640, 3, 0),
            (368, 0, 1),
        ] {
            let mut gpu = Gpu::new();
            gpu.gp1(gp1_display_mode(width));
            let stat = gpu.gpustat();
            assert_eq!(
                (stat >> 17 & 3, stat >> 16 & 1),
                (bits_17_18, bit_16),
                "{width}"
            );
            // 240 lines (bit 19), NTSC (20), 15-bit (21), no interlace (22).
            assert_eq!(stat >> 19 & 0xF, 0, "{width}");
        }
    }
}
