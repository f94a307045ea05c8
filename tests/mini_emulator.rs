//! The runnable example `examples/mini_emulator.rs` (an emulator loop written only against
//! the public API of `gte` and `gpu`) runs under `cargo test` and sees what a console shows.

#[path = "../examples/mini_emulator.rs"]
mod mini_emulator;

#[test]
fn mini_emulator_runs() {
    let png = std::env::temp_dir().join(format!("wobble-mini-emulator-{}.png", std::process::id()));
    let s = mini_emulator::run(&png).unwrap_or_else(|e| panic!("{e}"));
    // RTPT takes 23 cycles (docs/hardware/gte.md §1), three frames of it.
    assert_eq!(s.gte_cycles, 3 * 23);
    assert_eq!((s.vblanks, s.gpu_irqs), (3, 3));
    assert_eq!(s.frame, (320, 240));
    // Three NTSC frames from power-on: at most three frame periods of 263 lines of 3413 GPU
    // cycles at 7/11 CPU cycles each (docs/hardware/timing.md), and more than two.
    let frame = 263.0 * 3413.0 * 7.0 / 11.0;
    assert!((s.video_cycles as f64) > 2.0 * frame && (s.video_cycles as f64) <= 3.0 * frame + 1.0);
    assert!(png.exists());
    let _ = std::fs::remove_file(&png);
}
