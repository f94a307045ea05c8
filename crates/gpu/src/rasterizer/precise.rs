//! A non-hardware triangle path for accuracy studies: sub-pixel vertex positions and
//! perspective-correct texture coordinates, neither of which the console has (its vertices
//! are whole pixels and its texture coordinates are stepped affinely in screen space,
//! docs/hardware/gpu.md §2-§3). Everything after the coordinates (texel fetch, CLUT, modulation,
//! dithering, blending, mask) is the hardware pixel pipeline of `shade_pixel`.
//!
//! Coverage: pixel (x, y) is sampled at its integer coordinate; an edge function in 1/16
//! pixel decides, with a top-left rule for samples exactly on an edge. Attributes come from
//! barycentric weights (affine) or weights divided by depth (perspective), rounded like the
//! hardware's +0.5 bias. Integer maths throughout (i128 for the weighted sums).
//!
//! Why this shape: not a hot path. A plain per-pixel loop, about 5x the hardware path's
//! frame time on the default scene (docs/gpu.md, "The non-hardware precise path"), which is
//! never slowed by it.

use super::{PixelEnv, TEX_NONE, shade_pixel};
use crate::color::{DITHER_TABLES, PLAIN_TABLE};
use crate::primitive::Triangle;
use crate::state::DrawState;
use crate::{VRAM_LEN, VRAM_WIDTH};

/// Fractional bits of [`PreciseVertex`] positions.
pub const SUBPIXEL_BITS: u32 = 4;

/// Per-vertex data the hardware does not have.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PreciseVertex {
    /// X in 1/16 pixel (relative to the drawing offset, as packet vertices are).
    pub x: i32,
    /// Y in 1/16 pixel (relative to the drawing offset).
    pub y: i32,
    /// 1/z scaled by 2^24 (any positive scale shared by the three vertices works); used
    /// only for perspective-correct texture coordinates.
    pub inv_z: u32,
}

/// Draw `tri` (colours, texture, blend, dither as for the hardware path) at the sub-pixel
/// positions `at`, with texture coordinates perspective-correct when `PERSPECTIVE` and texels
/// read in the texture cache mode `CACHE` (docs/hardware/gpu.md §10).
pub(super) fn draw<
    const TEX: u8,
    const CACHE: u8,
    const RAW: bool,
    const BLEND: bool,
    const MASK_CHECK: bool,
    const PERSPECTIVE: bool,
>(
    vram: &mut [u16; VRAM_LEN],
    state: &DrawState,
    env: &PixelEnv,
    tri: &Triangle,
    at: &[PreciseVertex; 3],
    cache: &mut crate::texture_cache::TextureCache,
) {
    let p = at.map(|v| (v.x as i64, v.y as i64));
    // Same whole-polygon size drop as the hardware, on whole pixels.
    for (i, j) in [(0, 1), (1, 2), (0, 2)] {
        if ((p[i].0 - p[j].0) >> SUBPIXEL_BITS).abs() >= 1024
            || ((p[i].1 - p[j].1) >> SUBPIXEL_BITS).abs() >= 512
        {
            return;
        }
    }
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    if area == 0 {
        return;
    }
    // Order the vertices so the area is positive (the GPU draws both windings).
    let (order, area) = if area > 0 {
        ([0, 1, 2], area)
    } else {
        ([0, 2, 1], -area)
    };
    let v = order.map(|k| p[k]);
    let attr: [[i64; 5]; 3] = order.map(|k| {
        let t = &tri.vertices[k];
        let c = if tri.gouraud {
            t.color
        } else {
            tri.vertices[0].color
        };
        [
            c[0] as i64,
            c[1] as i64,
            c[2] as i64,
            t.u as i64,
            t.v as i64,
        ]
    });
    let inv_z = order.map(|k| at[k].inv_z.max(1) as i128);
    let one = 1i64 << SUBPIXEL_BITS;
    let area_rect = state.area;
    let min_x =
        (v.iter().map(|q| q.0).min().unwrap_or(0) >> SUBPIXEL_BITS).max(area_rect.left as i64);
    let max_x = ((v.iter().map(|q| q.0).max().unwrap_or(0) + one - 1) >> SUBPIXEL_BITS)
        .min(area_rect.right as i64);
    let min_y =
        (v.iter().map(|q| q.1).min().unwrap_or(0) >> SUBPIXEL_BITS).max(area_rect.top as i64);
    let max_y = ((v.iter().map(|q| q.1).max().unwrap_or(0) + one - 1) >> SUBPIXEL_BITS)
        .min(area_rect.bottom as i64);
    // Edge k runs from v[k] to v[k+1]; its function weights the opposite vertex v[k+2].
    let edges = [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])];
    // Top edges run right (Y down, positive area), left edges run up.
    let top_left = |a: (i64, i64), b: (i64, i64)| (a.1 == b.1 && b.0 > a.0) || b.1 < a.1;
    let bias = edges.map(|(a, b)| if top_left(a, b) { 0 } else { -1 });
    let flat = tri.vertices[0].color.map(|c| c as i32);
    for y in min_y..=max_y {
        let sy = y << SUBPIXEL_BITS;
        let row = ((y & 511) as usize) * VRAM_WIDTH;
        for x in min_x..=max_x {
            let sx = x << SUBPIXEL_BITS;
            let mut w = [0i64; 3];
            let mut inside = true;
            for (k, (a, b)) in edges.iter().enumerate() {
                let e = (b.0 - a.0) * (sy - a.1) - (b.1 - a.1) * (sx - a.0);
                if e + bias[k] < 0 {
                    inside = false;
                    break;
                }
                w[k] = e;
            }
            if !inside {
                continue;
            }
            // Weight of vertex i is the edge function of the edge opposite it.
            let weight = [w[1], w[2], w[0]];
            let value = |i: usize, perspective: bool| -> i32 {
                let (num, den) = if perspective {
                    (0..3).fold((0i128, 0i128), |(n, d), k| {
                        let wk = weight[k] as i128 * inv_z[k];
                        (n + wk * attr[k][i] as i128, d + wk)
                    })
                } else {
                    (
                        (0..3).map(|k| weight[k] as i128 * attr[k][i] as i128).sum(),
                        area as i128,
                    )
                };
                if den <= 0 {
                    return 0;
                }
                ((2 * num + den) / (2 * den)) as i32
            };
            let rgb = if tri.gouraud {
                [value(0, false), value(1, false), value(2, false)]
            } else {
                flat
            };
            let (u, tv) = if TEX == TEX_NONE {
                (0, 0)
            } else {
                (value(3, PERSPECTIVE) as u8, value(4, PERSPECTIVE) as u8)
            };
            let shade = if tri.dither {
                &DITHER_TABLES[(y & 3) as usize][(x & 3) as usize]
            } else {
                &PLAIN_TABLE
            };
            shade_pixel::<TEX, RAW, BLEND, MASK_CHECK, CACHE>(
                vram,
                row + (x & 1023) as usize,
                rgb,
                u,
                tv,
                shade,
                env,
                None,
                cache,
            );
        }
    }
}
