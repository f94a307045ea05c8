//! Beam queries: `Gpu::beam`, `Gpu::cycles_until`, `Gpu::cycles_until_dots`. The expected
//! positions come from the clock ratio, line length and line counts of
//! docs/hardware/timing.md §1-§3, computed here from the total CPU cycles run; the timer
//! figures from ps1-tests `timers/psx.log` (MIT, fixtures/gpu/LICENSE-ps1-tests).

use gpu::{Beam, EventKind, Events, Gpu, VideoStandard};
use proptest::prelude::*;

#[path = "support/video.rs"]
mod video;

use video::{INTERLACE, LINES480, PAL, gpu, ranged, sequence};

/// The beam after `cpu` CPU cycles from power-on, computed from the clock alone: video cycles
/// `cpu * clock / 33,868,800` rounded down; lines of 3413 (NTSC) or 3406 (PAL) cycles; fields
/// of 263/314 lines, or alternately 263 + 262 / 313 + 312 when interlaced (docs/gpu.md "Video
/// timing"); hblank outside X1..X2, vblank outside Y1..Y2.
fn expected_beam(
    standard: VideoStandard,
    mode: u32,
    (x1, x2): (u32, u32),
    (y1, y2): (u32, u32),
    cpu: u64,
) -> Beam {
    let clock = match standard {
        VideoStandard::Ntsc => 53_222_400u128,
        VideoStandard::Pal => 53_203_425,
    };
    let video = (cpu as u128 * clock / 33_868_800) as u64;
    let pal = mode & PAL != 0;
    let line_len: u64 = if pal { 3406 } else { 3413 };
    let first: u64 = if pal { 313 } else { 263 };
    let (field, pos) = if mode & INTERLACE != 0 {
        let frame = (2 * first - 1) * line_len;
        let p = video % frame;
        if p < first * line_len {
            (0, p)
        } else {
            (1, p - first * line_len)
        }
    } else {
        let lines = if pal { 314 } else { 263 };
        (0, video % (lines * line_len))
    };
    let lines = if mode & INTERLACE != 0 {
        first as u32 - field
    } else if pal {
        314
    } else {
        263
    };
    let (line, cycle) = ((pos / line_len) as u32, (pos % line_len) as u32);
    Beam {
        line,
        cycle,
        hblank: cycle < x1 || cycle >= x2,
        vblank: y2 < lines && !(y1 <= line && line < y2),
        field: field as u8,
    }
}

/// A deterministic sequence of chunk sizes in 1..=`max`.
fn chunks(seed: u64, max: u64) -> impl Iterator<Item = u32> {
    sequence(seed).map(move |x| (x % max) as u32 + 1)
}

#[test]
fn beam_follows_the_clock() {
    let ranges = [
        ((0x260u32, 0xC60u32), (0x10u32, 0x100u32)),
        ((608, 3168), (19, 307)),
    ];
    for (standard, mode) in [
        (VideoStandard::Ntsc, 0x01),
        (VideoStandard::Ntsc, INTERLACE | LINES480 | 0x03),
        (VideoStandard::Ntsc, PAL),
        (VideoStandard::Pal, PAL | 0x01),
        (VideoStandard::Pal, PAL | INTERLACE | LINES480),
        (VideoStandard::Pal, 0x40),
    ] {
        for ((x1, x2), (y1, y2)) in ranges {
            let mut g = ranged(standard, mode, (x1, x2), (y1, y2));
            let mut cpu = 0u64;
            for c in chunks(mode as u64 * 7 + x1 as u64, 40_000).take(3000) {
                g.run(c);
                cpu += c as u64;
                let expected = expected_beam(standard, mode, (x1, x2), (y1, y2), cpu);
                assert_eq!(g.beam(), expected, "{standard:?} mode {mode:#x} at {cpu}");
            }
        }
    }
}

#[test]
fn gpustat_bits_agree_with_the_beam() {
    // GPUSTAT.31 is 0 in vblank; GPUSTAT.13 is the field in 480i (docs/hardware/timing.md §7).
    let mut g = gpu(VideoStandard::Ntsc, INTERLACE | LINES480);
    for c in chunks(5, 30_000).take(2000) {
        g.run(c);
        let (beam, stat) = (g.beam(), g.gpustat());
        if beam.vblank {
            assert_eq!(stat >> 31, 0);
        }
        assert_eq!(stat >> 13 & 1, beam.field as u32);
    }
}

