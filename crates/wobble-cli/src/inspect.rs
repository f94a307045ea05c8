//! `wobble inspect`: the draw-by-draw report of a command stream (docs/inspect.md).

use crate::{input, output};
use std::io::IsTerminal;
use std::path::PathBuf;
use wobble::inspect::{InspectOptions, summary_line, write_report_with_progress};

/// Arguments of `wobble inspect`.
#[derive(Debug, Clone, clap::Args)]
pub struct InspectArgs {
    /// Command stream (.gpu text, docs/formats.md).
    pub stream: PathBuf,
    /// Output directory: created, or an existing directory whose report files are replaced
    /// (its other files are left alone). The report is moved into place when complete.
    #[arg(short, long, default_value = "inspect-report")]
    pub output: PathBuf,
    /// Commands that get a before/after image (the first this many that change VRAM);
    /// later ones are listed with their counts but no image.
    #[arg(long, default_value_t = InspectOptions::default().max_images)]
    pub max_images: usize,
}

/// Run `wobble inspect`; returns the summary line.
pub fn run(args: &InspectArgs) -> Result<String, String> {
    let options = InspectOptions {
        max_images: args.max_images,
        ..InspectOptions::default()
    };
    let out = output::OutputDir::open(&args.output)?;
    let commands = input::read_command_stream(&args.stream)?;
    let title = args.stream.file_name().map_or_else(
        || "stream".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut gpu = gpu::Gpu::new();
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
