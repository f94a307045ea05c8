//! GTE commands as an emulator drives them, in the two shapes an emulator's calls take.
//!
//! - `emulator/…`: per call, the inputs are written with MTC2 (and the command word issued) on
//!   an evolving register state, and the results and FLAG read back with MFC2/CFC2. The
//!   written values are made ahead of time, as an emulator finds them in CPU registers. Each
//!   command has a `registers only` row (the same MTC2/MFC2/CFC2 traffic without the command).
//! - `plain/…`: the command alone, back to back, each call reading what the previous ones
//!   left in the registers (no MTC2 or MFC2: a game's loop of one command, such as a
//!   light-transform loop).
//!
//! Register indices and command words pass through `black_box`, as a CPU decoder produces
//! them at run time. Both shapes are timed by one function each, of the shape of the C++ loops
//! that time Mednafen's GTE in the comparison (docs/performance.md, "The comparison with
//! Mednafen").

use criterion::{Criterion, criterion_group, criterion_main};
use gte::{Command, Gte, MatrixSel, Opcode, TranslationSel, VectorSel};
use std::hint::black_box;
use std::sync::atomic::{AtomicU32, Ordering};
use std::time::Instant;

/// A typical set-up: rotation, translation in front of the camera, projection, lights,
/// colours (values a PS1 program loads with CTC2).
fn loaded() -> Gte {
    let mut gte = Gte::new();
    let ctrl: [(u32, u32); 26] = [
        (0, 0x0F00_0100),
        (1, 0xFF00_0080),
        (2, 0x0080_0F00),
        (3, 0x00C0_FF40),
        (4, 0x0F80),
        (5, 10),
        (6, (-20i32) as u32),
        (7, 2000),
        (8, 0x0800_0B00),
        (9, 0xF800_0400),
        (10, 0x0C00_0200),
        (11, 0x0300_F900),
        (12, 0x0A00),
        (13, 400),
        (14, 400),
        (15, 400),
        (16, 0x0000_1000),
        (18, 0x0000_1000),
        (20, 0x1000),
        (21, 0x100),
        (22, 0x80),
        (23, 0x40),
        (24, 160 << 16),
        (25, 120 << 16),
        (26, 320),
        (27, (-0x100i32) as u32),
    ];
    for (r, v) in ctrl {
        gte.write_control(r, v);
    }
    gte.write_control(28, 0x0140_0000);
    gte.write_control(29, 0x1000 / 3);
    gte.write_control(30, 0x1000 / 4);
    gte
}

/// A fixed pseudo-random sequence (xorshift), so every run sees the same inputs.
fn inputs(n: usize) -> Vec<u32> {
    let mut x = 0x2545_F491u32;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        })
        .collect()
}

/// Pack two 16-bit halves.
fn xy(lo: i32, hi: i32) -> u32 {
    (lo as u16 as u32) | ((hi as u16 as u32) << 16)
}

/// A vertex in -1024..1023 from random bits: (VXY, VZ).
fn vertex(r: u32) -> (u32, u32) {
    let c = |s: u32| ((r >> s) & 0x7FF) as i32 - 1024;
    (xy(c(0), c(11)), c(22) as u32)
}

fn word(op: Opcode, lm: bool) -> u32 {
    Command::build(
        op,
        true,
        lm,
        MatrixSel::Rotation,
        VectorSel::V0,
        TranslationSel::Translation,
    )
    .word()
}

/// Where each call's result goes: one store per call, which the compiler must make and
/// cannot use as scratch space on the way. Each timed loop reads it once at its end: a
/// value no code reads is one the compiler may drop, and with it the store and the MFC2
/// loads that compute it.
static SINK: AtomicU32 = AtomicU32::new(0);

