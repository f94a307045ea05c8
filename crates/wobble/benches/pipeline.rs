//! Whole-pipeline frames: the default scene (as is, and tessellated two levels) and a
//! 3,000-triangle textured, lit sphere (half of it facing away) and a 3,042-triangle textured,
//! lit wall (all of it drawn) at 320x240. Besides criterion's frame times, prints the mean split between the GTE stage,
//! the OT build and the GPU over 500 frames. The `texture_cache` group times the default
//! scene's frames with the GPU's texture cache on and off.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wobble::pipeline::{FrameStats, PipelineOptions, Renderer};
use wobble::scene::mesh::{Mesh, MeshFace, MeshVertex};
use wobble::scene::{MeshAsset, Scene};

/// The default scene with its objects replaced by one sphere of 2,976 triangles
/// (32 rings x 48 segments) wearing the checker texture, spinning.
pub fn sphere_scene() -> Scene {
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

/// The default scene with its objects replaced by a textured, lit wall of 39 x 39 cells,
/// each two triangles (3,042 triangles), facing the camera and filling the middle of the screen:
/// every triangle is drawn.
pub fn wall_scene() -> Scene {
    let cells = 39u32;
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
    // Fixed camera 600 units in front of the wall, level: the wall spans about 200 x 200
    // pixels in the middle of the 320x240 screen, whatever the default animation does.
    s.camera.position = [0.0, -300.0, -1500.0];
    s.camera.rotation = [0.0; 3];
    wall.spin = [0.0; 3];
    s.objects = vec![wall];
    s
}

/// A scene with every object at tessellation level `level` (polygons over 64 pixels split).
fn tessellated(mut scene: Scene, level: u8) -> Scene {
    for o in &mut scene.objects {
        o.tessellation = level;
        o.split_extent = wobble::scene::DEFAULT_SPLIT_EXTENT;
    }
    scene
}

/// The sphere scene with nothing but flat polygons: no texture, no light (one colour per
/// polygon, so Gouraud-free G3/G4 packets with equal colours), no dithering, opaque.
pub fn flat_sphere_scene() -> Scene {
    let mut s = sphere_scene();
    s.light = None;
    s.screen.dither = false;
    for o in &mut s.objects {
        o.texture = None;
        o.blend = None;
        o.color = [200, 120, 60];
    }
    s
}

fn split(name: &str, scene: Scene) {
    let mut r = Renderer::new(scene, PipelineOptions::default()).unwrap();
    let frames = 500;
    let mut total = FrameStats::default();
    for f in 0..frames {
        total.accumulate(&r.render_frame(f));
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3 / frames as f64;
    println!(
        "{name}: {} polygons/frame ({} drawn, {} culled, {} off screen, {} dropped); mean per frame: GTE {:.3} ms, OT {:.3} ms, GPU {:.3} ms",
        total.polygons / frames as usize,
        total.drawn / frames as usize,
        total.culled / frames as usize,
        total.offscreen / frames as usize,
        total.dropped / frames as usize,
        ms(total.gte),
        ms(total.ot),
        ms(total.gpu)
    );
}

fn frames(c: &mut Criterion) {
    let mut group = c.benchmark_group("frame");
    for (name, scene) in [
        ("default_scene", Scene::default_scene()),
        (
            "default_scene_tessellation_2",
            tessellated(Scene::default_scene(), 2),
        ),
        ("sphere_2976_triangles", sphere_scene()),
        ("wall_3042_triangles", wall_scene()),
        ("sphere_2976_triangles_flat_only", flat_sphere_scene()),
    ] {
        assert!(
            name != "sphere_2976_triangles"
                || scene.meshes.last().unwrap().mesh.triangle_count() == 2976
        );
        let mut r = Renderer::new(scene.clone(), PipelineOptions::default()).unwrap();
        let mut frame = 0;
        group.bench_function(name, |b| {
            b.iter(|| {
                frame += 1;
                black_box(r.render_frame(frame))
            })
        });
        split(name, scene);
    }
    group.finish();
}

/// The default scene's frames with the GPU's texture cache on (as on the console) and off,
/// side by side: what the cache's tag tracking costs on textures drawn near their size,
/// whose reads step slowly (docs/gpu.md, "Texture cache"). `gpu_only` times the GPU alone,
/// fed the GP0 packets of the scene's first 24 frames (traced once) through
/// `Gpu::gp0_words`, from the state the renderer's GPU starts in.
fn texture_cache(c: &mut Criterion) {
    let mut group = c.benchmark_group("texture_cache");
    let mut r = Renderer::new(Scene::default_scene(), PipelineOptions::default()).unwrap();
    let start = r.gpu().clone();
    let frames: Vec<Vec<Vec<u32>>> = (0..24)
        .map(|f| {
            let (_, trace) = r.render_frame_traced(f).unwrap();
            trace.packets.into_iter().map(|p| p.words).collect()
        })
        .collect();
    for on in [true, false] {
        let mut gpu = start.clone();
        gpu.set_texture_cache(on);
        let name = if on { "gpu_only/on" } else { "gpu_only/off" };
        group.bench_function(name, |b| {
            b.iter(|| {
                for frame in &frames {
                    for packet in frame {
                        gpu.gp0_words(black_box(packet));
                    }
                }
            })
        });
    }
    for on in [true, false] {
        let options = PipelineOptions {
            texture_cache: on,
            ..PipelineOptions::default()
        };
        let mut r = Renderer::new(Scene::default_scene(), options).unwrap();
        let mut frame = 0;
        let name = if on {
            "default_scene/on"
        } else {
            "default_scene/off"
        };
        group.bench_function(name, |b| {
            b.iter(|| {
                frame += 1;
                black_box(r.render_frame(frame))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, frames, texture_cache);
criterion_main!(benches);
