//! The GTE stage (docs/pipeline.md steps 1-6 and 8): per object, the GTE set-up (RT, TR,
//! light, fog) and one RTPS per shared vertex; per mesh face, NCLIP, the clip verdict,
//! colours and AVSZ3/AVSZ4 for the ordering-table entry, the face split into pieces (each
//! through its own RTPT/RTPS) while tessellation asks; every polygon drawn is appended to the
//! stage's output, a list of [`ProjectedFace`]s.
//!
//! Why this shape: the stage does once per vertex what depends on the vertex alone (RTPS
//! once per shared vertex, NCCS/NCDS once per distinct normal: `projection`, `lighting`),
//! which took the benchmark wall's GTE stage from 3.37 M to 1.76 M instructions a frame
//! (docs/pipeline.md, "Benchmarks"); a polygon's steps (`examine`, `emit`) are inlined into
//! one loop, and the stage's buffers are kept from frame to frame, so a frame allocates
//! nothing once they have grown.

use super::clip::{Verdict, classify};
use super::lighting::{LitNormal, light, light_shared};
use super::object::{PreparedObject, object_light, object_transform};
use super::options::PipelineOptions;
use super::ot_stage::{OT_DEPTH, OT_SHIFT};
use super::polygon::{ProjectedFace, rgb_word};
use super::precise::{SubpixelVertex, subpixel_vertices};
use super::projection::{
    SharedProjection, Transformed, project_shared, transform, transform_shared,
};
use super::stats::FrameStats;
use super::tessellate::SplitStack;
use super::trace::{FaceFate, FaceRecord, FrameRecorder};
use crate::scene::prepared::PreparedFace;
use crate::scene::{Object, Scene};
use gte::typed::{Geometry, I8F8, I8F24, I16F16, Projection};

/// What the GTE stage reads for one frame.
pub(super) struct FrameInput<'a> {
    pub(super) scene: &'a Scene,
    /// The scene's objects, prepared.
    pub(super) objects: &'a [PreparedObject],
    pub(super) options: &'a PipelineOptions,
    pub(super) frame: u32,
    /// Every face through its own RTPT/RTPS (the path split faces take), no vertex shared:
    /// the reference the shared-vertex path is tested against.
    pub(super) per_polygon: bool,
}

/// The buffers the stage works in, kept from frame to frame (cleared, never shrunk).
#[derive(Debug, Default)]
pub(super) struct Workspace {
    /// The current object's vertices after RTPS.
    pub(super) shared: Vec<SharedProjection>,
    /// The current object's distinct normals, and their colours once lit.
    lit: Vec<LitNormal>,
    /// The pieces of the current face waiting to be examined.
    stack: SplitStack,
}

impl Workspace {
    /// Room for objects of up to `vertices` shared vertices.
    pub(super) fn with_capacity(vertices: usize) -> Self {
        Self {
            shared: Vec::with_capacity(vertices),
            lit: Vec::with_capacity(vertices),
            stack: SplitStack::default(),
        }
    }
}

/// The stage's output, in the order the polygons were emitted: each polygon to draw, and
/// for the precise path its vertices. Kept from frame to frame (cleared, never shrunk).
#[derive(Debug)]
pub(super) struct ProjectedFaces {
    pub(super) faces: Vec<ProjectedFace>,
    /// One entry per face when the precise path is on, none otherwise.
    pub(super) precise: Vec<[SubpixelVertex; 4]>,
    /// The most polygons a frame emits.
    capacity: usize,
}

impl ProjectedFaces {
    /// A list for at most `capacity` polygons a frame.
    pub(super) fn with_capacity(capacity: usize) -> Self {
        Self {
            faces: Vec::with_capacity(capacity),
            precise: Vec::new(),
            capacity,
        }
    }

    fn is_full(&self) -> bool {
        self.faces.len() >= self.capacity
    }
}

/// What every polygon of the frame is examined with.
#[derive(Clone, Copy)]
struct Rules {
    /// Screen width and height.
    screen: (i32, i32),
    /// The projection distance H: a vertex with SZ <= H/2 is too near to divide.
    h: u16,
    /// (a light, fog).
    lighting: (bool, bool),
    /// Sub-pixel positions kept (one RTPS per vertex, no shared vertices).
    subpixel: bool,
    /// The precise path's vertices emitted.
    precise: bool,
}

