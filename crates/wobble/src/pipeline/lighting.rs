//! Vertex colours (docs/pipeline.md step 5): NCCT/NCCS with a light, NCDT/NCDS with light
//! and fog, DPCS with fog only; on a mesh face's shared vertices, once per distinct normal
//! (and fade factor) a frame.
//!
//! Why this shape: NCCS/NCDS depend on a vertex through its normal alone, so a normal is lit
//! once a frame (the benchmark wall's 1,600 vertices share one normal: one NCDS a frame
//! instead of 1,600; docs/pipeline.md, "Benchmarks"); colours leave as GP0 colour words, and
//! `light_shared` is always inlined into the stage, where as a call it cost about 77
//! instructions a polygon (docs/performance.md, "Pipeline frames").

use super::polygon::rgb_word;
use crate::scene::prepared::PreparedFace;
use gte::typed::{Geometry, I4F12, Vector3};

/// One of an object's distinct normals, and its colour once a drawn face has lit it.
#[derive(Clone, Copy, Debug)]
pub(super) struct LitNormal {
    /// What `color` was computed for: the IR0 bits NCDS faded it by (0 for NCCS, which
    /// does not fade), or [`UNLIT`].
    lit: i32,
    /// R in bits 0-7, G 8-15, B 16-23.
    color: u32,
}

impl Default for LitNormal {
    fn default() -> Self {
        Self {
            lit: UNLIT,
            color: 0,
        }
    }
}

/// [`LitNormal::lit`] of a normal no face has lit yet this frame.
const UNLIT: i32 = -1;

/// Vertex colours: NCCT/NCCS with a light, NCDT/NCDS with light and fog, DPCS with fog only.
#[inline]
pub(super) fn light(
    g: &mut Geometry,
    (lit, fogged): (bool, bool),
    face: &PreparedFace,
    base: [u8; 3],
    ir0: I4F12,
) -> [[u8; 3]; 4] {
    let v = &face.v;
    let mut color = [base; 4];
    let normals = [v[0].normal, v[1].normal, v[2].normal];
    match (lit, fogged) {
        (true, false) => {
            let c = g.normal_color_color_triple(normals, base);
            color[..3].copy_from_slice(&c);
            if face.quad {
                color[3] = g.normal_color_color(v[3].normal, base);
            }
        }
        // NCDT/NCDS fade by IR0 as the last RTPT/RTPS left it: one factor
        // for the whole polygon, from its last vertex (docs/hardware/gte.md §5 step 7).
        (true, true) => {
            let c = g.normal_color_depth_triple(normals, base);
            color[..3].copy_from_slice(&c);
            if face.quad {
                color[3] = g.normal_color_depth(v[3].normal, base);
            }
        }
        (false, true) => color = [g.depth_cue(base, ir0); 4],
        (false, false) => {}
    }
    color
}

/// [`light`] for a mesh face from its shared vertices: NCCS once per distinct normal a
/// frame; with fog, NCDS with IR0 loaded with the face's factor (its last vertex's IR0, what
/// NCDT reads after RTPT, docs/hardware/gte.md §5.7), once per normal and factor: a normal
/// keeps the colour of the last factor it was faded by. NCCT and NCDT are NCCS and NCDS for
/// each of three normals (§8), so the colours are the same.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn light_shared(
    g: &mut Geometry,
    (lit, fogged): (bool, bool),
    cache: &mut [LitNormal],
    (normals, normal_of): (&[Vector3], &[u32]),
    (indices, quad): (&[u32; 4], bool),
    base: [u8; 3],
    ir0: I4F12,
) -> [u32; 4] {
    let flat = rgb_word(base);
    match (lit, fogged) {
        (true, _) => {
            let key = if fogged { i32::from(ir0.to_bits()) } else { 0 };
            let mut ir0_loaded = false;
            let mut vertex = |i: u32| {
                let Some(&m) = normal_of.get(i as usize) else {
                    return flat;
                };
                let Some(entry) = cache.get_mut(m as usize) else {
                    return flat;
                };
                if entry.lit != key {
                    let normal = normals.get(m as usize).copied().unwrap_or_default();
                    entry.color = rgb_word(if fogged {
                        if !ir0_loaded {
                            g.gte_mut().write_data(8, ir0.to_bits() as i32 as u32);
                            ir0_loaded = true;
                        }
                        g.normal_color_depth(normal, base)
                    } else {
                        g.normal_color_color(normal, base)
                    });
                    entry.lit = key;
                }
                entry.color
            };
            // The four words are made in registers and returned as one value.
            let [a, b, c] = [vertex(indices[0]), vertex(indices[1]), vertex(indices[2])];
            let d = if quad { vertex(indices[3]) } else { flat };
            [a, b, c, d]
        }
        (false, true) => [rgb_word(g.depth_cue(base, ir0)); 4],
        (false, false) => [flat; 4],
    }
}
