//! `wobble render`: the scene pipeline driven from the command line.

use crate::counts::count;
use crate::gif::GifWriter;
use crate::output::{self, OutputDir};
use gte::DivideMode;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use wobble::pipeline::{FrameStats, PipelineOptions, Renderer, TraceError};
use wobble::reference;
use wobble::scene::animation::Animation;
use wobble::scene::default::default_animation;
use wobble::scene::{Scene, WIDTHS};

/// The last frame's image when -o is not given (and --inspect is not).
pub const DEFAULT_OUTPUT: &str = "wobble.png";

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
    /// Output image of the last frame, format by extension (.png, .bmp, .tga, .ppm) or
    /// --format; a .gif with --frames above 1 or --compare is the whole animation. `-` is
    /// standard output. Default wobble.png, or none with --inspect.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    /// Image format of -o (needed for `-o -`; gif writes the animation as above).
    #[arg(long, value_enum)]
    pub format: Option<crate::output::FormatArg>,
    /// Number of frames to render (default 1; with --compare, the whole animation: 90 frames
    /// of the default scene, 60 of a scene file).
    #[arg(long)]
    pub frames: Option<u32>,
    /// Write all frames as an animated GIF (a .gif name, `-` or a device) at the scene's
    /// frame rate (30 a second). With --frames above 1 or --compare, and neither --gif nor
    /// --png-dir, the GIF goes beside the -o image (wobble.gif) when that is a file.
    #[arg(long, conflicts_with = "png_dir")]
    pub gif: Option<PathBuf>,
    /// Side by side: the hardware pipeline on the left, the f64 reference renderer
    /// (perspective-correct, sub-pixel, clipped at a near plane) on the right, each
    /// labelled in the image.
    #[arg(long, conflicts_with = "inspect")]
    pub compare: bool,
    /// Write every frame as a numbered PNG into this directory (created, or an existing one
    /// whose frame files are replaced; the frames are moved into place when all are done).
    #[arg(long)]
    pub png_dir: Option<PathBuf>,
    /// Screen size WxH (widths 256, 320, 368, 512, 640; height up to 256).
    #[arg(long)]
    pub size: Option<String>,
    /// Override every object's tessellation level (0-4).
    #[arg(long)]
    pub tessellation: Option<u8>,
    /// Override every object's split extent: split polygons larger than this many pixels on
    /// screen, up to the tessellation level (0: split every polygon to the full level). The
    /// scene's own extents otherwise (64 unless it says).
    #[arg(long)]
    pub split_extent: Option<u16>,
    /// Turn dithering off.
    #[arg(long)]
    pub no_dither: bool,
    /// Turn the GPU's texture cache off: texels are read straight from VRAM, so no stale
    /// texels and no miss time (docs/gpu.md, "Texture cache").
    #[arg(long)]
    pub no_texture_cache: bool,
    /// GTE divide (non-hardware: exact, f32); overrides the scene's `[accuracy] divide`.
    #[arg(long, value_enum)]
    pub divide: Option<DivideArg>,
    /// Non-hardware: sub-pixel vertex positions.
    #[arg(long)]
    pub subpixel: bool,
    /// Non-hardware: perspective-correct texture coordinates.
    #[arg(long)]
    pub perspective_uv: bool,
    /// Zoom into a region X,Y,W,H of the screen (pixels; it must lie inside the screen):
    /// every image written (-o, --gif, --png-dir) is the region scaled up --zoom-scale
    /// times nearest-neighbour, with --compare the hardware's region beside the
    /// reference's. Repeat for up to 8 regions, stacked top to bottom.
    #[arg(long, value_name = "X,Y,W,H")]
    pub zoom: Vec<String>,
    /// Scale of --zoom's regions (1-8).
    #[arg(long, default_value_t = 3, requires = "zoom")]
    pub zoom_scale: u32,
    /// Write outputs estimated above 256 MB (many frames) instead of refusing.
    #[arg(long)]
    pub large_output: bool,
    /// Write a draw-by-draw report of the last frame into this directory (docs/inspect.md);
    /// no image is written unless -o or --gif asks for one.
    #[arg(long)]
    pub inspect: Option<PathBuf>,
    /// Record what the GPU receives as a GPU dump (.psxgpu, .psxgpu.zst or .psxgpu.xz):
    /// the scene's VRAM and GPU state, then each frame's commands and a VSync
    /// (docs/formats.md); `wobble replay` plays it back frame for frame.
    #[arg(long, conflicts_with = "inspect")]
    pub record: Option<PathBuf>,
    /// Dialect of the --record dump (default: the spec's).
    #[arg(long, value_enum, requires = "record")]
    pub dialect: Option<crate::convert::DialectArg>,
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