/// The object whose polygons are examined.
struct ObjectPass<'a> {
    index: usize,
    prepared: &'a PreparedObject,
    /// Material colour.
    color: [u8; 3],
    /// Mesh faces from their shared vertices' RTPS.
    share: bool,
}

/// The stage's state for one frame: the GTE, its buffers, its output, the frame's counts
/// and the trace, each borrowed from the caller for the frame.
struct Stage<'a> {
    g: &'a mut Geometry,
    work: &'a mut Workspace,
    out: &'a mut ProjectedFaces,
    stats: &'a mut FrameStats,
    trace: Option<&'a mut FrameRecorder>,
    rules: Rules,
}

/// Run the GTE stage for a frame: every object's polygons examined, those drawn appended to
/// `out` (cleared first), each counted in `stats` and, when tracing, recorded.
pub(super) fn gte_stage(
    input: &FrameInput<'_>,
    g: &mut Geometry,
    work: &mut Workspace,
    out: &mut ProjectedFaces,
    stats: &mut FrameStats,
    trace: Option<&mut FrameRecorder>,
) {
    out.faces.clear();
    out.precise.clear();
    let scene = input.scene;
    set_up_frame(g, scene);
    let share = !input.options.subpixel && !input.per_polygon;
    let mut stage = Stage {
        g,
        work,
        out,
        stats,
        trace,
        rules: Rules {
            screen: (
                i32::from(scene.screen.width),
                i32::from(scene.screen.height),
            ),
            h: scene.camera.h,
            lighting: (scene.light.is_some(), scene.fog.is_some()),
            subpixel: input.options.subpixel,
            precise: input.options.precise(),
        },
    };
    for (index, (object, prepared)) in scene.objects.iter().zip(input.objects).enumerate() {
        set_up_object(stage.g, scene, object, input.frame);
        let pass = ObjectPass {
            index,
            prepared,
            color: object.color,
            share,
        };
        stage.object(&pass);
    }
}

/// The frame's GTE set-up: the screen centre and H (OFX, OFY, H), and with fog DQA/DQB and
/// the far colour FC.
fn set_up_frame(g: &mut Geometry, scene: &Scene) {
    let cam = &scene.camera;
    let (w, h) = (
        i32::from(scene.screen.width),
        i32::from(scene.screen.height),
    );
    let (dqa, dqb) = scene
        .fog
        .and_then(|f| f.coefficients(cam.h))
        .unwrap_or((0, 0));
    g.set_projection(&Projection {
        offset_x: I16F16::from_num(w / 2),
        offset_y: I16F16::from_num(h / 2),
        h: cam.h,
        dqa: I8F8::from_bits(dqa),
        dqb: I8F24::from_bits(dqb),
        ..Projection::default()
    });
    if let Some(fog) = &scene.fog {
        // FC is in colour units of 1/16: a colour C pushes as MAC >> 4 (docs/hardware/gte.md §8).
        g.set_far_color(fog.color.map(|c| i32::from(c) << 4));
    }
}

/// An object's GTE set-up at `frame`: RT and TR, and with a light LLM, LCM and BK.
fn set_up_object(g: &mut Geometry, scene: &Scene, object: &Object, frame: u32) {
    let (rt, tr) = object_transform(scene, object, frame);
    g.set_rotation(&rt);
    g.set_translation(tr);
    if let Some(light) = object_light(scene, object, frame) {
        g.set_light_matrix(&light.directions);
        g.set_light_colors(&light.colors);
        g.set_background_color(light.background);
    }
}

/// Whether a polygon is split again rather than drawn, given its verdict, its SZ values and
/// H. A dropped polygon whose every vertex is too near (SZ <= H/2, behind the camera
/// included: SZ clamps to 0) is not split: its pieces lie between its vertices in depth and
/// would all be dropped too.
fn needs_split(verdict: &Verdict, split_extent: i32, sz: &[u16], h: u16) -> bool {
    match verdict {
        Verdict::Drop(_) => sz.iter().any(|&z| 2 * u32::from(z) > u32::from(h)),
        Verdict::Draw { extent, .. } => *extent > split_extent,
        Verdict::Cull | Verdict::Offscreen => false,
    }
}

