//! The non-hardware accuracy options of `wobble render`: run with the `accuracy-knobs`
//! feature, refused with an error naming it without (`cargo test -p wobble-cli
//! --no-default-features`).

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn render(dir: &Path, name: &str, extra: &[&str]) -> Output {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = dir.join(format!("{name}.png"));
    Command::new(env!("CARGO_BIN_EXE_wobble"))
        .arg("render")
        .arg(root.join("fixtures/scenes/face-on.toml"))
        .arg("-o")
        .arg(&out)
        .args(extra)
        .output()
        .unwrap()
}

#[test]
fn non_hardware_options_need_the_feature() {
    let scratch = Scratch::new("non_hardware_options_need_the_feature");
    let cases: [(&str, &[&str], &str); 4] = [
        ("subpixel", &["--subpixel"], "sub-pixel vertices"),
        (
            "perspective",
            &["--perspective-uv"],
            "perspective-correct texture coordinates",
        ),
        ("exact", &["--divide", "exact"], "exact GTE divide"),
        ("f32", &["--divide", "f32"], "f32 GTE divide"),
    ];
    for (name, args, knob) in cases {
        let o = render(&scratch, name, args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        if cfg!(feature = "accuracy-knobs") {
            assert!(o.status.success(), "{args:?}: {stderr}");
        } else {
            assert!(!o.status.success(), "{args:?} ran without the feature");
            assert!(
                stderr.contains(knob) && stderr.contains("`accuracy-knobs`"),
                "{args:?}: {stderr}"
            );
        }
    }
}

/// The hardware divide is no knob: every build runs it.
#[test]
fn the_hardware_divide_runs_in_every_build() {
    let scratch = Scratch::new("the_hardware_divide_runs_in_every_build");
    let o = render(&scratch, "unr", &["--divide", "unr"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
