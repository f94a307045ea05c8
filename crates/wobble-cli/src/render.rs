//! `wobble render`: the scene pipeline driven from the command line.

use gte::DivideMode;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;
use wobble::pipeline::{FrameStats, PipelineOptions, Renderer};
use wobble::scene::{Scene, WIDTHS};

/// Largest estimated output written without `--large-output`.
pub const MAX_OUTPUT_BYTES: u64 = 256_000_000;

/// Most frames one command renders.
pub const MAX_FRAMES: u32 = 100_000;

/// Arguments of `wobble render`.
#[derive(Debug, Clone, clap::Args)]
pub struct RenderArgs {
    /// Scene file (TOML); the built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// Output PNG of the last frame.
    #[arg(short, long, default_value = "wobble.png")]
    pub output: PathBuf,
    /// Number of frames to render.
    #[arg(long, default_value_t = 1)]
    pub frames: u32,
    /// Write all frames as an animated GIF (30 frames per second). With --frames above 1
    /// and neither --gif nor --png-dir, the GIF goes beside the PNG (wobble.gif).
    #[arg(long, conflicts_with = "png_dir")]
    pub gif: Option<PathBuf>,
    /// Write every frame as a numbered PNG into this directory.
    #[arg(long)]
    pub png_dir: Option<PathBuf>,
    /// Screen size WxH (widths 256, 320, 368, 512, 640; height up to 256).
    #[arg(long)]
    pub size: Option<String>,
    /// Override every object's tessellation level (0-4).
    #[arg(long)]
    pub tessellation: Option<u8>,
    /// Split polygons larger than this many pixels on screen, up to the tessellation level
    /// (0: split every polygon to the full level).
    #[arg(long, default_value_t = wobble::pipeline::DEFAULT_SPLIT_EXTENT)]
    pub split_extent: u16,
    /// Turn dithering off.
    #[arg(long)]
    pub no_dither: bool,
    /// GTE divide (non-hardware: exact, f32); overrides the scene's `[accuracy] divide`.
    #[arg(long, value_enum)]
    pub divide: Option<DivideArg>,
    /// Non-hardware: sub-pixel vertex positions.
    #[arg(long)]
    pub subpixel: bool,
    /// Non-hardware: perspective-correct texture coordinates.
    #[arg(long)]
    pub perspective_uv: bool,
    /// Write outputs estimated above 256 MB (many frames) instead of refusing.
    #[arg(long)]
    pub large_output: bool,
    /// Write a draw-by-draw report of the last frame into this directory (docs/inspect.md).
    #[arg(long)]
    pub inspect: Option<PathBuf>,
}

/// The GTE divide, as `--divide` takes it (the scene's `[accuracy] divide`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum DivideArg {
    /// The console's UNR divide.
    Unr,
    /// Exact rounded division (non-hardware).
    Exact,
    /// f32 division (non-hardware).
    F32,
}

impl From<DivideArg> for DivideMode {
    fn from(d: DivideArg) -> DivideMode {
        match d {
            DivideArg::Unr => DivideMode::Unr,
            DivideArg::Exact => DivideMode::Exact,
            DivideArg::F32 => DivideMode::F32,
        }
    }
}

/// Parse `WxH`.
pub fn parse_size(text: &str) -> Result<(u16, u16), String> {
    let err = || {
        format!(
            "--size: expected WxH with W one of 256, 320, 368, 512, 640 and H 1..=256, got `{text}`"
        )
    };
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(err)?;
    let w: u16 = w.trim().parse().map_err(|_| err())?;
    let h: u16 = h.trim().parse().map_err(|_| err())?;
    if !WIDTHS.contains(&w) || h == 0 || h > 256 {
        return Err(err());
    }
    Ok((w, h))
}

