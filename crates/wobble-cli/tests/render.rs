//! `wobble render`: the example scene, a bad size, animated GIF output.

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn render_command_on_example_and_bad_size() {
    let scratch = Scratch::new("render_command_on_example_and_bad_size");
    let out = write(&scratch, "ex.png", "");
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
        summary.starts_with("3 frames -> ") && summary.contains("polygons drawn"),
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
    let scratch = Scratch::new("render_gif");
    let gif = write(&scratch, "anim.gif", "");
    let out = write(&scratch, "last.png", "");
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
    let scratch = Scratch::new("frames_without_gif_flag_write_a_gif_beside_the_png");
    let out = write(&scratch, "beside.png", "");
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
            && summary.contains(&format!("{} (2 frames, ", gif.display())),
        "{summary}"
    );
}

/// The README's largest size works on the default scene (its CLUT goes beside the buffers).
#[test]
fn default_scene_at_640x256() {
    let scratch = Scratch::new("default_scene_at_640x256");
    let out = write(&scratch, "big.png", "");
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
    let scratch = Scratch::new("progress_lines_and_large_output_refusal");
    let out = write(&scratch, "progress.png", "");
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
    // 100000 frames at 320x240: 320 * 240 / 6 = 12800 bytes a frame, 1280 MB in all.
    std::fs::remove_file(&gif).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(["render", "--frames", "100000", "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("1280 MB") && e.contains("--large-output"), "{e}");
    assert!(!gif.exists());
}

/// `--compare`: a GIF twice the screen's width, at the default scene's 30 frames a second
/// (3/100 s a frame), each half labelled: the label boxes are black with white ink, and the
/// first glyphs match the public-domain 8x8 font's table ('P' rows 0x3F, 0x66, 0x66; 'r' row
/// 2 0x3B, bit 0 leftmost), drawn 2 pixels in from the box corner.
#[test]
fn compare_side_by_side_with_labels() {
    let scratch = Scratch::new("compare_side_by_side_with_labels");
    use image::AnimationDecoder;
    let out = write(&scratch, "compare.gif", "");
    let o = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args([
            "render",
            "--compare",
            "--frames",
            "2",
            "-o",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(
        summary.contains("frames/s rendered") && summary.contains(" KB, 30 fps"),
        "{summary}"
    );
    let file = std::io::BufReader::new(std::fs::File::open(&out).unwrap());
    let frames = image::codecs::gif::GifDecoder::new(file)
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 2);
    assert_eq!(frames[0].delay().numer_denom_ms(), (30, 1));
    let img = frames[0].buffer();
    assert_eq!(img.dimensions(), (640, 240));
    let ink = |x: u32, y: u32| img.get_pixel(x, y).0[..3] == [255, 255, 255];
    let dark = |x: u32, y: u32| img.get_pixel(x, y).0[..3] == [0, 0, 0];
    let row = |x0: u32, y: u32, bits: u8| {
        (0..8).all(|i| {
            if bits >> i & 1 == 1 {
                ink(x0 + i, y)
            } else {
                dark(x0 + i, y)
            }
        })
    };
    // Left: "PS1: ..." starts with 'P'.
    assert!(row(2, 2, 0x3F) && row(2, 3, 0x66) && row(2, 4, 0x66));
    // Right: "reference: ..." starts with 'r' at x = 320.
    assert!(row(322, 4, 0x3B));
    // The top margin of both boxes is black across the first glyphs.
    assert!((0..20).all(|x| dark(x, 0) && dark(320 + x, 0)));
    let _ = std::fs::remove_file(&out);
}

/// Every size the README advertises renders the default scene (8-bit checker CLUT) and the
/// example scene (4-bit CLUT), including 256 lines where no VRAM line is left below the two
/// display buffers.
#[test]
fn advertised_sizes_render() {
    let scratch = Scratch::new("advertised_sizes_render");
    let example = root().join("fixtures/scenes/example.toml");
    for size in [
        "256x256", "320x256", "368x256", "512x256", "640x256", "640x240",
    ] {
        let out = write(&scratch, &format!("size-{size}.png"), "");
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

/// `--zoom`: each output pixel of a region is the unzoomed frame's pixel at the region's
/// corner plus the output position divided by the scale; regions stack with 4 rows between
/// them and 4 black columns at the right; a region outside the screen is refused.
#[test]
fn zoom_crops_and_scales_the_frame() {
    let scratch = Scratch::new("zoom_crops_and_scales_the_frame");
    let plain = write(&scratch, "plain.png", "");
    let zoomed = write(&scratch, "zoomed.png", "");
    let run = |extra: &[&str], out: &PathBuf| {
        let mut args = vec!["render", "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        Command::new(env!("CARGO_BIN_EXE_wobble"))
            .args(&args)
            .output()
            .unwrap()
    };
    let o = run(&[], &plain);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(
        &["--zoom", "100,60,20,10", "--zoom", "300,230,5,10"],
        &zoomed,
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let plain = image::open(&plain).unwrap().to_rgb8();
    let zoomed = image::open(&zoomed).unwrap().to_rgb8();
    assert_eq!(plain.dimensions(), (320, 240));
    // Widest region 20 * 3 + 4; heights 10 * 3 + 4 + 10 * 3.
    assert_eq!(zoomed.dimensions(), (64, 64));
    let mut distinct = std::collections::HashSet::new();
    for (x0, y0, w, h, top) in [(100, 60, 20, 10, 0), (300, 230, 5, 10, 34)] {
        for y in 0..h * 3 {
            for x in 0..w * 3 {
                let want = plain.get_pixel(x0 + x / 3, y0 + y / 3);
                distinct.insert(want.0);
                assert_eq!(zoomed.get_pixel(x, top + y), want, "({x}, {})", top + y);
            }
        }
    }
    // The regions are not one flat colour (the check would not see a shifted crop).
    assert!(distinct.len() > 4, "{distinct:?}");
    for y in 30..34 {
        assert_eq!(zoomed.get_pixel(0, y).0, [0, 0, 0]);
    }
    for x in 60..64 {
        assert_eq!(zoomed.get_pixel(x, 0).0, [0, 0, 0]);
    }
    let out = write(&scratch, "never.png", "");
    for (bad, says) in [
        ("310,0,11,10", "not inside the 320x240 screen"),
        ("0,235,10,6", "rows 235..241"),
        ("1,2,3", "expected X,Y,W,H"),
        ("1,2,0,4", "expected X,Y,W,H"),
    ] {
        let o = run(&["--zoom", bad], &out);
        assert!(!o.status.success(), "{bad}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{bad}: {err}");
    }
    let o = run(&["--zoom", "0,0,8,8", "--zoom-scale", "9"], &out);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--zoom-scale must be 1..=8"));
}