/// Runs `g` `n` cycles and says whether an event of `kind` was reported.
fn reports(g: &mut Gpu, n: u32, kind: EventKind) -> bool {
    let e: Events = g.run(n);
    match kind {
        EventKind::HblankStart => e.hblank_start,
        EventKind::HblankEnd => e.hblank_end,
        EventKind::VblankStart => e.vblank_start,
        EventKind::VblankEnd => e.vblank_end,
        EventKind::DrawingDone => e.drawing_done,
    }
}

const KINDS: [EventKind; 5] = [
    EventKind::HblankStart,
    EventKind::HblankEnd,
    EventKind::VblankStart,
    EventKind::VblankEnd,
    EventKind::DrawingDone,
];

#[test]
fn the_next_edge_of_each_kind_is_exact_across_modes() {
    for standard in [VideoStandard::Ntsc, VideoStandard::Pal] {
        for mode in [
            0u32,
            1,
            3,
            0x40,
            PAL,
            INTERLACE | LINES480,
            PAL | INTERLACE | 2,
        ] {
            let mut g = gpu(standard, mode);
            for (i, c) in chunks(mode as u64 + 11, 300_000).take(120).enumerate() {
                g.run(c);
                if i % 10 == 0 {
                    // Keep the drawing side busy now and then.
                    g.gp0_words(&[0x0200_0000, 0, (i as u32 % 200 + 8) << 16 | 320]);
                }
                for kind in KINDS {
                    let n = g.cycles_until(kind);
                    if kind == EventKind::DrawingDone && n == u32::MAX {
                        assert!(!reports(&mut g.clone(), 2_000_000, kind));
                        continue;
                    }
                    assert!(n != u32::MAX, "{kind:?} always comes here");
                    if n == 0 {
                        assert!(reports(&mut g.clone(), 0, kind), "{kind:?} pending");
                        continue;
                    }
                    assert!(!reports(&mut g.clone(), n - 1, kind), "{kind:?} early");
                    assert!(reports(&mut g.clone(), n, kind), "{kind:?} at {n}");
                }
            }
        }
    }
}

#[test]
fn vblank_kinds_never_come_without_vblank() {
    // Y2 past the last line: no vblank starts (docs/hardware/timing.md §6); Y1 >= Y2: no
    // line is shown and no vblank edge comes either.
    for (y1, y2) in [(0x10u32, 0x3FFu32), (0x100, 0x10)] {
        let mut g = gpu(VideoStandard::Ntsc, 0);
        g.gp1(0x0700_0000 | y2 << 10 | y1);
        assert_eq!(g.cycles_until(EventKind::VblankStart), u32::MAX);
        assert_eq!(g.cycles_until(EventKind::VblankEnd), u32::MAX);
        let mut e = Events::default();
        for _ in 0..4 {
            let step = g.run(300_000);
            e.vblank_start |= step.vblank_start;
            e.vblank_end |= step.vblank_end;
        }
        assert!(!e.vblank_start && !e.vblank_end);
        assert!(g.cycles_until(EventKind::HblankStart) < 2200);
    }
    // 480i with Y2 = 262: the first field (263 lines) reaches it, the second (262) does not;
    // the next vblank start is a field and a half away from the second field's start.
    let mut g = gpu(VideoStandard::Ntsc, INTERLACE | LINES480);
    g.gp1(0x0700_0000 | 262 << 10 | 0x10);
    while g.beam().field == 0 {
        g.run(g.cycles_until_next_event());
    }
    let beam = g.beam();
    let n = g.cycles_until(EventKind::VblankStart) as u64;
    // The rest of field 1, then 262 lines of field 0.
    let video = 262 * 3413 - (beam.line * 3413 + beam.cycle) as u64 + 262 * 3413;
    assert!(n.abs_diff(video * 7 / 11) <= 1, "{n} vs {}", video * 7 / 11);
}

