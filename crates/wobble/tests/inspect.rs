//! `wobble inspect` on the hardware fixture streams and on bad input: the report lists every
//! command, its pixel counts add up with the final VRAM, and the last-writer map agrees with
//! an independent per-line VRAM comparison.

// Pixel loops index several parallel per-pixel tables by the same index.
#![allow(clippy::needless_range_loop)]

mod common;

use common::Scratch;
use gpu::command_stream::{self, Port};
use gpu::encode::{self, Polygon, Rectangle, SpriteSize, Vertex};
use gpu::{Gpu, VRAM_LEN};
use serde_json::Value;
use std::path::{Path, PathBuf};
use wobble::inspect::{InspectOptions, InspectSummary, summary_line, write_report};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/gpu")
        .join(name)
}

/// All rows of a report, read back from its chunk files.
fn rows(dir: &Path) -> Vec<Value> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir.join("data"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("chunk-"))
        })
        .collect();
    files.sort();
    let mut all = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let start = text.find(",[").unwrap() + 1;
        let end = text.rfind(");").unwrap();
        let chunk: Vec<Value> = serde_json::from_str(&text[start..end]).unwrap();
        all.extend(chunk);
    }
    all
}

/// A command stream's text: one `gp0` line per packet.
fn gp0_lines<'a>(packets: impl IntoIterator<Item = &'a [u32]>) -> String {
    let mut text = String::new();
    for packet in packets {
        text.push_str("gp0");
        for w in packet {
            text.push_str(&format!(" {w:08x}"));
        }
        text.push('\n');
    }
    text
}

/// The drawing area from (0, 0) to (`right`, `bottom`) and no drawing offset.
fn area(right: u16, bottom: u16) -> [u32; 3] {
    [
        encode::area_top_left(0, 0),
        encode::area_bottom_right(right, bottom),
        encode::drawing_offset(0, 0),
    ]
}

/// A flat yellow triangle.
fn triangle(v: [(i16, i16); 3]) -> encode::Packet {
    Polygon::triangle(v.map(|(x, y)| Vertex {
        x,
        y,
        color: [0xFF, 0xFF, 0],
        ..Vertex::default()
    }))
    .packet()
}

/// The report of the stream `text`, written into a scratch directory named `name`.
fn report(text: &str, name: &str) -> (InspectSummary, Vec<Value>, Scratch) {
    let commands = command_stream::parse(text).unwrap();
    let dir = Scratch::new(name);
    let mut gpu = Gpu::new();
    let summary = write_report(
        &mut gpu,
        &commands,
        &dir,
        name,
        InspectOptions::default(),
        None,
        None,
    )
    .unwrap();
    let rows = rows(&dir);
    (summary, rows, dir)
}

/// The report covers every stream line and every word, in order.
fn check_lists_every_command(text: &str, rows: &[Value]) {
    let commands = command_stream::parse(text).unwrap();
    let words: usize = commands.iter().map(|c| c.words.len()).sum();
    let listed: usize = rows
        .iter()
        .map(|r| r["nwords"].as_u64().unwrap() as usize)
        .sum();
    assert_eq!(listed, words, "every word is in some row");
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(r["i"].as_u64().unwrap() as usize, i);
    }
    for c in &commands {
        assert!(
            rows.iter().any(|r| {
                let (a, b) = (r["line"].as_u64().unwrap(), r["last"].as_u64().unwrap());
                (a..=b).contains(&(c.line as u64))
            }),
            "line {} is in a row",
            c.line
        );
    }
}

