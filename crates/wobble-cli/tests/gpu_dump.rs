//! GPU dumps from the command line: `render --record` replays to the frames `render`
//! writes; a DuckStation-dialect dump built by hand from the format's text is listed,
//! replayed, inspected and dumped; `convert` round-trips between text and dumps, compressed
//! or not; errors name the format expected.

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

fn ok(args: &[&str]) -> Output {
    let o = wobble(args);
    assert!(
        o.status.success(),
        "wobble {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/gpu")
        .join(name)
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn rgb(path: &Path) -> image::RgbImage {
    image::open(path).unwrap().to_rgb8()
}

/// `render --record` on the default animation, replayed frame by frame with `replay`:
/// every frame's PNG is the one `render --png-dir` wrote; the GIF holds one frame each.
#[test]
fn recorded_render_replays_to_the_same_frames() {
    let scratch = Scratch::new("recorded_render_replays_to_the_same_frames");
    let frames = 12;
    let rendered = scratch.join("rendered");
    let replayed = scratch.join("replayed");
    let dump = scratch.join("anim.psxgpu.zst");
    ok(&[
        "render",
        "--frames",
        &frames.to_string(),
        "--png-dir",
        s(&rendered),
        "-o",
        s(&scratch.join("last.png")),
        "--record",
        s(&dump),
        "--dialect",
        "duckstation",
    ]);
    let o = ok(&[
        "replay",
        s(&dump),
        "--frames",
        &format!("0..{frames}"),
        "--png-dir",
        s(&replayed),
        "-o",
        s(&scratch.join("anim.gif")),
    ]);
    let text = out(&o);
    assert!(
        text.contains("zstd-compressed")
            && text.contains(&format!("{frames} frame(s)"))
            && text.contains("DuckStation dialect")
            && text.contains("NTSC")
            && text.contains("GPU v2, 1 MB VRAM"),
        "{text}"
    );
    for f in 0..frames {
        let name = format!("frame{f:05}.png");
        assert!(
            rgb(&rendered.join(&name)) == rgb(&replayed.join(&name)),
            "frame {f}"
        );
    }
    let gif = std::fs::File::open(scratch.join("anim.gif")).unwrap();
    let decoder = image::codecs::gif::GifDecoder::new(std::io::BufReader::new(gif)).unwrap();
    let gif_frames = image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .unwrap();
    assert_eq!(gif_frames.len(), frames);
    assert_eq!(gif_frames[0].buffer().dimensions(), (320, 240));
}

/// A packet header: length in bits 0-23, type in bits 24-31.
fn head(kind: u8, words: u32) -> [u8; 4] {
    ((kind as u32) << 24 | words).to_le_bytes()
}

/// A DuckStation-dialect dump written byte by byte: 14-byte magic, version 1 (v2 GPU in
/// DuckStation's numbering), game ID, video format, comment, an unknown packet, the
/// display turned on at 320x240, then two frames: a red 16x16 fill at (0, 0), a VSync; a
/// green 16x16 fill at (0, 4), a VRAM-to-CPU read of 4 words read back, a VSync.
fn duckstation_dump() -> Vec<u8> {
    let mut b = b"PSXGPUDUMPv1\0\0".to_vec();
    let words = |b: &mut Vec<u8>, kind, ws: &[u32]| {
        b.extend(head(kind, ws.len() as u32));
        ws.iter().for_each(|w| b.extend(w.to_le_bytes()));
    };
    words(&mut b, 0x06, &[1]);
    b.extend(head(0x10, 3));
    b.extend(b"SLPS-01234\0\0");
    b.extend(head(0x11, 2));
    b.extend(b"NTSC\0\0\0\0");
    b.extend(head(0x12, 2));
    b.extend(b"by hand\0");
    words(&mut b, 0x05, &[]);
    words(&mut b, 0x42, &[1, 2, 3]);
    words(&mut b, 0x01, &[0x0800_0001]);
    words(&mut b, 0x01, &[0x0300_0000]);
    words(&mut b, 0x00, &[0x0200_00FF, 0, 0x0010_0010]);
    words(&mut b, 0x02, &[]);
    words(&mut b, 0x00, &[0x0200_FF00, 0x0004_0004, 0x0010_0010]);
    words(&mut b, 0x00, &[0xC000_0000, 0, 0x0002_0004]);
    words(&mut b, 0x04, &[4]);
    words(&mut b, 0x02, &[0x0010_0000, 0]);
    b
}

#[test]
fn hand_built_duckstation_dump_lists_replays_inspects() {
    let scratch = Scratch::new("hand_built_duckstation_dump_lists_replays_inspects");
    let dump = scratch.join("hand.psxgpu");
    std::fs::write(&dump, duckstation_dump()).unwrap();
    let o = ok(&["replay", s(&dump), "--list"]);
    let text = out(&o);
    assert!(
        text.contains("2 frame(s)")
            && text.contains("game SLPS-01234")
            && text.contains("GPU v2, 1 MB VRAM")
            && text.contains("DuckStation dialect (v1)"),
        "{text}"
    );
    assert!(
        text.contains(
            "frame 0: 1 commands (0 draws), 3 GP0 words, 2 GP1 words; display 320x240 at (0, 0)"
        ),
        "{text}"
    );
    assert!(
        text.contains("frame 1: 2 commands (0 draws), 6 GP0 words, 0 GP1 words, 4 GPUREAD words")
            && text.contains("vsync at cycle 1048576"),
        "{text}"
    );
    // Frame 0 shows red at (0, 0); frame 1 green from line 4 (fill X is a multiple of 16).
    let f0 = scratch.join("hand0.png");
    ok(&["replay", s(&dump), "--frame", "0", "-o", s(&f0)]);
    let img = rgb(&f0);
    assert_eq!(img.dimensions(), (320, 240));
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]);
    assert_eq!(img.get_pixel(4, 4).0, [255, 0, 0]);
    let f1 = scratch.join("hand1.png");
    ok(&["replay", s(&dump), "--frame", "1", "-o", s(&f1)]);
    let img = rgb(&f1);
    assert_eq!(img.get_pixel(0, 0).0, [255, 0, 0]);
    assert_eq!(img.get_pixel(4, 4).0, [0, 255, 0]);
    // `dump` takes the VRAM at a frame.
    let v = scratch.join("hand-vram.png");
    ok(&["dump", s(&dump), "--frame", "1", "-o", s(&v)]);
    let img = rgb(&v);
    assert_eq!(img.dimensions(), (1024, 512));
    assert_eq!(img.get_pixel(15, 19).0, [0, 255, 0]);
    assert_eq!(img.get_pixel(16, 19).0, [0, 0, 0]);
    // The inspector on frame 1: its three packets, listed by packet number.
    let report = scratch.join("hand-report");
    let o = ok(&["inspect", s(&dump), "--frame", "1", "-o", s(&report)]);
    assert!(out(&o).starts_with("2 commands"), "{}", out(&o));
    assert!(err(&o).contains("4 GPUREAD words"), "{}", err(&o));
    let index = std::fs::read_to_string(report.join("data/index.js")).unwrap();
    assert!(
        index.contains("frame 1 of 2") && index.contains("SLPS-01234"),
        "{index}"
    );
    let chunk = std::fs::read_to_string(report.join("data/chunk-00000.js")).unwrap();
    assert!(
        chunk.contains("\"line\":11") && chunk.contains("\"line\":12"),
        "{chunk}"
    );
    // Frames past the end are refused with the count.
    let o = wobble(&[
        "replay",
        s(&dump),
        "--frame",
        "2",
        "-o",
        s(&scratch.join("x.png")),
    ]);
    assert!(
        !o.status.success() && err(&o).contains("it has 2 frame(s) (0..=1)"),
        "{}",
        err(&o)
    );
}

