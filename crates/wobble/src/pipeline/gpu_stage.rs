//! GPU submission: the drawing environment and background fill for the back buffer, the
//! ordering-table walk into the GPU (or, with the non-hardware knobs, the precise
//! rasterizer in the same order), the display flip, and texture uploads (GP0 A0h).

use super::Renderer;
use super::gte_stage::ProjectedFace;
use gpu::rasterizer::precise::{PreciseVertex, SUBPIXEL_BITS};
use gpu::texture::ClutCache;
use gpu::{BlendMode, ClutAttr, Gpu, Texpage};

/// Frame-wide settings of the precise path.
#[derive(Clone, Copy)]
struct PreciseFrame {
    /// Drawing offset Y of the back buffer.
    offset_y: i32,
    /// E1 dithering.
    dither: bool,
    /// Perspective-correct texture coordinates.
    perspective: bool,
}

/// Draw one polygon through the non-hardware precise rasterizer: the same colours, texture,
/// blending and dithering a GP0 packet would carry, at sub-pixel positions.
fn draw_precise(
    gpu: &mut Gpu,
    state: &gpu::state::DrawState,
    clut: &mut ClutCache,
    f: &ProjectedFace,
    precise: &[PreciseVertex; 4],
    place: PreciseFrame,
) {
    let PreciseFrame {
        offset_y,
        dither,
        perspective,
    } = place;
    let texture = f.texture.map(|(clut_attr, tpage)| {
        let (page, clut) = (Texpage::from_bits(tpage), ClutAttr::from_bits(clut_attr));
        gpu::primitive::Texture {
            page_x: page.page_x,
            page_y: page.page_y,
            depth: page.depth,
            clut_x: clut.x,
            clut_y: clut.y,
            raw: false,
        }
    });
    let n = if f.quad { 4 } else { 3 };
    let gouraud = f.color[1..n].iter().any(|c| *c != f.color[0]);
    let blend = f.blend.map(|b| BlendMode::from_bits(u32::from(b)));
    let vertex = |k: usize| gpu::primitive::Vertex {
        x: f.xy[k].0 as i32,
        y: f.xy[k].1 as i32,
        color: f.color[k],
        u: f.uv[k].0,
        v: f.uv[k].1,
    };
    let at = |k: usize| PreciseVertex {
        y: precise[k].y + (offset_y << SUBPIXEL_BITS),
        ..precise[k]
    };
    let triangles: &[[usize; 3]] = if f.quad {
        &[[0, 1, 2], [1, 2, 3]]
    } else {
        &[[0, 1, 2]]
    };
    for t in triangles {
        let tri = gpu::primitive::Triangle {
            vertices: t.map(vertex),
            gouraud,
            texture,
            blend,
            dither: dither && gpu::primitive::dither_applies(gouraud, texture.is_some(), false),
        };
        gpu::rasterizer::draw_triangle_precise(
            gpu.vram_mut(),
            state,
            clut,
            &tri,
            &t.map(at),
            perspective,
        );
    }
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
            let state = *gpu.draw_state();
            let (scratch, at, clut, perspective) = (
                &self.scratch,
                &self.precise_vertices,
                &mut self.clut,
                self.options.perspective_uv,
            );
            let _ = self.ot.walk(|words| {
                let i = words.first().map_or(usize::MAX, |&i| i as usize);
                if let (Some(f), Some(at)) = (scratch.get(i), at.get(i)) {
                    let place = PreciseFrame {
                        offset_y: buffer_y as i32,
                        dither,
                        perspective,
                    };
                    draw_precise(gpu, &state, clut, f, at, place);
                }
            });
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
