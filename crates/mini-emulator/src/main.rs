//! `mini-emulator [out.ppm]`: runs the loop of the library and prints what it saw; the
//! picture goes to `out.ppm`, by default `mini_emulator.ppm` in the current directory.

use std::path::PathBuf;

fn main() {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("mini_emulator.ppm"));
    match mini_emulator::run(&out) {
        Ok(s) => println!(
            "{} frames: GTE {} cycles, DMA {} cycles ({} waiting for FIFO room), {} CPU cycles \
             run through the GPU, {} vblanks, {} GPU IRQs, {} lines scanned out; {}x{} frame \
             -> {}",
            mini_emulator::FRAMES,
            s.gte_cycles,
            s.dma_cycles,
            s.dma_wait_cycles,
            s.video_cycles,
            s.vblanks,
            s.gpu_irqs,
            s.lines,
            s.frame.0,
            s.frame.1,
            s.out.display()
        ),
        Err(e) => {
            eprintln!("mini-emulator: {e}");
            std::process::exit(1);
        }
    }
}
