//! Replays a GPU command stream line by line on `gpu` directly (no inspector code) and
//! prints, as JSON, every line that changed VRAM pixel (x, y): `[line, before, after,
//! pixels the line changed]`. The browser test (.ci/browser-test.js) checks the
//! inspector's pixel history and changed-pixel highlight against it.
//!
//! Usage: `cargo run --example pixel_history -- STREAM X Y`

use gpu::Gpu;
use gpu::command_stream::{self, Port};

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [stream, x, y] = args.as_slice() else {
        return Err("usage: pixel_history STREAM X Y".into());
    };
    let num = |s: &str| s.parse::<usize>().map_err(|e| format!("{s}: {e}"));
    let (x, y) = (num(x)?, num(y)?);
    if x >= gpu::VRAM_WIDTH || y >= gpu::VRAM_HEIGHT {
        return Err(format!("({x}, {y}) is outside VRAM"));
    }
    let text = std::fs::read_to_string(stream).map_err(|e| format!("{stream}: {e}"))?;
    let commands = command_stream::parse(&text).map_err(|e| format!("{stream}: {e}"))?;
    let mut gpu = Gpu::new();
    let at = y * gpu::VRAM_WIDTH + x;
    let mut out = Vec::new();
    for c in &commands {
        let before = gpu.vram().as_slice().to_vec();
        match c.port {
            Port::Gp0 => gpu.gp0_words(&c.words),
            Port::Gp1 => c.words.iter().for_each(|&w| gpu.gp1(w)),
        }
        let after = gpu.vram().as_slice();
        if before[at] != after[at] {
            let n = before.iter().zip(after).filter(|(a, b)| a != b).count();
            out.push(format!("[{},{},{},{n}]", c.line, before[at], after[at]));
        }
    }
    println!("[{}]", out.join(","));
    Ok(())
}
