//! The shared-vertex GTE stage (one RTPS per vertex) against the per-polygon one (RTPT per
//! face, the path split faces take): the same VRAM, counts and traces, frame after frame,
//! and the default scene's golden image.

use super::{FrameStats, PipelineOptions, Renderer};
use crate::scene::mesh::{Mesh, MeshFace, MeshVertex};
use crate::scene::prepared::prepare;
use crate::scene::{MeshAsset, Scene};

/// The benchmark's sphere: the default scene's objects replaced by one sphere of 2,976
/// triangles (32 rings x 48 segments) wearing the checker texture, spinning.
fn sphere_scene() -> Scene {
    let mut s = Scene::default_scene();
    s.meshes.push(MeshAsset {
        name: "sphere".into(),
        mesh: Mesh::sphere(1.0, 32, 48),
    });
    let mut sphere = s.objects[0].clone();
    sphere.mesh = s.meshes.len() - 1;
    sphere.scale = 260.0;
    sphere.position = [0.0, -60.0, -300.0];
    s.objects = vec![sphere];
    s
}

/// Cells per side of the benchmark's wall.
const WALL_CELLS: u32 = 39;

/// The benchmark's wall: 39 x 39 cells of two triangles on a 40 x 40 vertex grid, textured,
/// lit and fogged, facing a fixed camera.
fn wall_scene() -> Scene {
    let cells = WALL_CELLS;
    let mut mesh = Mesh::default();
    for j in 0..=cells {
        for i in 0..=cells {
            let (s, t) = (i as f64 / cells as f64, j as f64 / cells as f64);
            mesh.vertices.push(MeshVertex {
                position: [2.0 * s - 1.0, 2.0 * t - 1.0, 0.0],
                normal: [0.0, 0.0, -1.0],
                uv: [s * 8.0, t * 8.0],
            });
        }
    }
    let n = cells + 1;
    for j in 0..cells {
        for i in 0..cells {
            let (tl, tr, bl, br) = (
                j * n + i,
                j * n + i + 1,
                (j + 1) * n + i,
                (j + 1) * n + i + 1,
            );
            for indices in [[tl, tr, bl, 0], [tr, br, bl, 0]] {
                mesh.faces.push(MeshFace {
                    indices,
                    quad: false,
                });
            }
        }
    }
    let mut s = Scene::default_scene();
    s.meshes.push(MeshAsset {
        name: "wall".into(),
        mesh,
    });
    let mut wall = s.objects[0].clone();
    wall.mesh = s.meshes.len() - 1;
    wall.scale = 200.0;
    wall.position = [0.0, -300.0, -900.0];
    wall.rotation = [0.0; 3];
    s.camera.position = [0.0, -300.0, -1500.0];
    s.camera.rotation = [0.0; 3];
    wall.spin = [0.0; 3];
    s.objects = vec![wall];
    s
}

/// The wall turned 70 degrees about Y and spinning about X, so its depth (and the fog
/// factor of each face) varies across it and part of it faces away.
fn slanted_wall_scene() -> Scene {
    let mut s = wall_scene();
    s.objects[0].rotation = [0.0, 70.0, 0.0];
    s.objects[0].spin = [9.0, 0.0, 0.0];
    s
}

/// The scenes compared, by name: every lighting case (NCDS, NCCS, DPCS, none), quads and
/// triangles, split faces mixed with whole ones, faces dropped at the near plane.
fn scenes() -> Vec<(&'static str, Scene)> {
    let unlit_fog = {
        let mut s = Scene::default_scene();
        s.light = None;
        s
    };
    let lit_clear = {
        let mut s = Scene::default_scene();
        s.fog = None;
        s
    };
    let plain = {
        let mut s = Scene::default_scene();
        s.light = None;
        s.fog = None;
        s
    };
    let tessellated = {
        let mut s = Scene::default_scene();
        for o in &mut s.objects {
            o.tessellation = 2;
        }
        s
    };
    // Fog from in front of the objects to behind them: every face is faded, each by its
    // own factor.
    let near_fog = |mut s: Scene, near, far| {
        s.fog = Some(crate::scene::Fog {
            color: [40, 60, 200],
            near,
            far,
        });
        s
    };
    vec![
        ("default", Scene::default_scene()),
        (
            "default, near fog",
            near_fog(Scene::default_scene(), 300.0, 1500.0),
        ),
        (
            "slanted wall, near fog",
            near_fog(slanted_wall_scene(), 300.0, 900.0),
        ),
        ("default, tessellation 2", tessellated),
        ("default, fog without light", unlit_fog),
        ("default, light without fog", lit_clear),
        ("default, neither", plain),
        ("sphere", sphere_scene()),
        ("wall", wall_scene()),
        ("slanted wall", slanted_wall_scene()),
    ]
}

/// A frame's counts without its times.
fn counts(s: &FrameStats) -> [usize; 6] {
    [
        s.polygons,
        s.drawn,
        s.culled,
        s.offscreen,
        s.dropped,
        s.capped,
    ]
}

fn renderers(scene: &Scene) -> (Renderer, Renderer) {
    renderers_with(scene, PipelineOptions::default())
}

fn renderers_with(scene: &Scene, options: PipelineOptions) -> (Renderer, Renderer) {
    let shared = Renderer::new(scene.clone(), options).expect("renderer");
    let mut reference = Renderer::new(scene.clone(), options).expect("renderer");
    reference.per_polygon = true;
    (shared, reference)
}

