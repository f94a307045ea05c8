//! The GTE stage: per object, RT/TR/light/fog set-up and one RTPS per shared vertex; per
//! mesh face, NCLIP on its vertices' screen positions, the clip verdict, colours (NCCS/NCDS
//! once per distinct normal, or per fade factor with fog; DPCS) and AVSZ3/AVSZ4 for the
//! ordering-table index. A face split by tessellation, and every face with sub-pixel
//! positions, goes through its own RTPT/RTPS, NCLIP and NCCT/NCDT instead.

use super::clip::{Verdict, classify};
use super::lighting::{LitNormal, light, light_shared};
use super::object::{object_light, object_transform};
use super::polygon::{ProjectedFace, rgb_word};
use super::precise::subpixel_vertices;
use super::projection::{project_shared, transform, transform_shared};
use super::trace::{FaceFate, FaceRecord};
use super::{FrameStats, OT_DEPTH, OT_SHIFT, Renderer};
use crate::scene::prepared::PreparedFace;
use gte::typed::{Geometry, I8F8, I8F24, I16F16, Projection};

/// Whether a polygon is split again rather than drawn, given its verdict.
fn needs_split(verdict: &Verdict, split_extent: i32) -> bool {
    match verdict {
        Verdict::Drop(_) => true,
        Verdict::Draw { extent, .. } => *extent > split_extent,
        Verdict::Cull | Verdict::Offscreen => false,
    }
}

/// Counts a polygon that is not drawn; whether it is drawn.
fn drawn(verdict: Verdict, stats: &mut FrameStats) -> bool {
    match verdict {
        Verdict::Drop(_) => stats.dropped += 1,
        Verdict::Cull => stats.culled += 1,
        Verdict::Offscreen => stats.offscreen += 1,
        Verdict::Draw { .. } => return true,
    }
    false
}

/// AVSZ3/AVSZ4 for the ordering-table index, and the polygon as the packet stage takes it.
fn emit(
    g: &mut Geometry,
    face: &PreparedFace,
    (xy, sz): ([(i16, i16); 4], [u16; 4]),
    color: [u32; 4],
    (texture, blend): (Option<(u32, u32)>, Option<u8>),
    uv: [(u8, u8); 4],
) -> ProjectedFace {
    let otz = if face.quad {
        g.average_z4(sz)
    } else {
        g.average_z3([sz[0], sz[1], sz[2]])
    };
    ProjectedFace {
        xy,
        color,
        uv,
        quad: face.quad,
        ot_index: ((otz >> OT_SHIFT) as usize).min(OT_DEPTH - 1) as u16,
        texture,
        blend,
    }
}

