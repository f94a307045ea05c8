//! Replays the GPU command streams recorded from tests run on a real PlayStation
//! (fixtures/gpu) and compares the whole VRAM with the console's capture: every pixel's 5-bit
//! channels against the capture's channel >> 3 (bit 15 is not recorded), only the white pixels
//! of `<name>.mask.png` where one exists.

use gpu::{Gpu, VRAM_HEIGHT, VRAM_WIDTH, command_stream};
use std::path::PathBuf;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/gpu")).join(name)
}

/// A PNG decoded to 8-bit RGB pixels (grey and palette images expanded, alpha dropped), with
/// its width and height.
fn load_rgb(path: &PathBuf) -> Option<(u32, u32, Vec<[u8; 3]>)> {
    let file = std::fs::File::open(path).ok()?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().expect("PNG header");
    let mut buf = vec![0; reader.output_buffer_size().expect("PNG size")];
    let info = reader.next_frame(&mut buf).expect("PNG data");
    let channels = info.color_type.samples();
    let pixels = buf[..info.buffer_size()]
        .chunks_exact(channels)
        .map(|p| match channels {
            1 | 2 => [p[0], p[0], p[0]],
            _ => [p[0], p[1], p[2]],
        })
        .collect();
    Some((info.width, info.height, pixels))
}

fn check(name: &str) {
    let text = std::fs::read_to_string(fixture(&format!("{name}.gpu"))).expect("stream");
    let commands = command_stream::parse(&text).expect("stream parses");
    let mut gpu = Gpu::new();
    command_stream::run(&mut gpu, &commands);
    let (width, height, capture) =
        load_rgb(&fixture(&format!("{name}.vram.png"))).expect("capture");
    assert_eq!((width, height), (VRAM_WIDTH as u32, VRAM_HEIGHT as u32));
    let mask = load_rgb(&fixture(&format!("{name}.mask.png"))).map(|(w, h, m)| {
        assert_eq!((w, h), (width, height));
        m
    });
    let mut differing = 0;
    let mut first = Vec::new();
    for y in 0..VRAM_HEIGHT {
        for x in 0..VRAM_WIDTH {
            let i = y * VRAM_WIDTH + x;
            if let Some(m) = &mask
                && m[i][0] != 255
            {
                continue;
            }
            let p = gpu.vram().pixel(x, y);
            let got = [p & 31, (p >> 5) & 31, (p >> 10) & 31];
            let c = capture[i];
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
