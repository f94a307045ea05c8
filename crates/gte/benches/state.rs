//! Save-state size and the time to save and load one (postcard) through the public API, as a
//! frontend does every frame for rewind or run-ahead: `Gte::state`, serialize, deserialize,
//! `Gte::load_state`.

use criterion::{Criterion, criterion_group, criterion_main};
use gte::{Gte, GteState};
use std::hint::black_box;

/// Every register written with a distinct value and a command run, so that no field is zero
/// and each varint has its full width.
fn loaded() -> Gte {
    let mut gte = Gte::new();
    for r in 0..64 {
        gte.write(r, 0x8765_4321u32.rotate_left(r));
    }
    gte.execute(0x0008_0030); // RTPT
    gte
}

fn state(c: &mut Criterion) {
    let mut group = c.benchmark_group("gte_state");
    let gte = loaded();
    let bytes = postcard::to_allocvec(&gte.state()).expect("serializes");
    println!("GTE state: {} bytes (postcard)", bytes.len());
    let mut buf = vec![0u8; bytes.len()];
    group.bench_function("save", |b| {
        b.iter(|| {
            let used = postcard::to_slice(&black_box(&gte).state(), &mut buf)
                .expect("fits")
                .len();
            black_box(used)
        })
    });
    let mut target = Gte::new();
    group.bench_function("load", |b| {
        b.iter(|| {
            let s: GteState = postcard::from_bytes(black_box(&bytes)).expect("loads");
            target.load_state(&s).expect("same version");
            black_box(&target);
        })
    });
    group.bench_function("save_load", |b| {
        b.iter(|| {
            let used = postcard::to_slice(&black_box(&gte).state(), &mut buf)
                .expect("fits")
                .len();
            let s: GteState = postcard::from_bytes(black_box(&buf[..used])).expect("loads");
            target.load_state(&s).expect("same version");
            black_box(&target);
        })
    });
    group.finish();
}

criterion_group!(benches, state);
criterion_main!(benches);
