//! Whole-pipeline frames: the default scene and a 3,000-triangle textured, lit sphere at
//! 320x240. Besides criterion's frame times, prints the mean split between the GTE stage,
//! the OT build and the GPU over 500 frames.

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wobble::mesh::Mesh;
use wobble::pipeline::{FrameStats, PipelineOptions, Renderer};
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
        ("sphere_2976_triangles", sphere_scene()),
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

criterion_group!(benches, frames);
criterion_main!(benches);