/// Pixel accounting: the final VRAM equals a plain replay; a pixel without a writer kept its
/// initial value; a pixel's writer changed something; the changes add up.
fn check_pixel_accounting(text: &str, s: &InspectSummary) {
    let commands = command_stream::parse(text).unwrap();
    let mut plain = Gpu::new();
    command_stream::run(&mut plain, &commands);
    assert!(
        s.final_vram == plain.vram().as_slice(),
        "report's final VRAM equals a plain replay"
    );
    let mut differing = 0u64;
    let mut written = 0u64;
    for i in 0..VRAM_LEN {
        let w = s.writers[i];
        if s.final_vram[i] != s.initial[i] {
            differing += 1;
            assert!(w != 0, "pixel {i} changed but has no last writer");
        }
        if w == 0 {
            assert_eq!(
                s.final_vram[i], s.initial[i],
                "pixel {i} has no writer but changed"
            );
        } else {
            written += 1;
            assert!(
                s.changed[(w - 1) as usize] > 0,
                "writer of pixel {i} changed nothing"
            );
        }
    }
    let total: u64 = s.changed.iter().sum();
    assert!(
        total >= written,
        "{total} changes cover the {written} written pixels"
    );
    assert!(written >= differing);
    // Each command's count is at least the pixels it is the last writer of.
    let mut last_of = vec![0u64; s.changed.len()];
    for &w in &s.writers {
        if w != 0 {
            last_of[(w - 1) as usize] += 1;
        }
    }
    for (i, (&c, &l)) in s.changed.iter().zip(&last_of).enumerate() {
        assert!(c >= l, "command {i}: changed {c} < last writer of {l}");
    }
}

/// An independent check by stream line: run the stream a line at a time comparing the
/// whole VRAM after each line; the last line that changed a pixel must lie in the line
/// range of the row the report names as its last writer, and a row whose command is exactly
/// one line must count exactly the pixels that line changed.
fn check_against_line_by_line(text: &str, rows: &[Value], s: &InspectSummary) {
    let commands = command_stream::parse(text).unwrap();
    let mut gpu = Gpu::new();
    let mut last_line = vec![0usize; VRAM_LEN];
    let mut changed_by_line = std::collections::HashMap::new();
    for c in &commands {
        let before = gpu.vram().as_slice().to_vec();
        match c.port {
            Port::Gp0 => gpu.gp0_words(&c.words),
            Port::Gp1 => c.words.iter().for_each(|&w| gpu.gp1(w)),
        }
        let mut n = 0u64;
        for (i, (a, b)) in before.iter().zip(gpu.vram().as_slice()).enumerate() {
            if a != b {
                last_line[i] = c.line;
                n += 1;
            }
        }
        changed_by_line.insert(c.line, (n, c.words.len()));
    }
    for i in 0..VRAM_LEN {
        let w = s.writers[i];
        if last_line[i] == 0 {
            assert_eq!(w, 0, "pixel {i}");
            continue;
        }
        assert!(w != 0, "pixel {i} last changed at line {}", last_line[i]);
        let r = &rows[(w - 1) as usize];
        let (a, b) = (
            r["line"].as_u64().unwrap() as usize,
            r["last"].as_u64().unwrap() as usize,
        );
        assert!(
            (a..=b).contains(&last_line[i]),
            "pixel {i}: line {} vs row lines {a}-{b}",
            last_line[i]
        );
    }
    let mut exact = 0;
    for r in rows {
        let line = r["line"].as_u64().unwrap() as usize;
        if r["last"].as_u64().unwrap() as usize == line
            && let Some(&(n, words)) = changed_by_line.get(&line)
            && words == r["nwords"].as_u64().unwrap() as usize
        {
            assert_eq!(r["changed"].as_u64().unwrap(), n, "line {line}");
            exact += 1;
        }
    }
    assert!(exact > 0);
}

/// Values of a history string: 4 hex digits each, `hhhh:N;` for N copies.
fn history_values(s: &str) -> Vec<u16> {
    let mut out = Vec::new();
    let mut rest = s;
    while rest.len() >= 4 {
        let v = u16::from_str_radix(&rest[..4], 16).unwrap();
        rest = &rest[4..];
        let mut n = 1;
        if let Some(r) = rest.strip_prefix(':') {
            let end = r.find(';').unwrap();
            n = r[..end].parse().unwrap();
            rest = &r[end + 1..];
        }
        out.extend(std::iter::repeat_n(v, n));
    }
    assert!(rest.is_empty(), "{rest}");
    out
}

