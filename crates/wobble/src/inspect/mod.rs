//! The draw-by-draw inspector: runs GPU commands one at a time and writes a self-contained
//! report (one HTML page, script data files and PNG images; no server, no network) showing
//! every command decoded by the `gpu` crate, what each draw changed in VRAM, the texture it
//! sampled, which command last changed each pixel, and every change to each pixel
//! (docs/inspect.md).
//!
//! Every command's names, fields and drop reasons come from [`gpu::decode`], typed; this
//! module runs the commands, compares VRAM before and after each, writes the decoded values
//! as text (`text`) and writes files.

use base64_lite::encode as base64;
use gpu::TextureDepth;
use gpu::command_stream::{Port, StreamCommand};
use gpu::decode::{Class, Decoded, Kind, Primitive, TracedCommand, Tracer};
use gpu::decode::{Coverage, PixelBounds};
use gpu::{Gpu, VRAM_HEIGHT, VRAM_LEN, VRAM_WIDTH};
use image::{Rgb, RgbImage};
use serde_json::{Value, json};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::vram_image::{self, Expand};

mod base64_lite;
mod frame;
mod history;
mod text;

pub use frame::write_frame_report;

/// The page, its script and its style, written next to the data.
const INDEX_HTML: &str = include_str!("assets/index.html");
const INSPECT_JS: &str = include_str!("assets/inspect.js");
const INSPECT_CSS: &str = include_str!("assets/inspect.css");

/// Commands per data file: the page loads one such file when its rows are shown.
pub const CHUNK: usize = 500;

/// Pixels around a draw's bounds in its before/after image.
const MARGIN: usize = 8;

/// Longest side of a before/after crop before it is scaled down.
const CROP_MAX: usize = 256;

/// Packet words listed in a row; longer commands (transfers) are cut with a count.
const WORDS_SHOWN: usize = 24;

/// Limits on what a report writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InspectOptions {
    /// Commands that get a before/after image (the first this many that change VRAM);
    /// later ones are listed with their pixel counts but no image.
    pub max_images: usize,
    /// Distinct texture-page views written.
    pub max_textures: usize,
}

impl Default for InspectOptions {
    fn default() -> Self {
        Self {
            max_images: 1_000,
            max_textures: 200,
        }
    }
}

/// Where a command came from in the scene pipeline (`wobble render --inspect`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Origin {
    /// Text shown in the command's row and detail, e.g. `object 1 cube, face 12, OT 300`.
    pub text: String,
}

/// What one report contains, for the command line's summary and for tests.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct InspectSummary {
    /// Commands listed.
    pub commands: usize,
    /// Drawing commands (polygons, lines, rectangles).
    pub draws: usize,
    /// Primitives dropped whole by the rasterizer (size limit, zero area, clipped).
    pub dropped: usize,
    /// Per command: pixels whose value it changed.
    pub changed: Vec<u64>,
    /// Per pixel: 1 + the index of the last command that changed it, 0 if none did.
    pub writers: Vec<u32>,
    /// VRAM before the first command.
    pub initial: Vec<u16>,
    /// VRAM after the last command.
    pub final_vram: Vec<u16>,
    /// Commands with a before/after image.
    pub images: usize,
    /// Texture-page views written.
    pub textures: usize,
    /// Per command: the GPU cycles the console spends on it ([`gpu::Gpu::work_cycles`]
    /// across the command: drawing, fills, copies, transfers; 0 for the rest).
    pub gpu_cycles: Vec<u64>,
    /// All commands' time in CPU cycles: the sum of `gpu_cycles` at the console's clock ratio.
    pub cpu_cycles: u64,
    /// Per command: the texture cache misses it took ([`gpu::Gpu::texture_cache_misses`]
    /// across the command), each part of its time.
    pub texture_misses: Vec<u64>,
}

fn io_err(path: &Path, e: std::io::Error) -> String {
    format!("{}: {e}", path.display())
}

fn write_file(path: &Path, contents: impl AsRef<[u8]>) -> Result<(), String> {
    std::fs::write(path, contents).map_err(|e| io_err(path, e))
}

