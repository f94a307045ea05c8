//! `wobble trade`: what each piece of PS1 accuracy costs in time, and what dropping it
//! costs in wrong pixels, texel error and vertex jitter, measured on one scene against the
//! f64 reference renderer (docs/trade.md).
//!
//! [`measure`] takes the figures, [`write_report`] turns them into `trade.md` (every sentence
//! of its conclusion computed from the figures, [`conclusion`]), the texel_error module
//! decodes the sampled texels and measures each pixel's texel error, the heat module
//! colours the texel-error maps and draws their colour bar, and the charts module draws the
//! other images.

mod charts;
mod heat;
mod measure;
mod report;
mod texel_error;

pub use charts::curve_image;
pub use heat::{
    BAR_HEIGHT, HEAT_STOPS, NO_SURFACE, colour_bar, colour_words, heat_colour, heat_map,
};
pub use measure::{Measurement, Skipped, divide_stability, measure, vertex_jitter};
pub use report::{conclusion, figures_table, write_report};
pub use texel_error::{coordinate_scene, decode_texel, texel_errors};

use crate::pipeline::{PipelineOptions, RenderError};
use gte::DivideMode;
use std::fmt;
use std::path::PathBuf;

/// The knob a report row turns, relative to the hardware-exact configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Knob {
    /// No knob: UNR divide, snapped vertices, affine UVs, dithering, no tessellation, the
    /// texture cache on.
    #[default]
    Hardware,
    /// Exact integer division instead of the UNR divide.
    DivideExact,
    /// `f32` division instead of the UNR divide.
    DivideF32,
    /// Dithering off.
    DitherOff,
    /// Sub-pixel vertex positions (not hardware).
    Subpixel,
    /// Perspective-correct texture coordinates (not hardware).
    PerspectiveUv,
    /// Sub-pixel vertices and perspective-correct texture coordinates (not hardware).
    SubpixelPerspective,
    /// Tessellation to this level.
    Tessellation(u8),
    /// The GPU's texture cache off: no stale texels, no miss time.
    TextureCacheOff,
}

impl Knob {
    /// Every row of the report, in report order: the hardware-exact configuration first.
    pub const ALL: [Knob; 12] = [
        Knob::Hardware,
        Knob::DivideExact,
        Knob::DivideF32,
        Knob::DitherOff,
        Knob::Subpixel,
        Knob::PerspectiveUv,
        Knob::SubpixelPerspective,
        Knob::Tessellation(1),
        Knob::Tessellation(2),
        Knob::Tessellation(3),
        Knob::Tessellation(4),
        Knob::TextureCacheOff,
    ];

    /// The row's label in the report.
    pub fn label(self) -> &'static str {
        match self {
            Knob::Hardware => "hardware (UNR, snapped, affine, dither, tess 0)",
            Knob::DivideExact => "divide: exact",
            Knob::DivideF32 => "divide: f32",
            Knob::DitherOff => "dithering off",
            Knob::Subpixel => "sub-pixel vertices (non-hardware)",
            Knob::PerspectiveUv => "perspective-correct UVs (non-hardware)",
            Knob::SubpixelPerspective => "sub-pixel + perspective (non-hardware)",
            Knob::Tessellation(1) => "tessellation 1",
            Knob::Tessellation(2) => "tessellation 2",
            Knob::Tessellation(3) => "tessellation 3",
            Knob::Tessellation(4) => "tessellation 4",
            Knob::Tessellation(_) => "tessellation",
            Knob::TextureCacheOff => "texture cache off",
        }
    }

    /// The pipeline options of the row. Every row overrides the scene's tessellation: level 0
    /// (no split at all) unless the row is a tessellation level, where every object's
    /// polygons are split by size at the default 64 pixels, so that the rows differ only by
    /// their knob and the levels form one curve (the default scene itself splits its floor
    /// near the camera only).
    pub fn options(self) -> PipelineOptions {
        let hw = PipelineOptions {
            tessellation: Some(0),
            split_extent: Some(crate::scene::DEFAULT_SPLIT_EXTENT),
            ..PipelineOptions::default()
        };
        match self {
            Knob::Hardware => hw,
            Knob::DivideExact => PipelineOptions {
                divide_mode: DivideMode::Exact,
                ..hw
            },
            Knob::DivideF32 => PipelineOptions {
                divide_mode: DivideMode::F32,
                ..hw
            },
            Knob::DitherOff => PipelineOptions {
                dither: Some(false),
                ..hw
            },
            Knob::Subpixel => PipelineOptions {
                subpixel: true,
                ..hw
            },
            Knob::PerspectiveUv => PipelineOptions {
                perspective_uv: true,
                ..hw
            },
            Knob::SubpixelPerspective => PipelineOptions {
                subpixel: true,
                perspective_uv: true,
                ..hw
            },
            Knob::Tessellation(level) => PipelineOptions {
                tessellation: Some(level),
                ..hw
            },
            Knob::TextureCacheOff => PipelineOptions {
                texture_cache: false,
                ..hw
            },
        }
    }

    /// Whether the row belongs on the tessellation curve (level 0 is the hardware row).
    pub(crate) fn on_tessellation_curve(self) -> bool {
        matches!(self, Knob::Hardware | Knob::Tessellation(_))
    }
}