/// Per pixel, every change the report's history files list: (command, before, after).
fn report_history(dir: &Path) -> std::collections::HashMap<usize, Vec<(usize, u16, u16)>> {
    let mut all = std::collections::HashMap::new();
    for e in std::fs::read_dir(dir.join("data/hist")).unwrap() {
        let text = std::fs::read_to_string(e.unwrap().path()).unwrap();
        let inner = text
            .strip_prefix("INSPECT.hist(")
            .and_then(|t| t.strip_suffix(");\n"))
            .unwrap();
        let v: Value = serde_json::from_str(inner).unwrap();
        let tile = v[0].as_u64().unwrap() as usize;
        let (tx, ty) = (tile % 16 * 64, tile / 16 * 64);
        let mut now = history_values(v[1].as_str().unwrap());
        assert_eq!(now.len(), 64 * 64);
        for rec in v[2].as_array().unwrap() {
            let (cmd, y, x) = (
                rec[0].as_u64().unwrap() as usize,
                rec[1].as_u64().unwrap() as usize,
                rec[2].as_u64().unwrap() as usize,
            );
            for (k, after) in history_values(rec[3].as_str().unwrap())
                .into_iter()
                .enumerate()
            {
                assert!(x + k >= tx && x + k < tx + 64 && y >= ty && y < ty + 64);
                let t = (y - ty) * 64 + x + k - tx;
                let before = now[t];
                assert_ne!(before, after, "a change changes the pixel");
                now[t] = after;
                all.entry(y * 1024 + x + k)
                    .or_insert_with(Vec::new)
                    .push((cmd, before, after));
            }
        }
    }
    all
}

/// The pixel history of every pixel agrees with a line-by-line replay: the same changes,
/// the same values before and after, each by the command holding the replay's line.
fn check_history(text: &str, rows: &[Value], dir: &Path) {
    let commands = command_stream::parse(text).unwrap();
    let mut gpu = Gpu::new();
    let mut want: std::collections::HashMap<usize, Vec<(usize, u16, u16)>> = Default::default();
    for c in &commands {
        let before = gpu.vram().as_slice().to_vec();
        match c.port {
            Port::Gp0 => gpu.gp0_words(&c.words),
            Port::Gp1 => c.words.iter().for_each(|&w| gpu.gp1(w)),
        }
        for (i, (&a, &b)) in before.iter().zip(gpu.vram().as_slice()).enumerate() {
            if a != b {
                want.entry(i).or_default().push((c.line, a, b));
            }
        }
    }
    let got = report_history(dir);
    assert_eq!(got.len(), want.len(), "pixels with a history");
    for (i, w) in &want {
        let g = &got[i];
        assert_eq!(g.len(), w.len(), "pixel {i}: {g:?} vs {w:?}");
        for (&(cmd, b, a), &(line, wb, wa)) in g.iter().zip(w) {
            assert_eq!((b, a), (wb, wa), "pixel {i}, line {line}");
            let r = &rows[cmd];
            let (l0, l1) = (r["line"].as_u64().unwrap(), r["last"].as_u64().unwrap());
            assert!(
                (l0..=l1).contains(&(line as u64)),
                "pixel {i}: line {line} vs {l0}-{l1}"
            );
        }
    }
    // Some pixel was written more than once, so before values other than the initial are checked.
    assert!(want.values().any(|w| w.len() >= 2));
}

#[test]
fn hardware_fixtures_small() {
    for name in ["quad.gpu", "triangle.gpu", "transparency.gpu", "lines.gpu"] {
        let text = std::fs::read_to_string(fixture(name)).unwrap();
        let (s, rows, dir) = report(&text, name);
        assert_eq!(rows.len(), s.commands);
        check_lists_every_command(&text, &rows);
        check_pixel_accounting(&text, &s);
        check_against_line_by_line(&text, &rows, &s);
        check_history(&text, &rows, &dir);
        assert!(dir.join("index.html").is_file());
        assert!(dir.join("img/final.png").is_file());
        assert!(s.draws > 0 && s.images > 0, "{name}");
        // Every image a row names exists.
        for r in &rows {
            if let Some(png) = r["img"]["png"].as_str() {
                assert!(dir.join(png).is_file(), "{png}");
            }
        }
    }
}