/// `data/NAME.js` under `out`: the call `INSPECT.NAME("...")` with `bytes` in base64.
fn write_base64_data(out: &Path, name: &str, bytes: &[u8]) -> Result<(), String> {
    write_file(
        &out.join(format!("data/{name}.js")),
        format!("INSPECT.{name}(\"{}\");\n", base64(bytes)),
    )
}

fn create_dir(path: &Path) -> Result<(), String> {
    std::fs::create_dir_all(path).map_err(|e| io_err(path, e))
}

/// Copy of the VRAM rectangle `b`, row by row.
fn snapshot(vram: &[u16], b: &PixelBounds, out: &mut Vec<u16>) {
    out.clear();
    for y in b.top as usize..=b.bottom as usize {
        let row = y * VRAM_WIDTH;
        if let Some(s) = vram.get(row + b.left as usize..=row + b.right as usize) {
            out.extend_from_slice(s);
        }
    }
}

const WHOLE_VRAM: PixelBounds = PixelBounds {
    left: 0,
    top: 0,
    right: (VRAM_WIDTH - 1) as u16,
    bottom: (VRAM_HEIGHT - 1) as u16,
};

/// The rectangle a command may write: the decoder's bounds, or all VRAM for words that
/// continue a packet begun earlier (their effect was not decoded).
fn write_region(d: &Decoded) -> Option<PixelBounds> {
    match d.kind {
        Kind::Continuation => Some(WHOLE_VRAM),
        _ => d.writes,
    }
}

/// A texture-page view: page X/Y, depth, CLUT X/Y, and the change counts of the VRAM
/// blocks it reads.
type ViewKey = (u16, u16, u8, u16, u16, [u64; 5]);

/// Texture-page views already written, keyed by what they show and the VRAM version of
/// the blocks they read.
struct TextureViews {
    /// Changes seen per 64x256 VRAM block (16 x 2 blocks).
    generation: [u64; 32],
    written: HashMap<ViewKey, String>,
    max: usize,
}

impl TextureViews {
    fn bump(&mut self, b: &PixelBounds) {
        for by in (b.top as usize / 256)..=(b.bottom as usize / 256).min(1) {
            for bx in (b.left as usize / 64)..=(b.right as usize / 64).min(15) {
                if let Some(g) = self.generation.get_mut(by * 16 + bx) {
                    *g += 1;
                }
            }
        }
    }

    fn block(&self, x: usize, y: usize) -> u64 {
        self.generation
            .get(((y / 256) & 1) * 16 + (x / 64) % 16)
            .copied()
            .unwrap_or(0)
    }

    /// The file name of the view of `t` as VRAM is now, writing it if new.
    fn view(
        &mut self,
        vram: &[u16],
        t: &gpu::decode::Texture,
        dir: &Path,
    ) -> Result<Option<String>, String> {
        let depth = t.depth;
        let (width, code) = match depth {
            TextureDepth::Clut4 => (64, 4),
            TextureDepth::Clut8 => (128, 8),
            TextureDepth::Direct15 => (256, 15),
        };
        let (px, py) = (t.page_x as usize, t.page_y as usize);
        let mut gens = [0u64; 5];
        for (i, g) in gens.iter_mut().take(4).enumerate() {
            if i * 64 < width {
                *g = self.block(px + i * 64, py);
            }
        }
        if code != 15 {
            gens[4] = self.block(t.clut_x as usize, t.clut_y as usize)
                ^ self.block(t.clut_x as usize + 255, t.clut_y as usize) << 32;
        }
        let key = (t.page_x, t.page_y, code, t.clut_x, t.clut_y, gens);
        if let Some(name) = self.written.get(&key) {
            return Ok(Some(name.clone()));
        }
        if self.written.len() >= self.max {
            return Ok(None);
        }
        let name = format!("tex/{}.png", self.written.len());
        let img = vram_image::texture_page_image(
            vram,
            px,
            py,
            depth,
            (t.clut_x as usize, t.clut_y as usize),
            Expand::Replicate,
        );
        vram_image::save_png(&img, &dir.join(&name)).map_err(|e| e.to_string())?;
        self.written.insert(key, name.clone());
        Ok(Some(name))
    }
}

