//! `wobble inspect`: the draw-by-draw report of a command stream (docs/inspect.md).

use std::path::PathBuf;
use wobble::inspect::{InspectOptions, inspect_stream, summary_line};

/// Arguments of `wobble inspect`.
#[derive(Debug, Clone, clap::Args)]
pub struct InspectArgs {
    /// Command stream (.gpu text, docs/formats.md).
    pub stream: PathBuf,
    /// Output directory (created; report files already in it are overwritten).
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
    let summary = inspect_stream(&args.stream, &args.output, options)?;
    Ok(summary_line(&summary, &args.output))
}
