//! `wobble trade`: the command writes the report on a small scene.

mod common;

use common::Scratch;
use std::path::PathBuf;

/// `wobble trade` runs on a small scene and writes the table, images and plot.
#[test]
fn trade_command_writes_report() {
    let scratch = Scratch::new("trade_command_writes_report");
    let out = scratch.join("report");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args([
            "trade",
            PathBuf::from(env!("CARGO_MANIFEST_DIR"))
                .join("../../fixtures/scenes/face-on.toml")
                .to_str()
                .unwrap(),
            "--frames",
            "2",
            "--repeats",
            "1",
            "--sweep-step",
            "4099",
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("trade.md")).unwrap();
    assert!(md.contains("| hardware (UNR, snapped, affine, dither, tess 0) |"));
    assert!(md.contains("| tessellation 4 |"));
    // Without a terminal, the divide sweep shows plain progress lines, every 10%: with
    // every 4099th H there are 16 rows per mode (H = 0 to 15 * 4099), 48 in all.
    let stderr = String::from_utf8_lossy(&o.stderr);
    let sweep: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("divide sweep: "))
        .collect();
    assert!(sweep.len() >= 10, "{stderr}");
    assert_eq!(
        sweep.last().copied(),
        Some("divide sweep: 48/48 rows (100%)"),
        "{stderr}"
    );
    for f in ["hardware-vs-reference.png", "tessellation-curve.png"] {
        assert!(out.join("trade").join(f).exists(), "{f}");
    }
}
