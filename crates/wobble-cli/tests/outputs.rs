//! Where outputs go (docs/formats.md, "Output files"): symbolic links are written through, FIFOs
//! and devices are never replaced, `-o -` is standard output, a read-only directory is a
//! clear error, and neither an error nor an interrupt leaves a partial or temporary file.

#![cfg(unix)]

mod common;

use common::Scratch;
use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn wobble(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The names in `d`, sorted (hidden ones too).
fn entries(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A raw VRAM file whose pixel (0,0) is red 31, (1,0) green 16.
fn raw_vram(d: &Path) -> PathBuf {
    let mut v = vec![0u16; 1024 * 512];
    v[0] = 0x001F;
    v[1] = 16 << 5;
    let bytes: Vec<u8> = v.iter().flat_map(|p| p.to_le_bytes()).collect();
    let f = d.join("in.vram.bin");
    std::fs::write(&f, bytes).unwrap();
    f
}

/// The PNG `dump` writes for `raw_vram`, decoded: 1024x512, red then green.
fn assert_dump_png(bytes: &[u8]) {
    assert_eq!(
        image::guess_format(bytes).ok(),
        Some(image::ImageFormat::Png)
    );
    let img = image::load_from_memory(bytes).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (1024, 512));
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]);
    assert_eq!(img.get_pixel(1, 0).0, [0, 132, 0]);
}