/// A duration in milliseconds for the summary, three significant digits (`0.0612`, `12.4`).
fn milliseconds(d: Duration) -> String {
    significant(d.as_secs_f64() * 1e3)
}

/// A duration for the summary: milliseconds below a second, else seconds.
fn duration(d: Duration) -> String {
    if d < Duration::from_secs(1) {
        format!("{} ms", milliseconds(d))
    } else {
        format!("{} s", significant(d.as_secs_f64()))
    }
}

/// A positive quantity with three significant digits and no exponent (`0.0123`, `4.56`,
/// `78.9`, `1234`).
pub fn significant(v: f64) -> String {
    if !v.is_finite() || v == 0.0 {
        return format!("{v}");
    }
    let digits = v.abs().log10().floor() as i32;
    let decimals = (2 - digits).clamp(0, 9) as usize;
    format!("{v:.decimals$}")
}

/// Run `wobble render`; returns the summary line printed at the end.
pub fn run(args: &RenderArgs) -> Result<String, String> {
    let (mut scene, animation) = match &args.scene {
        Some(path) => {
            if let Ok(bytes) = std::fs::read(path)
                && std::str::from_utf8(&bytes).is_err()
            {
                let what = "a scene file (TOML, docs/formats.md)";
                return Err(crate::gpu_input::binary_error(path, &bytes, what));
            }
            (Scene::load(path).map_err(|e| e.to_string())?, None)
        }
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
    if args.zoom.len() > crate::zoom::MAX_REGIONS {
        return Err(format!(
            "--zoom given {} times; at most {}",
            args.zoom.len(),
            crate::zoom::MAX_REGIONS
        ));
    }
    if !(1..=crate::zoom::MAX_SCALE).contains(&args.zoom_scale) {
        return Err(format!(
            "--zoom-scale must be 1..={}, got {}",
            crate::zoom::MAX_SCALE,
            args.zoom_scale
        ));
    }
    let regions = args
        .zoom
        .iter()
        .map(|text| {
            let region = crate::zoom::parse_region(text)?;
            crate::zoom::check_region(
                region,
                u32::from(scene.screen.width),
                u32::from(scene.screen.height),
            )?;
            Ok(region)
        })
        .collect::<Result<Vec<_>, String>>()?;
    let accuracy = scene.accuracy;
    let options = PipelineOptions {
        tessellation: args.tessellation,
        dither: args.no_dither.then_some(false),
        split_extent: args.split_extent,
        divide_mode: args.divide.map_or(accuracy.divide, DivideMode::from),
        subpixel: args.subpixel || accuracy.subpixel,
        perspective_uv: args.perspective_uv || accuracy.perspective_uv,
        texture_cache: !args.no_texture_cache,
    };
    // The last frame's image: -o, else wobble.png unless --inspect writes a report instead.
    let output = match (&args.output, &args.inspect) {
        (Some(path), _) => Some(path.clone()),
        (None, None) => Some(PathBuf::from(DEFAULT_OUTPUT)),
        (None, Some(_)) => None,
    };
    let out_format = match &output {
        Some(path) => Some(output::image_format(path, args.format)?),
        None if args.format.is_some() => {
            return Err("--format names the format of -o, which is not given".into());
        }
        None => None,
    };
    if let Some(path) = &args.gif {
        output::check_gif_name(path)?;
    }
    let animated = frames > 1 || args.compare;
    let gif_path = match &args.gif {
        Some(path) => Some(path.clone()),
        None if animated && args.png_dir.is_none() => match (&output, out_format) {
            // `-o anim.gif --frames N`: the output is the animation itself.
            (Some(path), Some(image::ImageFormat::Gif)) => Some(path.clone()),
            (Some(path), _) if output::is_file_target(path) => Some(path.with_extension("gif")),
            _ => None,
        },
        None => None,
    };
    let last_frame = match &output {
        Some(path) if gif_path.as_ref() != Some(path) => Some(output::open(path)?),
        _ => None,
    };
    let mut gif_file = gif_path.as_deref().map(output::open).transpose()?;
    let png_dir = args.png_dir.as_deref().map(OutputDir::open).transpose()?;
    let inspect_dir = args.inspect.as_deref().map(OutputDir::open).transpose()?;
    let halves = if args.compare { 2 } else { 1 };
    let (w, h) = if regions.is_empty() {
        (
            u64::from(scene.screen.width) * halves,
            u64::from(scene.screen.height),
        )
    } else {
        let (zw, zh) = crate::zoom::zoomed_size(&regions, args.zoom_scale);
        (u64::from(zw) * halves, u64::from(zh))
    };
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
    let record_file = match &args.record {
        Some(path) => match crate::gpu_input::output_format(path)? {
            crate::gpu_input::OutputFormat::Dump(_) => Some(output::open(path)?),
            crate::gpu_input::OutputFormat::Text => {
                return Err(format!(
                    "{}: --record writes a GPU dump: name it .psxgpu, .psxgpu.zst or .psxgpu.xz",
                    path.display()
                ));
            }
        },
        None => None,
    };
    let base = scene.clone();
    let mut renderer = Renderer::new(scene, options).map_err(|e| e.to_string())?;
    let comment = format!(
        "wobble {} render of {}",
        env!("CARGO_PKG_VERSION"),
        args.scene.as_ref().map_or_else(
            || "the built-in default scene".to_string(),
            |p| p.display().to_string()
        )
    );
    let mut recorder = match &args.record {
        Some(_) => {
            let info = gpu::dump::RecordInfo {
                dialect: args.dialect.map_or(gpu::dump::Dialect::Spec, Into::into),
                game_id: None,
                comment: Some(&comment),
            };
            Some(
                renderer
                    .start_recording(Vec::new(), &info)
                    .map_err(|e| e.to_string())?,
            )
        }
        None => None,
    };
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
    let mut gif = match &mut gif_file {
        Some(file) => {
            let gw = u16::try_from(w).map_err(|_| format!("GIF width {w} above 65535"))?;
            let gh = u16::try_from(h).map_err(|_| format!("GIF height {h} above 65535"))?;
            Some(GifWriter::new(file, gw, gh, animation.fps)?)
        }
        None => None,
    };
    let gif_err = |e: String| match &gif_path {
        Some(p) => format!("{}: {e}", p.display()),
        None => e,
    };
    let start = Instant::now();
    let mut report_time = Duration::ZERO;
    let mut total = FrameStats::default();
    let mut last_image = None;
    let mut inspect_summary = None;
    for frame in 0..frames {
        renderer
            .pose(&animation, &base, frame)
            .map_err(|e| format!("animation frame {frame}: {e}"))?;
        let stats = match &inspect_dir {
            Some(dir) if frame + 1 == frames => {
                let (stats, trace) = renderer
                    .render_frame_traced(frame)
                    .map_err(|e| e.to_string())?;
                let title = format!("frame {frame}");
                let writing = Instant::now();
                inspect_summary = Some(wobble::inspect::write_frame_report(
                    renderer.scene(),
                    &trace,
                    dir.path(),
                    &title,
                    wobble::inspect::InspectOptions::default(),
                )?);
                report_time += writing.elapsed();
                stats
            }
            _ => match recorder.as_mut() {
                Some(rec) => renderer
                    .render_frame_recorded(frame, rec)
                    .map_err(|e| match e {
                        TraceError::PrecisePath => "--record needs the hardware path: drop \
                                                    --subpixel / --perspective-uv"
                            .to_string(),
                    })?,
                None => renderer.render_frame(frame),
            },
        };
        total.accumulate(&stats);
        let wanted =
            gif.is_some() || png_dir.is_some() || (last_frame.is_some() && frame + 1 == frames);
        if wanted {
            let zoomed = |img: image::RgbImage| {
                if regions.is_empty() {
                    img
                } else {
                    crate::zoom::zoom(&img, &regions, args.zoom_scale)
                }
            };
            let img = if args.compare {
                let reference = reference::render(&animation.scene_at(&base, frame), frame);
                crate::compare::side_by_side(&zoomed(renderer.image()), &zoomed(reference.image()))
            } else {
                zoomed(renderer.image())
            };
            if let Some(dir) = &png_dir {
                let path = dir.path().join(format!("frame{frame:05}.png"));
                img.save_with_format(&path, image::ImageFormat::Png)
                    .map_err(|e| format!("{}: {e}", path.display()))?;
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
    // Writing the --inspect report is not rendering: it is timed apart.
    let elapsed = start.elapsed().saturating_sub(report_time);
    progress.finish_and_clear();
    let gif_done = gif
        .map(GifWriter::finish)
        .transpose()
        .map_err(gif_err)?
        .is_some();
    let mut written = Vec::new();
    if let (Some(file), Some(img), Some(format)) = (last_frame, last_image, out_format) {
        let name = file.name().to_string();
        output::write_image(img, file, format)?;
        written.push(format!("{name} (last frame)"));
    }
    if let (true, Some(file)) = (gif_done, gif_file) {
        let (name, bytes) = (file.name().to_string(), file.written());
        file.commit()?;
        written.push(format!(
            "{name} ({}, {:.1} KB, {} fps)",
            count(frames as usize, "frame", "frames"),
            bytes as f64 / 1000.0,
            animation.fps
        ));
    }
    if let (Some(rec), Some(file), Some(path)) = (recorder, record_file, &args.record) {
        let bytes = rec
            .finish()
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let name = file.name().to_string();
        let size = crate::gpu_input::write_dump(path, &bytes, file)?;
        written.push(format!(
            "{name} (GPU dump of {}, {:.1} KB)",
            count(frames as usize, "frame", "frames"),
            size as f64 / 1000.0
        ));
    }
    if let Some(dir) = png_dir {
        let target = dir.target().to_path_buf();
        dir.commit("")?;
        written.push(format!(
            "{} ({})",
            target
                .join(format!("frame00000..frame{:05}.png", frames - 1))
                .display(),
            count(frames as usize, "frame", "frames"),
        ));
    }
    let mut report_line = None;
    if let (Some(dir), Some(report)) = (inspect_dir, &inspect_summary) {
        let target = dir.target().to_path_buf();
        dir.commit("index.html")?;
        report_line = Some(format!(
            "report of frame {}: {}, written in {} (not counted in the rendering time)",
            frames - 1,
            wobble::inspect::summary_line(report, &target),
            duration(report_time)
        ));
    }
    let seconds = elapsed.as_secs_f64();
    let mut summary = format!(
        "{} {}: {} drawn, {} culled (NCLIP), {} off screen, {} dropped ({}); GTE {} ms, OT \
         {} ms, GPU {} ms over {}{}; total {}, {} frames/s rendered{}",
        count(frames as usize, "frame", "frames"),
        if written.is_empty() {
            "rendered".to_string()
        } else {
            format!("-> {}", written.join("; "))
        },
        count(total.drawn, "polygon", "polygons"),
        total.culled,
        total.offscreen,
        total.dropped,
        if total.capped > 0 {
            "whole-polygon clip, and past the per-frame polygon cap"
        } else {
            "whole-polygon clip"
        },
        milliseconds(total.gte),
        milliseconds(total.ot),
        milliseconds(total.gpu),
        if frames == 1 {
            "the frame"
        } else {
            "all frames"
        },
        if inspect_summary.is_some() {
            " (the traced last frame's times include the tracing)"
        } else {
            ""
        },
        duration(elapsed),
        significant(f64::from(frames) / seconds.max(1e-9)),
        if args.compare {
            " (with the reference and the output)"
        } else {
            ""
        }
    );
    if let Some(line) = report_line {
        summary.push('\n');
        summary.push_str(&line);
    }
    if let Some(cap) = wobble::pipeline::cap_message(&total) {
        summary.push('\n');
        summary.push_str(&cap);
    }
    Ok(summary)
}