/// The crop shown for a command: its write bounds plus a margin, scaled down to fit.
#[derive(Clone, Copy, Debug)]
struct Crop {
    x: usize,
    y: usize,
    w: usize,
    h: usize,
    scale: usize,
}

fn crop_for(b: &PixelBounds) -> Crop {
    let x = (b.left as usize).saturating_sub(MARGIN);
    let y = (b.top as usize).saturating_sub(MARGIN);
    let x1 = (b.right as usize + MARGIN).min(VRAM_WIDTH - 1);
    let y1 = (b.bottom as usize + MARGIN).min(VRAM_HEIGHT - 1);
    let (w, h) = (x1 - x + 1, y1 - y + 1);
    let scale = w.max(h).div_ceil(CROP_MAX).max(1);
    Crop { x, y, w, h, scale }
}

/// Gap in pixels between the panels of a before/after image.
const GAP: usize = 4;

/// Before, after and changed panels of a crop (`before` and `after` both `c.w` x `c.h`,
/// row-major), side by side with a 4-pixel gap. The changed panel shows the pixels whose value changed in magenta
/// and the others as the after image at a quarter of its brightness.
fn before_after(before: &[u16], after: &[u16], c: &Crop) -> RgbImage {
    let (w, h) = (c.w.div_ceil(c.scale), c.h.div_ceil(c.scale));
    RgbImage::from_fn((3 * w + 2 * GAP) as u32, h as u32, |x, y| {
        let (x, y) = (x as usize, y as usize);
        let (panel, cx) = (x / (w + GAP), x % (w + GAP));
        if cx >= w {
            return Rgb([40, 40, 48]);
        }
        let px = (cx * c.scale).min(c.w - 1);
        let py = (y * c.scale).min(c.h - 1);
        let at = |src: &[u16]| src.get(py * c.w + px).copied().unwrap_or(0);
        match panel {
            0 => Rgb(Expand::Replicate.pixel(at(before))),
            1 => Rgb(Expand::Replicate.pixel(at(after))),
            _ if at(before) != at(after) => Rgb([255, 0, 255]),
            _ => Rgb(Expand::Replicate.pixel(at(after)).map(|v| v / 4)),
        }
    })
}

fn prim_json(p: &Primitive) -> Value {
    let kind = match p {
        Primitive::Triangle(..) => "triangle",
        Primitive::Line(..) => "line",
        Primitive::Rectangle(..) => "rectangle",
    };
    // Outline corners wrapped to 11 bits like the rasterizer's vertices (docs/hardware/gpu.md §3.5).
    let wrap = |v: i32| (v << 21) >> 21;
    let pts: Vec<[i32; 2]> = p
        .outline()
        .iter()
        .map(|&(x, y)| [wrap(x), wrap(y)])
        .collect();
    let (fate, bounds) = match p.coverage() {
        Coverage::Drawn(b) => (Value::Null, json!([b.left, b.top, b.right, b.bottom])),
        Coverage::Dropped(r) => (json!(text::drop_reason(r)), Value::Null),
    };
    json!({ "kind": kind, "pts": pts, "fate": fate, "bounds": bounds })
}

fn words_text(words: &[u32]) -> String {
    let mut s = String::new();
    for (i, w) in words.iter().take(WORDS_SHOWN).enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{w:08x}");
    }
    if words.len() > WORDS_SHOWN {
        let _ = write!(s, " … ({} words)", words.len());
    }
    s
}

/// One-letter class codes for the page's filter: d draw (D with a dropped primitive),
/// t transfer, e environment, g GP1 display, o other.
fn class_code(d: &Decoded) -> char {
    match d.kind.class() {
        Class::Draw
            if d.primitives
                .iter()
                .any(|p| p.coverage().dropped().is_some()) =>
        {
            'D'
        }
        Class::Draw => 'd',
        Class::Transfer => 't',
        Class::Environment => 'e',
        Class::Display => 'g',
        Class::Other => 'o',
    }
}

