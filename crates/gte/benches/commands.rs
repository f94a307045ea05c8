//! Cost of each GTE command through `Gte::execute`, of a typed RTPT, and of the divide
//! modes over 100,000 vertices (the accuracy knob's price).

use criterion::{Criterion, criterion_group, criterion_main};
use gte::Opcode;
use gte::typed::{Geometry, Matrix, Projection, Translation, Vector3};
use gte::{DivideMode, Gte};
use std::hint::black_box;

/// A representative register state: a rotation, a translation in front of the camera,
/// lights, colours and vertices in typical ranges.
fn loaded() -> Gte {
    let mut g = Geometry::new();
    g.set_rotation(&Matrix::rotation(300, 700, 100));
    g.set_translation(Translation {
        x: 10,
        y: -20,
        z: 2000,
    });
    g.set_projection(&Projection::default());
    g.set_light_matrix(&Matrix::rotation(100, 200, 300));
    g.set_light_colors(&Matrix::IDENTITY);
    g.set_background_color([400, 400, 400]);
    g.set_far_color([0x100, 0x80, 0x40]);
    let mut gte = g.gte().clone();
    let verts = [(100i16, -50i16, 30i16), (-80, 60, -20), (40, 90, 10)];
    for (i, (x, y, z)) in verts.into_iter().enumerate() {
        gte.write_data(
            (2 * i) as u32,
            (x as u16 as u32) | ((y as u16 as u32) << 16),
        );
        gte.write_data((2 * i + 1) as u32, z as u16 as u32);
    }
    gte.write_data(6, 0x0080_8080);
    gte.write_data(8, 0x800);
    for r in 9..12 {
        gte.write_data(r, 0x400);
    }
    gte
}

fn commands(c: &mut Criterion) {
    let base = loaded();
    let mut group = c.benchmark_group("gte_command");
    for op in Opcode::ALL {
        let word = op.bits() | 1 << 19;
        group.bench_function(format!("{op:?}"), |b| {
            let mut gte = base.clone();
            b.iter(|| {
                // Re-running on the previous result keeps the state realistic; the
                // FIFOs shift but stay in range.
                black_box(gte.execute(black_box(word)));
            })
        });
    }
    group.finish();
}

fn typed_projection(c: &mut Criterion) {
    let mut g = Geometry::from_gte(loaded());
    let tri = [
        Vector3 {
            x: 100,
            y: -50,
            z: 30,
        },
        Vector3 {
            x: -80,
            y: 60,
            z: -20,
        },
        Vector3 {
            x: 40,
            y: 90,
            z: 10,
        },
    ];
    c.bench_function("typed_project_triangle", |b| {
        b.iter(|| black_box(g.project_triangle(black_box(tri))))
    });
}

fn divide_modes(c: &mut Criterion) {
    let vertices: Vec<Vector3> = (0..100_000u32)
        .map(|i| {
            let a = i.wrapping_mul(2_654_435_761);
            Vector3 {
                x: (a & 0x7FF) as i16 - 1024,
                y: ((a >> 11) & 0x7FF) as i16 - 1024,
                z: ((a >> 22) & 0x3FF) as i16 - 512,
            }
        })
        .collect();
    let mut group = c.benchmark_group("project_100k_vertices");
    group.sample_size(20);
    for mode in [DivideMode::Unr, DivideMode::Exact, DivideMode::F32] {
        let mut g = Geometry::from_gte(loaded());
        if g.set_divide_mode(mode).is_err() {
            continue; // built without `divide-modes`
        }
        group.bench_function(format!("{mode:?}"), |b| {
            b.iter(|| {
                let mut acc = 0i32;
                for chunk in vertices.chunks_exact(3) {
                    let p = g.project_triangle([chunk[0], chunk[1], chunk[2]]);
                    acc = acc.wrapping_add(p.xy[2].0 as i32);
                }
                black_box(acc)
            })
        });
    }
    group.finish();
}

criterion_group!(benches, commands, typed_projection, divide_modes);
criterion_main!(benches);
