//! The pipeline's knobs: tessellation, split extent and dithering (all hardware behaviour),
//! and the non-hardware accuracy knobs (the GTE divide, sub-pixel vertices,
//! perspective-correct texture coordinates), which need the `accuracy-knobs` feature.

use gte::DivideMode;
use std::fmt;

/// Knobs, all defaulting to what the scene says and to hardware behaviour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PipelineOptions {
    /// Override every object's tessellation level (0..=4).
    pub tessellation: Option<u8>,
    /// Override every object's split extent: a polygon whose screen bounding box is wider or
    /// taller than this many pixels is split (up to its object's tessellation level); 0
    /// splits every polygon to the full level.
    pub split_extent: Option<u16>,
    /// Override the scene's dithering.
    pub dither: Option<bool>,
    /// GTE divide (hardware UNR by default).
    pub divide_mode: DivideMode,
    /// Non-hardware: keep 4 fractional bits of each screen position (the GTE's 16.16 result
    /// before its truncation to whole pixels) and rasterize with the precise path.
    pub subpixel: bool,
    /// Non-hardware: perspective-correct texture coordinates (the precise path with 1/SZ
    /// per vertex) instead of the GPU's affine stepping.
    pub perspective_uv: bool,
    /// The GPU's texture cache (on, as on the console; `gpu::Gpu::set_texture_cache`): off,
    /// texels are read straight from VRAM and cache misses cost no drawing time.
    pub texture_cache: bool,
}

impl PipelineOptions {
    /// Whether polygons go through the non-hardware precise rasterizer (never, when built
    /// without the `accuracy-knobs` feature: such options are refused by [`Self::check`]).
    pub fn precise(&self) -> bool {
        cfg!(feature = "accuracy-knobs") && (self.subpixel || self.perspective_uv)
    }

    /// The first knob these options turn that this build does not include: every
    /// non-hardware knob (a divide other than UNR, sub-pixel vertices, perspective-correct
    /// texture coordinates) needs the `accuracy-knobs` feature.
    pub fn check(&self) -> Result<(), UnsupportedKnob> {
        if cfg!(feature = "accuracy-knobs") {
            return Ok(());
        }
        if self.divide_mode != DivideMode::Unr {
            Err(UnsupportedKnob::Divide(self.divide_mode))
        } else if self.subpixel {
            Err(UnsupportedKnob::Subpixel)
        } else if self.perspective_uv {
            Err(UnsupportedKnob::PerspectiveUv)
        } else {
            Ok(())
        }
    }
}

/// A non-hardware knob asked of a build without the `accuracy-knobs` feature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnsupportedKnob {
    /// A GTE divide other than the hardware's UNR divide.
    Divide(DivideMode),
    /// Sub-pixel vertex positions.
    Subpixel,
    /// Perspective-correct texture coordinates.
    PerspectiveUv,
}

impl fmt::Display for UnsupportedKnob {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let knob = match self {
            UnsupportedKnob::Divide(DivideMode::Exact) => "the exact GTE divide",
            UnsupportedKnob::Divide(DivideMode::F32) => "the f32 GTE divide",
            UnsupportedKnob::Divide(DivideMode::Unr) => "the UNR GTE divide",
            UnsupportedKnob::Subpixel => "sub-pixel vertices",
            UnsupportedKnob::PerspectiveUv => "perspective-correct texture coordinates",
        };
        write!(
            f,
            "{knob} is not built: it needs the `accuracy-knobs` feature of the wobble crate"
        )
    }
}

impl std::error::Error for UnsupportedKnob {}

impl Default for PipelineOptions {
    /// What the scene says, with the hardware's behaviour (the texture cache on).
    fn default() -> Self {
        Self {
            tessellation: None,
            split_extent: None,
            dither: None,
            divide_mode: DivideMode::default(),
            subpixel: false,
            perspective_uv: false,
            texture_cache: true,
        }
    }
}
