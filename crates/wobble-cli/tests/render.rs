//! `wobble render`: the example scene, a bad size, animated GIF output.

use std::path::PathBuf;
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wobble-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn render_command_on_example_and_bad_size() {
    let out = write("ex.png", "");
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args([
            "render",
            root()
                .join("fixtures/scenes/example.toml")
                .to_str()
                .unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--frames",
            "3",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(
        summary.starts_with("3 frame(s)") && summary.contains("polygons drawn"),
        "{summary}"
    );
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().dimensions(),
        (320, 240)
    );
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--size", "300x200", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--size"));
}

#[test]
fn render_gif() {
    let gif = write("anim.gif", "");
    let out = write("last.png", "");
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args([
            "render",
            "--frames",
            "4",
            "--gif",
            gif.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    use image::AnimationDecoder;
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&gif).unwrap(),
    ))
    .unwrap();
    assert_eq!(decoder.into_frames().count(), 4);
}

#[test]
fn frames_without_gif_flag_write_a_gif_beside_the_png() {
    let out = write("beside.png", "");
    let gif = out.with_extension("gif");
    let _ = std::fs::remove_file(&gif);
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--frames", "2", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    use image::AnimationDecoder;
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&gif).unwrap(),
    ))
    .unwrap();
    assert_eq!(decoder.into_frames().count(), 2);
}
