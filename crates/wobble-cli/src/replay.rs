//! `wobble replay`: run a command stream or a GPU dump on a fresh GPU, frame by frame, and
//! write VRAM or the displayed picture at a frame, a range of frames as an animated GIF or
//! numbered PNGs, and the raw VRAM.

use crate::gif::{GifWriter, image_rgb15};
use crate::gpu_input::{self, InputKind};
use crate::output::{self, FormatArg, OutputDir};
use crate::{ExpandArg, Region, input};
use gpu::VideoStandard;
use gpu::dump::Packet;
use image::RgbImage;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use wobble::gpu_dump::{Dump, Player, displayed_image};
use wobble::vram_image::{self, Expand};

/// Arguments of `wobble replay`.
#[derive(clap::Args)]
pub struct ReplayArgs {
    /// Command stream (.gpu text) or GPU dump (.psxgpu, .psxgpu.zst, .psxgpu.xz);
    /// docs/formats.md.
    pub stream: PathBuf,
    /// Image of the last frame replayed, format by extension or --format; `-` is standard
    /// output (default: the input's name with .png, in the current directory). A GIF gets
    /// every selected frame, animated.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image format of -o (needed for `-o -`).
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
    /// Also write the raw VRAM after the last frame replayed (1024*512 little-endian u16);
    /// `-` is standard output.
    #[arg(long)]
    pub raw: Option<PathBuf>,
    /// What the images show: the whole VRAM, or the displayed picture (default: display
    /// for a dump, vram for a command stream).
    #[arg(long, value_enum)]
    pub region: Option<Region>,
    /// 5-bit to 8-bit conversion.
    #[arg(long, value_enum, default_value_t = ExpandArg::Replicate)]
    pub expand: ExpandArg,
    /// Replay up to the end of frame N (0-based; frames end at VSync packets).
    #[arg(long, conflicts_with = "frames")]
    pub frame: Option<usize>,
    /// Frames A..B (B excluded), A..=B or A..: the image is the last one's; a GIF or
    /// --png-dir gets each.
    #[arg(long)]
    pub frames: Option<String>,
    /// Write each selected frame as a numbered PNG (frame00012.png) into this directory
    /// (moved into place when complete).
    #[arg(long)]
    pub png_dir: Option<PathBuf>,
    /// Print a line per selected frame (commands, draws, words, display area); without
    /// -o, --raw or --png-dir no image is written.
    #[arg(long)]
    pub list: bool,
    /// Also print the time the stream takes on a console: CPU cycles, hblanks (what timer 1
    /// counts) and milliseconds until the GPU has finished, and each `report` line. Accepts
    /// timed streams (docs/formats.md, "Timed streams"); not GPU dumps.
    #[arg(long, conflicts_with_all = ["frame", "frames", "png_dir", "list"])]
    pub timing: bool,
    /// Turn the GPU's texture cache off: texels are read straight from VRAM, so no stale
    /// texels and no miss time (docs/gpu.md, "Texture cache").
    #[arg(long)]
    pub no_texture_cache: bool,
    /// The console whose clocks time the stream.
    #[arg(long, value_enum, default_value_t = ConsoleArg::Ntsc, requires = "timing")]
    pub console: ConsoleArg,
}

/// A console region, as `--console` takes it.
#[derive(Clone, Copy, Debug, clap::ValueEnum, PartialEq, Eq)]
pub enum ConsoleArg {
    /// NTSC console: GPU clock 11/7 of the CPU clock.
    Ntsc,
    /// PAL console: GPU clock 53.203425 MHz.
    Pal,
}

impl From<ConsoleArg> for VideoStandard {
    fn from(c: ConsoleArg) -> VideoStandard {
        match c {
            ConsoleArg::Ntsc => VideoStandard::Ntsc,
            ConsoleArg::Pal => VideoStandard::Pal,
        }
    }
}

/// Milliseconds in `cycles` CPU cycles.
fn millis(cycles: u64) -> f64 {
    cycles as f64 * 1000.0 / gpu::CPU_CLOCK_HZ as f64
}