#[test]
fn hardware_fixtures_large() {
    for name in ["rectangles.gpu", "texture-overflow.gpu"] {
        let text = std::fs::read_to_string(fixture(name)).unwrap();
        let (s, rows, dir) = report(&text, name);
        check_lists_every_command(&text, &rows);
        check_pixel_accounting(&text, &s);
        if name == "texture-overflow.gpu" {
            // Textured draws carry a texture-page view and their UV rectangle.
            let textured: Vec<&Value> = rows.iter().filter(|r| !r["tex"].is_null()).collect();
            assert!(!textured.is_empty());
            for r in textured {
                let png = r["tex"]["png"].as_str().unwrap();
                assert!(dir.join(png).is_file());
                assert_eq!(r["tex"]["uv"].as_array().unwrap().len(), 4);
            }
        }
    }
}

#[test]
fn drop_reasons_are_reported() {
    // Drawing area 0,0-1023,511, then: a triangle 1024 wide (size limit), a collinear one
    // (zero area), and with a 16x16 area one outside it (clipped away).
    let [top_left, bottom_right, offset] = area(1023, 511);
    let text = gp0_lines([
        &[top_left][..],
        &[bottom_right],
        &[offset],
        &triangle([(0, 0), (1024, 0), (0, 16)]),
        &triangle([(0, 0), (1, 1), (2, 2)]),
        &[encode::area_bottom_right(15, 15)],
        &triangle([(32, 32), (48, 32), (32, 48)]),
        &triangle([(0, 0), (8, 0), (0, 8)]),
    ]);
    let (s, rows, _dir) = report(&text, "drops");
    let fate = |i: usize| rows[i]["prims"][0]["fate"].as_str().map(str::to_string);
    assert!(fate(3).unwrap().starts_with("size limit"));
    assert_eq!(fate(4).unwrap(), "zero area");
    assert!(fate(6).unwrap().starts_with("clipped"));
    assert_eq!(fate(7), None);
    assert_eq!(s.dropped, 3);
    assert_eq!(s.changed[3] + s.changed[4] + s.changed[6], 0);
    assert!(s.changed[7] > 0);
}

/// Each command's GPU time is listed, in GPU and CPU cycles, from the cost table of
/// docs/emulator.md ("Drawing time", figures in CPU cycles): a 320x240 fill costs
/// 23 + 240 x (320 / 16 + 1870 / 256), a 64x64 rectangle 8 + 64 x 615 / 256 + 4096 x
/// 136 / 256; the NTSC GPU clock is 11/7 of the CPU's, the fraction of a cycle carried from
/// one command to the next. Environment commands take none. The report's total is their sum.
#[test]
fn each_command_has_its_gpu_time() {
    let text = "gp0 e3000000\ngp0 e407ffff\ngp0 e5000000\n\
                gp0 02000000 00000000 00f00140\n\
                gp0 6000ff00 00000000 00400040\n\
                gp0 e1000000\n";
    let (s, rows, dir) = report(text, "times");
    let fill: f64 = 23.0 + 240.0 * (20.0 + 1870.0 / 256.0);
    let rect: f64 = 8.0 + 64.0 * 615.0 / 256.0 + 4096.0 * 136.0 / 256.0;
    let gpu = |cpu: f64| (cpu * 11.0 / 7.0 + 1e-9).floor() as u64;
    let fill_gpu = gpu(fill);
    let rect_gpu = gpu(fill + rect) - fill_gpu;
    assert_eq!(s.gpu_cycles, [0, 0, 0, fill_gpu, rect_gpu, 0]);
    assert_eq!(rows[3]["gpu"].as_u64(), Some(fill_gpu));
    assert_eq!(
        rows[3]["cyc"].as_u64(),
        Some((fill_gpu as f64 * 7.0 / 11.0).ceil() as u64)
    );
    assert_eq!(rows[4]["gpu"].as_u64(), Some(rect_gpu));
    assert!(rows[5].get("gpu").is_none() && rows[0].get("cyc").is_none());
    let total = ((fill_gpu + rect_gpu) as f64 * 7.0 / 11.0).ceil() as u64;
    assert_eq!(s.cpu_cycles, total);
    let index = std::fs::read_to_string(dir.join("data/index.js")).unwrap();
    assert!(index.contains(&format!("\"cpuCycles\":{total}")), "{index}");
}