/// `-o link.png` writes the file the link points to; the link stays a link. A link to a
/// file that does not exist yet creates that file.
#[test]
fn symbolic_links_are_written_through() {
    let d = Scratch::new("symlink");
    let raw = raw_vram(&d);
    std::fs::write(d.join("real.png"), b"old").unwrap();
    std::os::unix::fs::symlink("real.png", d.join("link.png")).unwrap();
    let o = wobble(&["dump", s(&raw), "-o", s(&d.join("link.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    let link = std::fs::symlink_metadata(d.join("link.png")).unwrap();
    assert!(link.file_type().is_symlink(), "the link was replaced");
    assert_dump_png(&std::fs::read(d.join("real.png")).unwrap());
    // A dangling link into a subdirectory: the file is created there.
    std::fs::create_dir(d.join("sub")).unwrap();
    std::os::unix::fs::symlink("sub/new.png", d.join("dangling.png")).unwrap();
    let o = wobble(&["dump", s(&raw), "-o", s(&d.join("dangling.png"))]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::symlink_metadata(d.join("dangling.png"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_dump_png(&std::fs::read(d.join("sub/new.png")).unwrap());
    assert_eq!(
        entries(&d),
        ["dangling.png", "in.vram.bin", "link.png", "real.png", "sub"]
    );
    assert_eq!(entries(&d.join("sub")), ["new.png"]);
}

/// A FIFO is written through (a reader gets the PNG) and is still a FIFO afterwards; with no
/// image extension its format is PNG.
#[test]
fn fifo_is_written_through() {
    let d = Scratch::new("fifo");
    let raw = raw_vram(&d);
    let fifo = d.join("pipe");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let o = wobble(&["dump", s(&raw), "-o", s(&fifo)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_dump_png(&reader.join().unwrap());
    let m = std::fs::symlink_metadata(&fifo).unwrap();
    assert!(m.file_type().is_fifo(), "the FIFO was replaced");
    assert_eq!(entries(&d), ["in.vram.bin", "pipe"]);
}

/// `/dev/null` takes images, raw VRAM and GIFs, and stays a character device.
#[test]
fn dev_null_takes_every_output() {
    let stream = root().join("fixtures/gpu/quad.gpu");
    let o = wobble(&[
        "replay",
        s(&stream),
        "-o",
        "/dev/null",
        "--raw",
        "/dev/null",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = wobble(&[
        "render",
        "--frames",
        "2",
        "-o",
        "/dev/null",
        "--gif",
        "/dev/null",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let m = std::fs::metadata("/dev/null").unwrap();
    assert!(m.file_type().is_char_device());
    assert_eq!(m.len(), 0);
}

/// `-o -` writes the image to standard output when a format is given, byte for byte what a
/// file gets; without one it is refused naming `--format`. The summary then goes to stderr.
#[test]
fn dash_is_standard_output() {
    let d = Scratch::new("stdout");
    let raw = raw_vram(&d);
    let o = wobble(&["dump", s(&raw), "-o", "-", "--format", "png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_dump_png(&o.stdout);
    let file = d.join("file.png");
    let f = wobble(&["dump", s(&raw), "-o", s(&file)]);
    assert!(f.status.success());
    assert_eq!(std::fs::read(&file).unwrap(), o.stdout);
    // BMP to stdout.
    let o = wobble(&["dump", s(&raw), "-o", "-", "--format", "bmp"]);
    assert_eq!(
        image::guess_format(&o.stdout).ok(),
        Some(image::ImageFormat::Bmp)
    );
    // No format: refused, nothing on stdout.
    let o = wobble(&["dump", s(&raw), "-o", "-"]);
    assert!(!o.status.success());
    assert!(o.stdout.is_empty());
    assert!(stderr(&o).contains("--format"), "{}", stderr(&o));
    // Raw VRAM to stdout: the 1 MiB file.
    let stream = root().join("fixtures/gpu/quad.gpu");
    let o = wobble(&["replay", s(&stream), "-o", "/dev/null", "--raw", "-"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(o.stdout.len(), 1024 * 512 * 2);
    // Two outputs on stdout: refused.
    let o = wobble(&[
        "replay",
        s(&stream),
        "-o",
        "-",
        "--format",
        "png",
        "--raw",
        "-",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("only one output"), "{}", stderr(&o));
    // render: the last frame on stdout, the summary on stderr.
    let o = wobble(&["render", "-o", "-", "--format", "png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::load_from_memory(&o.stdout).unwrap();
    assert_eq!((img.width(), img.height()), (320, 240));
    assert!(stderr(&o).contains("polygons drawn"), "{}", stderr(&o));
    // A GIF animation on stdout.
    let o = wobble(&["render", "--frames", "3", "--gif", "-", "-o", "/dev/null"]);
    assert!(o.status.success(), "{}", stderr(&o));
    use image::AnimationDecoder;
    let frames = image::codecs::gif::GifDecoder::new(std::io::Cursor::new(o.stdout))
        .unwrap()
        .into_frames()
        .count();
    assert_eq!(frames, 3);
}

/// Whether this process runs as root (a file it creates is owned by uid 0).
fn running_as_root(d: &Path) -> bool {
    let probe = d.join("uid-probe");
    std::fs::write(&probe, b"").unwrap();
    let uid = std::fs::metadata(&probe).unwrap().uid();
    std::fs::remove_file(&probe).unwrap();
    uid == 0
}

/// `wobble` run so that a directory without write permission refuses it: as the `nobody`
/// user (65534) when the tests run as root, who may write anywhere.
fn wobble_unprivileged(d: &Path, args: &[&str]) -> Output {
    use std::os::unix::process::CommandExt;
    let mut c = Command::new(env!("CARGO_BIN_EXE_wobble"));
    c.args(args);
    if running_as_root(d) {
        c.uid(65534).gid(65534);
    }
    c.output().unwrap()
}

/// A read-only directory: a new output and the replacement of an existing (writable) file
/// are refused before any work, naming the directory and the reason; nothing changes.
#[test]
fn read_only_directory_is_a_clear_error() {
    let d = Scratch::new("readonly");
    let raw = raw_vram(&d);
    std::fs::set_permissions(&raw, std::fs::Permissions::from_mode(0o644)).unwrap();
    let ro = d.join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::write(ro.join("old.png"), b"old").unwrap();
    std::fs::set_permissions(ro.join("old.png"), std::fs::Permissions::from_mode(0o666)).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    for name in ["new.png", "old.png"] {
        let target = ro.join(name);
        let o = wobble_unprivileged(&d, &["dump", s(&raw), "-o", s(&target)]);
        assert!(
            !o.status.success(),
            "{name} written in a read-only directory"
        );
        let e = stderr(&o);
        assert!(
            e.contains(s(&ro)) && e.contains("Permission denied"),
            "{name}: {e}"
        );
    }
    let o = wobble_unprivileged(
        &d,
        &[
            "inspect",
            s(&root().join("fixtures/gpu/quad.gpu")),
            "-o",
            s(&ro.join("report")),
        ],
    );
    assert!(!o.status.success());
    assert!(stderr(&o).contains("Permission denied"), "{}", stderr(&o));
    assert_eq!(entries(&ro), ["old.png"]);
    assert_eq!(std::fs::read(ro.join("old.png")).unwrap(), b"old");
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
}

/// Replacing an existing file keeps its permission bits and leaves no temporary file.
#[test]
fn replaced_file_keeps_its_permissions() {
    let d = Scratch::new("mode");
    let raw = raw_vram(&d);
    let out = d.join("out.png");
    std::fs::write(&out, b"old").unwrap();
    std::fs::set_permissions(&out, std::fs::Permissions::from_mode(0o640)).unwrap();
    let o = wobble(&["dump", s(&raw), "-o", s(&out)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_dump_png(&std::fs::read(&out).unwrap());
    let mode = std::fs::metadata(&out).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640);
    assert_eq!(entries(&d), ["in.vram.bin", "out.png"]);
}

/// `--gif x.png` is refused before any work: GIF bytes never go into a file named as a PNG.
#[test]
fn gif_option_needs_a_gif_name() {
    let d = Scratch::new("gifname");
    let out = d.join("x.png");
    let o = wobble(&["render", "--frames", "2", "--gif", s(&out)]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("x.png") && e.contains(".gif"), "{e}");
    assert!(entries(&d).is_empty(), "{:?}", entries(&d));
}

/// A failure after the outputs were opened (a stream with a bad line, a raw file of the
/// wrong size) removes their temporary files: the directory is as it was.
#[test]
fn errors_leave_nothing_behind() {
    let d = Scratch::new("errors");
    let bad = d.join("bad.gpu");
    std::fs::write(&bad, "gp0 e1000000\ngp0 zz\n").unwrap();
    let o = wobble(&[
        "replay",
        s(&bad),
        "-o",
        s(&d.join("x.png")),
        "--raw",
        s(&d.join("x.bin")),
    ]);
    assert!(!o.status.success());
    let o = wobble(&["inspect", s(&bad), "-o", s(&d.join("report"))]);
    assert!(!o.status.success());
    let short = d.join("short.bin");
    std::fs::write(&short, [0u8; 10]).unwrap();
    let o = wobble(&["dump", s(&short), "-o", s(&d.join("y.png"))]);
    assert!(!o.status.success());
    assert_eq!(entries(&d), ["bad.gpu", "short.bin"]);
}

/// A directory output into an existing directory replaces the report's files and leaves the
/// directory's other files alone.
#[test]
fn existing_report_directory_keeps_other_files() {
    let d = Scratch::new("existing");
    let report = d.join("report");
    std::fs::create_dir(&report).unwrap();
    std::fs::write(report.join("notes.txt"), b"mine").unwrap();
    std::fs::write(report.join("index.html"), b"stale").unwrap();
    let o = wobble(&[
        "inspect",
        s(&root().join("fixtures/gpu/quad.gpu")),
        "-o",
        s(&report),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(report.join("notes.txt")).unwrap(), b"mine");
    let index = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(index.contains("<html"), "{index}");
    assert_eq!(
        entries(&report),
        [
            "data",
            "img",
            "index.html",
            "inspect.css",
            "inspect.js",
            "notes.txt",
            "tex"
        ]
    );
    // Frames into an existing directory, twice: the second run replaces the first's frames.
    let frames = d.join("frames");
    std::fs::create_dir(&frames).unwrap();
    for _ in 0..2 {
        let o = wobble(&[
            "render",
            "--frames",
            "2",
            "--png-dir",
            s(&frames),
            "-o",
            "/dev/null",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    assert_eq!(entries(&frames), ["frame00000.png", "frame00001.png"]);
}

/// Start `wobble` with `args`, wait until `ready` holds (checked every 20 ms, at most 60 s),
/// send it `signal`, and return its exit status and stderr.
fn interrupt(args: &[&str], signal: &str, ready: impl Fn() -> bool) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_wobble"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !ready() {
        assert!(
            child.try_wait().unwrap().is_none(),
            "finished before it could be interrupted"
        );
        assert!(start.elapsed() < Duration::from_secs(60), "never ready");
        std::thread::sleep(Duration::from_millis(20));
    }
    let sent = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let o = child.wait_with_output().unwrap();
    (o.status.code(), stderr(&o))
}

/// Whether `d` holds a hidden temporary entry with something in it (a file of at least one
/// byte, or a directory holding `inner`).
fn temporary_in_progress(d: &Path, inner: Option<&str>) -> bool {
    std::fs::read_dir(d).unwrap().flatten().any(|e| {
        let name = e.file_name().to_string_lossy().into_owned();
        name.starts_with('.')
            && name.ends_with(".tmp")
            && match inner {
                None => e.metadata().is_ok_and(|m| m.len() > 0),
                Some(inner) => e.path().join(inner).exists(),
            }
    })
}

/// Ctrl-C in the middle of an animation: the half-written GIF and the last frame's temporary
/// file are removed; nothing is left under any name.
#[test]
fn interrupted_render_leaves_nothing() {
    let d = Scratch::new("sigint-render");
    let out = d.join("x.png");
    let (code, e) = interrupt(
        &["render", "--frames", "3000", "-o", s(&out)],
        "-INT",
        || temporary_in_progress(&d, None),
    );
    assert_eq!(code, Some(130), "{e}");
    assert!(e.contains("interrupted: unfinished output removed"), "{e}");
    assert!(entries(&d).is_empty(), "left: {:?}", entries(&d));
}

/// SIGTERM while the trade report is in its divide sweep (its images already written): no
/// images without trade.md, no temporary directory.
#[test]
fn interrupted_trade_leaves_nothing() {
    let d = Scratch::new("sigterm-trade");
    let scene = root().join("fixtures/scenes/face-on.toml");
    let out = d.join("report");
    let (code, e) = interrupt(
        &[
            "trade",
            s(&scene),
            "--frames",
            "2",
            "--repeats",
            "1",
            "--sweep-step",
            "1",
            "-o",
            s(&out),
        ],
        "-TERM",
        || temporary_in_progress(&d, Some("trade/tessellation-curve.png")),
    );
    assert_eq!(code, Some(130), "{e}");
    assert!(entries(&d).is_empty(), "left: {:?}", entries(&d));
}

/// Ctrl-C while `inspect` writes a long stream's report into an existing directory: the
/// directory holds what it held before, and no temporary directory.
#[test]
fn interrupted_inspect_leaves_the_directory_as_it_was() {
    let d = Scratch::new("sigint-inspect");
    let stream = d.join("long.gpu");
    // 3000 fills of the whole drawing area, each a different colour: one image each.
    let text: String = (0..3000u32)
        .map(|i| {
            format!(
                "gp0 02{:06X} 00000000 01FF03FF\n",
                i.wrapping_mul(2654435) & 0xFFFFFF
            )
        })
        .collect();
    std::fs::write(&stream, text).unwrap();
    let report = d.join("report");
    std::fs::create_dir(&report).unwrap();
    std::fs::write(report.join("notes.txt"), b"mine").unwrap();
    let (code, e) = interrupt(&["inspect", s(&stream), "-o", s(&report)], "-INT", || {
        temporary_in_progress(&report, Some("data/chunk-00000.js"))
    });
    assert_eq!(code, Some(130), "{e}");
    assert_eq!(entries(&report), ["notes.txt"]);
    assert_eq!(entries(&d), ["long.gpu", "report"]);
}
