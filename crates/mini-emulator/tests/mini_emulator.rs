//! The emulator loop (written only against the public API of `gte` and `gpu`) runs under
//! `cargo test` and sees what a console shows.

#[path = "../../../tests/support/scratch.rs"]
mod scratch;

#[test]
fn mini_emulator_runs() {
    let dir = scratch::Scratch::new("run");
    let out = dir.join("frame.ppm");
    let s = mini_emulator::run(&out).unwrap_or_else(|e| panic!("{e}"));
    // RTPT takes 23 cycles (docs/hardware/gte.md §1), three frames of it.
    assert_eq!(s.gte_cycles, 3 * 23);
    assert_eq!((s.vblanks, s.gpu_irqs), (3, 3));
    assert_eq!(s.frame, (320, 240));
    assert_eq!(s.lines, 240);
    // The lists waited for FIFO room, and that wait is counted once: DMA time is one cycle a
    // word plus one per 16 (110h per 100h, docs/hardware/dma.md §10), plus the wait, plus
    // three OTC clears of 8 words.
    assert!(s.dma_wait_cycles > 0);
    let transfer = |words: u32| words + words / 16;
    let per_frame_words = s.list_words / 3;
    assert_eq!(per_frame_words * 3, s.list_words);
    assert_eq!(
        s.dma_cycles,
        3 * transfer(per_frame_words) + s.dma_wait_cycles + 3 * transfer(8)
    );
    // Three NTSC frames from power-on: up to the third vblank start, 256 lines of 3413 GPU
    // cycles (GP1(07h) Y2) and two whole 263-line frames, at 7/11 CPU cycles each
    // (docs/hardware/timing.md §1-§3, §6).
    let line = 3413.0 * 7.0 / 11.0;
    let expected = (256.0 + 2.0 * 263.0) * line;
    assert!(
        (s.video_cycles as f64 - expected).abs() < 2.0,
        "{}",
        s.video_cycles
    );
    let ppm = std::fs::read(&out).expect("PPM written");
    assert!(ppm.starts_with(b"P6\n320 240\n255\n"));
    assert_eq!(ppm.len(), b"P6\n320 240\n255\n".len() + 320 * 240 * 3);
}