/// Perspective-correct texture coordinates (the precise path, whole-pixel vertices) take
/// their screen positions and 1/SZ from the shared vertices: the same VRAM.
#[cfg(feature = "accuracy-knobs")]
#[test]
fn shared_vertices_feed_the_precise_path() {
    let options = PipelineOptions {
        perspective_uv: true,
        ..PipelineOptions::default()
    };
    for (name, scene) in scenes() {
        let (mut shared, mut reference) = renderers_with(&scene, options);
        for frame in [0, 7, 90] {
            let a = shared.render_frame(frame);
            let b = reference.render_frame(frame);
            assert_eq!(counts(&a), counts(&b), "{name}, frame {frame}");
            assert!(
                shared.gpu().vram().as_slice() == reference.gpu().vram().as_slice(),
                "{name}, frame {frame}: VRAM differs"
            );
        }
        assert!(
            !shared.work.shared.is_empty(),
            "{name}: no vertex projected"
        );
    }
}

/// Several frames of each scene: the same VRAM (both display buffers and the textures)
/// and the same counts after every frame, with the vertices really shared.
#[test]
fn shared_vertices_draw_what_per_polygon_transforms_draw() {
    for (name, scene) in scenes() {
        let (mut shared, mut reference) = renderers(&scene);
        let mut drawn = 0;
        for frame in [0, 1, 2, 3, 10, 45, 90, 200] {
            let a = shared.render_frame(frame);
            let b = reference.render_frame(frame);
            assert_eq!(counts(&a), counts(&b), "{name}, frame {frame}");
            assert!(
                shared.gpu().vram().as_slice() == reference.gpu().vram().as_slice(),
                "{name}, frame {frame}: VRAM differs"
            );
            drawn += a.drawn;
        }
        assert!(drawn > 0, "{name}: nothing drawn");
        assert!(
            !shared.work.shared.is_empty(),
            "{name}: no vertex projected"
        );
        assert!(
            reference.work.shared.is_empty(),
            "{name}: reference shared a vertex"
        );
    }
}

/// Traced frames agree face by face (fate, OT slot) and packet by packet.
#[test]
fn shared_vertices_trace_as_per_polygon_transforms() {
    for (name, scene) in scenes() {
        let (mut shared, mut reference) = renderers(&scene);
        for frame in [0, 33] {
            let (a, ta) = shared.render_frame_traced(frame).expect("trace");
            let (b, tb) = reference.render_frame_traced(frame).expect("trace");
            assert_eq!(counts(&a), counts(&b), "{name}, frame {frame}");
            assert_eq!(ta.faces, tb.faces, "{name}, frame {frame}");
            assert_eq!(ta.packets, tb.packets, "{name}, frame {frame}");
            assert_eq!(ta.display_word, tb.display_word, "{name}, frame {frame}");
        }
    }
}

/// The shared-vertex path draws the default scene's golden image
/// (fixtures/golden/default-scene.png, frame 0).
#[test]
fn shared_vertices_draw_the_golden_default_scene() {
    let mut r =
        Renderer::new(Scene::default_scene(), PipelineOptions::default()).expect("renderer");
    assert!(!r.per_polygon);
    r.render_frame(0);
    let golden = image::open(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/golden/default-scene.png"
    ))
    .expect("golden image")
    .to_rgb8();
    let image = r.image();
    assert_eq!(image.dimensions(), golden.dimensions());
    let differing = image
        .pixels()
        .zip(golden.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{differing} pixels differ from the golden image"
    );
}

/// The wall's 3,042 triangles share the 40 x 40 = 1,600 grid points and their one normal;
/// each face's indices name vertices with its own corners' positions and normals, and its
/// texels are its corners' rounded texture coordinates.
#[test]
fn prepared_faces_index_their_shared_vertices() {
    let wall = prepare(&wall_scene(), 0);
    assert_eq!(wall.faces.len(), 3042);
    assert_eq!(wall.vertices.len(), 1600);
    assert_eq!(wall.normals.len(), 1);
    for (name, scene) in scenes() {
        for object in 0..scene.objects.len() {
            let mesh = prepare(&scene, object);
            assert_eq!(mesh.faces.len(), mesh.indices.len(), "{name}");
            let face_vertices: usize = mesh.faces.iter().map(|f| if f.quad { 4 } else { 3 }).sum();
            assert!(mesh.vertices.len() <= face_vertices, "{name}");
            for ((face, indices), texels) in mesh.faces.iter().zip(&mesh.indices).zip(&mesh.texels)
            {
                let n = if face.quad { 4 } else { 3 };
                for ((corner, &i), &texel) in face.v.iter().zip(indices).zip(texels).take(n) {
                    let v = mesh.vertices[i as usize];
                    assert_eq!(v.position, corner.position, "{name}");
                    assert_eq!(v.normal, corner.normal, "{name}");
                    assert_eq!(texel, corner.texel(), "{name}");
                }
            }
            // Each vertex names its own normal in the table, which holds each normal once.
            assert_eq!(mesh.normal_of.len(), mesh.vertices.len(), "{name}");
            for (v, &m) in mesh.vertices.iter().zip(&mesh.normal_of) {
                assert_eq!(mesh.normals[m as usize], v.normal, "{name}");
            }
            let mut distinct = mesh.normals.clone();
            distinct.sort_by_key(|n| (n.x, n.y, n.z));
            distinct.dedup();
            assert_eq!(distinct.len(), mesh.normals.len(), "{name}");
        }
    }
}
