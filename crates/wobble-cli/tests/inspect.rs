//! `wobble inspect` and `wobble render --inspect` from the command line.

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/gpu")
        .join(name)
}

#[test]
fn command_line() {
    let scratch = Scratch::new("command_line");
    let dir = scratch.join("report");
    let out = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["inspect", fixture("triangle.gpu").to_str().unwrap(), "-o"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("commands") && stdout.contains("index.html"),
        "{stdout}"
    );
    assert!(dir.join("index.html").is_file());
    // A malformed stream is a clear error naming the line.
    let bad = dir.join("bad.gpu");
    std::fs::write(&bad, "gp0 e3000000\ngp0 zz\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["inspect", bad.to_str().unwrap(), "-o"])
        .arg(dir.join("bad"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 2"));
}

#[test]
fn render_inspect() {
    let dir = Scratch::new("render_inspect");
    let png = dir.join("frame.png");
    let out = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--frames", "2", "--inspect"])
        .arg(dir.join("report"))
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.join("report/index.html").is_file());
    let faces = std::fs::read_to_string(dir.join("report/data/faces.js")).unwrap();
    assert!(faces.contains("drawn, OT slot"));
    // The precise path cannot be traced: a clear error.
    let out = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--subpixel", "--inspect"])
        .arg(dir.join("report2"))
        .arg("-o")
        .arg(&png)
        .output()
        .unwrap();
    assert!(!out.status.success());
    // Without the `accuracy-knobs` feature, `--subpixel` itself is refused first.
    let why = if cfg!(feature = "accuracy-knobs") {
        "hardware path"
    } else {
        "`accuracy-knobs`"
    };
    assert!(String::from_utf8_lossy(&out.stderr).contains(why));
}
