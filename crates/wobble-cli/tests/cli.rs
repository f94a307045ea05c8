//! The `wobble` binary on the fixtures and on bad input.

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn wobble(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn gte_replay_hardware_vectors() {
    let f = root().join("fixtures/gte/ps1-tests-hw.jsonl");
    let o = wobble(&["gte", "replay", f.to_str().unwrap()]);
    assert!(o.status.success());
    assert_eq!(stdout(&o).lines().last(), Some("1150 passed, 0 failed"));
}

#[test]
fn gte_replay_reports_failures_and_bad_lines() {
    let scratch = Scratch::new("gte_replay_reports_failures_and_bad_lines");
    let zeros = format!("[{}]", vec!["0"; 32].join(","));
    // A register-only vector expecting all zeros fails on LZCR (reads 32 for LZCS = 0).
    let text = format!(
        "{{\"name\":\"z\",\"cmd\":null,\"in_data\":{zeros},\"in_ctrl\":{zeros},\"out_data\":{zeros},\"out_ctrl\":{zeros}}}\nnot json\n"
    );
    let f = scratch.join("bad.jsonl");
    std::fs::write(&f, text).unwrap();
    let o = wobble(&["gte", "replay", f.to_str().unwrap()]);
    assert!(!o.status.success());
    let out = stdout(&o);
    assert!(out.contains("FAIL z (line 1)"), "{out}");
    assert!(out.contains("LZCR"));
    assert_eq!(out.lines().last(), Some("0 passed, 2 failed"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("line 2: not JSON"));
}

#[test]
fn gte_replay_emit_is_json() {
    let scratch = Scratch::new("gte_replay_emit_is_json");
    let f = scratch.join("emit.jsonl");
    std::fs::write(
        &f,
        "{\"name\":\"w\",\"cmd\":null,\"writes\":[[30,4294967295]]}\n",
    )
    .unwrap();
    let o = wobble(&["gte", "replay", "--emit", f.to_str().unwrap()]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    assert_eq!(v["name"], "w");
    assert_eq!(v["out_data"][31], 32); // LZCR of FFFFFFFFh
}

#[test]
fn replay_writes_png_and_raw() {
    let scratch = Scratch::new("replay_writes_png_and_raw");
    let stream = root().join("fixtures/gpu/quad.gpu");
    let png = scratch.join("quad.png");
    let raw = scratch.join("quad.vram.bin");
    let o = wobble(&[
        "replay",
        stream.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--raw",
        raw.to_str().unwrap(),
        "--expand",
        "shift",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1024, 512));
    // With --expand shift the PNG equals the console capture.
    let capture = image::open(root().join("fixtures/gpu/quad.vram.png"))
        .unwrap()
        .to_rgb8();
    assert!(img == capture);
    assert_eq!(std::fs::metadata(&raw).unwrap().len(), 1024 * 512 * 2);
}

#[test]
fn replay_names_bad_line() {
    let scratch = Scratch::new("replay_names_bad_line");
    let f = scratch.join("bad.gpu");
    std::fs::write(&f, "gp0 e1000000\ngp9 1\n").unwrap();
    let o = wobble(&[
        "replay",
        f.to_str().unwrap(),
        "-o",
        scratch.join("x.png").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.gpu") && err.contains("line 2"), "{err}");
}

/// A hand-built raw VRAM: pixel (0,0) = red 31, (1,0) = green 16; a 4-bit texture page at
/// (64,0) whose first halfword 0021h holds indices 1, 2, 0, 0 and a CLUT at (0,1) with
/// entry 1 = blue 31, entry 2 = 7FFFh (white).
fn raw_vram(dir: &Path) -> PathBuf {
    let mut v = vec![0u16; 1024 * 512];
    v[0] = 0x001F;
    v[1] = 16 << 5;
    v[64] = 0x0021;
    v[1024 + 1] = 0x7C00;
    v[1024 + 2] = 0x7FFF;
    let bytes: Vec<u8> = v.iter().flat_map(|p| p.to_le_bytes()).collect();
    let f = dir.join("hand.vram.bin");
    std::fs::write(&f, bytes).unwrap();
    f
}

#[test]
fn dump_whole_and_display() {
    let scratch = Scratch::new("dump_whole_and_display");
    let raw = raw_vram(&scratch);
    let png = scratch.join("dump.png");
    let o = wobble(&["dump", raw.to_str().unwrap(), "-o", png.to_str().unwrap()]);
    assert!(o.status.success());
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]);
    assert_eq!(img.get_pixel(1, 0).0, [0, 132, 0]); // 16 << 3 | 16 >> 2
    let o = wobble(&[
        "dump",
        raw.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--region",
        "display",
        "--display",
        "1,0,256x240",
    ]);
    assert!(o.status.success());
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (256, 240));
    assert_eq!(img.get_pixel(0, 0).0, [0, 132, 0]);
}

#[test]
fn dump_texture_page() {
    let scratch = Scratch::new("dump_texture_page");
    let raw = raw_vram(&scratch);
    let png = scratch.join("page.png");
    let o = wobble(&[
        "dump",
        raw.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--texpage",
        "64,0",
        "--depth",
        "4",
        "--clut",
        "0,1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image::open(&png).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (256, 256));
    assert_eq!(img.get_pixel(0, 0).0, [0, 0, 255, 255]);
    assert_eq!(img.get_pixel(1, 0).0, [255, 255, 255, 255]);
    assert_eq!(
        img.get_pixel(2, 0).0[3],
        0,
        "index 0 -> CLUT entry 0000h, transparent"
    );
}

#[test]
fn dump_rejects_wrong_size() {
    let scratch = Scratch::new("dump_rejects_wrong_size");
    let f = scratch.join("short.bin");
    std::fs::write(&f, [0u8; 100]).unwrap();
    let o = wobble(&[
        "dump",
        f.to_str().unwrap(),
        "-o",
        scratch.join("y.png").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("got 100"));
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `dump` refuses arguments that would be ignored or are out of range, saying why.
#[test]
fn dump_argument_errors() {
    let scratch = Scratch::new("dump_argument_errors");
    let raw = raw_vram(&scratch);
    let raw = raw.to_str().unwrap();
    let png = scratch.join("dump-args.png");
    let png = png.to_str().unwrap();
    let o = wobble(&[
        "dump",
        raw,
        "-o",
        png,
        "--region",
        "display",
        "--display",
        "0,0,100000x100000",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("outside 1..=1024 x 1..=512"),
        "{}",
        stderr(&o)
    );
    let o = wobble(&["dump", raw, "-o", png, "--texpage", "64,0", "--depth", "16"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("4, 8 or 15"), "{}", stderr(&o));
    for extra in [["--depth", "8"], ["--clut", "0,1"]] {
        let o = wobble(&["dump", raw, "-o", png, extra[0], extra[1]]);
        assert!(!o.status.success(), "{extra:?} without --texpage");
        assert!(stderr(&o).contains("--texpage"), "{}", stderr(&o));
    }
    let o = wobble(&[
        "dump",
        raw,
        "-o",
        png,
        "--display",
        "0,0,256x240",
        "--region",
        "vram",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--region vram"), "{}", stderr(&o));
}

/// `--display` implies `--region display`: the image is the display area alone, its first
/// pixel the hand-made VRAM's green pixel at (1,0).
#[test]
fn dump_display_implies_the_region() {
    let scratch = Scratch::new("dump_display_implies_the_region");
    let raw = raw_vram(&scratch);
    let png = scratch.join("dump-display.png");
    let o = wobble(&[
        "dump",
        raw.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--display",
        "1,0,256x240",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (256, 240));
    assert_eq!(img.get_pixel(0, 0).0, [0, 132, 0]);
}

/// `-o` picks the image format from the extension, or refuses with the list.
#[test]
fn output_format_from_extension() {
    let scratch = Scratch::new("output_format_from_extension");
    let raw = raw_vram(&scratch);
    let raw = raw.to_str().unwrap();
    for (ext, format) in [
        ("bmp", image::ImageFormat::Bmp),
        ("tga", image::ImageFormat::Tga),
        ("ppm", image::ImageFormat::Pnm),
        ("gif", image::ImageFormat::Gif),
        ("PNG", image::ImageFormat::Png),
    ] {
        let out = scratch.join(format!("fmt.{ext}"));
        let o = wobble(&["dump", raw, "-o", out.to_str().unwrap()]);
        assert!(o.status.success(), "{ext}: {}", stderr(&o));
        let bytes = std::fs::read(&out).unwrap();
        if format != image::ImageFormat::Tga {
            // TGA has no signature to recognise it by.
            assert_eq!(image::guess_format(&bytes).ok(), Some(format), "{ext}");
        }
        if format != image::ImageFormat::Gif {
            // Lossless formats: the first pixel is red 31 expanded to 255.
            let img = image::load_from_memory_with_format(&bytes, format)
                .unwrap()
                .to_rgb8();
            assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0], "{ext}");
        }
    }
    for name in ["out.txt", "out.jpg", "noextension"] {
        let out = scratch.join(name);
        let o = wobble(&["dump", raw, "-o", out.to_str().unwrap()]);
        assert!(!o.status.success(), "{name}");
        let e = stderr(&o);
        assert!(e.contains(".png, .gif, .bmp, .tga, .ppm"), "{name}: {e}");
        assert!(!out.exists(), "{name} written");
    }
}

/// Output paths are checked before the work: an unwritable `--raw` fails before the PNG is
/// written, and nothing is left behind.
#[test]
fn replay_checks_outputs_before_writing() {
    let scratch = Scratch::new("replay_checks_outputs_before_writing");
    let stream = root()
        .join("fixtures/gpu")
        .read_dir()
        .unwrap()
        .find_map(|e| {
            let p = e.ok()?.path();
            (p.extension()? == "gpu").then_some(p)
        });
    let stream = stream.expect("a .gpu fixture");
    let dir = scratch.join("replay-check");
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("out.png");
    let _ = std::fs::remove_file(&png);
    let o = wobble(&[
        "replay",
        stream.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
        "--raw",
        "/nonexistent-dir/x.vram.bin",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("/nonexistent-dir"), "{}", stderr(&o));
    assert!(!png.exists(), "PNG written before the raw path was checked");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

/// A stream that ends mid-packet, mid-transfer or inside a polyline is warned about on
/// stderr with the line where the unfinished input started.
#[test]
fn replay_warns_on_unfinished_stream() {
    let scratch = Scratch::new("replay_warns_on_unfinished_stream");
    let cases = [
        // Line 2: a flat triangle (GP0 20h, 4 words) given only 2.
        (
            "gp1 00000000\ngp0 20FF0000 00000000\n",
            "mid-packet",
            "line 2",
        ),
        // Line 3: a 2x2 CPU-to-VRAM transfer (2 data words) given one.
        (
            "# copy\n\ngp0 A0000000 00000000 00020002 7FFF7FFF\n",
            "mid-transfer",
            "line 3",
        ),
        // Line 1: a polyline with no terminator.
        ("gp0 48FFFFFF 00000000 00100010\n", "polyline", "line 1"),
    ];
    for (i, (text, what, line)) in cases.iter().enumerate() {
        let stream = scratch.join(format!("unfinished{i}.gpu"));
        std::fs::write(&stream, text).unwrap();
        let png = scratch.join(format!("unfinished{i}.png"));
        let o = wobble(&[
            "replay",
            stream.to_str().unwrap(),
            "-o",
            png.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let e = stderr(&o);
        assert!(
            e.contains("warning") && e.contains(what) && e.contains(line),
            "case {i}: {e}"
        );
    }
    let stream = scratch.join("finished.gpu");
    std::fs::write(&stream, "gp0 20FF0000 00000000 00100000 00000010\n").unwrap();
    let png = scratch.join("finished.png");
    let o = wobble(&[
        "replay",
        stream.to_str().unwrap(),
        "-o",
        png.to_str().unwrap(),
    ]);
    assert!(
        o.status.success() && !stderr(&o).contains("warning"),
        "{}",
        stderr(&o)
    );
}

/// What the README claims of the seven console captures: `replay --expand shift` writes each
/// capture PNG pixel for pixel; the default `--expand replicate` does not (it writes 5-bit
/// 31 as 255 where the capture tool wrote 248).
#[test]
fn replay_reproduces_every_capture_with_expand_shift() {
    let scratch = Scratch::new("replay_reproduces_every_capture_with_expand_shift");
    let mut names: Vec<String> = std::fs::read_dir(root().join("fixtures/gpu"))
        .unwrap()
        .filter_map(|e| {
            let name = e.ok()?.file_name().to_string_lossy().into_owned();
            name.strip_suffix(".vram.png").map(str::to_string)
        })
        .collect();
    names.sort();
    assert_eq!(names.len(), 7, "{names:?}");
    for name in &names {
        let stream = root().join(format!("fixtures/gpu/{name}.gpu"));
        let capture = image::open(root().join(format!("fixtures/gpu/{name}.vram.png")))
            .unwrap()
            .to_rgb8();
        for (expand, equal) in [("shift", true), ("replicate", false)] {
            let png = scratch.join(format!("capture-{name}-{expand}.png"));
            let o = wobble(&[
                "replay",
                stream.to_str().unwrap(),
                "-o",
                png.to_str().unwrap(),
                "--expand",
                expand,
            ]);
            assert!(o.status.success(), "{name}: {}", stderr(&o));
            let img = image::open(&png).unwrap().to_rgb8();
            assert_eq!(img == capture, equal, "{name} with --expand {expand}");
        }
    }
}

/// `replay --timing` on a plain stream: two environment words and a 320x240 fill, stored by
/// the CPU word by word (one cycle each); the fill starts with the fifth store and takes
/// 23 + 240 x (320 / 16 + 1870 / 256) CPU cycles (docs/emulator.md, "Drawing time"); the GPU
/// time is printed in CPU cycles, hblanks and milliseconds (33.8688 MHz).
#[test]
fn replay_timing_prints_the_gpu_time() {
    let scratch = Scratch::new("replay_timing_prints_the_gpu_time");
    let stream = scratch.join("timing-fill.gpu");
    std::fs::write(&stream, "gp0 e3000000 e407ffff\ngp0 02000000 0 00f00140\n").unwrap();
    let o = wobble(&[
        "replay",
        "--timing",
        stream.to_str().unwrap(),
        "-o",
        scratch.join("timing-fill.png").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let fill: f64 = 23.0 + 240.0 * (20.0 + 1870.0 / 256.0);
    let gpu = (fill * 11.0 / 7.0).floor();
    let expected = 5.0 + (gpu * 7.0 / 11.0).ceil();
    let line = out.lines().next().unwrap();
    let cycles: f64 = line
        .strip_prefix("GPU time: ")
        .and_then(|l| l.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    assert!((cycles - expected).abs() <= 1.0, "{out}");
    let ms = format!("{:.3} ms", cycles * 1000.0 / 33_868_800.0);
    assert!(line.contains(&ms) && line.contains("NTSC"), "{out}");
    // About 3 hblanks of 2171.9 CPU cycles each.
    assert!(line.contains(" 3 hblanks,"), "{out}");
}

/// `replay --timing` on the timed stream of ps1-tests gpu/bandwidth's FillScreen workload
/// prints what timer 1 counted; the console counted 1216 hblanks (psx.log, f727802).
#[test]
fn replay_timing_reports_a_timed_stream() {
    let scratch = Scratch::new("replay_timing_reports_a_timed_stream");
    let stream = root().join("fixtures/gpu/bandwidth/fill.gpu");
    let o = wobble(&[
        "replay",
        "--timing",
        stream.to_str().unwrap(),
        "-o",
        scratch.join("bandwidth-fill.png").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let report = out
        .lines()
        .find(|l| l.starts_with("report \"FillScreen GP0(2)\""))
        .unwrap_or_else(|| panic!("{out}"));
    let hblanks: f64 = report
        .split(": ")
        .nth(1)
        .and_then(|r| r.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{report}"));
    assert!((hblanks / 1216.0 - 1.0).abs() < 0.1, "{report}");
    // Without --timing the directives are refused, naming the flag.
    let o = wobble(&[
        "replay",
        stream.to_str().unwrap(),
        "-o",
        scratch.join("bandwidth-fill2.png").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--timing"), "{}", stderr(&o));
    // --console needs --timing.
    let o = wobble(&["replay", "--console", "pal", stream.to_str().unwrap()]);
    assert!(!o.status.success());
}

/// `replay --no-texture-cache` reads texels straight from VRAM. Four 15-bit texels (7C1Fh)
/// are uploaded at x = 512 and drawn by a 4x1 sprite, which loads them into the texture
/// cache; a fill then paints them green (03E0h: 24-bit 00FF00h as 5:5:5) and a second
/// sprite draws them on line 1. With the cache, the fill under a resident entry is not seen
/// and line 1 gets the stale 7C1Fh; without it, the fill's 03E0h (docs/hardware/gpu.md §10).
#[test]
fn replay_without_the_texture_cache_shows_no_stale_texels() {
    let scratch = Scratch::new("replay_without_the_texture_cache_shows_no_stale_texels");
    let stream = scratch.join("stale.gpu");
    std::fs::write(
        &stream,
        "gp1 00000000\ngp0 e3000000\ngp0 e407ffff\ngp0 e5000000\n\
         # 15-bit texture page at x = 512\ngp0 e1000108\n\
         gp0 a0000000\ngp0 00000200\ngp0 00010004\ngp0 7c1f7c1f\ngp0 7c1f7c1f\n\
         gp0 65000000\ngp0 00000000\ngp0 00000000\ngp0 00010004\n\
         gp0 0200ff00\ngp0 00000200\ngp0 00010010\n\
         gp0 65000000\ngp0 00010000\ngp0 00000000\ngp0 00010004\n",
    )
    .unwrap();
    let line1 = |extra: &[&str]| {
        let raw = scratch.join(format!("stale{}.bin", extra.len()));
        let mut args = vec![
            "replay",
            stream.to_str().unwrap(),
            "-o",
            "/dev/null",
            "--format",
            "png",
            "--raw",
            raw.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = wobble(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let vram = std::fs::read(&raw).unwrap();
        (0..4)
            .map(|x| {
                let at = (1024 + x) * 2;
                u16::from_le_bytes([vram[at], vram[at + 1]])
            })
            .collect::<Vec<_>>()
    };
    assert_eq!(line1(&[]), [0x7C1F; 4]);
    assert_eq!(line1(&["--no-texture-cache"]), [0x03E0; 4]);
}
