//! Replays the GPU command streams recorded from tests run on a real PlayStation
//! (fixtures/gpu) and compares the whole VRAM with the console's capture: every pixel's 5-bit
//! channels against the capture's channel >> 3 (bit 15 is not recorded), only the white pixels
//! of `<name>.mask.png` where one exists.

use gpu::{Gpu, VRAM_HEIGHT, VRAM_WIDTH, command_stream};
use std::path::PathBuf;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/gpu")
        .join(name)
}

fn check(name: &str) {
    let text = std::fs::read_to_string(fixture(&format!("{name}.gpu"))).expect("stream");
    let commands = command_stream::parse(&text).expect("stream parses");
    let mut gpu = Gpu::new();
    command_stream::run(&mut gpu, &commands);
    let capture = image::open(fixture(&format!("{name}.vram.png")))
        .expect("capture")
        .to_rgb8();
    assert_eq!(
        capture.dimensions(),
        (VRAM_WIDTH as u32, VRAM_HEIGHT as u32)
    );
    let mask = image::open(fixture(&format!("{name}.mask.png")))
        .ok()
        .map(|m| m.to_luma8());
    let mut differing = 0;
    let mut first = Vec::new();
    for y in 0..VRAM_HEIGHT {
        for x in 0..VRAM_WIDTH {
            if let Some(m) = &mask
                && m.get_pixel(x as u32, y as u32)[0] != 255
            {
                continue;
            }
            let p = gpu.vram().pixel(x, y);
            let got = [p & 31, (p >> 5) & 31, (p >> 10) & 31];
            let c = capture.get_pixel(x as u32, y as u32);
            let want = [c[0] as u16 >> 3, c[1] as u16 >> 3, c[2] as u16 >> 3];
            if got != want {
                differing += 1;
                if first.len() < 10 {
                    first.push(format!("({x},{y}) got {got:?} want {want:?}"));
                }
            }
        }
    }
    assert_eq!(
        differing,
        0,
        "{name}: {differing} pixels differ; first: {}",
        first.join("; ")
    );
}

#[test]
fn quad() {
    check("quad");
}

#[test]
fn triangle() {
    check("triangle");
}

#[test]
fn transparency() {
    check("transparency");
}

#[test]
fn lines() {
    check("lines");
}

#[test]
fn rectangles() {
    check("rectangles");
}

#[test]
fn texture_overflow() {
    check("texture-overflow");
}

#[test]
fn texture_flip() {
    check("texture-flip");
}