/// Run `wobble render`; returns the summary line printed at the end.
pub fn run(args: &RenderArgs) -> Result<String, String> {
    if args.frames == 0 || args.frames > MAX_FRAMES {
        return Err(format!(
            "--frames must be 1..={MAX_FRAMES}, got {}",
            args.frames
        ));
    }
    if let Some(t) = args.tessellation
        && t > 4
    {
        return Err(format!("--tessellation must be 0..=4, got {t}"));
    }
    let mut scene = match &args.scene {
        Some(path) => Scene::load(path).map_err(|e| e.to_string())?,
        None => Scene::default_scene(),
    };
    if let Some(size) = &args.size {
        let (w, h) = parse_size(size)?;
        scene.screen.width = w;
        scene.screen.height = h;
    }
    let accuracy = scene.accuracy;
    let options = PipelineOptions {
        tessellation: args.tessellation,
        dither: args.no_dither.then_some(false),
        split_extent: args.split_extent,
        divide_mode: args.divide.map_or(accuracy.divide, DivideMode::from),
        subpixel: args.subpixel || accuracy.subpixel,
        perspective_uv: args.perspective_uv || accuracy.perspective_uv,
    };
    crate::output::image_format(&args.output)?;
    let gif_path = match &args.gif {
        Some(path) => Some(path.clone()),
        None if args.frames > 1 && args.png_dir.is_none() => {
            Some(args.output.with_extension("gif"))
        }
        None => None,
    };
    // `-o anim.gif --frames N`: the output is the animation itself.
    let last_frame = if gif_path.as_ref() == Some(&args.output) {
        None
    } else {
        Some(crate::output::OutputFile::create(&args.output)?)
    };
    if let Some(dir) = &args.png_dir {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        crate::output::check_dir(dir)?;
    }
    let mut gif_file = gif_path
        .as_deref()
        .map(crate::output::OutputFile::create)
        .transpose()?;
    let (w, h) = (
        u64::from(scene.screen.width),
        u64::from(scene.screen.height),
    );
    let frame_bytes = if args.png_dir.is_some() {
        w * h / 4
    } else if gif_path.is_some() {
        w * h / 16
    } else {
        0
    };
    let estimate = frame_bytes * u64::from(args.frames);
    if estimate > MAX_OUTPUT_BYTES && !args.large_output {
        return Err(format!(
            "--frames {} would write about {} MB of {} (estimated at {:.1} KB a frame); fewer \
             frames, a smaller --size, or --large-output to write it anyway",
            args.frames,
            estimate / 1_000_000,
            if args.png_dir.is_some() {
                "PNG frames"
            } else {
                "GIF"
            },
            frame_bytes as f64 / 1000.0
        ));
    }
    let mut renderer = Renderer::new(scene, options).map_err(|e| e.to_string())?;
    let plain_progress = args.frames > 1 && !std::io::stderr().is_terminal();
    let progress_step = (args.frames / 10).max(1);
    let progress = if args.frames > 1 {
        let bar = ProgressBar::new(args.frames as u64);
        if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} frames {eta}") {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let mut gif = match (&mut gif_file, &gif_path) {
        (Some(file), Some(path)) => {
            let mut encoder = image::codecs::gif::GifEncoder::new_with_speed(file.writer()?, 10);
            encoder
                .set_repeat(image::codecs::gif::Repeat::Infinite)
                .map_err(|e| format!("{}: {e}", path.display()))?;
            Some(encoder)
        }
        _ => None,
    };
    let start = Instant::now();
    let mut total = FrameStats::default();
    for frame in 0..args.frames {
        let stats = match &args.inspect {
            Some(dir) if frame + 1 == args.frames => {
                let (stats, trace) = renderer.render_frame_traced(frame)?;
                let title = format!("frame {frame}");
                wobble::inspect::write_frame_report(
                    renderer.scene(),
                    &trace,
                    dir,
                    &title,
                    wobble::inspect::InspectOptions::default(),
                )?;
                stats
            }
            _ => renderer.render_frame(frame),
        };
        total.accumulate(&stats);
        if gif_path.is_some() || args.png_dir.is_some() {
            let img = renderer.image();
            if let Some(dir) = &args.png_dir {
                let path = dir.join(format!("frame{frame:05}.png"));
                crate::output::save_image(img.clone(), &path)?;
            }
            if let (Some(encoder), Some(path)) = (gif.as_mut(), &gif_path) {
                let rgba = image::DynamicImage::ImageRgb8(img).to_rgba8();
                let delay = image::Delay::from_numer_denom_ms(100, 3);
                encoder
                    .encode_frame(image::Frame::from_parts(rgba, 0, 0, delay))
                    .map_err(|e| format!("{}: {e}", path.display()))?;
            }
        }
        progress.inc(1);
        if plain_progress && ((frame + 1) % progress_step == 0 || frame + 1 == args.frames) {
            eprintln!("rendered {}/{} frames", frame + 1, args.frames);
        }
    }
    progress.finish_and_clear();
    drop(gif);
    if let Some(file) = gif_file {
        file.commit()?;
    }
    let elapsed = start.elapsed();
    let mut written = Vec::new();
    if let Some(file) = last_frame {
        crate::output::write_image(renderer.image(), file)?;
        written.push(format!("{} (last frame)", args.output.display()));
    }
    if let Some(path) = &gif_path {
        written.push(format!("{} ({} frames)", path.display(), args.frames));
    }
    if let Some(dir) = &args.png_dir {
        written.push(format!(
            "{} ({} frames)",
            dir.join(format!("frame00000..frame{:05}.png", args.frames - 1))
                .display(),
            args.frames
        ));
    }
    let mut summary = format!(
        "{} frame(s) -> {}: {} polygons drawn, {} culled (NCLIP), {} off screen, {} dropped \
         ({}); GTE {:.2} ms, OT {:.2} ms, GPU {:.2} ms; total {:.2} s",
        args.frames,
        written.join(", "),
        total.drawn,
        total.culled,
        total.offscreen,
        total.dropped,
        if total.capped > 0 {
            "whole-polygon clip, and past the per-frame polygon cap"
        } else {
            "whole-polygon clip"
        },
        total.gte.as_secs_f64() * 1e3,
        total.ot.as_secs_f64() * 1e3,
        total.gpu.as_secs_f64() * 1e3,
        elapsed.as_secs_f64()
    );
    if let Some(cap) = wobble::pipeline::cap_message(&total) {
        summary.push('\n');
        summary.push_str(&cap);
    }
    Ok(summary)
}