/// Each command's texture cache misses are listed (docs/hardware/gpu.md §10: an entry holds
/// four 15-bit texels, and a 32-texel row lies in one 32x32 block): a raw 32x1 sprite from a
/// 15-bit page misses on its 8 entries from an empty cache, on none when drawn again, and on
/// all 8 after GP0(01h) empties the cache. Untextured commands take none.
#[test]
fn each_command_has_its_texture_cache_misses() {
    let text = "gp0 e3000000\ngp0 e407ffff\ngp0 e5000000\ngp0 e1000108\n\
                gp0 65000000 00000000 00000000 00010020\n\
                gp0 65000000 00010000 00000000 00010020\n\
                gp0 01000000\n\
                gp0 65000000 00020000 00000000 00010020\n";
    let (s, rows, dir) = report(text, "misses");
    assert_eq!(s.texture_misses, [0, 0, 0, 0, 8, 0, 0, 8]);
    assert_eq!(rows[4]["miss"].as_u64(), Some(8));
    assert!(rows[5].get("miss").is_none() && rows[6].get("miss").is_none());
    assert_eq!(rows[7]["miss"].as_u64(), Some(8));
    let index = std::fs::read_to_string(dir.join("data/index.js")).unwrap();
    assert!(index.contains("\"missesTotal\":16"), "{index}");
    assert!(
        summary_line(&s, &dir).contains("16 texture cache misses"),
        "{}",
        summary_line(&s, &dir)
    );
}

#[test]
fn truncated_stream_gives_a_report_with_the_cut_command_marked() {
    let text = std::fs::read_to_string(fixture("quad.gpu")).unwrap();
    // Cut inside the last polygon packet.
    let lines: Vec<&str> = text.lines().collect();
    let cut = lines[..lines.len() - 2].join("\n");
    let (s, rows, _dir) = report(&cut, "truncated");
    let last = rows.last().unwrap();
    assert!(last["truncated"].as_str().unwrap().starts_with("truncated"));
    check_pixel_accounting(&cut, &s);
}

#[test]
fn draw_covering_all_vram() {
    // Fills of the whole VRAM (1024x511 and the last line: fill heights are 9 bits), then
    // a 1023x511 rectangle: scaled-down images, exact counts (docs/hardware/gpu.md §8: w = ((3F1h & 3FFh)
    // + Fh) & ~Fh = 1024).
    let [top_left, bottom_right, offset] = area(1023, 511);
    let color = [0x30, 0x20, 0x10];
    let rectangle = Rectangle {
        color: [0, 0xFF, 0],
        width: 1023,
        height: 511,
        ..Rectangle::default()
    };
    let text = gp0_lines([
        &[top_left][..],
        &[bottom_right],
        &[offset],
        &encode::fill(color, 0, 0, 0x3F1, 511),
        &encode::fill(color, 0, 511, 0x3F1, 1),
        &rectangle.packet(),
    ]);
    let text = text.as_str();
    let (s, rows, _dir) = report(text, "whole");
    assert_eq!(s.changed[3], 1024 * 511);
    assert_eq!(s.changed[4], 1024);
    assert_eq!(s.changed[5], 1023 * 511);
    let crop = rows[5]["img"]["crop"].as_array().unwrap();
    assert!(crop[4].as_u64().unwrap() >= 4, "scaled down");
    check_pixel_accounting(text, &s);
}