/// A root counter as an emulator keeps it (psx-spx "Timers"; docs/hardware/timing.md §8),
/// synchronised to a blank signal: `sync` 0 pauses during the blank, 1 resets at its start,
/// 2 resets at its start and pauses outside it, 3 waits for the first start, then runs free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Timer {
    sync: u8,
    count: u64,
    started: bool,
}

impl Timer {
    fn new(sync: u8) -> Self {
        Self {
            sync,
            count: 0,
            started: false,
        }
    }

    /// `ticks` of the timer's clock passed with the blank signal `blank` throughout; then, if
    /// `edge`, the blank started.
    fn step(&mut self, ticks: u64, blank: bool, edge: bool) {
        let counting = match self.sync {
            0 => !blank,
            1 => true,
            2 => blank,
            _ => self.started,
        };
        if counting {
            self.count += ticks;
        }
        if edge {
            match self.sync {
                1 | 2 => self.count = 0,
                _ => self.started = true,
            }
        }
    }
}

/// Which signal and clock a timer uses.
#[derive(Clone, Copy, Debug)]
enum Source {
    /// Timer 0 on the system clock, synchronised to hblank.
    T0System,
    /// Timer 0 on the dot clock, synchronised to hblank.
    T0Dots,
    /// Timer 1 on hblanks, synchronised to vblank.
    T1Hblank,
}

impl Source {
    fn ticks(self, cpu: u32, e: &Events) -> u64 {
        match self {
            Source::T0System => cpu as u64,
            Source::T0Dots => e.dots as u64,
            Source::T1Hblank => e.hblanks as u64,
        }
    }

    fn blank(self, b: Beam) -> bool {
        match self {
            Source::T0System | Source::T0Dots => b.hblank,
            Source::T1Hblank => b.vblank,
        }
    }

    fn edge(self, e: &Events) -> bool {
        match self {
            Source::T0System | Source::T0Dots => e.hblank_start,
            Source::T1Hblank => e.vblank_start,
        }
    }

    /// The blank edges that change what the timer does.
    fn kinds(self) -> [EventKind; 2] {
        match self {
            Source::T0System | Source::T0Dots => [EventKind::HblankStart, EventKind::HblankEnd],
            Source::T1Hblank => [EventKind::VblankStart, EventKind::VblankEnd],
        }
    }
}

/// Drive `timer` for `total` CPU cycles as an emulator does: stop at the CPU slice ends in
/// `slices` and at the blank edges `cycles_until` names, reading the blank from `beam` and the
/// ticks from `run`'s events. Returns the counter at each slice end.
fn drive_by_edges(g: &mut Gpu, source: Source, mut timer: Timer, slices: &[u32]) -> Vec<u64> {
    let mut seen = vec![];
    for &slice in slices {
        let mut left = slice;
        while left > 0 {
            let edge = source
                .kinds()
                .map(|k| g.cycles_until(k))
                .into_iter()
                .min()
                .unwrap();
            let n = edge.min(left);
            let blank = source.blank(g.beam());
            let e = g.run(n);
            timer.step(source.ticks(n, &e), blank, source.edge(&e));
            left -= n;
        }
        seen.push(timer.count);
    }
    seen
}

/// The same timer polled at every CPU cycle.
fn drive_by_cycles(g: &mut Gpu, source: Source, mut timer: Timer, slices: &[u32]) -> Vec<u64> {
    let mut seen = vec![];
    for &slice in slices {
        for _ in 0..slice {
            let blank = source.blank(g.beam());
            let e = g.run(1);
            timer.step(source.ticks(1, &e), blank, source.edge(&e));
        }
        seen.push(timer.count);
    }
    seen
}

