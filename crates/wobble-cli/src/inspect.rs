//! `wobble inspect`: the draw-by-draw report of a command stream (docs/inspect.md).

use crate::{input, output};
use std::path::PathBuf;
use wobble::inspect::{InspectOptions, summary_line, write_report};

/// Arguments of `wobble inspect`.
#[derive(Debug, Clone, clap::Args)]
pub struct InspectArgs {
    /// Command stream (.gpu text, docs/formats.md).
    pub stream: PathBuf,
    /// Output directory: created, or an existing directory whose report files are replaced
    /// (its other files are left alone). The report is moved into place when complete.
    #[arg(short, long, default_value = "inspect-report")]
    pub output: PathBuf,
    /// Commands that get a before/after image; later ones are listed without.
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
    let summary = write_report(&mut gpu, &commands, out.path(), &title, options, None, None)?;
    out.commit("index.html")?;
    Ok(summary_line(&summary, &args.output))
}
