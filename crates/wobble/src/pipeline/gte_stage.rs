//! The GTE stage: per object, RT/TR/light/fog set-up; per polygon, RTPT/RTPS and NCLIP,
//! the clip verdict, splitting while the tessellation level allows, NCCT/NCDT/DPCS colours
//! and AVSZ3/AVSZ4 for the ordering-table index.

use super::clip::{Verdict, classify};
use super::object::{angle, object_rotation, object_transform, to_fixed};
use super::tessellate::PreparedFace;
use super::trace::{FaceFate, FaceRecord};
use super::{FrameStats, OT_DEPTH, OT_SHIFT, Renderer};
use gpu::rasterizer::precise::{PreciseVertex, SUBPIXEL_BITS};
use gte::typed::{Geometry, I8F8, I8F24, I16F16, Matrix, Projection};

/// A polygon after the GTE stage, waiting for its packet.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct ProjectedFace {
    pub(super) xy: [(i16, i16); 4],
    pub(super) color: [[u8; 3]; 4],
    pub(super) uv: [(u8, u8); 4],
    pub(super) quad: bool,
    pub(super) ot_index: u16,
    pub(super) texture: Option<(u32, u32)>,
    pub(super) blend: Option<u8>,
}

/// RTPT (and RTPS for a quad's fourth vertex), NCLIP, and the whole-polygon tests.
fn transform(g: &mut Geometry, face: &PreparedFace, screen: (i32, i32)) -> Verdict {
    let v = &face.v;
    let p = g.project_triangle([v[0].position, v[1].position, v[2].position]);
    let mut flag = p.flag;
    let area = g.nclip_current();
    let mut xy = [p.xy[0], p.xy[1], p.xy[2], (0, 0)];
    let mut sz = [p.sz[0], p.sz[1], p.sz[2], 0];
    let mut ir0 = p.ir0;
    if face.quad {
        let q = g.project(v[3].position);
        flag = flag.union(q.flag);
        xy[3] = (q.x, q.y);
        sz[3] = q.sz;
        ir0 = q.ir0;
    }
    classify(flag, area, xy, sz, ir0, face.quad, screen)
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
            // FC is in colour units of 1/16: a colour C pushes as MAC >> 4 (gte.md §8).
            g.set_far_color(fog.color.map(|c| i32::from(c) << 4));
        }
        let mut trace = self.trace.as_deref_mut();
        if let Some(t) = trace.as_deref_mut() {
            t.clear();
        }
        for (object_index, (object, prepared)) in
            scene.objects.iter().zip(&self.objects).enumerate()
        {
            let r = object_rotation(object, frame);
            let rot = Matrix::rotation(angle(r[0]), angle(r[1]), angle(r[2]));
            let (rt, tr) = object_transform(scene, object, frame);
            g.set_rotation(&rt);
            g.set_translation(tr);
            if let Some(light) = &scene.light {
                // LLM row = -(light direction) in object space: (R^T (-d))^T.
                let d = light.direction;
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
                let to_light = [-d[0] / len, -d[1] / len, -d[2] / len];
                let rb = rot.to_bits();
                let obj: [f64; 3] = std::array::from_fn(|c| {
                    (0..3).map(|r| rb[r][c] as f64 * to_light[r]).sum::<f64>() / 4096.0
                });
                let zero = [0i16; 3];
                g.set_light_matrix(&Matrix::from_bits([obj.map(to_fixed), zero, zero]));
                let col = light.color.map(|c| to_fixed(c as f64 / 255.0));
                g.set_light_colors(&Matrix::from_bits([
                    [col[0], 0, 0],
                    [col[1], 0, 0],
                    [col[2], 0, 0],
                ]));
                g.set_background_color(light.ambient.map(|c| (c as i32 * 4096) / 255));
            }
            let blend = object.blend;
            let texture = prepared.texture.map(|(p, depth)| {
                let tpage = p.texpage(depth) | (blend.unwrap_or(0) as u32) << 5;
                (p.clut_attr(), tpage)
            });
            for (face_index, face) in prepared.faces.iter().enumerate() {
                stack.push(*face, 0);
                while let Some((face, level)) = stack.pop() {
                    let verdict = transform(g, &face, (w, h));
                    let split = level < prepared.level
                        && match verdict {
                            Verdict::Drop(_) => true,
                            Verdict::Draw { extent, .. } => extent > split_extent,
                            Verdict::Cull | Verdict::Offscreen => false,
                        };
                    if let Some(t) = trace.as_deref_mut() {
                        let fate = match verdict {
                            _ if split => FaceFate::Split,
                            Verdict::Drop(c) => FaceFate::Dropped(c),
                            Verdict::Cull => FaceFate::Culled,
                            Verdict::Offscreen => FaceFate::Offscreen,
                            Verdict::Draw { .. } if scratch.len() >= capacity => FaceFate::Overflow,
                            // The slot is filled in below.
                            Verdict::Draw { .. } => FaceFate::Drawn { ot_slot: 0 },
                        };
                        t.faces.push(FaceRecord {
                            object: object_index,
                            face: face_index,
                            level,
                            fate,
                        });
                    }
                    if split {
                        stack.push_split(&face, level + 1);
                        continue;
                    }
                    stats.polygons += 1;
                    let (xy, sz, ir0) = match verdict {
                        Verdict::Drop(_) => {
                            stats.dropped += 1;
                            continue;
                        }
                        Verdict::Cull => {
                            stats.culled += 1;
                            continue;
                        }
                        Verdict::Offscreen => {
                            stats.offscreen += 1;
                            continue;
                        }
                        Verdict::Draw { xy, sz, ir0, .. } => (xy, sz, ir0),
                    };
                    if scratch.len() >= capacity {
                        stats.dropped += 1;
                        continue;
                    }
                    let v = &face.v;
                    let mut color = [object.color; 4];
                    let normals = [v[0].normal, v[1].normal, v[2].normal];
                    match (scene.light.is_some(), scene.fog.is_some()) {
                        (true, false) => {
                            let c = g.normal_color_color_triple(normals, object.color);
                            color[..3].copy_from_slice(&c);
                            if face.quad {
                                color[3] = g.normal_color_color(v[3].normal, object.color);
                            }
                        }
                        // NCDT/NCDS fade by IR0 as the last RTPT/RTPS left it: one factor
                        // for the whole polygon, from its last vertex (gte.md §5 step 7).
                        (true, true) => {
                            let c = g.normal_color_depth_triple(normals, object.color);
                            color[..3].copy_from_slice(&c);
                            if face.quad {
                                color[3] = g.normal_color_depth(v[3].normal, object.color);
                            }
                        }
                        (false, true) => color = [g.depth_cue(object.color, ir0); 4],
                        (false, false) => {}
                    }
                    let otz = if face.quad {
                        g.average_z4(sz)
                    } else {
                        g.average_z3([sz[0], sz[1], sz[2]])
                    };
                    if options.precise() {
                        let mut precise = [PreciseVertex::default(); 4];
                        let n = if face.quad { 4 } else { 3 };
                        for k in 0..n {
                            let (mut x, mut y) = (
                                (xy[k].0 as i32) << SUBPIXEL_BITS,
                                (xy[k].1 as i32) << SUBPIXEL_BITS,
                            );
                            if options.subpixel {
                                // The GTE's screen position before truncation: q*IR + OF
                                // in 16.16, kept to 1/16 pixel.
                                let q = g.project(v[k].position);
                                let ir1 = g.gte().read_data(9) as i32 as i64;
                                let ir2 = g.gte().read_data(10) as i32 as i64;
                                let (qd, _) = gte::unr::divide(options.divide_mode, cam.h, q.sz);
                                let fx = qd as i64 * ir1 + ((w as i64 / 2) << 16);
                                let fy = qd as i64 * ir2 + ((h as i64 / 2) << 16);
                                let limit = 0x400i64 << SUBPIXEL_BITS;
                                x = (fx >> (16 - SUBPIXEL_BITS)).clamp(-limit, limit - 1) as i32;
                                y = (fy >> (16 - SUBPIXEL_BITS)).clamp(-limit, limit - 1) as i32;
                            }
                            precise[k] = PreciseVertex {
                                x,
                                y,
                                inv_z: (1u32 << 24) / (sz[k] as u32).max(1),
                            };
                        }
                        precise_vertices.push(precise);
                    }
                    let ot_index = ((otz >> OT_SHIFT) as usize).min(OT_DEPTH - 1) as u16;
                    if let Some(t) = trace.as_deref_mut() {
                        let record = t.faces.len().saturating_sub(1);
                        if let Some(r) = t.faces.last_mut() {
                            r.fate = FaceFate::Drawn { ot_slot: ot_index };
                        }
                        t.scratch_face.push(record);
                    }
                    scratch.push(ProjectedFace {
                        xy,
                        color,
                        uv: v.map(|p| p.texel()),
                        quad: face.quad,
                        ot_index,
                        texture,
                        blend,
                    });
                }
            }
        }
    }
}