/// One configuration of the knobs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Config {
    /// The knob the row turns.
    pub knob: Knob,
    /// Row label.
    pub name: &'static str,
    /// Pipeline knobs.
    pub options: PipelineOptions,
}

/// The rows of the report: the hardware-exact configuration first.
pub fn configs() -> Vec<Config> {
    Knob::ALL
        .iter()
        .map(|&knob| Config {
            knob,
            name: knob.label(),
            options: knob.options(),
        })
        .collect()
}

/// Measured figures of one configuration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Row {
    /// The knob the row turns.
    pub knob: Knob,
    /// Label.
    pub name: String,
    /// Median time per frame, milliseconds.
    pub frame_ms: f64,
    /// Ratio to the hardware configuration's median.
    pub ratio: f64,
    /// Polygons drawn per frame (mean).
    pub drawn: f64,
    /// Pixels differing from the hardware-exact image, summed over the frames.
    pub differing_pixels: usize,
    /// Mean texel error against the reference over textured pixels both cover.
    pub texel_mean: f64,
    /// Largest texel error.
    pub texel_max: f64,
    /// Mean vertex jitter in pixels.
    pub jitter: f64,
}

/// Report settings.
#[derive(Clone, Copy, Debug)]
pub struct TradeSettings {
    /// Frames measured (consecutive).
    pub frames: u32,
    /// Timing repetitions (the median is reported).
    pub repeats: u32,
    /// Divide-stability sweep: every SZ3 and every `sweep_step`-th H (1: exhaustive).
    pub sweep_step: usize,
}

/// How far [`write_report`] has come; its `Display` is the line to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TradeProgress {
    /// Measuring every configuration is starting.
    Measuring {
        /// Configurations measured.
        configurations: usize,
        /// Frames per configuration.
        frames: u32,
        /// Timing runs per configuration.
        repeats: u32,
    },
    /// The divide sweep over all 2^32 (H, SZ3) pairs is starting.
    FullSweep,
    /// The divide sweep has done `done` of its `total` rows (one row: one divide mode and
    /// one H against every SZ3); reported after every row.
    Sweep {
        /// Rows done.
        done: u64,
        /// Rows in the sweep.
        total: u64,
    },
}

impl fmt::Display for TradeProgress {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TradeProgress::Measuring {
                configurations,
                frames,
                repeats,
            } => write!(
                f,
                "measuring {configurations} configurations over {frames} frames, {repeats} \
                 timing runs each"
            ),
            TradeProgress::FullSweep => write!(
                f,
                "sweeping the GTE divide over all 2^32 (H, SZ3) pairs in three modes \
                 ({FULL_SWEEP_TIME})"
            ),
            TradeProgress::Sweep { done, total } => {
                let percent = if *total == 0 {
                    100
                } else {
                    done.saturating_mul(100) / total
                };
                write!(f, "divide sweep: {done}/{total} rows ({percent}%)")
            }
        }
    }
}

/// How long the full divide sweep took when measured: a release build on a 2-core machine
/// shared with other builds (1/64 of the sweep in 1.9 s, the whole report in 2.5 minutes).
pub const FULL_SWEEP_TIME: &str = "about two minutes in a release build";

/// Why the trade report could not be written.
#[derive(Debug)]
pub enum TradeError {
    /// A renderer could not be built for the scene.
    Render(RenderError),
    /// Creating a directory or writing the report failed.
    Io {
        /// The directory or file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Drawing a chart failed.
    Chart {
        /// The chart's file name.
        file: PathBuf,
        /// What the charting library reported.
        message: String,
    },
    /// Writing an image failed.
    Image {
        /// The image file.
        file: PathBuf,
        /// The cause.
        source: image::ImageError,
    },
}

impl fmt::Display for TradeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TradeError::Render(e) => write!(f, "{e}"),
            TradeError::Io { file, source } => write!(f, "{}: {source}", file.display()),
            TradeError::Chart { file, message } => write!(f, "{}: {message}", file.display()),
            TradeError::Image { file, source } => write!(f, "{}: {source}", file.display()),
        }
    }
}

impl std::error::Error for TradeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TradeError::Render(e) => Some(e),
            TradeError::Io { source, .. } => Some(source),
            TradeError::Chart { .. } => None,
            TradeError::Image { source, .. } => Some(source),
        }
    }
}

impl From<RenderError> for TradeError {
    fn from(e: RenderError) -> Self {
        TradeError::Render(e)
    }
}
