//! Non-hardware drawing for accuracy studies (cargo feature `precise`): a GP0 polygon packet
//! drawn at sub-pixel vertex positions, with perspective-correct texture coordinates on
//! request. The console has neither: its vertices are whole pixels and its texture
//! coordinates step affinely in screen space (docs/hardware/gpu.md §2-§3). Everything after
//! the coordinates (texel fetch, CLUT, modulation, dithering, blending, mask) is the
//! hardware pixel pipeline, so the difference between this path and [`Gpu::gp0_words`] is
//! exactly what whole-pixel vertices and affine texture coordinates cost.
//!
//! Drawing here takes no GPU time, skips interlaced-field rows, and sets no GPUSTAT bit: it is
//! a rendering tool beside the chip, not part of it.

use crate::Gpu;
use crate::command::{Command, Kind, MAX_PACKET};
use crate::gp0::polygon_packet;
use crate::rasterizer::draw_triangle_precise;
pub use crate::rasterizer::precise::{PreciseVertex, SUBPIXEL_BITS};

/// Why [`Gpu::draw_polygon_precise`] refused a packet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PreciseError {
    /// The first word is not a polygon command (20h-3Fh).
    NotPolygon(u32),
    /// The packet's length is not the one its command word gives.
    PacketLength {
        /// Words the command needs.
        expected: usize,
        /// Words given.
        got: usize,
    },
    /// The number of sub-pixel positions is not the polygon's vertex count.
    VertexCount {
        /// 3 or 4.
        expected: usize,
        /// Positions given.
        got: usize,
    },
}

impl core::fmt::Display for PreciseError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            PreciseError::NotPolygon(w) => write!(f, "{w:08X}h is not a polygon command"),
            PreciseError::PacketLength { expected, got } => {
                write!(
                    f,
                    "polygon packet of {got} words; its command needs {expected}"
                )
            }
            PreciseError::VertexCount { expected, got } => {
                write!(
                    f,
                    "{got} sub-pixel positions for a {expected}-vertex polygon"
                )
            }
        }
    }
}

impl core::error::Error for PreciseError {}

impl Gpu {
    /// Draw the GP0 polygon `packet` (command 20h-3Fh and its words, exactly as it would be
    /// written to GP0) with each vertex at the sub-pixel position `at[i]` instead of the
    /// packet's whole-pixel one, and texture coordinates perspective-correct when
    /// `perspective`. Positions are relative to the drawing offset, like packet vertices; the
    /// packet's colours, texture, texpage attribute (which updates the draw mode as on the
    /// console), blending and dithering apply as for [`Gpu::gp0_words`].
    ///
    /// ```
    /// use gpu::Gpu;
    /// use gpu::precise::PreciseVertex;
    /// let mut g = Gpu::new();
    /// g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]); // whole VRAM, offset 0
    /// // A flat red triangle (0,0) (4,0) (0,4), moved right by half a pixel.
    /// let at = [(0, 0), (4, 0), (0, 4)].map(|(x, y)| PreciseVertex { x: x * 16 + 8, y: y * 16, inv_z: 1 });
    /// g.draw_polygon_precise(&[0x2000_00FF, 0, 4, 4 << 16], &at, false).unwrap();
    /// assert_eq!(g.vram().pixel(0, 0), 0); // sample (0, 0) lies left of the edge x = 0.5
    /// assert_eq!(g.vram().pixel(1, 0), 31);
    /// ```
    pub fn draw_polygon_precise(
        &mut self,
        packet: &[u32],
        at: &[PreciseVertex],
        perspective: bool,
    ) -> Result<(), PreciseError> {
        let cmd = packet.first().copied().unwrap_or(0);
        let Kind::Polygon(op) = Command::of(cmd).kind else {
            return Err(PreciseError::NotPolygon(cmd));
        };
        let expected = op.words();
        if packet.len() != expected {
            return Err(PreciseError::PacketLength {
                expected,
                got: packet.len(),
            });
        }
        let vertices = op.vertices();
        if at.len() != vertices {
            return Err(PreciseError::VertexCount {
                expected: vertices,
                got: at.len(),
            });
        }
        let mut words = [0u32; MAX_PACKET];
        for (w, p) in words.iter_mut().zip(packet) {
            *w = *p;
        }
        let decoded = polygon_packet(op, &words, &self.draw, self.texture_disable_allowed);
        self.texture_cache
            .texpage_change(&self.draw.mode, &decoded.mode);
        self.draw.mode = decoded.mode;
        self.prepare_texture_cache(decoded.first.texture.as_ref());
        let (ox, oy) = (
            i32::from(self.draw.offset_x) << SUBPIXEL_BITS,
            i32::from(self.draw.offset_y) << SUBPIXEL_BITS,
        );
        let place = |v: &PreciseVertex| PreciseVertex {
            x: v.x.saturating_add(ox),
            y: v.y.saturating_add(oy),
            inv_z: v.inv_z,
        };
        let first = [place(&at[0]), place(&at[1]), place(&at[2])];
        draw_triangle_precise(
            &mut self.vram,
            &self.draw,
            &mut self.clut,
            &mut self.texture_cache,
            &decoded.first,
            &first,
            perspective,
        );
        if let (Some(second), Some(v3)) = (&decoded.second, at.get(3)) {
            let at = [first[1], first[2], place(v3)];
            draw_triangle_precise(
                &mut self.vram,
                &self.draw,
                &mut self.clut,
                &mut self.texture_cache,
                second,
                &at,
                perspective,
            );
        }
        Ok(())
    }
}
