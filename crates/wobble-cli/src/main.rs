//! `wobble`: render scenes the PS1 way, replay GTE vectors, GPU command streams and GPU dumps,
//! inspect them draw by draw, convert them, dump VRAM, and measure the accuracy trade.

#![forbid(unsafe_code)]
#![deny(missing_docs, rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand, ValueEnum};
use gpu::DisplayArea;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use wobble::vram_image::{self, Expand};

mod compare;
mod compress;
mod convert;
mod counts;
mod gif;
mod gpu_input;
mod input;
mod inspect;
mod output;
mod render;
mod replay;
mod zoom;

use output::FormatArg;

#[derive(Parser)]
#[command(
    name = "wobble",
    version,
    about = "PS1 GTE + GPU emulation: render a scene, gte replay test vectors, replay a GPU \
             command stream or dump, inspect one draw by draw, convert streams and dumps, \
             dump VRAM, trade: measure the accuracy trade",
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
    /// Run a GP0/GP1 command stream or a GPU dump (.psxgpu) on a fresh GPU frame by frame;
    /// write VRAM or the displayed frames (an image, an animated GIF) and/or raw VRAM.
    Replay(replay::ReplayArgs),
    /// Step through a command stream, or one frame of a GPU dump, draw by draw: writes an
    /// HTML report (docs/inspect.md).
    Inspect(inspect::InspectArgs),
    /// Convert between command-stream text (.gpu) and GPU dumps (.psxgpu, .psxgpu.zst,
    /// .psxgpu.xz) in either dialect.
    Convert(convert::ConvertArgs),
    /// Convert raw VRAM (or the VRAM a command stream or GPU dump leaves) to an image: whole
    /// VRAM, a display area, or a texture page.
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

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
enum Region {
    /// The whole 1024x512 VRAM.
    Vram,
    /// The display area.
    Display,
}

/// 5-bit to 8-bit conversion, as `--expand` takes it.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
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
struct DumpArgs {
    /// Raw VRAM file (1024*512 little-endian u16), or a command stream or GPU dump whose
    /// VRAM is taken after replaying it (to --frame N, or to its end).
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
    /// --region display, or for a stream or dump the area its GP1 state selects); implies
    /// --region display.
    #[arg(long, conflicts_with = "texpage")]
    display: Option<String>,
    /// For a command stream or GPU dump: the VRAM at the end of frame N (0-based).
    #[arg(long)]
    frame: Option<usize>,
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

/// The VRAM `wobble dump` converts: a raw VRAM file, or what a command stream or GPU dump
/// leaves at the end of frame `frame` (or its end), with the display area it selects.
fn dump_input(path: &Path, frame: Option<usize>) -> Result<(Vec<u16>, Option<DisplayArea>)> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    // Raw VRAM: neither a dump (compressed or not) nor text, or exactly VRAM's size.
    let text = !bytes.contains(&0) && std::str::from_utf8(&bytes).is_ok();
    let raw = compress::Compression::sniff(&bytes) == compress::Compression::None
        && !bytes.starts_with(gpu::dump::MAGIC_PREFIX)
        && (bytes.len() == gpu::VRAM_LEN * 2 || !text);
    if raw {
        if frame.is_some() {
            return Err("--frame applies to a command stream or GPU dump, not raw VRAM".into());
        }
        let vram =
            vram_image::raw_from_bytes(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        return Ok((vram, None));
    }
    drop(bytes);
    let loaded = gpu_input::load(path)?;
    let name = path.display().to_string();
    let summary = loaded
        .dump
        .summary(&mut |_| {})
        .map_err(|e| format!("{name}: {e}"))?;
    let mut player = wobble::gpu_dump::Player::new(&loaded.dump, summary.video_standard());
    let total = summary.frames.len();
    let end = match frame {
        Some(n) if n >= total => {
            return Err(format!(
                "{name}: frame {n} does not exist: it has {total} frame(s)"
            ));
        }
        Some(n) => n + 1,
        None => total,
    };
    let mut progress = replay::FrameProgress::new(end as u64, "replayed");
    player.skip_to(end, &mut |_| progress.inc())?;
    progress.finish();
    let gpu = player.into_gpu();
    Ok((gpu.vram().as_slice().to_vec(), Some(gpu.display_area())))
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
    let area = match (region, &args.display) {
        (Region::Display, Some(text)) => Some(parse_display(text)?),
        (Region::Display, None) => None,
        (Region::Vram, _) => None,
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
    let (vram, shown) = dump_input(&args.raw, args.frame)?;
    let area = match (region, area, shown) {
        (Region::Display, Some(a), _) => Some(a),
        (Region::Display, None, Some(a)) => Some(a),
        (Region::Display, None, None) => Some(parse_display("0,0,320x240")?),
        (Region::Vram, _, _) => None,
    };
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
        Command::Replay(args) => replay::run(args).map(|summary| {
            output::say(&summary);
            true
        }),
        Command::Convert(args) => convert::run(args).map(|summary| {
            output::say(&summary);
            true
        }),
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