/// What `replay --timing` prints: the GPU time of the whole stream, then each report.
fn timing_text(t: &gpu::bus::TimedRun, console: ConsoleArg) -> String {
    let console = match console {
        ConsoleArg::Ntsc => "NTSC",
        ConsoleArg::Pal => "PAL",
    };
    let mut s = format!(
        "GPU time: {} CPU cycles, {} hblanks, {:.3} ms ({console} console)\n\
         stream: {} CPU cycles, {} of them waiting on the GPU\n",
        t.gpu_cycles,
        t.hblanks,
        millis(t.gpu_cycles),
        t.stream_cycles,
        t.stall_cycles,
    );
    for r in &t.reports {
        s += &format!(
            "report {:?} (line {}): {} hblanks, {} CPU cycles, {:.3} ms\n",
            r.name,
            r.line,
            r.hblanks,
            r.cycles,
            millis(r.cycles)
        );
    }
    s
}

/// `wobble replay --timing`: a (timed) command stream run through the bus model on the
/// chosen console; its times printed, then the image and raw VRAM written as without it.
fn run_timed(args: &ReplayArgs) -> Result<String, String> {
    let path = args
        .output
        .clone()
        .unwrap_or_else(|| input::default_output(&args.stream));
    let format = output::image_format(&path, args.format)?;
    input::not_the_input(&path, &args.stream)?;
    if let Some(raw) = &args.raw {
        if raw == &path && output::is_file_target(raw) {
            return Err(format!(
                "{}: given both as the image (-o) and the raw VRAM (--raw)",
                raw.display()
            ));
        }
        input::not_the_input(raw, &args.stream)?;
    }
    let image_out = output::open(&path)?;
    let raw_out = args.raw.as_deref().map(output::open).transpose()?;
    let mut gpu = gpu::Gpu::with_standard(args.console.into());
    gpu.set_texture_cache(!args.no_texture_cache);
    let text = input::read_text(
        &args.stream,
        "a timed command stream (.gpu text; docs/formats.md)",
    )?;
    let in_file = |e: gpu::command_stream::StreamError| format!("{}: {e}", args.stream.display());
    let stream = gpu::bus::parse(&text).map_err(in_file)?;
    let timed = gpu::bus::run(&mut gpu, &stream).map_err(in_file)?;
    let report = timing_text(&timed, args.console);
    // Standard output may carry the image or the raw VRAM: the times then go to stderr.
    if output::is_stdout(&path) || args.raw.as_deref().is_some_and(output::is_stdout) {
        eprint!("{report}");
    } else {
        print!("{report}");
    }
    if let Some(u) = timed.unfinished {
        eprintln!(
            "warning: {}: the stream ends {} (started at line {})",
            args.stream.display(),
            unfinished_text(u.pending),
            u.line
        );
    }
    let vram = gpu.vram().as_slice();
    let expand = Expand::from(args.expand);
    let img = match args.region.unwrap_or(Region::Vram) {
        Region::Vram => vram_image::vram_image(vram, expand),
        Region::Display => vram_image::display_image(vram, gpu.display_area(), expand),
    };
    let mut written = Vec::new();
    if let Some(mut raw) = raw_out {
        raw.write_all(&vram_image::raw_to_bytes(vram))
            .map_err(|e| format!("{}: {e}", raw.name()))?;
        written.push(raw.name().to_string());
        raw.commit()?;
    }
    written.push(image_out.name().to_string());
    output::write_image(img, image_out, format)?;
    for w in &written {
        eprintln!("wrote {w}");
    }
    Ok(format!("{}: replayed with timing", args.stream.display()))
}

/// Frames selected: from `start` to `end` (excluded), `None` for the end of the dump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// First frame.
    pub start: usize,
    /// One past the last frame, or the end of the dump.
    pub end: Option<usize>,
}