/// AVSZ3/AVSZ4 on a polygon's screen Z, and the ordering-table entry of the result.
fn ot_entry(g: &mut Geometry, quad: bool, sz: [u16; 4]) -> u16 {
    let otz = if quad {
        g.average_z4(sz)
    } else {
        g.average_z3([sz[0], sz[1], sz[2]])
    };
    ((otz >> OT_SHIFT) as usize).min(OT_DEPTH - 1) as u16
}

impl Stage<'_> {
    /// All of an object's mesh faces. Its vertices are projected first (one RTPS each), and
    /// its normals start the frame unlit, when the faces share them.
    fn object(&mut self, pass: &ObjectPass<'_>) {
        let mesh = &pass.prepared.mesh;
        if pass.share {
            project_shared(self.g, &mesh.vertices, &mut self.work.shared);
            self.work.lit.clear();
            self.work
                .lit
                .resize(mesh.normals.len(), LitNormal::default());
        }
        for (face_index, face) in mesh.faces.iter().enumerate() {
            self.mesh_face(pass, face_index, face);
        }
    }

    /// A mesh face, and depth first the pieces tessellation splits it into: the face itself
    /// from its shared vertices, the pieces (new vertices) through RTPT/RTPS one at a time,
    /// from the split stack. Each is recorded in the trace.
    fn mesh_face(&mut self, pass: &ObjectPass<'_>, face_index: usize, mesh_face: &PreparedFace) {
        let shared = pass
            .prepared
            .mesh
            .indices
            .get(face_index)
            .filter(|_| pass.share);
        let mut piece;
        let (mut face, mut level, mut indices) = (mesh_face, 0u8, shared);
        loop {
            let fate = self.examine(pass, (face_index, face, level), indices);
            if let Some(t) = self.trace.as_deref_mut() {
                t.face(FaceRecord {
                    object: pass.index,
                    face: face_index,
                    level,
                    fate,
                });
            }
            if fate == FaceFate::Split {
                self.work.stack.push_split(face, level + 1);
            }
            let Some((next, next_level)) = self.work.stack.pop() else {
                break;
            };
            piece = next;
            (face, level, indices) = (&piece, next_level, None);
        }
    }

    /// One polygon through the GTE: RTPT/RTPS (or its shared vertices' results, `indices`)
    /// and NCLIP, the clip verdict, and either a split, a count of a polygon not drawn, or
    /// the polygon emitted. Its fate.
    #[inline(always)]
    fn examine(
        &mut self,
        pass: &ObjectPass<'_>,
        (face_index, face, level): (usize, &PreparedFace, u8),
        indices: Option<&[u32; 4]>,
    ) -> FaceFate {
        let rules = self.rules;
        let t = match indices {
            Some(indices) => transform_shared(self.g, &self.work.shared, indices, face.quad),
            None => transform(self.g, face, rules.subpixel),
        };
        let verdict = classify(t.flag, t.area, t.xy, face.quad, rules.screen);
        if level < pass.prepared.level
            && needs_split(
                &verdict,
                pass.prepared.split_extent,
                &t.sz[..if face.quad { 4 } else { 3 }],
                rules.h,
            )
        {
            return FaceFate::Split;
        }
        let stats = &mut *self.stats;
        stats.polygons += 1;
        match verdict {
            Verdict::Drop(cause) => {
                stats.dropped += 1;
                FaceFate::Dropped(cause)
            }
            Verdict::Cull => {
                stats.culled += 1;
                FaceFate::Culled
            }
            Verdict::Offscreen => {
                stats.offscreen += 1;
                FaceFate::Offscreen
            }
            Verdict::Draw { .. } if self.out.is_full() => {
                stats.dropped += 1;
                FaceFate::Overflow
            }
            Verdict::Draw { .. } => FaceFate::Drawn {
                ot_slot: self.emit(pass, (face_index, face), indices, &t),
            },
        }
    }

    /// A drawn polygon's vertex colours, texels and ordering-table entry, appended to the
    /// output (with its precise-path vertices when the path is on); the entry.
    #[inline(always)]
    fn emit(
        &mut self,
        pass: &ObjectPass<'_>,
        (face_index, face): (usize, &PreparedFace),
        indices: Option<&[u32; 4]>,
        t: &Transformed,
    ) -> u16 {
        let mesh = &pass.prepared.mesh;
        let rules = self.rules;
        let color = match indices {
            Some(indices) => light_shared(
                self.g,
                rules.lighting,
                &mut self.work.lit,
                (&mesh.normals, &mesh.normal_of),
                (indices, face.quad),
                pass.color,
                t.ir0,
            ),
            None => light(self.g, rules.lighting, face, pass.color, t.ir0).map(rgb_word),
        };
        if rules.precise {
            self.out
                .precise
                .push(subpixel_vertices(t.xy, t.sz, t.fine, face.quad));
        }
        // A mesh face's texels are rounded once, when the object is prepared.
        let uv = match indices.and(mesh.texels.get(face_index)) {
            Some(&uv) => uv,
            None => face.v.map(|p| p.texel()),
        };
        let ot_index = ot_entry(self.g, face.quad, t.sz);
        self.out.faces.push(ProjectedFace {
            xy: t.xy,
            color,
            uv,
            quad: face.quad,
            ot_index,
            texture: pass.prepared.texture,
            blend: pass.prepared.blend,
        });
        ot_index
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::precise::SUBPIXEL_BITS;
    use crate::scene::prepared::{PreparedVertex, SharedVertex, normal_table};
    use gte::Flag;
    use gte::typed::Translation;
    use gte::typed::{I4F12, Matrix, Vector3};
    use proptest::prelude::*;

    fn vertex() -> impl Strategy<Value = Vector3> {
        (-2000i16..2000, -2000i16..2000, -2000i16..2000).prop_map(|(x, y, z)| Vector3 { x, y, z })
    }

    /// A 1.3.12 normal, not necessarily of unit length.
    fn normal() -> impl Strategy<Value = Vector3> {
        (-4096i16..=4096, -4096i16..=4096, -4096i16..=4096).prop_map(|(x, y, z)| Vector3 {
            x,
            y,
            z,
        })
    }

    /// A GTE set up as the stage sets it for an object: RT, TR, projection with fog
    /// coefficients, one light (LLM row 0, LCM column 0), BK and FC.
    fn object_geometry(
        angles: (i32, i32, i32),
        tz: i32,
        h: u16,
        (dqa, dqb): (i16, i32),
        (light, color, ambient): ([i16; 3], [i16; 3], [i32; 3]),
        far: [i32; 3],
    ) -> Geometry {
        let mut g = Geometry::new();
        g.set_projection(&Projection {
            offset_x: I16F16::from_num(160),
            offset_y: I16F16::from_num(120),
            h,
            dqa: I8F8::from_bits(dqa),
            dqb: I8F24::from_bits(dqb),
            ..Projection::default()
        });
        g.set_rotation(&Matrix::rotation(angles.0, angles.1, angles.2));
        g.set_translation(Translation { x: 0, y: 0, z: tz });
        let zero = [0i16; 3];
        g.set_light_matrix(&Matrix::from_bits([light, zero, zero]));
        g.set_light_colors(&Matrix::from_bits([
            [color[0], 0, 0],
            [color[1], 0, 0],
            [color[2], 0, 0],
        ]));
        g.set_background_color(ambient);
        g.set_far_color(far);
        g
    }

    /// A face with these corners, and the shared vertices it indexes, listed in another
    /// order (last corner first) with an unused vertex in front.
    fn indexed(
        positions: [Vector3; 4],
        normals: [Vector3; 4],
        quad: bool,
    ) -> (PreparedFace, Vec<SharedVertex>, [u32; 4]) {
        let face = PreparedFace {
            v: std::array::from_fn(|k| PreparedVertex {
                position: positions[k],
                normal: normals[k],
                ..PreparedVertex::default()
            }),
            quad,
        };
        let mut vertices = vec![SharedVertex::default()];
        vertices.extend((0..4).rev().map(|k| SharedVertex {
            position: positions[k],
            normal: normals[k],
        }));
        (face, vertices, [4, 3, 2, 1])
    }

    proptest! {
        /// One RTPS per vertex leaves the clip verdict's inputs as RTPT (+ RTPS) does, and its
        /// sub-pixel positions are q * IR + OF (docs/hardware/gte.md §5 step 6) computed here
        /// from a separate RTPS per vertex, in 1/16 pixel, saturated to -400h..3FFh.
        #[test]
        fn one_rtps_per_vertex_matches_rtpt(
            v in proptest::array::uniform4(vertex()),
            quad in any::<bool>(),
            angles in (0i32..4096, 0i32..4096, 0i32..4096),
            tz in -500i32..8000,
            h in 100u16..1000,
        ) {
            let mut g = Geometry::new();
            g.set_projection(&Projection {
                offset_x: I16F16::from_num(160),
                offset_y: I16F16::from_num(120),
                h,
                ..Projection::default()
            });
            g.set_rotation(&Matrix::rotation(angles.0, angles.1, angles.2));
            g.set_translation(Translation { x: 0, y: 0, z: tz });
            let face = PreparedFace {
                v: v.map(|position| PreparedVertex { position, ..PreparedVertex::default() }),
                quad,
            };
            let fast = transform(&mut g, &face, false);
            let fine = transform(&mut g, &face, true);
            prop_assert_eq!(fast.flag, fine.flag);
            prop_assert_eq!(fast.area, fine.area);
            prop_assert_eq!(fast.xy, fine.xy);
            prop_assert_eq!(fast.sz, fine.sz);
            prop_assert_eq!(fast.ir0, fine.ir0);
            let positions = fine.fine.unwrap_or_default();
            let n = if quad { 4 } else { 3 };
            for k in 0..n {
                let q = g.project(v[k]);
                let ir1 = i64::from(g.gte().read_data(9) as i32);
                let ir2 = i64::from(g.gte().read_data(10) as i32);
                let (qd, _) = gte::unr::divide(gte::DivideMode::default(), h, q.sz);
                let limit = 0x400i64 << SUBPIXEL_BITS;
                let to_sixteenth = |f: i64| (f >> (16 - SUBPIXEL_BITS)).clamp(-limit, limit - 1) as i32;
                let x = to_sixteenth(i64::from(qd) * ir1 + (160 << 16));
                let y = to_sixteenth(i64::from(qd) * ir2 + (120 << 16));
                prop_assert_eq!(positions[k], (x, y));
            }
        }
    }

    proptest! {
        /// A face from its vertices' own RTPS (one per shared vertex) gets the clip verdict,
        /// NCLIP area, screen positions, screen Z, IR0, colours and OTZ that RTPT (+ RTPS),
        /// NCLIP and NCCT/NCDT (+ NCCS/NCDS) or DPCS give it, with and without light and
        /// fog; a vertex lit for one fade factor is lit again for another.
        #[test]
        fn shared_vertices_match_per_polygon(
            positions in proptest::array::uniform4(vertex()),
            normals in proptest::array::uniform4(normal()),
            quad in any::<bool>(),
            angles in (0i32..4096, 0i32..4096, 0i32..4096),
            tz in -500i32..8000,
            h in 100u16..1000,
            fog in (50.0f64..3000.0, 100.0f64..6000.0),
            lamp in (proptest::array::uniform3(-4096i16..=4096), proptest::array::uniform3(0i16..=4096), proptest::array::uniform3(0i32..=4096)),
            far in proptest::array::uniform3(0i32..=0xFF0),
            base in proptest::array::uniform3(any::<u8>()),
            lighting in (any::<bool>(), any::<bool>()),
            other_ir0 in 0i16..=0x1000,
        ) {
            let screen = (320, 240);
            // DQA and DQB of a fog from `near` to `near + depth`, across the vertices' SZ.
            let (near, depth) = fog;
            let fog = crate::scene::Fog { color: [0; 3], near, far: near + depth };
            let coefficients = fog.coefficients(h).unwrap_or((0, 0));
            let mut g = object_geometry(angles, tz, h, coefficients, lamp, far);
            let (face, vertices, indices) = indexed(positions, normals, quad);

            let t = transform(&mut g, &face, false);
            let verdict = classify(t.flag, t.area, t.xy, quad, screen);
            let color = light(&mut g, lighting, &face, base, t.ir0).map(rgb_word);
            let otz = ot_entry(&mut g, quad, t.sz);

            let mut shared = Vec::new();
            project_shared(&mut g, &vertices, &mut shared);
            let s = transform_shared(&mut g, &shared, &indices, quad);
            prop_assert_eq!(
                format!("{:?}", classify(s.flag, s.area, s.xy, quad, screen)),
                format!("{verdict:?}")
            );
            prop_assert_eq!(s.area, t.area);
            prop_assert_eq!(s.xy, t.xy);
            prop_assert_eq!(s.sz, t.sz);
            prop_assert_eq!(s.ir0, t.ir0);
            let (normals, normal_of) = normal_table(&vertices);
            let mut cache = vec![LitNormal::default(); normals.len()];
            let vertex_color = |g: &mut Geometry, cache: &mut Vec<LitNormal>, ir0| {
                light_shared(g, lighting, cache, (&normals, &normal_of), (&indices, quad), base, ir0)
            };
            prop_assert_eq!(vertex_color(&mut g, &mut cache, s.ir0), color);
            prop_assert_eq!(ot_entry(&mut g, quad, s.sz), otz);
            // Once more from the lit vertices, then after they were faded by another factor.
            prop_assert_eq!(vertex_color(&mut g, &mut cache, s.ir0), color);
            let other = I4F12::from_bits(other_ir0);
            g.gte_mut().write_data(8, other_ir0 as i32 as u32);
            let other_color = light(&mut g, lighting, &face, base, other).map(rgb_word);
            prop_assert_eq!(vertex_color(&mut g, &mut cache, other), other_color);
            prop_assert_eq!(vertex_color(&mut g, &mut cache, s.ir0), color);
        }
    }

    /// RTPT runs the depth cue for its last vertex only, RTPS for every vertex
    /// (docs/hardware/gte.md §5.7): with DQA = -500, DQB = 1.0, a vertex at SZ 300
    /// (q = 256/300 in 1.16, D = 1000000h - 500 q < 0) saturates IR0 to 0 and sets FLAG bit
    /// 12, one at SZ 1000 (D = 1000000h - 500 q, about 800000h) does not. A triangle whose
    /// near vertex comes first carries bit 12 from its three RTPS but not from its RTPT, and
    /// gets the same verdict, as the verdict reads no depth-cue bit.
    #[test]
    fn rtpt_depth_cues_its_last_vertex_only() {
        let mut g = object_geometry(
            (0, 0, 0),
            0,
            256,
            (-500, 0x0100_0000),
            ([0; 3], [0; 3], [0; 3]),
            [0; 3],
        );
        let at = |x, y, z| Vector3 { x, y, z };
        let positions = [
            at(0, 0, 300),
            at(400, 0, 1000),
            at(0, 400, 1000),
            at(0, 0, 0),
        ];
        let (face, vertices, indices) = indexed(positions, [Vector3::default(); 4], false);
        let t = transform(&mut g, &face, false);
        let mut shared = Vec::new();
        project_shared(&mut g, &vertices, &mut shared);
        let s = transform_shared(&mut g, &shared, &indices, false);
        assert!(!t.flag.intersects(Flag::IR0_SATURATED), "{:?}", t.flag);
        assert!(s.flag.intersects(Flag::IR0_SATURATED), "{:?}", s.flag);
        // q = 256 * 65536 / 1000 = 16777 (within 3 by UNR): IR0 = (1000000h - 500 q) >> 12.
        let expected = (0x0100_0000 - 500 * 16777) >> 12;
        assert!(
            (i32::from(t.ir0.to_bits()) - expected).abs() <= 1,
            "{:?}",
            t.ir0
        );
        assert_eq!(s.ir0, t.ir0);
        let screen = (320, 240);
        let a = classify(t.flag, t.area, t.xy, false, screen);
        let b = classify(s.flag, s.area, s.xy, false, screen);
        assert!(matches!(a, Verdict::Draw { .. }), "{a:?}");
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }
}
