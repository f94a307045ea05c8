//! Transform and project (docs/pipeline.md steps 2-3): RTPT (+ RTPS) and NCLIP on a
//! polygon's own vertices, or one RTPS per shared vertex of an object into a scratch list
//! and NCLIP on a mesh face's vertices from it.
//!
//! Why this shape: a vertex shared by faces is projected once a frame, into a list the faces
//! index, and NCLIP takes SXY0-2 from the words RTPS left; NCLIP and AVSZ stay calls through
//! the typed API, as inlining them as well cost instructions (8.79 M against 8.63 M a wall
//! frame, docs/performance.md, "Pipeline frames").

use super::precise::SUBPIXEL_BITS;
use crate::scene::prepared::{PreparedFace, SharedVertex};
use gte::Flag;
use gte::typed::{Geometry, I4F12};

/// A polygon's vertices after RTPT/RTPS and NCLIP, before the clip verdict.
#[derive(Default)]
pub(super) struct Transformed {
    pub(super) flag: Flag,
    pub(super) area: i32,
    pub(super) xy: [(i16, i16); 4],
    pub(super) sz: [u16; 4],
    pub(super) ir0: I4F12,
    /// Screen positions in 1/16 pixel from the 16.16 values before truncation
    /// (docs/hardware/gte.md §5 step 6), when the sub-pixel knob is on.
    pub(super) fine: Option<[(i32, i32); 4]>,
}

/// RTPT (and RTPS for a quad's fourth vertex) and NCLIP; with `subpixel`, one RTPS per
/// vertex instead, keeping each vertex's 16.16 screen position. Three RTPS leave the same
/// SXY/SZ FIFOs, IR0 and FLAG (ORed over the commands) as one RTPT (docs/hardware/gte.md §5).
#[inline]
pub(super) fn transform(g: &mut Geometry, face: &PreparedFace, subpixel: bool) -> Transformed {
    let v = &face.v;
    let n = if face.quad { 4 } else { 3 };
    if subpixel {
        let mut t = Transformed::default();
        let mut fine = [(0, 0); 4];
        for k in 0..n {
            let s = g.project_subpixel(v[k].position);
            let p = s.projected;
            t.flag = t.flag.union(p.flag);
            t.xy[k] = (p.x, p.y);
            t.sz[k] = p.sz;
            t.ir0 = p.ir0;
            fine[k] = (
                s.x.to_bits() >> (16 - SUBPIXEL_BITS),
                s.y.to_bits() >> (16 - SUBPIXEL_BITS),
            );
            if k == 2 {
                t.area = g.nclip_current();
            }
        }
        t.fine = Some(fine);
        return t;
    }
    let p = g.project_triangle([v[0].position, v[1].position, v[2].position]);
    let area = g.nclip_current();
    let mut t = Transformed {
        flag: p.flag,
        area,
        xy: [p.xy[0], p.xy[1], p.xy[2], (0, 0)],
        sz: [p.sz[0], p.sz[1], p.sz[2], 0],
        ir0: p.ir0,
        fine: None,
    };
    if face.quad {
        let q = g.project(v[3].position);
        t.flag = t.flag.union(q.flag);
        t.xy[3] = (q.x, q.y);
        t.sz[3] = q.sz;
        t.ir0 = q.ir0;
    }
    t
}

/// A shared vertex after its RTPS.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct SharedProjection {
    xy: (i16, i16),
    /// SXY as the GTE holds it: X in bits 0-15, Y in bits 16-31.
    sxy: u32,
    sz: u16,
    ir0: I4F12,
    flag: Flag,
}

/// One RTPS per shared vertex of an object, as games run RTPS/RTPT over a vertex list into
/// a scratch buffer. Each vertex gets its SXY, SZ, IR0 and FLAG from its own command: what
/// RTPT leaves for it, as its steps 5.1-5.6 run per vertex (docs/hardware/gte.md §5).
///
/// As a game's loop does it: V0 loaded (VXY0, VZ0), RTPS, then SXY2, SZ3, IR0 and FLAG read
/// back from their registers.
pub(super) fn project_shared(
    g: &mut Geometry,
    vertices: &[SharedVertex],
    out: &mut Vec<SharedProjection>,
) {
    out.clear();
    let gte = g.gte_mut();
    out.extend(vertices.iter().map(|v| {
        let p = v.position;
        gte.write_data(0, u32::from(p.x as u16) | u32::from(p.y as u16) << 16);
        gte.write_data(1, p.z as i32 as u32);
        gte.execute(RTPS);
        let sxy = gte.read_data(14);
        SharedProjection {
            xy: (sxy as u16 as i16, (sxy >> 16) as u16 as i16),
            sxy,
            sz: gte.read_data(19) as u16,
            ir0: I4F12::from_bits(gte.read_data(8) as u16 as i16),
            flag: gte.flag(),
        }
    }));
}

/// What an index outside the projected vertices reads (none does: the indices are the
/// object's own).
static UNPROJECTED: SharedProjection = SharedProjection {
    xy: (0, 0),
    sxy: 0,
    sz: 0,
    ir0: I4F12::ZERO,
    flag: Flag::EMPTY,
};

/// The RTPS command word (sf = 1, as [`Geometry::project`] issues it).
const RTPS: u32 = gte::typed::command(gte::Opcode::Rtps);

/// A mesh face's vertices from their RTPS, and NCLIP on the first three loaded into SXY0-2.
///
/// Equal to [`transform`] for the clip verdict: FLAG is the OR of the vertices' FLAGs. The
/// verdict reads only SZ3 saturation, divide overflow and SX2/SY2 saturation, which RTPT
/// sets per vertex (docs/hardware/gte.md §5.4-5.6, §6); RTPT runs the depth cue (§5.7, IR0
/// saturation and MAC0 flags) for its last vertex only, RTPS for each, so those bits may
/// differ and are not read. IR0 is the last vertex's, SXY and SZ the vertices' own, and
/// NCLIP is a function of SXY0-2 alone (§7).
#[inline(always)]
pub(super) fn transform_shared(
    g: &mut Geometry,
    shared: &[SharedProjection],
    indices: &[u32; 4],
    quad: bool,
) -> Transformed {
    let n = if quad { 4 } else { 3 };
    let mut t = Transformed::default();
    let mut sxy = [0u32; 3];
    for (k, &i) in indices.iter().enumerate().take(n) {
        let v = shared.get(i as usize).unwrap_or(&UNPROJECTED);
        t.flag = t.flag.union(v.flag);
        t.xy[k] = v.xy;
        t.sz[k] = v.sz;
        t.ir0 = v.ir0;
        if let Some(w) = sxy.get_mut(k) {
            *w = v.sxy;
        }
    }
    // SXY0-2 take the register words as RTPS left them.
    let gte = g.gte_mut();
    for (r, w) in (12..).zip(sxy) {
        gte.write_data(r, w);
    }
    t.area = g.nclip_current();
    t
}