#[test]
fn a_million_commands_stay_usable() {
    // 10^6 commands: environment words and small rectangles. The report must finish and
    // page its rows into chunk files.
    let mut text = gp0_lines(area(1023, 511).iter().map(core::slice::from_ref));
    let environment = [
        encode::draw_mode(gpu::DrawMode::default()),
        encode::mask_bits(gpu::MaskSettings::default()),
    ];
    for i in 0..333_333u32 {
        let (x, y) = ((i % 1000) as i16, ((i / 1000) % 500) as i16);
        let [r, g, ..] = i.to_le_bytes();
        let pixel = Rectangle {
            x,
            y,
            color: [r, g, 0],
            size: SpriteSize::One,
            ..Rectangle::default()
        };
        text.push_str(&gp0_lines([
            &environment[..1],
            &environment[1..],
            &pixel.packet(),
        ]));
    }
    let commands = command_stream::parse(&text).unwrap();
    assert_eq!(commands.len(), 1_000_002);
    let dir = Scratch::new("million");
    let mut gpu = Gpu::new();
    let start = std::time::Instant::now();
    let s = write_report(
        &mut gpu,
        &commands,
        &dir,
        "million",
        InspectOptions {
            max_images: 1000,
            ..InspectOptions::default()
        },
        None,
        None,
    )
    .unwrap();
    eprintln!("10^6 commands: {:.1} s", start.elapsed().as_secs_f64());
    assert_eq!(s.commands, 1_000_002);
    assert_eq!(s.images, 1000);
    let index = std::fs::read_to_string(dir.join("data/index.js")).unwrap();
    assert!(index.contains("\"commands\":1000002"));
    assert!(
        dir.join(format!(
            "data/chunk-{:05}.js",
            1_000_001 / wobble::inspect::CHUNK
        ))
        .is_file()
    );
}

#[test]
fn rendered_frame_traces_faces_to_packets() {
    use wobble::pipeline::{FaceFate, PacketOrigin, PipelineOptions, Renderer};
    // The sphere made semi-transparent: untextured, each of its polygons takes a
    // blend-mode word.
    let mut scene = wobble::scene::Scene::default_scene();
    scene.objects[wobble::scene::default::SPHERE].blend = Some(1);
    let mut renderer = Renderer::new(scene, PipelineOptions::default()).unwrap();
    renderer.render_frame(0);
    let (stats, trace) = renderer.render_frame_traced(1).unwrap();
    // The fates add up to the frame's counts.
    let count = |f: &dyn Fn(&FaceFate) -> bool| trace.faces.iter().filter(|r| f(&r.fate)).count();
    assert_eq!(count(&|f| matches!(f, FaceFate::Drawn { .. })), stats.drawn);
    assert_eq!(count(&|f| matches!(f, FaceFate::Culled)), stats.culled);
    assert_eq!(
        count(&|f| matches!(f, FaceFate::Offscreen)),
        stats.offscreen
    );
    assert_eq!(
        count(&|f| matches!(f, FaceFate::Dropped(_) | FaceFate::Overflow)),
        stats.dropped
    );
    assert_eq!(count(&|f| !matches!(f, FaceFate::Split)), stats.polygons);
    // Every drawn face has exactly one packet.
    for (i, r) in trace.faces.iter().enumerate() {
        let packets = trace
            .packets
            .iter()
            .filter(|p| p.origin == Some(PacketOrigin::Face(i)))
            .count();
        let drawn = matches!(r.fate, FaceFate::Drawn { .. });
        assert_eq!(packets, usize::from(drawn), "face record {i}");
    }
    // The frame's set-up comes first (E1h-E6h and the fill), then the ordering table's
    // packets, each blend-mode word just before the polygon it is for.
    let (setup, table) = trace.packets.split_at(7);
    assert!(
        setup
            .iter()
            .all(|p| p.origin == Some(PacketOrigin::Environment))
    );
    let mut blend_words = 0;
    for (k, p) in table.iter().enumerate() {
        match p.origin {
            Some(PacketOrigin::Face(_)) => {}
            Some(PacketOrigin::BlendMode(f)) => {
                blend_words += 1;
                assert_eq!(p.words.len(), 1);
                assert_eq!(p.words[0] >> 24, 0xE1);
                let next = table.get(k + 1).and_then(|n| n.origin);
                assert_eq!(next, Some(PacketOrigin::Face(f)), "packet {k}");
                let object = trace.faces[f].object;
                assert_eq!(object, wobble::scene::default::SPHERE);
            }
            other => panic!("packet {k} of the table: {other:?}"),
        }
    }
    assert!(blend_words > 0, "no blend-mode word");
    // Replaying the traced packets on the GPU as it was reproduces the frame.
    let dir = Scratch::new("frame");
    let s = wobble::inspect::write_frame_report(
        renderer.scene(),
        &trace,
        &dir,
        "frame",
        InspectOptions::default(),
    )
    .unwrap();
    assert!(s.final_vram == renderer.gpu().vram().as_slice());
    assert_eq!(s.commands, trace.packets.len() + 1);
    let rows = rows(&dir);
    let traced = rows
        .iter()
        .filter(|r| r["origin"].as_str().is_some_and(|o| o.contains("face")))
        .count();
    assert_eq!(traced, stats.drawn);
    assert!(
        std::fs::read_to_string(dir.join("data/faces.js"))
            .unwrap()
            .contains("culled")
    );
}