/// `N`, `A..B`, `A..=B` or `A..`.
pub fn parse_frames(text: &str) -> Result<FrameRange, String> {
    let err = || format!("--frames: expected N, A..B, A..=B or A.., got `{text}`");
    let num = |s: &str| s.trim().parse::<usize>().map_err(|_| err());
    let t = text.trim();
    let range = match t.split_once("..") {
        None => {
            let n = num(t)?;
            FrameRange {
                start: n,
                end: Some(n + 1),
            }
        }
        Some((a, b)) => {
            let start = num(a)?;
            let end = if let Some(b) = b.strip_prefix('=') {
                Some(num(b)?.checked_add(1).ok_or_else(err)?)
            } else if b.trim().is_empty() {
                None
            } else {
                Some(num(b)?)
            };
            FrameRange { start, end }
        }
    };
    if range.end.is_some_and(|e| e <= range.start) {
        return Err(format!("--frames: `{text}` selects no frame"));
    }
    Ok(range)
}

/// The largest display area any frame of `range` ends with (the GIF's canvas): the dump
/// replayed with its GP1 words only, which alone decide the display area.
fn largest_display(dump: &Dump, range: FrameRange, standard: VideoStandard) -> (u16, u16) {
    let mut gpu = gpu::Gpu::with_standard(standard);
    let (mut w, mut h) = (0u16, 0u16);
    let mut frame = 0usize;
    let mut take = |gpu: &gpu::Gpu, frame: usize| {
        if frame >= range.start && range.end.is_none_or(|e| frame < e) {
            let a = gpu.display_area();
            w = w.max(a.width);
            h = h.max(a.height);
        }
    };
    for item in dump.reader() {
        match item {
            Ok((_, Packet::Gp1(words))) => words.iter().for_each(|x| gpu.gp1(x)),
            Ok((_, Packet::VSync(_))) => {
                take(&gpu, frame);
                frame += 1;
            }
            Ok(_) => {}
            Err(_) => break,
        }
    }
    take(&gpu, frame);
    (w.max(1), h.max(1))
}

/// The picture of `region` the GPU shows now; `None` for an empty display area.
fn picture(gpu: &gpu::Gpu, region: Region, expand: Expand) -> Option<RgbImage> {
    match region {
        Region::Vram => Some(vram_image::vram_image(gpu.vram().as_slice(), expand)),
        Region::Display => displayed_image(gpu, expand),
    }
}

/// `img` at the top left of a black `w` x `h` canvas (cut to fit).
fn on_canvas(img: Option<&RgbImage>, w: u32, h: u32) -> RgbImage {
    let mut canvas = RgbImage::new(w, h);
    if let Some(img) = img {
        for (x, y, p) in img.enumerate_pixels() {
            if x < w && y < h {
                canvas.put_pixel(x, y, *p);
            }
        }
    }
    canvas
}

/// What a stream left unfinished, for the end-of-stream warning.
pub fn unfinished_text(pending: gpu::PendingInput) -> String {
    match pending {
        gpu::PendingInput::Packet {
            command,
            received,
            expected,
        } => format!("mid-packet: command {command:08X} has {received} of its {expected} words"),
        gpu::PendingInput::Transfer { remaining_words } => {
            format!("mid-transfer: a CPU-to-VRAM transfer still expects {remaining_words} words")
        }
        gpu::PendingInput::Polyline => {
            "inside a polyline with no terminator word (5xxx5xxxh)".to_string()
        }
    }
}

/// "zstd-compressed; " for a compressed input.
pub fn compressed(c: crate::compress::Compression) -> String {
    match c {
        crate::compress::Compression::None => String::new(),
        c => format!("{}-compressed; ", c.name()),
    }
}

/// Frames per second of the console's video: a VSync each field.
fn vsync_rate(standard: VideoStandard) -> u32 {
    match standard {
        VideoStandard::Ntsc => 60,
        VideoStandard::Pal => 50,
    }
}

/// A progress bar over `total` frames on a terminal, plain lines every 10% otherwise.
pub struct FrameProgress {
    bar: ProgressBar,
    plain: bool,
    total: u64,
    done: u64,
    verb: &'static str,
}

