//! `wobble`: render scenes the PS1 way, replay GTE vectors and GPU command streams, inspect a
//! stream draw by draw, dump VRAM, and measure the accuracy trade.

#![forbid(unsafe_code)]
#![deny(missing_docs, rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand, ValueEnum};
use gpu::{CPU_CLOCK_HZ, DisplayArea, Gpu, VideoStandard, command_stream};
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use wobble::vram_image::{self, Expand};

mod compare;
mod counts;
mod gif;
mod input;
mod inspect;
mod output;
mod render;
mod zoom;

use output::FormatArg;

#[derive(Parser)]
#[command(
    name = "wobble",
    version,
    about = "PS1 GTE + GPU emulation: render a scene, gte replay test vectors, replay a GPU \
             command stream, inspect one draw by draw, dump raw VRAM, trade: measure the \
             accuracy trade",
    after_help = "Outputs: `-o -` writes to standard output (with --format for images); a \
                  FIFO or device is written through, a regular file is replaced only when \
                  complete (docs/formats.md, \"Output files\")."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene (the built-in default scene without an argument) through GTE ->
    /// ordering table -> GPU.
    Render(render::RenderArgs),
    /// GTE tools: replay JSON-lines test vectors.
    Gte {
        #[command(subcommand)]
        command: GteCommand,
    },
    /// Run a GP0/GP1 command stream on a fresh GPU and write VRAM as an image and/or raw.
    Replay(ReplayArgs),
    /// Step through a GP0/GP1 command stream draw by draw: writes an HTML report
    /// (docs/inspect.md).
    Inspect(inspect::InspectArgs),
    /// Convert a raw VRAM file to an image: whole VRAM, a display area, or a texture page.
    Dump(DumpArgs),
    /// Measure what each accuracy knob costs in time and in error against an f64 reference
    /// renderer; writes DIR/trade.md and images under DIR/trade/.
    Trade(TradeArgs),
}

#[derive(clap::Args)]
struct TradeArgs {
    /// Scene file (TOML); the built-in default scene when omitted.
    scene: Option<PathBuf>,
    /// Output directory: trade.md and trade/ are written into it (other files in it are left
    /// alone). `--out` is the old spelling.
    #[arg(short, long, alias = "out", default_value = "trade-report")]
    output: PathBuf,
    /// Consecutive frames measured (2..=600).
    #[arg(long, default_value_t = 24)]
    frames: u32,
    /// Timing repetitions; the median is reported (1..=50).
    #[arg(long, default_value_t = 5)]
    repeats: u32,
    /// Divide-stability sweep over every SZ3 and every Nth H; 1 sweeps all 2^32 pairs.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u16).range(1..))]
    sweep_step: u16,
}

#[derive(Subcommand)]
enum GteCommand {
    /// Replay a JSON-lines file of GTE vectors and compare every register.
    Replay {
        /// Vector file (schema: docs/formats.md).
        file: PathBuf,
        /// Print the computed registers as JSON lines instead of comparing.
        #[arg(long)]
        emit: bool,
    },
}

#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum Region {
    /// The whole 1024x512 VRAM.
    Vram,
    /// The display area.
    Display,
}

/// 5-bit to 8-bit conversion, as `--expand` takes it.
#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum ExpandArg {
    /// `c << 3 | c >> 2`: 31 maps to 255.
    Replicate,
    /// `c << 3`: what console capture tools wrote (31 maps to 248); the fixtures' capture
    /// PNGs are reproduced with it.
    Shift,
}

impl From<ExpandArg> for Expand {
    fn from(e: ExpandArg) -> Expand {
        match e {
            ExpandArg::Replicate => Expand::Replicate,
            ExpandArg::Shift => Expand::Shift,
        }
    }
}