/// Write the report for `commands` run on `gpu` into `out`. `origins`, when given, is
/// indexed by stream line (1-based) and annotates the command starting there. `faces`
/// is an optional table (rows of text cells under `face_columns`) shown on its own tab.
pub fn write_report(
    gpu: &mut Gpu,
    commands: &[StreamCommand],
    out: &Path,
    title: &str,
    options: InspectOptions,
    origins: Option<&HashMap<usize, Origin>>,
    faces: Option<(&[&str], &[Vec<String>])>,
) -> Result<InspectSummary, String> {
    write_report_with_progress(
        gpu,
        commands,
        out,
        title,
        options,
        origins,
        faces,
        &mut |_, _| {},
    )
}

/// [`write_report`], calling `progress(done, total)` with the stream lines run so far and
/// the stream's last line after every command.
#[allow(clippy::too_many_arguments)]
pub fn write_report_with_progress(
    gpu: &mut Gpu,
    commands: &[StreamCommand],
    out: &Path,
    title: &str,
    options: InspectOptions,
    origins: Option<&HashMap<usize, Origin>>,
    faces: Option<(&[&str], &[Vec<String>])>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<InspectSummary, String> {
    let total_lines = commands.last().map_or(0, |c| c.line);
    let mut display = Vec::new();
    let mut last_area = None;
    for sub in ["data", "img", "tex"] {
        create_dir(&out.join(sub))?;
    }
    let initial = gpu.vram().as_slice().to_vec();
    let mut summary = InspectSummary {
        writers: vec![0u32; VRAM_LEN],
        initial,
        ..InspectSummary::default()
    };
    let mut textures = TextureViews {
        generation: [0; 32],
        written: HashMap::new(),
        max: options.max_textures,
    };
    let mut history = history::History::new(out)?;
    let mut tracer = Tracer::new(commands);
    let mut rows: Vec<Value> = Vec::with_capacity(CHUNK);
    let mut classes = String::new();
    let mut chunk_lines: Vec<usize> = Vec::new();
    let mut draw_indices = 0usize;
    let mut before = Vec::new();
    let mut index = 0usize;
    // Per command: its time in CPU cycles, for the page's "slowest first" order.
    let mut times: Vec<u64> = Vec::new();
    let (num, den) = gpu.video_standard().clock_ratio();
    // CPU cycles of one NTSC or PAL scanline (docs/hardware/timing.md §2), for hblanks.
    let line_cycles = if gpu.video_standard() == gpu::VideoStandard::Pal {
        3406.0 * den as f64 / num as f64
    } else {
        3413.0 * den as f64 / num as f64
    };
    while let Some(cmd) = tracer.next_command(gpu) {
        let row = run_one(
            gpu,
            &cmd,
            index,
            out,
            options,
            &mut summary,
            &mut textures,
            &mut before,
            &mut history,
            origins,
        )?;
        if rows.is_empty() {
            chunk_lines.push(cmd.line);
        }
        times.push((summary.gpu_cycles.last().copied().unwrap_or(0) * den).div_ceil(num));
        classes.push(class_code(&cmd.decoded));
        if cmd.decoded.kind.class() == Class::Draw {
            draw_indices += 1;
        }
        rows.push(row);
        let a = gpu.display_area();
        let area = [a.x, a.y, a.width, a.height, u16::from(a.color_24bit)];
        if last_area != Some(area) {
            last_area = Some(area);
            display.push(json!([index, area]));
        }
        index += 1;
        progress(cmd.last_line, total_lines);
        if rows.len() == CHUNK {
            write_chunk(out, (index - 1) / CHUNK, &rows)?;
            rows.clear();
        }
    }
    if !rows.is_empty() {
        write_chunk(out, index.saturating_sub(1) / CHUNK, &rows)?;
    }
    summary.commands = index;
    summary.draws = draw_indices;
    let gpu_total: u64 = summary.gpu_cycles.iter().sum();
    let misses_total: u64 = summary.texture_misses.iter().sum();
    let cpu_total = (gpu_total * den).div_ceil(num);
    summary.cpu_cycles = cpu_total;
    let hist_tiles = history.finish()?;
    summary.final_vram = gpu.vram().as_slice().to_vec();

    let final_img = vram_image::vram_image(&summary.final_vram, Expand::Replicate);
    vram_image::save_png(&final_img, &out.join("img/final.png")).map_err(|e| e.to_string())?;
    let initial_img = vram_image::vram_image(&summary.initial, Expand::Replicate);
    vram_image::save_png(&initial_img, &out.join("img/initial.png")).map_err(|e| e.to_string())?;

    let writers: Vec<u8> = summary
        .writers
        .iter()
        .flat_map(|w| w.to_le_bytes())
        .collect();
    write_base64_data(out, "writers", &writers)?;
    let vram: Vec<u8> = summary
        .final_vram
        .iter()
        .flat_map(|p| p.to_le_bytes())
        .collect();
    write_base64_data(out, "vram", &vram)?;
    let changed_total: u64 = summary.changed.iter().sum();
    let index_json = json!({
        "title": title,
        "commands": summary.commands,
        "draws": summary.draws,
        "dropped": summary.dropped,
        "changedTotal": changed_total,
        "images": summary.images,
        "textures": summary.textures,
        "chunk": CHUNK,
        "chunkLines": chunk_lines,
        "classes": classes,
        "hasFaces": faces.is_some(),
        "gpuCycles": gpu_total,
        "cpuCycles": cpu_total,
        "missesTotal": misses_total,
        "cpuHz": gpu::CPU_CLOCK_HZ,
        "lineCycles": line_cycles,
        "times": times,
        "display": display,
        "histTiles": hist_tiles,
        "histTile": history::TILE,
    });
    write_file(
        &out.join("data/index.js"),
        format!("INSPECT.index({index_json});\n"),
    )?;
    if let Some((columns, face_rows)) = faces {
        let faces_json = json!({ "columns": columns, "rows": face_rows });
        write_file(
            &out.join("data/faces.js"),
            format!("INSPECT.faces({faces_json});\n"),
        )?;
    }
    write_file(&out.join("index.html"), INDEX_HTML)?;
    write_file(&out.join("inspect.js"), INSPECT_JS)?;
    write_file(&out.join("inspect.css"), INSPECT_CSS)?;
    Ok(summary)
}

fn write_chunk(out: &Path, n: usize, rows: &[Value]) -> Result<(), String> {
    let path = out.join(format!("data/chunk-{n:05}.js"));
    write_file(
        &path,
        format!("INSPECT.chunk({n},{});\n", Value::from(rows)),
    )
}

#[allow(clippy::too_many_arguments)]
fn run_one(
    gpu: &mut Gpu,
    cmd: &TracedCommand,
    index: usize,
    out: &Path,
    options: InspectOptions,
    summary: &mut InspectSummary,
    textures: &mut TextureViews,
    before: &mut Vec<u16>,
    history: &mut history::History,
    origins: Option<&HashMap<usize, Origin>>,
) -> Result<Value, String> {
    let d = &cmd.decoded;
    let region = write_region(d);
    // The texture as sampled: VRAM before the draw.
    let texture = d.primitives.iter().find_map(|p| {
        p.texture()
            .map(|t| (t, p.uv_bounds().unwrap_or((0, 0, 255, 255))))
    });
    let tex_json = match texture {
        Some((t, uv)) => {
            let file = textures.view(gpu.vram().as_slice(), &t, out)?;
            // The CLUT as the draw reads it: 16 or 256 halfwords from (clut_x, clut_y),
            // x wrapping at the VRAM's width (docs/hardware/gpu.md §7).
            let entries = match t.depth {
                TextureDepth::Clut4 => 16,
                TextureDepth::Clut8 => 256,
                TextureDepth::Direct15 => 0,
            };
            let mut clut = String::with_capacity(entries * 4);
            let vram = gpu.vram().as_slice();
            for i in 0..entries {
                let x = (t.clut_x as usize + i) % VRAM_WIDTH;
                let y = t.clut_y as usize % VRAM_HEIGHT;
                let _ = write!(
                    clut,
                    "{:04x}",
                    vram.get(y * VRAM_WIDTH + x).copied().unwrap_or(0)
                );
            }
            summary.textures = textures.written.len();
            json!({
                "png": file,
                "page": [t.page_x, t.page_y],
                "clut": [t.clut_x, t.clut_y],
                "depth": match t.depth {
                    TextureDepth::Clut4 => 4,
                    TextureDepth::Clut8 => 8,
                    TextureDepth::Direct15 => 15,
                },
                "uv": [uv.0, uv.1, uv.2, uv.3],
                "clutv": clut,
            })
        }
        None => Value::Null,
    };
    if let Some(b) = &region {
        snapshot(gpu.vram().as_slice(), b, before);
    }
    let crop = region.map(|b| crop_for(&b));
    let crop_bounds = |c: &Crop| PixelBounds {
        left: c.x as u16,
        top: c.y as u16,
        right: (c.x + c.w - 1) as u16,
        bottom: (c.y + c.h - 1) as u16,
    };
    let before_crop: Option<Vec<u16>> = match (&crop, summary.images < options.max_images) {
        (Some(c), true) => {
            let mut v = Vec::new();
            snapshot(gpu.vram().as_slice(), &crop_bounds(c), &mut v);
            Some(v)
        }
        _ => None,
    };
    let work = gpu.work_cycles();
    let misses_before = gpu.texture_cache_misses();
    Tracer::execute(gpu, cmd);
    let gpu_cycles = gpu.work_cycles().saturating_sub(work);
    summary.gpu_cycles.push(gpu_cycles);
    let misses = gpu.texture_cache_misses().saturating_sub(misses_before);
    summary.texture_misses.push(misses);
    let (num, den) = gpu.video_standard().clock_ratio();
    let cpu_cycles = (gpu_cycles * den).div_ceil(num);
    let mut changed = 0u64;
    if let Some(b) = &region {
        let vram = gpu.vram().as_slice();
        let w = b.width();
        let mut changed_bounds: Option<PixelBounds> = None;
        // The run of changed pixels being collected for the history: its column and values.
        let mut run: (usize, Vec<u16>) = (0, Vec::new());
        for (r, y) in (b.top as usize..=b.bottom as usize).enumerate() {
            let row = y * VRAM_WIDTH;
            for x in b.left as usize..=b.right as usize {
                let i = row + x;
                let old = before.get(r * w + (x - b.left as usize)).copied();
                let now = vram.get(i).copied();
                if !run.1.is_empty() && (now == old || x % history::TILE == 0) {
                    history.run(index, y, run.0, &run.1, &summary.initial)?;
                    run.1.clear();
                }
                if now != old {
                    if run.1.is_empty() {
                        run.0 = x;
                    }
                    run.1.push(now.unwrap_or(0));
                    changed += 1;
                    if let Some(slot) = summary.writers.get_mut(i) {
                        *slot = index as u32 + 1;
                    }
                    let (x, y) = (x as u16, y as u16);
                    changed_bounds = Some(match changed_bounds {
                        None => PixelBounds {
                            left: x,
                            top: y,
                            right: x,
                            bottom: y,
                        },
                        Some(c) => PixelBounds {
                            left: c.left.min(x),
                            top: c.top.min(y),
                            right: c.right.max(x),
                            bottom: c.bottom.max(y),
                        },
                    });
                }
            }
            if !run.1.is_empty() {
                history.run(index, y, run.0, &run.1, &summary.initial)?;
                run.1.clear();
            }
        }
        if let Some(cb) = &changed_bounds {
            textures.bump(cb);
        }
    }
    summary.changed.push(changed);
    summary.dropped += d
        .primitives
        .iter()
        .filter(|p| p.coverage().dropped().is_some())
        .count();
    let mut img = Value::Null;
    if let (Some(c), Some(bc)) = (&crop, &before_crop)
        && changed > 0
    {
        let mut after_crop = Vec::new();
        snapshot(gpu.vram().as_slice(), &crop_bounds(c), &mut after_crop);
        let image = before_after(bc, &after_crop, c);
        let name = format!("img/{:03}/{index}.png", index / 1000);
        let path: PathBuf = out.join(&name);
        if let Some(parent) = path.parent() {
            create_dir(parent)?;
        }
        vram_image::save_png(&image, &path).map_err(|e| e.to_string())?;
        summary.images += 1;
        img = json!({ "png": name, "crop": [c.x, c.y, c.w, c.h, c.scale] });
    }
    let mut fields = Vec::with_capacity(d.fields.len());
    for f in &d.fields {
        text::field_rows(f, &mut fields);
    }
    let fields: Vec<[&str; 2]> = fields
        .iter()
        .map(|(name, value)| [name.as_str(), value.as_str()])
        .collect();
    let truncated = d.truncated.map(|t| match t.need {
        Some(n) => format!("truncated: {} of {n} words", t.have),
        None => format!("truncated: no terminator after {} words", t.have),
    });
    let origin = origins
        .and_then(|o| o.get(&cmd.line))
        .map(|o| o.text.clone());
    let mut row = json!({
        "i": index,
        "line": cmd.line,
        "last": cmd.last_line,
        "port": match cmd.port { Port::Gp0 => "GP0", Port::Gp1 => "GP1" },
        "kind": text::class_name(d.kind.class()),
        "name": d.name,
        "fields": fields,
        "words": words_text(&cmd.words),
        "nwords": cmd.words.len(),
        "prims": d.primitives.iter().map(prim_json).collect::<Vec<_>>(),
        "writes": d.writes.map(|b| [b.left, b.top, b.right, b.bottom]),
        "changed": changed,
        "img": img,
        "tex": tex_json,
        "truncated": truncated,
        "origin": origin,
        "gpu": (gpu_cycles > 0).then_some(gpu_cycles),
        "cyc": (cpu_cycles > 0).then_some(cpu_cycles),
        "miss": (misses > 0).then_some(misses),
    });
    // Empty entries are left out: the page treats a missing key as null or empty.
    if let Value::Object(m) = &mut row {
        m.retain(|_, v| !(v.is_null() || v.as_array().is_some_and(|a| a.is_empty())));
    }
    Ok(row)
}

/// Write the report of the command stream in file `stream` into `out`; the title is the
/// file's name. Errors name the file (and, for a malformed stream, the line).
pub fn inspect_stream(
    stream: &Path,
    out: &Path,
    options: InspectOptions,
) -> Result<InspectSummary, String> {
    let text = std::fs::read_to_string(stream).map_err(|e| io_err(stream, e))?;
    let commands =
        gpu::command_stream::parse(&text).map_err(|e| format!("{}: {e}", stream.display()))?;
    let title = stream.file_name().map_or_else(
        || "stream".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut gpu = Gpu::new();
    write_report(&mut gpu, &commands, out, &title, options, None, None)
}

/// The line printed after a report is written.
pub fn summary_line(s: &InspectSummary, out: &Path) -> String {
    let count = |n: u64, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    format!(
        "{} ({}, {} dropped, {}; GPU time {} CPU cycles = {:.3} ms, {}) -> {}",
        count(s.commands as u64, "command", "commands"),
        count(s.draws as u64, "draw", "draws"),
        count(s.dropped as u64, "primitive", "primitives"),
        count(
            s.changed.iter().sum::<u64>(),
            "pixel change",
            "pixel changes"
        ),
        s.cpu_cycles,
        s.cpu_cycles as f64 * 1000.0 / gpu::CPU_CLOCK_HZ as f64,
        count(
            s.texture_misses.iter().sum::<u64>(),
            "texture cache miss",
            "texture cache misses"
        ),
        out.join("index.html").display()
    )
}
