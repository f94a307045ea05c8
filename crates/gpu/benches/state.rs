//! Save-state size and the time to save and load one (postcard), and a save and load in a
//! row as rewind or run-ahead does every frame, for an idle GPU with zero VRAM and for one with
//! a drawn VRAM, a transfer in progress and queued FIFO words.

use criterion::{Criterion, criterion_group, criterion_main};
use gpu::encode::{self, Polygon, Vertex};
use gpu::{Gpu, SaveState};
use std::hint::black_box;

/// Every VRAM pixel written (a gradient with the mask bit in half of them), then a
/// CPU-to-VRAM transfer left unfinished behind a busy GPU.
fn drawn() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&encode::cpu_to_vram(0, 0, 1024, 512));
    for i in 0..512 * 1024 / 2 {
        let p = (i as u32).wrapping_mul(0x9E37_79B9) >> 1;
        g.gp0(p);
    }
    g.gp0_words(&[
        encode::area_top_left(0, 0),
        encode::area_bottom_right(1023, 511),
    ]);
    let red = |x, y| Vertex {
        x,
        y,
        color: [0xFF, 0, 0],
        ..Vertex::default()
    };
    g.gp0_words(&Polygon::triangle([red(0, 0), red(300, 0), red(0, 200)]).packet());
    g.gp0_words(&encode::cpu_to_vram(100, 100, 4, 4));
    g.gp0_words(&[1, 2]);
    g
}

fn state(c: &mut Criterion) {
    let mut group = c.benchmark_group("save_state");
    for (name, g) in [("zero_vram", Gpu::new()), ("drawn_vram", drawn())] {
        let bytes = postcard::to_allocvec(&g.save_state()).expect("serializes");
        println!("{name}: {} bytes (postcard)", bytes.len());
        let mut buf = vec![0u8; bytes.len()];
        group.bench_function(format!("save_{name}"), |b| {
            b.iter(|| {
                let used = postcard::to_slice(&g.save_state(), &mut buf)
                    .expect("fits")
                    .len();
                black_box(used)
            })
        });
        group.bench_function(format!("load_{name}"), |b| {
            b.iter(|| {
                let s: SaveState = postcard::from_bytes(black_box(&bytes)).expect("loads");
                black_box(s.into_gpu())
            })
        });
        group.bench_function(format!("save_load_{name}"), |b| {
            b.iter(|| {
                let used = postcard::to_slice(&g.save_state(), &mut buf)
                    .expect("fits")
                    .len();
                let s: SaveState = postcard::from_bytes(black_box(&buf[..used])).expect("loads");
                black_box(s.into_gpu())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, state);
criterion_main!(benches);