/// Decodes standard base64 (the report's data scripts), independently of the writer.
fn unbase64(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        b'/' => 63,
        _ => panic!("not base64: {c}"),
    };
    let mut out = Vec::new();
    for q in s.as_bytes().chunks(4) {
        let n = q.iter().filter(|&&c| c != b'=').count();
        let mut v = 0u32;
        for (i, &c) in q.iter().enumerate() {
            v |= u32::from(if c == b'=' { 0 } else { val(c) }) << (18 - 6 * i);
        }
        out.extend_from_slice(&v.to_be_bytes()[1..n]);
    }
    out
}

/// The page's pixel readout reads `data/vram.js`: the final VRAM of a plain replay, as
/// little-endian halfwords. The display-area list starts at command 0 and ends with the area
/// the GPU shows after the last command. A before/after image's third panel marks in
/// magenta exactly the pixels the command changed (crops shown at 1:1).
#[test]
fn raw_vram_display_area_and_changed_panel() {
    let text = std::fs::read_to_string(fixture("transparency.gpu")).unwrap();
    let (s, rows, dir) = report(&text, "raw-vram");
    let mut plain = Gpu::new();
    command_stream::run(&mut plain, &command_stream::parse(&text).unwrap());
    let js = std::fs::read_to_string(dir.join("data/vram.js")).unwrap();
    let b64 = js
        .strip_prefix("INSPECT.vram(\"")
        .and_then(|t| t.strip_suffix("\");\n"))
        .unwrap();
    let raw: Vec<u16> = unbase64(b64)
        .chunks(2)
        .map(|p| u16::from_le_bytes([p[0], p[1]]))
        .collect();
    assert!(raw == plain.vram().as_slice());

    let index = std::fs::read_to_string(dir.join("data/index.js")).unwrap();
    let index: Value = serde_json::from_str(
        index
            .strip_prefix("INSPECT.index(")
            .and_then(|t| t.strip_suffix(");\n"))
            .unwrap(),
    )
    .unwrap();
    let display = index["display"].as_array().unwrap();
    assert_eq!(display[0][0], 0);
    let a = plain.display_area();
    let last = &display[display.len() - 1][1];
    assert_eq!(
        last,
        &serde_json::json!([a.x, a.y, a.width, a.height, u16::from(a.color_24bit)])
    );

    let mut checked = 0;
    for r in &rows {
        let (Some(png), Some(crop)) = (r["img"]["png"].as_str(), r["img"]["crop"].as_array())
        else {
            continue;
        };
        if crop[4] != 1 {
            continue;
        }
        let img = image::open(dir.join(png)).unwrap().to_rgb8();
        let w = crop[2].as_u64().unwrap() as u32;
        assert_eq!(img.width(), 3 * w + 8);
        let magenta = (0..img.height())
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| img.get_pixel(2 * (w + 4) + x, y).0 == [255, 0, 255])
            .count();
        assert_eq!(magenta as u64, r["changed"].as_u64().unwrap(), "{}", r["i"]);
        checked += 1;
    }
    assert!(checked > 0 && s.images > 0);
}