/// `iters` calls as an emulator makes them: per call, MTC2 of call `i & 1023`'s `writes`,
/// the command (when `execute`), MFC2 of `reads` and CFC2 of FLAG, the sum stored to
/// [`SINK`]. One function with the body in line, the read list fixed in length and one store
/// of the result per call: the shape of the C++ loop that times Mednafen's GTE
/// (docs/performance.md, "The comparison with Mednafen"). A closure handed to
/// `Bencher::iter`, a read list walked at run time and a result summed in memory cost
/// wobble's side time that the other side's loop did not ("The timed loop", in that
/// document).
#[inline(never)]
fn emulator_loop<const N: usize, const R: usize>(
    gte: &mut Gte,
    calls: &[[(u32, u32); N]; 1024],
    reads: &[u32; R],
    cmd: u32,
    execute: bool,
    iters: u64,
    i: &mut usize,
) {
    for _ in 0..iters {
        for &(reg, value) in &calls[*i & 1023] {
            gte.write_data(black_box(reg), value);
        }
        *i = i.wrapping_add(1);
        let mut acc = if execute {
            gte.execute(black_box(cmd)).unwrap_or(0)
        } else {
            0
        };
        for &reg in reads {
            acc = acc.wrapping_add(gte.read_data(black_box(reg)));
        }
        SINK.store(
            acc.wrapping_add(gte.read_control(black_box(31))),
            Ordering::Relaxed,
        );
    }
    black_box(SINK.load(Ordering::Relaxed));
}

/// `iters` calls of `cmd` alone, back to back on the register state the previous calls left:
/// no MTC2, MFC2 or CFC2, each call's cycle count stored to [`SINK`]. The command word passes
/// through `black_box` per call, as a CPU decoder produces it. The shape of the C++ loop that
/// times Mednafen's GTE in the same way (docs/performance.md, "The plain loop").
#[inline(never)]
fn plain_loop(gte: &mut Gte, cmd: u32, iters: u64) {
    for _ in 0..iters {
        SINK.store(gte.execute(black_box(cmd)).unwrap_or(0), Ordering::Relaxed);
    }
    black_box(SINK.load(Ordering::Relaxed));
}

/// Which loop a row runs in.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// [`emulator_loop`]: the row and its `registers only` row.
    Emulator,
    /// [`plain_loop`].
    Plain,
}

/// Benchmark `op` in `shape`. [`Shape::Emulator`] ([`emulator_loop`]): per call, MTC2 of
/// `writes` (register, value) pairs made from a random word ahead of time (an emulator takes
/// them from CPU registers), the command, then MFC2 of `reads` and CFC2 of FLAG; a second row,
/// `…/registers only`, does the same register traffic without the command: the share of the
/// per-call time that is register access rather than the command. [`Shape::Plain`]
/// ([`plain_loop`]): the command alone, from the set-up with the first call's `writes`.
fn run<const N: usize, const R: usize>(
    c: &mut Criterion,
    shape: Shape,
    name: &str,
    op: Opcode,
    lm: bool,
    writes: impl Fn(u32) -> [(u32, u32); N],
    reads: &[u32; R],
) {
    let calls: Box<[[(u32, u32); N]; 1024]> = inputs(1024)
        .into_iter()
        .map(writes)
        .collect::<Vec<_>>()
        .try_into()
        .expect("1024 calls");
    let cmd = word(op, lm);
    if shape == Shape::Plain {
        let mut gte = loaded();
        for &(reg, value) in &calls[0] {
            gte.write_data(reg, value);
        }
        c.bench_function(&format!("plain/{name}"), |b| {
            b.iter_custom(|iters| {
                let start = Instant::now();
                plain_loop(&mut gte, cmd, iters);
                start.elapsed()
            })
        });
        return;
    }
    for execute in [true, false] {
        let mut gte = loaded();
        let mut i = 0usize;
        let label = if execute {
            format!("emulator/{name}")
        } else {
            format!("emulator/{name}/registers only")
        };
        c.bench_function(&label, |b| {
            b.iter_custom(|iters| {
                let start = Instant::now();
                emulator_loop(&mut gte, &calls, reads, cmd, execute, iters, &mut i);
                start.elapsed()
            })
        });
    }
}

/// The three vertices of RTPT/NCDT/NCCT (r0-r5) from one random word.
fn vertices(r: u32) -> [(u32, u32); 6] {
    let mut w = [(0, 0); 6];
    for k in 0..3 {
        let (v, z) = vertex(r.rotate_left(k * 11));
        w[2 * k as usize] = (2 * k, v);
        w[2 * k as usize + 1] = (2 * k + 1, z);
    }
    w
}

