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
    // The summary names both files written.
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(
        summary.contains(&format!("{} (last frame)", out.display()))
            && summary.contains(&format!("{} (2 frames)", gif.display())),
        "{summary}"
    );
}

/// The README's largest size works on the default scene (its CLUT goes beside the buffers).
#[test]
fn default_scene_at_640x256() {
    let out = write("big.png", "");
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--size", "640x256", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (640, 256));
}

/// Many frames: plain progress lines when stderr is not a terminal, and an output
/// estimated above the limit is refused before any work unless forced.
#[test]
fn progress_lines_and_large_output_refusal() {
    let out = write("progress.png", "");
    let gif = out.with_extension("gif");
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--frames", "20", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("rendered 2/20 frames") && e.contains("rendered 20/20 frames"),
        "{e}"
    );
    // 100000 frames at 320x240: 320 * 240 / 16 = 4800 bytes a frame, 480 MB in all.
    std::fs::remove_file(&gif).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--frames", "100000", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("480 MB") && e.contains("--large-output"), "{e}");
    assert!(!gif.exists());
}

/// Every size the README advertises renders the default scene (8-bit checker CLUT) and the
/// example scene (4-bit CLUT), including 256 lines where no VRAM line is left below the two
/// display buffers.
#[test]
fn advertised_sizes_render() {
    let example = root().join("fixtures/scenes/example.toml");
    for size in [
        "256x256", "320x256", "368x256", "512x256", "640x256", "640x240",
    ] {
        let out = write(&format!("size-{size}.png"), "");
        for scene in [None, Some(example.to_str().unwrap())] {
            let mut args = vec!["render", "--size", size, "-o", out.to_str().unwrap()];
            args.extend(scene);
            let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
                .args(&args)
                .output()
                .unwrap();
            assert!(
                o.status.success(),
                "{size} {scene:?}: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            let (w, h) = size.split_once('x').unwrap();
            assert_eq!(
                image::open(&out).unwrap().to_rgb8().dimensions(),
                (w.parse().unwrap(), h.parse().unwrap())
            );
        }
    }
}