#[test]
fn timers_in_every_sync_mode_run_from_the_beam_queries() {
    // Timer 0 in 320x240 with the 2560-cycle range the timers log used (608..3168), timer 1
    // with the GP1(07h) reset range.
    for (source, slices) in [
        (Source::T0System, vec![122u32; 60]),
        (Source::T0Dots, vec![122u32; 60]),
        (Source::T1Hblank, vec![40_000u32; 30]),
    ] {
        for sync in 0..4u8 {
            let mut a = gpu(VideoStandard::Ntsc, 0x01);
            a.gp1(0x0600_0000 | 3168 << 12 | 608);
            a.run(1234);
            let mut b = a.clone();
            let by_edges = drive_by_edges(&mut a, source, Timer::new(sync), &slices);
            let by_cycles = drive_by_cycles(&mut b, source, Timer::new(sync), &slices);
            assert_eq!(by_edges, by_cycles, "{source:?} sync {sync}");
            assert!(a == b);
            let max = *by_edges.iter().max().unwrap();
            // What the log's rows show of each mode, in bounds (timers/psx.log, 100-cycle
            // delays, samples 122 cycles apart): mode 2 counts only inside one hblank (at
            // most 543 system clocks, 510 seen at 320 wide), mode 1 restarts every line
            // (under 2172 system clocks, 1367 seen; under 426 dots, 178 seen), mode 3 is 0
            // until the first hblank.
            match (source, sync) {
                (Source::T0System, 2) => assert!(max <= 543, "{by_edges:?}"),
                (Source::T0System, 1) => assert!(max < 2172, "{by_edges:?}"),
                (Source::T0Dots, 1) => assert!(max <= 426, "{by_edges:?}"),
                (Source::T0Dots, 2) => assert!(max <= 543 * 11 / 7 / 8 + 1, "{by_edges:?}"),
                (Source::T1Hblank, 1) => assert!(max <= 263, "{by_edges:?}"),
                (Source::T1Hblank, 2) => assert!(max <= 263 - 240, "{by_edges:?}"),
                _ => {}
            }
            if sync == 3 {
                assert_eq!(by_edges[0], 0, "{source:?}: nothing before the first blank");
                assert!(max > 0);
            }
        }
    }
}

proptest! {
    /// The beam after a span of time run in any split is the beam after one call, and the
    /// whole GPU is equal.
    #[test]
    fn any_split_gives_the_same_beam(
        mode in 0u32..0x80,
        x1 in 0u32..4096, x2 in 0u32..4096, y1 in 0u32..1024, y2 in 0u32..1024,
        splits in prop::collection::vec(1u32..200_000, 1..40),
    ) {
        let mut a = ranged(VideoStandard::Pal, mode, (x1, x2), (y1, y2));
        let mut b = a.clone();
        a.run(splits.iter().sum());
        for s in &splits {
            b.run(*s);
            let beam = b.beam();
            prop_assert!(beam.cycle < 3413 && beam.field <= 1);
        }
        prop_assert_eq!(a.beam(), b.beam());
        prop_assert!(a == b);
    }

    /// Every kind's deadline, in any mode and range: one cycle early it has not happened,
    /// at the deadline it has; none announced means none in two frames.
    #[test]
    fn each_kind_is_exact(
        mode in 0u32..0x80,
        x1 in 0u32..4096, x2 in 0u32..4096, y1 in 0u32..1024, y2 in 0u32..1024,
        pre in 0u32..2_000_000,
    ) {
        let mut g = ranged(VideoStandard::Ntsc, mode, (x1, x2), (y1, y2));
        g.run(pre);
        for kind in KINDS {
            let n = g.cycles_until(kind);
            if n == u32::MAX {
                prop_assert!(!reports(&mut g.clone(), 1_400_000, kind), "{:?}", kind);
            } else {
                prop_assert!(n >= 1);
                prop_assert!(!reports(&mut g.clone(), n - 1, kind), "{:?} early", kind);
                prop_assert!(reports(&mut g.clone(), n, kind), "{:?} late", kind);
            }
        }
    }

    /// A dot deadline: one CPU cycle early fewer dots have ticked, at it exactly enough (a
    /// CPU cycle is 1.6 video cycles, a dot at least 4).
    #[test]
    fn dot_deadlines_are_exact(
        mode in 0u32..0x80,
        pre in 0u32..2_000_000,
        dots in 1u32..3_000_000,
        pal_console in any::<bool>(),
    ) {
        let standard = if pal_console { VideoStandard::Pal } else { VideoStandard::Ntsc };
        let mut g = gpu(standard, mode);
        g.run(pre);
        let n = g.cycles_until_dots(dots);
        prop_assert!(n >= 1);
        prop_assert!(g.clone().run(n - 1).dots < dots);
        let got = g.run(n).dots;
        prop_assert_eq!(got, dots);
    }
}
