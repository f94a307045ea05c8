//! `wobble convert`: between command-stream text (`.gpu`) and GPU dumps (`.psxgpu`,
//! `.psxgpu.zst`, `.psxgpu.xz`) in either dialect, keeping every packet (docs/formats.md,
//! "Converting").

use crate::gpu_input::{self, InputKind, OutputFormat};
use crate::{input, output};
use gpu::dump::{Dialect, Writer};
use std::io::Write;
use std::path::PathBuf;

/// The dialect of a written dump, as `--dialect` takes it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DialectArg {
    /// GPUDUMP.md: magic PSXGPUDUMPv1r1 (16 bytes), GPU versions numbered from 1.
    Spec,
    /// DuckStation's: magic PSXGPUDUMPv1 (14 bytes), GPU versions numbered from 0.
    Duckstation,
}

impl From<DialectArg> for Dialect {
    fn from(d: DialectArg) -> Dialect {
        match d {
            DialectArg::Spec => Dialect::Spec,
            DialectArg::Duckstation => Dialect::DuckStation,
        }
    }
}

/// Arguments of `wobble convert`.
#[derive(Debug, Clone, clap::Args)]
pub struct ConvertArgs {
    /// Input: command stream (.gpu text) or GPU dump (.psxgpu, .psxgpu.zst, .psxgpu.xz).
    pub input: PathBuf,
    /// Output, its format by its name: .gpu (text), .psxgpu, .psxgpu.zst or .psxgpu.xz.
    pub output: PathBuf,
    /// Dialect of a written dump (default: the input dump's; the spec's for text).
    #[arg(long, value_enum)]
    pub dialect: Option<DialectArg>,
}

/// Run `wobble convert`; returns the summary line.
pub fn run(args: &ConvertArgs) -> Result<String, String> {
    let format = gpu_input::output_format(&args.output)?;
    if format == OutputFormat::Text && args.dialect.is_some() {
        return Err("--dialect applies to a dump output (.psxgpu...), not to .gpu text".into());
    }
    input::not_the_input(&args.output, &args.input)?;
    let mut out = output::open(&args.output)?;
    let input = gpu_input::load(&args.input)?;
    let name = args.input.display().to_string();
    let at = |e: &dyn std::fmt::Display| format!("{name}: {e}");
    let summary = input.dump.summary(&mut |_| {}).map_err(|e| at(&e))?;
    let written = match format {
        OutputFormat::Text => {
            let mut text = String::new();
            gpu::command_stream::from_dump(input.dump.reader(), &mut text).map_err(|e| at(&e))?;
            out.write_all(text.as_bytes())
                .map_err(|e| format!("{}: {e}", out.name()))?;
            out.commit()?;
            format!("{} bytes of text", text.len())
        }
        OutputFormat::Dump(compression) => {
            let dialect = match (args.dialect, input.kind) {
                (Some(d), _) => Dialect::from(d),
                (None, InputKind::Dump) => input.dump.header().dialect,
                (None, InputKind::Text) => Dialect::Spec,
            };
            let mut w = Writer::new(Vec::new(), dialect).map_err(|e| e.to_string())?;
            for item in input.dump.reader() {
                let (_, packet) = item.map_err(|e| at(&e))?;
                w.packet(&packet).map_err(|e| e.to_string())?;
            }
            if dialect == Dialect::DuckStation
                && (summary.trace_begin.is_none()
                    || summary.frames.iter().all(|f| f.vsync.is_none()))
            {
                eprintln!(
                    "warning: DuckStation plays a dump only from a trace-begin packet and with at \
                     least one VSync; add `trace-begin` and `vsync` lines to the text"
                );
            }
            let bytes = w.into_inner();
            let size = gpu_input::write_dump(&args.output, &bytes, out)?;
            format!(
                "a {} dialect dump of {} bytes{}",
                dialect.name(),
                bytes.len(),
                match compression {
                    crate::compress::Compression::None => String::new(),
                    c => format!(", {size} bytes {}", c.name()),
                }
            )
        }
    };
    Ok(format!(
        "{} ({} packets, {} frame(s)) -> {}: {written}",
        name,
        summary.packets,
        summary.frames.len(),
        args.output.display()
    ))
}
