//! `wobble inspect`: the draw-by-draw report of a command stream, or of one frame of a GPU
//! dump with the VRAM state entering it (docs/inspect.md).

use crate::gpu_input::{self, InputKind};
use crate::output;
use crate::replay::{FrameProgress, compressed};
use std::io::IsTerminal;
use std::path::PathBuf;
use wobble::gpu_dump::Player;
use wobble::inspect::{InspectOptions, summary_line, write_report_with_progress};

/// Arguments of `wobble inspect`.
#[derive(Debug, Clone, clap::Args)]
pub struct InspectArgs {
    /// Command stream (.gpu text) or GPU dump (.psxgpu, .psxgpu.zst, .psxgpu.xz);
    /// docs/formats.md.
    pub stream: PathBuf,
    /// Output directory: created, or an existing directory whose report files are replaced
    /// (its other files are left alone). The report is moved into place when complete.
    #[arg(short, long, default_value = "inspect-report")]
    pub output: PathBuf,
    /// Commands that get a before/after image (the first this many that change VRAM);
    /// later ones are listed with their counts but no image.
    #[arg(long, default_value_t = InspectOptions::default().max_images)]
    pub max_images: usize,
    /// Inspect frame N only (0-based; frames end at VSync packets), replaying the frames
    /// before it first. Without it, the whole input.
    #[arg(long)]
    pub frame: Option<usize>,
}

/// Run `wobble inspect`; returns the summary line.
pub fn run(args: &InspectArgs) -> Result<String, String> {
    let options = InspectOptions {
        max_images: args.max_images,
        ..InspectOptions::default()
    };
    let out = output::OutputDir::open(&args.output)?;
    let file_name = args.stream.file_name().map_or_else(
        || "stream".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let name = args.stream.display().to_string();
    let input = gpu_input::load(&args.stream)?;
    let dump = &input.dump;
    let summary = dump
        .summary(&mut |_| {})
        .map_err(|e| format!("{name}: {e}"))?;
    if input.kind == InputKind::Dump {
        eprintln!("{name}: {}{summary}", compressed(input.compression));
    }
    let total = summary.frames.len();
    let mut player = Player::new(dump, summary.video_standard());
    let (commands, title) = match args.frame {
        Some(n) => {
            if n >= total {
                return Err(format!(
                    "{name}: frame {n} does not exist: it has {total} frame(s)"
                ));
            }
            let mut progress = FrameProgress::new(n as u64, "replayed");
            player.skip_to(n, &mut |_| progress.inc())?;
            progress.finish();
            let frame = player
                .take_frame_commands()
                .map_err(|e| format!("{name}: {e}"))?
                .ok_or_else(|| format!("{name}: frame {n} is empty"))?;
            if frame.read_words > 0 {
                eprintln!(
                    "note: frame {n} reads {} GPUREAD words (discard/readback packets); they \
                     change no VRAM and are not listed",
                    frame.read_words
                );
            }
            let game = summary
                .game_id
                .as_deref()
                .map(|g| format!(" ({g})"))
                .unwrap_or_default();
            (
                frame.commands,
                format!("{file_name}{game}, frame {n} of {total}"),
            )
        }
        None => {
            let mut commands = Vec::new();
            while let Some(f) = player
                .take_frame_commands()
                .map_err(|e| format!("{name}: {e}"))?
            {
                commands.extend(f.commands);
            }
            if total > 1 {
                eprintln!(
                    "note: all {total} frames as one list (VSyncs skipped); --frame N inspects one"
                );
            }
            (commands, file_name)
        }
    };
    let mut gpu = player.into_gpu();
    let mut progress = Progress::new();
    let summary = write_report_with_progress(
        &mut gpu,
        &commands,
        out.path(),
        &title,
        options,
        None,
        None,
        &mut |done, total| progress.show(done, total),
    )?;
    progress.finish();
    out.commit("index.html")?;
    Ok(summary_line(&summary, &args.output))
}

/// Progress of a report: a bar on a terminal, otherwise a line every 10% of the stream
/// (streams of 10,000 lines and more).
struct Progress {
    bar: Option<indicatif::ProgressBar>,
    terminal: bool,
    last_tenth: Option<usize>,
}

impl Progress {
    fn new() -> Self {
        Self {
            bar: None,
            terminal: std::io::stderr().is_terminal(),
            last_tenth: None,
        }
    }

    fn show(&mut self, done: usize, total: usize) {
        if total < 10_000 {
            return;
        }
        if self.terminal {
            let bar = self.bar.get_or_insert_with(|| {
                let bar = indicatif::ProgressBar::new(total as u64);
                if let Ok(style) =
                    indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} lines {eta}")
                {
                    bar.set_style(style);
                }
                bar
            });
            bar.set_position(done as u64);
        } else {
            let tenth = done.saturating_mul(10) / total;
            if self.last_tenth != Some(tenth) {
                self.last_tenth = Some(tenth);
                eprintln!("inspect: {done}/{total} lines");
            }
        }
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