/// `.gpu` -> `.psxgpu` -> `.gpu` -> `.psxgpu.xz` (DuckStation) -> `.psxgpu.zst` (spec): the
/// VRAM replayed from each equals the fixture's; the second text equals the first.
#[test]
fn convert_round_trips() {
    let scratch = Scratch::new("convert_round_trips");
    let quad = fixture("quad.gpu");
    let dump = scratch.join("quad.psxgpu");
    let text = scratch.join("quad-back.gpu");
    let text2 = scratch.join("quad-back2.gpu");
    let xz = scratch.join("quad.psxgpu.xz");
    let zst = scratch.join("quad.psxgpu.zst");
    ok(&["convert", s(&quad), s(&dump)]);
    assert!(
        std::fs::read(&dump)
            .unwrap()
            .starts_with(b"PSXGPUDUMPv1r1\0\0")
    );
    ok(&["convert", s(&dump), s(&text)]);
    ok(&["convert", s(&text), s(&xz), "--dialect", "duckstation"]);
    let o = ok(&["convert", s(&xz), s(&zst), "--dialect", "spec"]);
    assert!(out(&o).contains("zstd"), "{}", out(&o));
    ok(&["convert", s(&zst), s(&text2)]);
    let t1 = std::fs::read_to_string(&text).unwrap();
    let t2 = std::fs::read_to_string(&text2).unwrap();
    assert_eq!(t1, t2);
    let raw = |input: &Path, name: &str| {
        let r = scratch.join(name);
        ok(&[
            "replay",
            s(input),
            "--region",
            "vram",
            "-o",
            s(&scratch.join(format!("{name}.png"))),
            "--raw",
            s(&r),
        ]);
        std::fs::read(r).unwrap()
    };
    let expected = raw(&quad, "quad.raw");
    for (input, name) in [
        (&dump, "a.raw"),
        (&text, "b.raw"),
        (&xz, "c.raw"),
        (&zst, "d.raw"),
    ] {
        assert!(raw(input, name) == expected, "{}", input.display());
    }
    // The DuckStation file has the 14-byte magic once decompressed: check via text.
    let o = ok(&["convert", s(&xz), s(&scratch.join("ds.psxgpu"))]);
    assert!(out(&o).contains("DuckStation dialect"), "{}", out(&o));
    assert!(
        std::fs::read(scratch.join("ds.psxgpu"))
            .unwrap()
            .starts_with(b"PSXGPUDUMPv1\0\0")
    );
    // Unknown output names are refused with the list.
    let o = wobble(&["convert", s(&quad), s(&scratch.join("x.bin"))]);
    assert!(
        !o.status.success() && err(&o).contains(".psxgpu.zst"),
        "{}",
        err(&o)
    );
}

