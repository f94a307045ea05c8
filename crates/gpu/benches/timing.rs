//! Cost of advancing one NTSC frame of video timing with its events, in the chunks an
//! emulator would use: one `run` per frame, one per scanline, one per event found with
//! `cycles_until_next_event` (every hblank edge and the vblank edges), and one per field
//! found with `cycles_until(EventKind::VblankStart)`; and of scanning a frame out line by
//! line with `run_lines`, each line decoded to RGBA. The GPU is idle, the display in its reset
//! mode (256x240, hblank and vblank ranges set; turned on for the scan-out).

use criterion::{Criterion, criterion_group, criterion_main};
use gpu::{EventKind, Events, Gpu, PixelFormat};
use std::hint::black_box;

/// CPU cycles of one progressive NTSC frame: 263 lines of 3413 video cycles at 7/11 CPU
/// cycles each (docs/hardware/timing.md §1, §3), rounded up.
const FRAME_CPU_CYCLES: u32 = (263 * 3413 * 7_u32).div_ceil(11);
/// CPU cycles of one NTSC scanline, rounded down.
const LINE_CPU_CYCLES: u32 = 3413 * 7 / 11;

fn merge(total: &mut Events, e: Events) {
    total.dots += e.dots;
    total.hblanks += e.hblanks;
    total.vblank_start |= e.vblank_start;
    total.vblank_end |= e.vblank_end;
}

fn frame(c: &mut Criterion) {
    let mut group = c.benchmark_group("ntsc_frame");
    let mut g = Gpu::new();
    group.bench_function("one_run_per_frame", |b| {
        b.iter(|| black_box(g.run(black_box(FRAME_CPU_CYCLES))))
    });
    let mut g = Gpu::new();
    group.bench_function("one_run_per_line", |b| {
        b.iter(|| {
            let mut total = Events::default();
            for _ in 0..263 {
                merge(&mut total, g.run(black_box(LINE_CPU_CYCLES)));
            }
            black_box(total)
        })
    });
    let mut g = Gpu::new();
    group.bench_function("one_run_per_event", |b| {
        b.iter(|| {
            // Until the vblank start: one frame of hblank and vblank edges.
            let mut total = Events::default();
            let mut runs = 0u32;
            loop {
                let wait = g.cycles_until_next_event();
                let e = g.run(wait.max(1));
                runs += 1;
                merge(&mut total, e);
                if e.vblank_start {
                    break;
                }
            }
            black_box((total, runs))
        })
    });
    let mut g = Gpu::new();
    group.bench_function("one_run_per_vblank", |b| {
        b.iter(|| {
            let wait = g.cycles_until(EventKind::VblankStart);
            black_box(g.run(wait))
        })
    });
    let mut g = Gpu::new();
    g.gp1(0x0300_0000);
    let mut rgba = vec![0u8; 256 * 240 * 4];
    group.bench_function("run_lines_rgba", |b| {
        b.iter(|| {
            let wait = g.cycles_until(EventKind::VblankStart);
            black_box(g.run_lines(wait, |line| {
                let at = line.row as usize * 256 * 4;
                if let Some(row) = rgba.get_mut(at..at + 256 * 4) {
                    black_box(line.decode(row, PixelFormat::Rgba8888).ok());
                }
            }))
        })
    });
    let mut g = Gpu::new();
    g.gp1(0x0300_0000);
    group.bench_function("display_frame_rgba", |b| {
        b.iter(|| black_box(g.display_frame(&mut rgba, PixelFormat::Rgba8888).ok()))
    });
    group.finish();
    // Calls per frame, for reading the per-event figure.
    let mut runs = 0;
    let mut seen = 0;
    while seen < 2 {
        let e = g.run(g.cycles_until_next_event().max(1));
        if seen == 1 {
            runs += 1;
        }
        if e.vblank_start {
            seen += 1;
        }
    }
    println!("one_run_per_event: {runs} run calls per frame");
}

criterion_group!(benches, frame);
criterion_main!(benches);