/// The rows, each in `shape`: the ten commands of the comparison with Mednafen since issue 9,
/// then GPL, AVSZ4, SQR and OP, the other short commands.
fn rows(c: &mut Criterion, shape: Shape) {
    run(
        c,
        shape,
        "RTPS",
        Opcode::Rtps,
        false,
        |r| {
            let (v, z) = vertex(r);
            [(0, v), (1, z)]
        },
        &[14, 19, 8],
    );
    run(
        c,
        shape,
        "RTPT",
        Opcode::Rtpt,
        false,
        vertices,
        &[12, 13, 14, 17, 18, 19, 8],
    );
    run(
        c,
        shape,
        "NCLIP",
        Opcode::Nclip,
        false,
        |r| -> [(u32, u32); 3] {
            core::array::from_fn(|k| {
                let s = r.rotate_left(k as u32 * 10);
                (
                    12 + k as u32,
                    xy((s & 0x3FF) as i32 - 512, ((s >> 10) & 0x1FF) as i32 - 256),
                )
            })
        },
        &[24],
    );
    run(
        c,
        shape,
        "NCDS",
        Opcode::Ncds,
        true,
        |r| {
            let (v, z) = vertex(r);
            [
                (0, v),
                (1, z),
                (6, 0x3080_8080 ^ (r & 0x3F3F3F)),
                (8, r >> 20),
            ]
        },
        &[22],
    );
    let vertices_and_colour = |r: u32| {
        let v = vertices(r);
        let mut w = [(6, 0x3080_8080 ^ (r & 0x3F3F3F)); 7];
        w[..6].copy_from_slice(&v);
        w
    };
    run(
        c,
        shape,
        "NCDT",
        Opcode::Ncdt,
        true,
        vertices_and_colour,
        &[20, 21, 22],
    );
    run(
        c,
        shape,
        "NCCT",
        Opcode::Ncct,
        true,
        vertices_and_colour,
        &[20, 21, 22],
    );
    run(
        c,
        shape,
        "MVMVA",
        Opcode::Mvmva,
        false,
        |r| {
            let (v, z) = vertex(r);
            [(0, v), (1, z)]
        },
        &[25, 26, 27, 9, 10, 11],
    );
    run(
        c,
        shape,
        "AVSZ3",
        Opcode::Avsz3,
        false,
        |r| {
            [
                (17, r & 0xFFFF),
                (18, r >> 16),
                (19, r.rotate_left(8) & 0xFFFF),
            ]
        },
        &[7],
    );
    run(
        c,
        shape,
        "DPCS",
        Opcode::Dpcs,
        false,
        |r| [(6, 0x3000_0000 | (r & 0xFF_FFFF)), (8, r >> 19)],
        &[22],
    );
    let interpolated = |r: u32| {
        [
            (8, r >> 19),
            (9, r & 0x7FFF),
            (10, (r >> 8) & 0x7FFF),
            (11, (r >> 16) & 0x7FFF),
        ]
    };
    run(c, shape, "GPF", Opcode::Gpf, false, interpolated, &[22]);
    run(c, shape, "GPL", Opcode::Gpl, false, interpolated, &[22]);
    run(
        c,
        shape,
        "AVSZ4",
        Opcode::Avsz4,
        false,
        |r| {
            [
                (16, r & 0xFFFF),
                (17, r >> 16),
                (18, r.rotate_left(8) & 0xFFFF),
                (19, r.rotate_left(24) & 0xFFFF),
            ]
        },
        &[7],
    );
    // IR1-3 in -1000h..=FFFh (a unit vector's components, 1.3.12).
    let ir = |r: u32| -> [(u32, u32); 3] {
        core::array::from_fn(|k| {
            let v = ((r >> (10 * k)) & 0x1FFF) as i32 - 0x1000;
            (9 + k as u32, v as u32)
        })
    };
    run(c, shape, "SQR", Opcode::Sqr, false, ir, &[25, 26, 27]);
    run(c, shape, "OP", Opcode::Op, false, ir, &[25, 26, 27]);
}

fn emulator(c: &mut Criterion) {
    rows(c, Shape::Emulator);
}

fn plain(c: &mut Criterion) {
    rows(c, Shape::Plain);
}

criterion_group!(benches, emulator, plain);
criterion_main!(benches);
