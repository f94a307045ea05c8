//! `wobble render`: the scene pipeline driven from the command line.

use crate::gif::GifWriter;
use gte::DivideMode;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;
use wobble::pipeline::{FrameStats, PipelineOptions, Renderer};
use wobble::reference;
use wobble::scene::animation::Animation;
use wobble::scene::default::default_animation;
use wobble::scene::{Scene, WIDTHS};

/// Largest estimated output written without `--large-output`.
pub const MAX_OUTPUT_BYTES: u64 = 256_000_000;

/// Most frames one command renders.
pub const MAX_FRAMES: u32 = 100_000;

/// Estimated output above which a warning is printed before writing.
pub const WARN_OUTPUT_BYTES: u64 = 50_000_000;

/// Frames `--compare` renders of a scene file (which has no animation of its own).
pub const COMPARE_FRAMES: u32 = 60;

/// Arguments of `wobble render`.
#[derive(Debug, Clone, clap::Args)]
pub struct RenderArgs {
    /// Scene file (TOML); the built-in default scene when omitted.
    pub scene: Option<PathBuf>,
    /// Output PNG of the last frame.
    #[arg(short, long, default_value = "wobble.png")]
    pub output: PathBuf,
    /// Number of frames to render (default 1; with --compare, the whole animation: 90 frames
    /// of the default scene, 60 of a scene file).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Write all frames as an animated GIF at the scene's frame rate (30 a second). With
    /// --frames above 1 or --compare, and neither --gif nor --png-dir, the GIF goes beside
    /// the PNG (wobble.gif).
    #[arg(long, conflicts_with = "png_dir")]
    pub gif: Option<PathBuf>,
    /// Side by side: the hardware pipeline on the left, the f64 reference renderer
    /// (perspective-correct, sub-pixel, clipped at a near plane) on the right, each
    /// labelled in the image.
    #[arg(long, conflicts_with = "inspect")]
    pub compare: bool,
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
    let (mut scene, animation) = match &args.scene {
        Some(path) => (Scene::load(path).map_err(|e| e.to_string())?, None),
        None => (Scene::default_scene(), Some(default_animation())),
    };
    let frames = args.frames.unwrap_or(match (&animation, args.compare) {
        (Some(a), true) => a.frames,
        (None, true) => COMPARE_FRAMES,
        (_, false) => 1,
    });
    if frames == 0 || frames > MAX_FRAMES {
        return Err(format!("--frames must be 1..={MAX_FRAMES}, got {frames}"));
    }
    let animation = animation.unwrap_or_else(|| Animation::still(frames));
    if let Some(t) = args.tessellation
        && t > 4
    {
        return Err(format!("--tessellation must be 0..=4, got {t}"));
    }
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
        None if (frames > 1 || args.compare) && args.png_dir.is_none() => {
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
    let halves = if args.compare { 2 } else { 1 };
    let (w, h) = (
        u64::from(scene.screen.width) * halves,
        u64::from(scene.screen.height),
    );
    // Measured on the default animation side by side (640x240, dithered): 0.74 bytes a pixel
    // as PNG, 0.13 as a GIF with a palette per frame; rounded up to 1 and 1/6.
    let frame_bytes = if args.png_dir.is_some() {
        w * h
    } else if gif_path.is_some() {
        w * h / 6
    } else {
        0
    };
    let estimate = frame_bytes * u64::from(frames);
    let what = if args.png_dir.is_some() {
        "PNG frames"
    } else {
        "GIF"
    };
    if estimate > MAX_OUTPUT_BYTES && !args.large_output {
        return Err(format!(
            "--frames {frames} would write about {} MB of {what} (estimated at {:.1} KB a \
             frame); fewer frames, a smaller --size, or --large-output to write it anyway",
            estimate / 1_000_000,
            frame_bytes as f64 / 1000.0
        ));
    }
    if estimate > WARN_OUTPUT_BYTES {
        eprintln!(
            "warning: about {} MB of {what} to write ({frames} frames at {:.1} KB each)",
            estimate / 1_000_000,
            frame_bytes as f64 / 1000.0
        );
    }
    let base = scene.clone();
    let mut renderer = Renderer::new(scene, options).map_err(|e| e.to_string())?;
    let plain_progress = frames > 1 && !std::io::stderr().is_terminal();
    let progress_step = (frames / 10).max(1);
    let progress = if frames > 1 {
        let bar = ProgressBar::new(u64::from(frames));
        if let Ok(style) = ProgressStyle::with_template("{bar:40} {pos}/{len} frames {eta}") {
            bar.set_style(style);
        }
        bar
    } else {
        ProgressBar::hidden()
    };
    let mut gif_file = gif_path
        .as_deref()
        .map(crate::output::OutputFile::create)
        .transpose()?;
    let mut gif = match &mut gif_file {
        Some(file) => {
            let gw = u16::try_from(w).map_err(|_| format!("GIF width {w} above 65535"))?;
            let gh = u16::try_from(h).map_err(|_| format!("GIF height {h} above 65535"))?;
            Some(GifWriter::new(file.writer()?, gw, gh, animation.fps)?)
        }
        None => None,
    };
    let gif_err = |e: String| match &gif_path {
        Some(p) => format!("{}: {e}", p.display()),
        None => e,
    };
    let start = Instant::now();
    let mut total = FrameStats::default();
    let mut last_image = None;
    for frame in 0..frames {
        animation.pose(&mut renderer, &base, frame)?;
        let stats = match &args.inspect {
            Some(dir) if frame + 1 == frames => {
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
        let wanted = gif.is_some() || args.png_dir.is_some() || frame + 1 == frames;
        if wanted {
            let img = if args.compare {
                let reference = reference::render(&animation.scene_at(&base, frame), frame);
                crate::compare::side_by_side(&renderer.image(), &reference.image())
            } else {
                renderer.image()
            };
            if let Some(dir) = &args.png_dir {
                let path = dir.join(format!("frame{frame:05}.png"));
                crate::output::save_image(img.clone(), &path)?;
            }
            if let Some(g) = gif.as_mut() {
                g.frame(&crate::gif::image_rgb15(&img)).map_err(gif_err)?;
            }
            if frame + 1 == frames {
                last_image = Some(img);
            }
        }
        progress.inc(1);
        if plain_progress && ((frame + 1) % progress_step == 0 || frame + 1 == frames) {
            eprintln!("rendered {}/{} frames", frame + 1, frames);
        }
    }
    let elapsed = start.elapsed();
    progress.finish_and_clear();
    gif.map(GifWriter::finish).transpose().map_err(gif_err)?;
    let mut written = Vec::new();
    if let Some(file) = gif_file {
        file.commit()?;
    }
    if let (Some(file), Some(img)) = (last_frame, last_image) {
        crate::output::write_image(img, file)?;
        written.push(format!("{} (last frame)", args.output.display()));
    }
    if let Some(path) = &gif_path {
        let bytes = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
        written.push(format!(
            "{} ({frames} frames, {:.1} KB, {} fps)",
            path.display(),
            bytes as f64 / 1000.0,
            animation.fps
        ));
    }
    if let Some(dir) = &args.png_dir {
        written.push(format!(
            "{} ({frames} frames)",
            dir.join(format!("frame00000..frame{:05}.png", frames - 1))
                .display(),
        ));
    }
    let seconds = elapsed.as_secs_f64();
    let mut summary = format!(
        "{frames} frame(s) -> {}: {} polygons drawn, {} culled (NCLIP), {} off screen, {} \
         dropped ({}); GTE {:.2} ms, OT {:.2} ms, GPU {:.2} ms; total {seconds:.2} s, {:.1} \
         frames/s rendered{}",
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
        f64::from(frames) / seconds.max(1e-9),
        if args.compare {
            " (with the reference and the output)"
        } else {
            ""
        }
    );
    if let Some(cap) = wobble::pipeline::cap_message(&total) {
        summary.push('\n');
        summary.push_str(&cap);
    }
    Ok(summary)
}