#[derive(clap::Args)]
struct ReplayArgs {
    /// Command stream (.gpu text, docs/formats.md).
    stream: PathBuf,
    /// Image output, format by extension or --format; `-` is standard output (default: the
    /// stream's file name with .png, in the current directory).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Image format of -o (needed for `-o -`).
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
    /// Also write the raw VRAM (1024*512 little-endian u16); `-` is standard output.
    #[arg(long)]
    raw: Option<PathBuf>,
    /// What to write as the image.
    #[arg(long, value_enum, default_value_t = Region::Vram)]
    region: Region,
    /// 5-bit to 8-bit conversion (`shift` reproduces the fixtures' console captures).
    #[arg(long, value_enum, default_value_t = ExpandArg::Replicate)]
    expand: ExpandArg,
    /// Also print the time the stream takes on a console: CPU cycles, hblanks (what timer 1
    /// counts) and milliseconds until the GPU has finished, and each `report` line. Accepts
    /// timed streams (docs/formats.md, "Timed streams").
    #[arg(long)]
    timing: bool,
    /// The console whose clocks time the stream.
    #[arg(long, value_enum, default_value_t = ConsoleArg::Ntsc, requires = "timing")]
    console: ConsoleArg,
}

/// A console region, as `--console` takes it.
#[derive(Clone, Copy, ValueEnum, PartialEq, Eq)]
enum ConsoleArg {
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

#[derive(clap::Args)]
struct DumpArgs {
    /// Raw VRAM file (1024*512 little-endian u16).
    raw: PathBuf,
    /// Image output, format by extension or --format; `-` is standard output (default: the
    /// raw file's name with .png, in the current directory: x.vram.bin -> x.png).
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Image format of -o (needed for `-o -`).
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
    /// What to write (default vram; display when --display is given).
    #[arg(long, value_enum, conflicts_with = "texpage")]
    region: Option<Region>,
    /// Display area X,Y,WxH or X,Y,WxH,24 for 24-bit colour (default 0,0,320x240 with
    /// --region display); implies --region display.
    #[arg(long, conflicts_with = "texpage")]
    display: Option<String>,
    /// View a texture page at VRAM X,Y (X multiple of 64, Y 0 or 256 on hardware).
    #[arg(long)]
    texpage: Option<String>,
    /// Texture depth for --texpage: 4, 8 or 15 (default 4).
    #[arg(long, requires = "texpage", value_parser = parse_depth)]
    depth: Option<u8>,
    /// CLUT position X,Y for 4/8-bit pages (default 0,0).
    #[arg(long, requires = "texpage")]
    clut: Option<String>,
    /// 5-bit to 8-bit conversion.
    #[arg(long, value_enum, default_value_t = ExpandArg::Replicate)]
    expand: ExpandArg,
}

type Result<T> = std::result::Result<T, String>;

/// `--depth`: the texture page depths, 4, 8 or 15 bits.
fn parse_depth(text: &str) -> Result<u8> {
    match text.trim() {
        "4" => Ok(4),
        "8" => Ok(8),
        "15" => Ok(15),
        _ => Err(format!("expected 4, 8 or 15, got `{text}`")),
    }
}

fn parse_pair(text: &str, what: &str) -> Result<(usize, usize)> {
    let mut it = text.split(',').map(|s| s.trim().parse::<usize>());
    match (it.next(), it.next(), it.next()) {
        (Some(Ok(a)), Some(Ok(b)), None) if a < 1024 && b < 512 => Ok((a, b)),
        _ => Err(format!(
            "{what}: expected X,Y with X < 1024 and Y < 512, got `{text}`"
        )),
    }
}

fn parse_display(text: &str) -> Result<DisplayArea> {
    let err = || format!("--display: expected X,Y,WxH[,24], got `{text}`");
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() < 3 || parts.len() > 4 {
        return Err(err());
    }
    let (x, y) = parse_pair(&format!("{},{}", parts[0], parts[1]), "--display")?;
    let (w, h) = parts[2].split_once('x').ok_or_else(err)?;
    let w: u64 = w.trim().parse().map_err(|_| err())?;
    let h: u64 = h.trim().parse().map_err(|_| err())?;
    if w == 0 || h == 0 || w > 1024 || h > 512 {
        return Err(format!(
            "--display: size {w}x{h} outside 1..=1024 x 1..=512"
        ));
    }
    let (w, h) = (w as u16, h as u16);
    let color_24bit = match parts.get(3) {
        None => false,
        Some(&"24") => true,
        Some(_) => return Err(err()),
    };
    Ok(DisplayArea {
        x: x as u16,
        y: y as u16,
        width: w,
        height: h,
        color_24bit,
    })
}

fn gte_replay(file: &Path, emit: bool) -> Result<bool> {
    let what = "a GTE vector file (JSON lines, one vector object a line; docs/formats.md)";
    let text = input::read_text(file, what)?;
    let outcome =
        wobble::gte_vectors::replay(&text, emit).map_err(|e| format!("{}: {e}", file.display()))?;
    for e in &outcome.errors {
        eprintln!("{}: {e}", file.display());
    }
    for line in &outcome.output {
        println!("{line}");
    }
    let summary = format!("{} passed, {} failed", outcome.passed, outcome.failed);
    if emit {
        eprintln!("{summary}");
    } else {
        println!("{summary}");
    }
    Ok(outcome.failed == 0)
}

/// What a stream left unfinished, for the end-of-stream warning.
fn unfinished_text(pending: gpu::PendingInput) -> String {
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

/// Milliseconds in `cycles` CPU cycles.
fn millis(cycles: u64) -> f64 {
    cycles as f64 * 1000.0 / CPU_CLOCK_HZ as f64
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

fn replay(args: &ReplayArgs) -> Result<()> {
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
    let mut gpu = Gpu::with_standard(args.console.into());
    let unfinished = if args.timing {
        let text = input::read_text(&args.stream, input::COMMAND_STREAM)?;
        let in_file = |e: command_stream::StreamError| format!("{}: {e}", args.stream.display());
        let stream = gpu::bus::parse(&text).map_err(in_file)?;
        let timed = gpu::bus::run(&mut gpu, &stream).map_err(in_file)?;
        let report = timing_text(&timed, args.console);
        // Standard output may carry the image or the raw VRAM: the times then go to stderr.
        if output::is_stdout(&path) || args.raw.as_deref().is_some_and(output::is_stdout) {
            eprint!("{report}");
        } else {
            print!("{report}");
        }
        timed.unfinished
    } else {
        let commands = input::read_command_stream(&args.stream)?;
        command_stream::run(&mut gpu, &commands).unfinished
    };
    if let Some(u) = unfinished {
        eprintln!(
            "warning: {}: the stream ends {} (started at line {})",
            args.stream.display(),
            unfinished_text(u.pending),
            u.line
        );
    }
    let vram = gpu.vram().as_slice();
    let expand = Expand::from(args.expand);
    let img = match args.region {
        Region::Vram => vram_image::vram_image(vram, expand),
        Region::Display => vram_image::display_image(vram, gpu.display_area(), expand),
    };
    if let Some(mut raw) = raw_out {
        raw.write_all(&vram_image::raw_to_bytes(vram))
            .map_err(|e| format!("{}: {e}", raw.name()))?;
        let name = raw.name().to_string();
        raw.commit()?;
        eprintln!("wrote {name}");
    }
    let name = image_out.name().to_string();
    output::write_image(img, image_out, format)?;
    eprintln!("wrote {name}");
    Ok(())
}

fn dump(args: &DumpArgs) -> Result<()> {
    let path = args
        .output
        .clone()
        .unwrap_or_else(|| input::default_output(&args.raw));
    let format = output::image_format(&path, args.format)?;
    // --display names a display area: it implies --region display.
    let region = match (args.region, &args.display) {
        (Some(Region::Vram), Some(_)) => {
            return Err("--display names a display area, but --region vram was given".into());
        }
        (Some(r), _) => r,
        (None, Some(_)) => Region::Display,
        (None, None) => Region::Vram,
    };
    let area = match region {
        Region::Display => Some(parse_display(
            args.display.as_deref().unwrap_or("0,0,320x240"),
        )?),
        Region::Vram => None,
    };
    let page = match &args.texpage {
        Some(page) => {
            let (px, py) = parse_pair(page, "--texpage")?;
            let depth = match args.depth.unwrap_or(4) {
                4 => gpu::TextureDepth::Clut4,
                8 => gpu::TextureDepth::Clut8,
                15 => gpu::TextureDepth::Direct15,
                d => return Err(format!("--depth: expected 4, 8 or 15, got {d}")),
            };
            let clut = parse_pair(args.clut.as_deref().unwrap_or("0,0"), "--clut")?;
            Some((px, py, depth, clut))
        }
        None => None,
    };
    input::not_the_input(&path, &args.raw)?;
    let out = output::open(&path)?;
    let vram = input::read_raw_vram(&args.raw)?;
    let expand = Expand::from(args.expand);
    let name = out.name().to_string();
    if let Some((px, py, depth, clut)) = page {
        let img = vram_image::texture_page_image(&vram, px, py, depth, clut, expand);
        output::write_image(img, out, format)?;
    } else {
        let img = match area {
            None => vram_image::vram_image(&vram, expand),
            Some(area) => vram_image::display_image(&vram, area, expand),
        };
        output::write_image(img, out, format)?;
    }
    eprintln!("wrote {name}");
    Ok(())
}

fn trade(args: &TradeArgs) -> Result<()> {
    if !(2..=600).contains(&args.frames) || !(1..=50).contains(&args.repeats) {
        return Err("--frames must be 2..=600 and --repeats 1..=50".into());
    }
    let (scene, name) = match &args.scene {
        Some(p) => (
            wobble::scene::Scene::load(p).map_err(|e| e.to_string())?,
            p.display().to_string(),
        ),
        None => (
            wobble::scene::Scene::default_scene(),
            "the default scene".to_string(),
        ),
    };
    let settings = wobble::trade::TradeSettings {
        frames: args.frames,
        repeats: args.repeats,
        sweep_step: args.sweep_step as usize,
    };
    let out = output::OutputDir::open(&args.output)?;
    let mut progress = TradeProgressView::new();
    let rows = wobble::trade::write_report(&scene, &name, settings, out.path(), &mut |step| {
        progress.show(step)
    })
    .map_err(|e| e.to_string())?;
    out.commit("trade.md")?;
    for r in &rows {
        println!(
            "{:<50} {:>8.3} ms {:>6.2}x  texel error mean {:.3} max {:.2}  jitter {:.3} px",
            r.name, r.frame_ms, r.ratio, r.texel_mean, r.texel_max, r.jitter
        );
    }
    println!("wrote {}", args.output.join("trade.md").display());
    Ok(())
}

/// How `wobble trade` shows its progress: a bar for the divide sweep on a terminal, a plain
/// line every 10% of it otherwise, and one line per other step.
struct TradeProgressView {
    terminal: bool,
    bar: Option<indicatif::ProgressBar>,
    last_tenth: Option<u64>,
}

impl TradeProgressView {
    fn new() -> Self {
        Self {
            terminal: std::io::stderr().is_terminal(),
            bar: None,
            last_tenth: None,
        }
    }

    fn show(&mut self, step: wobble::trade::TradeProgress) {
        let wobble::trade::TradeProgress::Sweep { done, total } = step else {
            eprintln!("{step}");
            return;
        };
        if self.terminal {
            let bar = self.bar.get_or_insert_with(|| {
                let bar = indicatif::ProgressBar::new(total);
                if let Ok(style) =
                    indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} sweep rows {eta}")
                {
                    bar.set_style(style);
                }
                bar
            });
            bar.set_position(done);
            if done >= total {
                bar.finish_and_clear();
            }
        } else {
            let tenth = done.saturating_mul(10) / total.max(1);
            if self.last_tenth != Some(tenth) {
                self.last_tenth = Some(tenth);
                eprintln!("{step}");
            }
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(e) = output::remove_unfinished_on_interrupt() {
        eprintln!("warning: {e}");
    }
    let result = match &cli.command {
        Command::Render(args) => render::run(args).map(|summary| {
            output::say(&summary);
            true
        }),
        Command::Gte {
            command: GteCommand::Replay { file, emit },
        } => gte_replay(file, *emit),
        Command::Replay(args) => replay(args).map(|()| true),
        Command::Dump(args) => dump(args).map(|()| true),
        Command::Inspect(args) => inspect::run(args).map(|summary| {
            output::say(&summary);
            true
        }),
        Command::Trade(args) => trade(args).map(|()| true),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
