//! Drawing and transfer time against a console: ps1-tests `gpu/bandwidth` (JaCzekanski, MIT,
//! Copyright (c) 2020 Jakub Czekański, fixtures/gpu/LICENSE-ps1-tests) draws 400 primitives
//! per workload while timer 1 counts hblanks, and its `psx.log` (commit f727802) holds what
//! the console counted. Each workload is transcribed, with the CPU's behaviour, as a timed
//! stream in fixtures/gpu/bandwidth/ and played through the public API by `gpu::bus::run`.
//!
//! Eight rows of the log calibrated the cost model (docs/emulator.md, "Drawing time"); each
//! has a test here that the model stays within 10% of the console. The other six rows are the
//! validation set: their tests print the model's prediction, have no expected figure, and are
//! ignored, so that the model is never fitted to them.

use gpu::Gpu;
use std::path::PathBuf;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/gpu/bandwidth"
    ))
    .join(name)
}

/// What the test program prints as "hblanks": `getTimer()` adds FFFFh when timer 1 wrapped
/// (it cannot tell two wraps from one), and `calculate` takes the sum as a 16-bit value.
fn printed_hblanks(counted: u64) -> u64 {
    let value = counted % 0x1_0000 + if counted >= 0x1_0000 { 0xFFFF } else { 0 };
    value % 0x1_0000
}

/// The hblanks the console's timer 1 reads for a workload, as the test prints them, and the
/// texture cache misses counted.
fn model_hblanks(file: &str) -> (u64, u64) {
    let text = std::fs::read_to_string(fixture(file)).expect("workload stream");
    let stream = gpu::bus::parse(&text).expect("workload stream parses");
    let mut gpu = Gpu::new();
    let run = gpu::bus::run(&mut gpu, &stream).expect("workload stream runs");
    let report = run.reports.last().expect("the workload reads timer 1");
    (printed_hblanks(report.hblanks), gpu.texture_cache_misses())
}

/// The model within 10% of the console's count, `console` as `psx.log` prints it.
fn calibration_row(file: &str, console: u64) {
    let (model, misses) = model_hblanks(file);
    let ratio = model as f64 / console as f64;
    println!("{file}: model {model} hblanks, console {console}, {ratio:.3}x, {misses} misses");
    assert!(
        (0.9..=1.1).contains(&ratio),
        "{file}: model {model} hblanks, console {console} ({ratio:.3}x)"
    );
}

/// A validation row: the prediction only.
fn validation_row(file: &str) {
    let (model, misses) = model_hblanks(file);
    println!("{file}: model {model} hblanks, {misses} misses");
}

// ---- Calibration rows (psx.log: "hblanks: N") ----

#[test]
fn vram_to_cpu() {
    calibration_row("vram-to-cpu.gpu", 15770);
}

#[test]
fn vram_to_vram() {
    calibration_row("vram-to-vram.gpu", 19132);
}

#[test]
fn fill_screen() {
    calibration_row("fill.gpu", 1216);
}

#[test]
fn rectangle() {
    calibration_row("rectangle.gpu", 7603);
}

#[test]
fn rectangle_semitransparent() {
    calibration_row("rectangle-semi.gpu", 11455);
}

#[test]
fn polygon_quad() {
    calibration_row("quad.gpu", 7727);
}

#[test]
fn polygon_quad_semi() {
    calibration_row("quad-semi.gpu", 11648);
}

#[test]
fn polygon_quad_textured() {
    calibration_row("quad-textured.gpu", 39938);
}

// ---- Validation rows: predictions only (run with --ignored --nocapture) ----

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn cpu_to_vram() {
    validation_row("cpu-to-vram.gpu");
}

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn rectangle_textured() {
    validation_row("rectangle-textured.gpu");
}

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn rectangle_textured_semi() {
    validation_row("rectangle-textured-semi.gpu");
}

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn polygon_quad_textured_semi() {
    validation_row("quad-textured-semi.gpu");
}

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn polygon_quad_quarter_off_screen() {
    validation_row("quad-quarter-off.gpu");
}

#[test]
#[ignore = "validation row: prints the prediction, checked against psx.log by hand"]
fn polygon_quad_half_off_screen() {
    validation_row("quad-half-off.gpu");
}