impl Renderer {
    pub(super) fn gte_stage(&mut self, frame: u32, stats: &mut FrameStats) {
        self.scratch.clear();
        let scene = &self.scene;
        let (w, h) = (scene.screen.width as i32, scene.screen.height as i32);
        let cam = &scene.camera;
        let g = &mut self.geometry;
        let stack = &mut self.stack;
        let scratch = &mut self.scratch;
        let precise_vertices = &mut self.precise_vertices;
        precise_vertices.clear();
        let capacity = self.capacity;
        let split_extent = i32::from(self.options.split_extent);
        let options = self.options;
        let lighting = (scene.light.is_some(), scene.fog.is_some());
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
        let mut trace = self.trace.as_deref_mut();
        if let Some(t) = trace.as_deref_mut() {
            t.clear();
        }
        let share = !options.subpixel && !self.per_polygon;
        let shared = &mut self.shared;
        let lit_normals = &mut self.lit_normals;
        for (object_index, (object, prepared)) in
            scene.objects.iter().zip(&self.objects).enumerate()
        {
            let (rt, tr) = object_transform(scene, object, frame);
            g.set_rotation(&rt);
            g.set_translation(tr);
            if let Some(light) = object_light(scene, object, frame) {
                g.set_light_matrix(&light.directions);
                g.set_light_colors(&light.colors);
                g.set_background_color(light.background);
            }
            let (texture, blend) = (prepared.texture, prepared.blend);
            if share {
                project_shared(g, &prepared.mesh.vertices, shared);
                lit_normals.clear();
                lit_normals.resize(prepared.mesh.normals.len(), LitNormal::default());
            }
            for (face_index, mesh_face) in prepared.mesh.faces.iter().enumerate() {
                // The mesh face itself uses its shared vertices; its pieces, new vertices
                // made by splitting, go through RTPT/RTPS one piece at a time, depth first
                // from the split stack.
                let indices = prepared.mesh.indices.get(face_index).filter(|_| share);
                let mut piece;
                let (mut face, mut level) = (mesh_face, 0u8);
                loop {
                    'examine: {
                        let indices = indices.filter(|_| level == 0);
                        let t = match indices {
                            Some(indices) => transform_shared(g, shared, indices, face.quad),
                            None => transform(g, face, options.subpixel),
                        };
                        let verdict = classify(t.flag, t.area, t.xy, face.quad, (w, h));
                        let split = level < prepared.level && needs_split(&verdict, split_extent);
                        if let Some(tr) = trace.as_deref_mut() {
                            let fate = match verdict {
                                _ if split => FaceFate::Split,
                                Verdict::Drop(c) => FaceFate::Dropped(c),
                                Verdict::Cull => FaceFate::Culled,
                                Verdict::Offscreen => FaceFate::Offscreen,
                                Verdict::Draw { .. } if scratch.len() >= capacity => {
                                    FaceFate::Overflow
                                }
                                // The slot is filled in below.
                                Verdict::Draw { .. } => FaceFate::Drawn { ot_slot: 0 },
                            };
                            tr.faces.push(FaceRecord {
                                object: object_index,
                                face: face_index,
                                level,
                                fate,
                            });
                        }
                        if split {
                            stack.push_split(face, level + 1);
                            break 'examine;
                        }
                        stats.polygons += 1;
                        if !drawn(verdict, stats) {
                            break 'examine;
                        }
                        let (xy, sz, ir0) = (t.xy, t.sz, t.ir0);
                        if scratch.len() >= capacity {
                            stats.dropped += 1;
                            break 'examine;
                        }
                        let color = match indices {
                            Some(indices) => light_shared(
                                g,
                                lighting,
                                lit_normals,
                                (&prepared.mesh.normals, &prepared.mesh.normal_of),
                                (indices, face.quad),
                                object.color,
                                ir0,
                            ),
                            None => light(g, lighting, face, object.color, ir0).map(rgb_word),
                        };
                        if options.precise() {
                            precise_vertices.push(subpixel_vertices(xy, sz, t.fine, face.quad));
                        }
                        // A mesh face's texels are rounded once, when the object is prepared.
                        let uv = match indices.and(prepared.mesh.texels.get(face_index)) {
                            Some(&uv) => uv,
                            None => face.v.map(|p| p.texel()),
                        };
                        let projected = emit(g, face, (xy, sz), color, (texture, blend), uv);
                        if let Some(tr) = trace.as_deref_mut() {
                            let record = tr.faces.len().saturating_sub(1);
                            if let Some(r) = tr.faces.last_mut() {
                                r.fate = FaceFate::Drawn {
                                    ot_slot: projected.ot_index,
                                };
                            }
                            tr.scratch_face.push(record);
                        }
                        scratch.push(projected);
                    }
                    let Some((next, next_level)) = stack.pop() else {
                        break;
                    };
                    piece = next;
                    (face, level) = (&piece, next_level);
                }
            }
        }
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
            let uv = face.v.map(|p| p.texel());
            let otz = emit(&mut g, &face, (t.xy, t.sz), color, (None, None), uv).ot_index;

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
            prop_assert_eq!(emit(&mut g, &face, (s.xy, s.sz), color, (None, None), uv).ot_index, otz);
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