impl FrameProgress {
    /// Progress of `total` frames (hidden for fewer than 2).
    pub fn new(total: u64, verb: &'static str) -> Self {
        let terminal = std::io::stderr().is_terminal();
        let bar = if total > 1 && terminal {
            let bar = ProgressBar::new(total);
            if let Ok(style) = ProgressStyle::with_template(&format!(
                "{{bar:40}} {{pos}}/{{len}} frames {verb} {{eta}}"
            )) {
                bar.set_style(style);
            }
            bar
        } else {
            ProgressBar::hidden()
        };
        FrameProgress {
            bar,
            plain: total > 1 && !terminal,
            total,
            done: 0,
            verb,
        }
    }

    /// One more frame done.
    pub fn inc(&mut self) {
        self.done += 1;
        self.bar.inc(1);
        let step = (self.total / 10).max(1);
        if self.plain && (self.done.is_multiple_of(step) || self.done == self.total) {
            eprintln!("{} {}/{} frames", self.verb, self.done, self.total);
        }
    }

    /// Remove the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// Run `wobble replay`; returns the summary printed at the end.
pub fn run(args: &ReplayArgs) -> Result<String, String> {
    if args.timing {
        return run_timed(args);
    }
    let range = match (&args.frames, args.frame) {
        (Some(text), _) => parse_frames(text)?,
        (None, Some(n)) => FrameRange {
            start: n,
            end: Some(n + 1),
        },
        (None, None) => FrameRange {
            start: 0,
            end: None,
        },
    };
    let image_path = match (&args.output, args.list) {
        (Some(p), _) => Some(p.clone()),
        (None, true) => None,
        (None, false) => Some(input::default_output(&args.stream)),
    };
    let format = match &image_path {
        Some(p) => Some(output::image_format(p, args.format)?),
        None if args.format.is_some() => {
            return Err("--format names the format of -o, which is not given".into());
        }
        None => None,
    };
    let gif = format == Some(image::ImageFormat::Gif);
    if let Some(p) = &image_path {
        input::not_the_input(p, &args.stream)?;
    }
    if let Some(raw) = &args.raw {
        if image_path.as_ref() == Some(raw) && output::is_file_target(raw) {
            return Err(format!(
                "{}: given both as the image (-o) and the raw VRAM (--raw)",
                raw.display()
            ));
        }
        input::not_the_input(raw, &args.stream)?;
    }
    let image_file = image_path.as_deref().map(output::open).transpose()?;
    let raw_file = args.raw.as_deref().map(output::open).transpose()?;
    let png_dir = args.png_dir.as_deref().map(OutputDir::open).transpose()?;

    let input = gpu_input::load(&args.stream)?;
    let dump = &input.dump;
    let name = args.stream.display().to_string();
    let summary = dump
        .summary(&mut |_| {})
        .map_err(|e| format!("{name}: {e}"))?;
    if input.kind == InputKind::Dump {
        println!("{name}: {}{summary}", compressed(input.compression));
        if let Some(w) = summary.version_warning() {
            eprintln!("warning: {name}: {w}");
        }
    }
    let total = summary.frames.len();
    if range.start > 0 && range.start >= total {
        return Err(format!(
            "{name}: frame {} does not exist: it has {total} frame(s){}",
            range.start,
            if total > 0 {
                format!(" (0..={})", total - 1)
            } else {
                String::new()
            }
        ));
    }
    let run_to = range.end.map_or(total, |e| e.min(total));
    let region = args.region.unwrap_or(match input.kind {
        InputKind::Dump => Region::Display,
        InputKind::Text => Region::Vram,
    });
    let expand = Expand::from(args.expand);
    let standard = summary.video_standard();

    // The animation: every selected frame, on a canvas the size of the largest.
    let (mut gif_file, image_file) = if gif {
        (image_file, None)
    } else {
        (None, image_file)
    };
    let (cw, ch) = match region {
        Region::Vram => (1024, 512),
        Region::Display => largest_display(dump, range, standard),
    };
    let mut gif_writer = match &mut gif_file {
        Some(f) => Some(GifWriter::new(f, cw, ch, vsync_rate(standard))?),
        None => None,
    };

    let mut player = Player::new(dump, standard);
    player.set_texture_cache(!args.no_texture_cache);
    let mut progress = FrameProgress::new(run_to as u64, "replayed");
    let mut selected = 0usize;
    for i in 0..run_to {
        let Some(r) = player.run_frame().map_err(|e| format!("{name}: {e}"))? else {
            break;
        };
        progress.inc();
        if i < range.start {
            continue;
        }
        selected += 1;
        if args.list {
            progress.bar.suspend(|| println!("{r}"));
        }
        if gif_writer.is_some() || png_dir.is_some() {
            let img = picture(player.gpu(), region, expand);
            if let Some(dir) = &png_dir {
                let img = img.as_ref().ok_or_else(|| empty_display(i, player.gpu()))?;
                let path = dir.path().join(format!("frame{i:05}.png"));
                img.save_with_format(&path, image::ImageFormat::Png)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
            }
            if let Some(g) = gif_writer.as_mut() {
                let canvas = on_canvas(img.as_ref(), u32::from(cw), u32::from(ch));
                g.frame(&image_rgb15(&canvas))?;
            }
        }
    }
    progress.finish();
    if run_to == total
        && let Some(u) = player.unfinished()
    {
        let place = match input.kind {
            InputKind::Text => format!("line {}", u.line),
            InputKind::Dump => format!("packet {}", u.line),
        };
        eprintln!(
            "warning: {name}: the {} ends {} (started at {place})",
            match input.kind {
                InputKind::Text => "stream",
                InputKind::Dump => "dump",
            },
            unfinished_text(u.pending),
        );
    }

    let mut written = Vec::new();
    gif_writer.map(GifWriter::finish).transpose()?;
    if let Some(file) = gif_file {
        let name = file.name().to_string();
        file.commit()?;
        written.push(format!("{name} ({selected} frames)"));
    }
    if let (Some(file), Some(format)) = (image_file, format) {
        let name = file.name().to_string();
        let img = picture(player.gpu(), region, expand)
            .ok_or_else(|| empty_display(run_to.saturating_sub(1), player.gpu()))?;
        output::write_image(img, file, format)?;
        written.push(name);
    }
    if let Some(mut raw) = raw_file {
        raw.write_all(&vram_image::raw_to_bytes(player.gpu().vram().as_slice()))
            .map_err(|e| format!("{}: {e}", raw.name()))?;
        let name = raw.name().to_string();
        raw.commit()?;
        written.push(name);
    }
    if let Some(dir) = png_dir {
        let target = dir.target().to_path_buf();
        dir.commit("")?;
        written.push(format!("{} ({selected} frames)", target.display()));
    }
    for w in &written {
        eprintln!("wrote {w}");
    }
    let frames = match (selected, range.start) {
        (0, _) => "no frame".to_string(),
        (1, s) => format!("frame {s}"),
        (n, s) => format!("frames {s}..={}", s + n - 1),
    };
    Ok(format!("{name}: replayed {frames} of {total}"))
}

fn empty_display(frame: usize, gpu: &gpu::Gpu) -> String {
    let a = gpu.display_area();
    format!(
        "frame {frame} shows nothing: its display area is {}x{} (the GP1(06h)/(07h) ranges); \
         use --region vram",
        a.width, a.height
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_ranges() {
        let r = |s, e| FrameRange { start: s, end: e };
        assert_eq!(parse_frames("3"), Ok(r(3, Some(4))));
        assert_eq!(parse_frames("2..5"), Ok(r(2, Some(5))));
        assert_eq!(parse_frames("2..=5"), Ok(r(2, Some(6))));
        assert_eq!(parse_frames(" 7.. "), Ok(r(7, None)));
        for bad in ["", "a", "5..5", "5..2", "..3", "1..=x", "-1"] {
            assert!(parse_frames(bad).is_err(), "{bad}");
        }
    }
}