/// A binary file where text is expected names what it is and what was expected; a damaged
/// dump names the byte.
#[test]
fn wrong_inputs_name_the_format() {
    let scratch = Scratch::new("wrong_inputs_name_the_format");
    let dump = scratch.join("bin.psxgpu");
    std::fs::write(&dump, duckstation_dump()).unwrap();
    let o = wobble(&["gte", "replay", s(&dump)]);
    assert!(
        !o.status.success()
            && err(&o).contains("not a GTE vector file")
            && err(&o).contains("the file is binary (a PS1 GPU dump (.psxgpu)"),
        "{}",
        err(&o)
    );
    let o = wobble(&["render", s(&dump)]);
    assert!(err(&o).contains("not a scene file (TOML"), "{}", err(&o));
    let png = fixture("quad.vram.png");
    let o = wobble(&["replay", s(&png), "-o", s(&scratch.join("p.png"))]);
    assert!(
        err(&o).contains("not a GPU command stream (.gpu text) or a GPU dump")
            && err(&o).contains("binary (a PNG image"),
        "{}",
        err(&o)
    );
    let mut cut = duckstation_dump();
    cut.truncate(cut.len() - 6);
    let damaged = scratch.join("cut.psxgpu");
    std::fs::write(&damaged, cut).unwrap();
    let o = wobble(&["replay", s(&damaged), "-o", s(&scratch.join("c.png"))]);
    assert!(
        !o.status.success() && err(&o).contains("byte ") && err(&o).contains("only"),
        "{}",
        err(&o)
    );
    let text = scratch.join("text.psxgpu");
    std::fs::write(&text, "garbage\n").unwrap();
    let o = wobble(&["replay", s(&text), "-o", s(&scratch.join("t.png"))]);
    assert!(
        !o.status.success()
            && err(&o).contains("not a GPU dump (it does not start with `PSXGPUDUMP`)")
            && err(&o).contains("line 1: unknown port `garbage`"),
        "{}",
        err(&o)
    );
    let fake = scratch.join("fake.psxgpu.zst");
    std::fs::write(&fake, "gp0 1\n").unwrap();
    let o = wobble(&["replay", s(&fake)]);
    assert!(
        err(&o).contains("the name says zstd but the contents are text"),
        "{}",
        err(&o)
    );
}
