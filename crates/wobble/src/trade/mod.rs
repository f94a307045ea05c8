//! `wobble trade`: what each piece of PS1 accuracy costs in time, and what dropping it
//! costs in wrong pixels, texel error and vertex jitter, measured on one scene against the
//! f64 reference renderer (docs/trade.md).

use crate::pipeline::{PipelineOptions, RenderError, Renderer, object_transform, prepare};
use crate::reference::{self, ReferenceFrame, rotation};
use crate::scene::Scene;
use crate::scene::texture::{Depth, Texture};
use gte::DivideMode;
use gte::typed::{Geometry, I16F16, Projection, Vector3};
use std::fmt;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The knob a report row turns, relative to the hardware-exact configuration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Knob {
    /// No knob: UNR divide, snapped vertices, affine UVs, dithering, no tessellation.
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
}

impl Knob {
    /// Every row of the report, in report order: the hardware-exact configuration first.
    pub const ALL: [Knob; 11] = [
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
        }
    }

    /// The pipeline options of the row.
    pub fn options(self) -> PipelineOptions {
        let hw = PipelineOptions::default();
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
        }
    }

    /// Whether the row belongs on the tessellation curve (level 0 is the hardware row).
    fn on_tessellation_curve(self) -> bool {
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

/// A scene whose textures encode their own texel coordinates (15-bit: R = u & 31,
/// G = v & 31, B = u >> 5 | (v >> 5) << 2, for textures up to 128 texels a side; larger
/// textures are encoded at half resolution), lit by nothing, unfogged, undithered, opaque: drawing it
/// through the pipeline shows which texel the hardware sampled at every pixel.
pub fn coordinate_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for t in &mut s.textures {
        let (w, h) = (t.texture.width, t.texture.height);
        let pixels: Vec<[u8; 4]> = (0..w as usize * h as usize)
            .map(|i| {
                let (u, v) = ((i % w as usize) as u32, (i / w as usize) as u32);
                let (u, v) = if w > 128 || h > 128 {
                    (u / 2, v / 2)
                } else {
                    (u, v)
                };
                let b = (u >> 5) | ((v >> 5) << 2);
                [
                    ((u & 31) << 3) as u8,
                    ((v & 31) << 3) as u8,
                    (b << 3) as u8,
                    255,
                ]
            })
            .collect();
        if let Ok(tex) = Texture::from_rgba(w, h, &pixels, Depth::Direct15) {
            t.texture = tex;
        }
    }
    s.light = None;
    s.fog = None;
    s.screen.dither = false;
    s.screen.background = [0, 0, 0];
    for o in &mut s.objects {
        o.blend = None;
        o.color = if o.texture.is_some() {
            [128, 128, 128]
        } else {
            [0, 0, 0]
        };
    }
    s
}

/// Decode a coordinate-scene pixel: `None` for background or untextured surfaces.
pub fn decode_texel(p: u16, scale: i32) -> Option<(i32, i32)> {
    if p == 0 {
        return None;
    }
    let (r, g, b) = (
        (p & 31) as i32,
        ((p >> 5) & 31) as i32,
        ((p >> 10) & 31) as i32,
    );
    Some((
        (r | (b & 3) << 5) * scale,
        (g | ((b >> 2) & 3) << 5) * scale,
    ))
}

fn frame_pixels(r: &Renderer) -> Vec<u16> {
    let area = r.display_area();
    let vram = r.gpu().vram();
    let mut out = Vec::with_capacity(area.width as usize * area.height as usize);
    for y in 0..area.height as usize {
        for x in 0..area.width as usize {
            out.push(vram.pixel(area.x as usize + x, area.y as usize + y));
        }
    }
    out
}

/// Distance between two texels of a texture that repeats every `size` texels: the shorter
/// way round, so a seam between repeats is not an error.
fn wrapped(d: i32, size: i32) -> f64 {
    let d = d.rem_euclid(size.max(1));
    d.min(size - d) as f64
}

/// Texel errors (Euclidean, in texels, repeat-aware) over pixels where both the hardware and
/// the reference show a textured surface.
pub fn texel_errors(hw: &[u16], reference: &ReferenceFrame, scale: i32) -> Vec<f64> {
    hw.iter()
        .zip(reference.texel.iter().zip(&reference.texture_size))
        .filter_map(|(&p, (r, size))| {
            let (hu, hv) = decode_texel(p, scale)?;
            let (ru, rv) = (*r)?;
            let (w, h) = (*size)?;
            let (du, dv) = (wrapped(hu - ru, w), wrapped(hv - rv, h));
            Some((du * du + dv * dv).sqrt())
        })
        .collect()
}

/// Per-pixel texel error image (black = exact, bright = large, blue = no comparison).
pub fn heat_map(hw: &[u16], reference: &ReferenceFrame, scale: i32) -> image::RgbImage {
    image::RgbImage::from_fn(reference.width as u32, reference.height as u32, |x, y| {
        let i = y as usize * reference.width + x as usize;
        match (
            decode_texel(hw[i], scale),
            reference.texel[i],
            reference.texture_size[i],
        ) {
            (Some((hu, hv)), Some((ru, rv)), Some((tw, th))) => {
                let (du, dv) = (wrapped(hu - ru, tw), wrapped(hv - rv, th));
                let e = (du * du + dv * dv).sqrt();
                let t = (e / 8.0).min(1.0);
                image::Rgb([
                    (255.0 * t) as u8,
                    (255.0 * (1.0 - (1.0 - t) * (1.0 - t))) as u8 / 2,
                    0,
                ])
            }
            _ => image::Rgb([0, 0, 40]),
        }
    })
}

/// A vertex's screen position, when it is on screen.
type ScreenPoint = Option<(f64, f64)>;

/// Mean frame-to-frame vertex displacement of the hardware projection minus the reference's
/// smooth motion, in pixels, over every mesh vertex in front of the camera.
pub fn vertex_jitter(scene: &Scene, mode: DivideMode, subpixel: bool, frames: u32) -> f64 {
    let (w, h) = (scene.screen.width as f64, scene.screen.height as f64);
    let hp = scene.camera.h as f64;
    let mut g = Geometry::new();
    if g.set_divide_mode(mode).is_err() {
        // A build without the knob cannot run this mode: NaN marks it as not measured.
        return f64::NAN;
    }
    g.set_projection(&Projection {
        offset_x: I16F16::from_num(scene.screen.width / 2),
        offset_y: I16F16::from_num(scene.screen.height / 2),
        h: scene.camera.h,
        ..Projection::default()
    });
    let view = rotation(scene.camera.rotation);
    let (mut sum, mut count) = (0.0, 0usize);
    for (index, object) in scene.objects.iter().enumerate() {
        let vertices: Vec<Vector3> = prepare(scene, index)
            .iter()
            .flat_map(|f| f.v[..if f.quad { 4 } else { 3 }].to_vec())
            .map(|v| v.position)
            .collect();
        let mut last: Option<(Vec<ScreenPoint>, Vec<ScreenPoint>)> = None;
        for frame in 0..frames {
            let (rt, tr) = object_transform(scene, object, frame);
            g.set_rotation(&rt);
            g.set_translation(tr);
            let rot = rotation(crate::pipeline::object_rotation(object, frame));
            let rel: [f64; 3] =
                std::array::from_fn(|i| object.position[i] - scene.camera.position[i]);
            let mut hw = Vec::with_capacity(vertices.len());
            let mut rf = Vec::with_capacity(vertices.len());
            for vertex in &vertices {
                let q = g.project_subpixel(*vertex);
                let p = [vertex.x as f64, vertex.y as f64, vertex.z as f64];
                let world: [f64; 3] =
                    std::array::from_fn(|r| (0..3).map(|c| rot[r][c] * p[c]).sum::<f64>() + rel[r]);
                let cam: [f64; 3] =
                    std::array::from_fn(|r| (0..3).map(|c| view[r][c] * world[c]).sum());
                let visible = cam[2] > hp / 2.0;
                let sx = w / 2.0 + hp * cam[0] / cam[2];
                let sy = h / 2.0 + hp * cam[1] / cam[2];
                let on_screen = visible && (0.0..w).contains(&sx) && (0.0..h).contains(&sy);
                // The GTE's 16.16 screen position before truncation, saturated to
                // -400h..3FFh.FFFFh: only positions whose reference lies on the screen count,
                // and those are well inside that range, so the saturation never applies.
                let position = if subpixel {
                    (q.x.to_num::<f64>(), q.y.to_num::<f64>())
                } else {
                    (f64::from(q.projected.x), f64::from(q.projected.y))
                };
                hw.push(on_screen.then_some(position));
                rf.push(on_screen.then_some((sx, sy)));
            }
            if let Some((lh, lr)) = &last {
                for i in 0..vertices.len() {
                    if let (Some(a), Some(b), Some(c), Some(d)) = (lh[i], hw[i], lr[i], rf[i]) {
                        let (dx, dy) = ((b.0 - a.0) - (d.0 - c.0), (b.1 - a.1) - (d.1 - c.1));
                        sum += (dx * dx + dy * dy).sqrt();
                        count += 1;
                    }
                }
            }
            last = Some((hw, rf));
        }
    }
    if count == 0 { 0.0 } else { sum / count as f64 }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// A long step [`write_report`] is starting; its `Display` is the line to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TradeProgress {
    /// Measuring every configuration.
    Measuring {
        /// Configurations measured.
        configurations: usize,
        /// Frames per configuration.
        frames: u32,
        /// Timing runs per configuration.
        repeats: u32,
    },
    /// The divide sweep over all 2^32 (H, SZ3) pairs.
    FullSweep,
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
                "sweeping the GTE divide over all 2^32 (H, SZ3) pairs in three modes (about a \
                 minute)"
            ),
        }
    }
}

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
            TradeError::Image { file, source } => write!(f, "{}: {source}", file.display()),
        }
    }
}

impl std::error::Error for TradeError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TradeError::Render(e) => Some(e),
            TradeError::Io { source, .. } => Some(source),
            TradeError::Image { source, .. } => Some(source),
        }
    }
}

impl From<RenderError> for TradeError {
    fn from(e: RenderError) -> Self {
        TradeError::Render(e)
    }
}

/// Measure every configuration on `scene`.
pub fn measure(
    scene: &Scene,
    settings: TradeSettings,
) -> Result<(Vec<Row>, Vec<image::RgbImage>), RenderError> {
    let frames = settings.frames.max(2);
    let refs: Vec<ReferenceFrame> = (0..frames).map(|f| reference::render(scene, f)).collect();
    let coords = coordinate_scene(scene);
    let scale = if scene
        .textures
        .iter()
        .any(|t| t.texture.width > 128 || t.texture.height > 128)
    {
        2
    } else {
        1
    };
    let mut rows = Vec::new();
    let mut heat = Vec::new();
    let mut baseline: Vec<Vec<u16>> = Vec::new();
    let mut baseline_ms = 0.0;
    for (k, config) in configs().into_iter().enumerate() {
        let mut renderer = Renderer::new(scene.clone(), config.options)?;
        let mut times = Vec::new();
        let mut drawn = 0usize;
        let mut images = Vec::new();
        for rep in 0..settings.repeats.max(1) {
            let start = Instant::now();
            for f in 0..frames {
                let s = renderer.render_frame(f);
                if rep == 0 {
                    drawn += s.drawn;
                    images.push(frame_pixels(&renderer));
                }
            }
            times.push(start.elapsed().as_secs_f64() * 1e3 / frames as f64);
        }
        let frame_ms = median(times);
        if k == 0 {
            baseline_ms = frame_ms;
            baseline = images.clone();
        }
        let differing_pixels = images
            .iter()
            .zip(&baseline)
            .map(|(a, b)| {
                a.iter()
                    .zip(b)
                    .filter(|(x, y)| (**x & 0x7FFF) != (**y & 0x7FFF))
                    .count()
            })
            .sum();
        let mut coord_renderer = Renderer::new(
            coords.clone(),
            PipelineOptions {
                dither: Some(false),
                ..config.options
            },
        )?;
        let mut errors = Vec::new();
        for (f, reference) in refs.iter().enumerate() {
            coord_renderer.render_frame(f as u32);
            let hw = frame_pixels(&coord_renderer);
            errors.extend(texel_errors(&hw, reference, scale));
            if f == 0 {
                heat.push(heat_map(&hw, reference, scale));
            }
        }
        let texel_mean = if errors.is_empty() {
            0.0
        } else {
            errors.iter().sum::<f64>() / errors.len() as f64
        };
        let texel_max = errors.iter().copied().fold(0.0, f64::max);
        rows.push(Row {
            knob: config.knob,
            name: config.name.to_string(),
            frame_ms,
            ratio: if baseline_ms > 0.0 {
                frame_ms / baseline_ms
            } else {
                1.0
            },
            drawn: drawn as f64 / frames as f64,
            differing_pixels,
            texel_mean,
            texel_max,
            jitter: vertex_jitter(
                scene,
                config.options.divide_mode,
                config.options.subpixel,
                frames,
            ),
        });
    }
    Ok((rows, heat))
}

/// Largest |screen error| in pixels, for a vertex at the extreme |IR| = 7FFFh, over a sweep
/// of every SZ3 and every `h_step`-th H (non-overflowing pairs), for each divide mode against
/// the real quotient H*65536/SZ3; and the quotient at the SZ3 -> 0 and H >= 2*SZ3 edges.
pub fn divide_stability(h_step: usize) -> Vec<(DivideMode, f64, u32, u32)> {
    [DivideMode::Unr, DivideMode::Exact, DivideMode::F32]
        .into_iter()
        .map(|mode| {
            let mut worst = 0.0f64;
            for h in (0..=0xFFFFu32).step_by(h_step.max(1)) {
                for sz3 in 1..=0xFFFFu32 {
                    if h >= 2 * sz3 {
                        continue;
                    }
                    let (q, _) = gte::unr::divide(mode, h as u16, sz3 as u16);
                    let real = (h as f64 * 65536.0 / sz3 as f64).min(0x1FFFF as f64);
                    worst = worst.max((q as f64 - real).abs() * 32767.0 / 65536.0);
                }
            }
            let (at_zero, _) = gte::unr::divide(mode, 1000, 0);
            let (at_edge, _) = gte::unr::divide(mode, 1000, 500);
            (mode, worst, at_zero, at_edge)
        })
        .collect()
}

/// Draw error-against-cost points for the tessellation levels as a small chart (x: frame
/// time, y: mean texel error; axes from zero; one dot per level joined in order).
pub fn curve_image(points: &[(f64, f64)]) -> image::RgbImage {
    let (w, h, m) = (480u32, 320u32, 40i32);
    let mut img = image::RgbImage::from_pixel(w, h, image::Rgb([255, 255, 255]));
    let max_x = points.iter().map(|p| p.0).fold(1e-9, f64::max) * 1.1;
    let max_y = points.iter().map(|p| p.1).fold(1e-9, f64::max) * 1.1;
    let to_px = |p: (f64, f64)| {
        (
            m + ((p.0 / max_x) * (w as i32 - 2 * m) as f64) as i32,
            h as i32 - m - ((p.1 / max_y) * (h as i32 - 2 * m) as f64) as i32,
        )
    };
    let mut put = |x: i32, y: i32, c: [u8; 3]| {
        if x >= 0 && y >= 0 && (x as u32) < w && (y as u32) < h {
            img.put_pixel(x as u32, y as u32, image::Rgb(c));
        }
    };
    for x in m..w as i32 - m {
        put(x, h as i32 - m, [0, 0, 0]);
    }
    for y in m..h as i32 - m {
        put(m, y, [0, 0, 0]);
    }
    // Tick marks with numeric labels at 0, a half and the whole of each axis.
    for k in 0..=2 {
        let fx = max_x * k as f64 / 2.0;
        let fy = max_y * k as f64 / 2.0;
        let (tx, _) = to_px((fx, 0.0));
        let (_, ty) = to_px((0.0, fy));
        for d in 0..6 {
            put(tx, h as i32 - m + d, [0, 0, 0]);
            put(m - d, ty, [0, 0, 0]);
        }
        let label_x = format!("{fx:.2}");
        draw_text(
            &mut put,
            tx - 3 * label_x.len() as i32,
            h as i32 - m + 10,
            &label_x,
        );
        let label_y = format!("{fy:.1}");
        draw_text(&mut put, m - 8 - 6 * label_y.len() as i32, ty - 3, &label_y);
    }
    for pair in points.windows(2) {
        let (a, b) = (to_px(pair[0]), to_px(pair[1]));
        let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).max(1);
        for i in 0..=n {
            put(
                a.0 + (b.0 - a.0) * i / n,
                a.1 + (b.1 - a.1) * i / n,
                [40, 90, 200],
            );
        }
    }
    for &p in points {
        let (x, y) = to_px(p);
        for dy in -3..=3 {
            for dx in -3..=3 {
                put(x + dx, y + dy, [200, 40, 40]);
            }
        }
    }
    img
}

/// 3x5 pixel glyphs for digits and the decimal point, rows top to bottom, 3 bits a row.
const GLYPHS: [(char, [u8; 5]); 11] = [
    ('0', [7, 5, 5, 5, 7]),
    ('1', [2, 6, 2, 2, 7]),
    ('2', [7, 1, 7, 4, 7]),
    ('3', [7, 1, 7, 1, 7]),
    ('4', [5, 5, 7, 1, 1]),
    ('5', [7, 4, 7, 1, 7]),
    ('6', [7, 4, 7, 5, 7]),
    ('7', [7, 1, 1, 1, 1]),
    ('8', [7, 5, 7, 5, 7]),
    ('9', [7, 5, 7, 1, 7]),
    ('.', [0, 0, 0, 0, 2]),
];

/// Draw `text` (digits and '.') at (x, y), each glyph pixel doubled.
fn draw_text(put: &mut impl FnMut(i32, i32, [u8; 3]), x: i32, y: i32, text: &str) {
    for (i, ch) in text.chars().enumerate() {
        let Some((_, rows)) = GLYPHS.iter().find(|(c, _)| *c == ch) else {
            continue;
        };
        for (r, bits) in rows.iter().enumerate() {
            for c in 0..3 {
                if bits >> (2 - c) & 1 == 1 {
                    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                        put(
                            x + i as i32 * 8 + c * 2 + dx,
                            y + r as i32 * 2 + dy,
                            [0, 0, 0],
                        );
                    }
                }
            }
        }
    }
}

fn side_by_side(a: &image::RgbImage, b: &image::RgbImage) -> image::RgbImage {
    let (w, h) = a.dimensions();
    image::RgbImage::from_fn(w * 2 + 8, h, |x, y| {
        if x < w {
            *a.get_pixel(x, y)
        } else if x < w + 8 {
            image::Rgb([255, 255, 255])
        } else {
            *b.get_pixel((x - w - 8).min(w - 1), y)
        }
    })
}

/// Slug for file names.
fn slug(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    while s.contains("--") {
        s = s.replace("--", "-");
    }
    let s: String = s.trim_matches('-').chars().take(40).collect();
    s.trim_end_matches('-').to_string()
}

/// Measure, then write `<out>/trade.md` and its images under `<out>/trade/`.
pub fn write_report(
    scene: &Scene,
    scene_name: &str,
    settings: TradeSettings,
    out: &Path,
    progress: &mut dyn FnMut(TradeProgress),
) -> Result<Vec<Row>, TradeError> {
    let images_dir = out.join("trade");
    std::fs::create_dir_all(&images_dir).map_err(|source| TradeError::Io {
        file: images_dir.clone(),
        source,
    })?;
    progress(TradeProgress::Measuring {
        configurations: configs().len(),
        frames: settings.frames.max(2),
        repeats: settings.repeats.max(1),
    });
    let (rows, heat) = measure(scene, settings)?;
    let save = |img: &image::RgbImage, name: &str| -> Result<(), TradeError> {
        let p = images_dir.join(name);
        img.save_with_format(&p, image::ImageFormat::Png)
            .map_err(|source| TradeError::Image { file: p, source })
    };
    let mut hw = Renderer::new(scene.clone(), PipelineOptions::default())?;
    hw.render_frame(0);
    let reference = reference::render(scene, 0);
    save(
        &side_by_side(&hw.image(), &reference.image()),
        "hardware-vs-reference.png",
    )?;
    for (row, img) in rows.iter().zip(&heat) {
        save(img, &format!("heat-{}.png", slug(&row.name)))?;
    }
    let curve: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.knob.on_tessellation_curve())
        .map(|r| (r.frame_ms, r.texel_mean))
        .collect();
    save(&curve_image(&curve), "tessellation-curve.png")?;
    if settings.sweep_step <= 1 {
        progress(TradeProgress::FullSweep);
    }
    let stability = divide_stability(settings.sweep_step);

    let mut md = String::new();
    let _ = writeln!(md, "# The accuracy trade, measured\n");
    let _ = writeln!(
        md,
        "Scene: {scene_name}, {}x{}, {} consecutive frames; times are the median of {} runs of \
         all frames, measured one configuration after another in the same process. Generated \
         by `wobble trade`; regenerate with `cargo run --release -- trade --out docs`.\n",
        scene.screen.width,
        scene.screen.height,
        settings.frames.max(2),
        settings.repeats.max(1)
    );
    let _ = writeln!(
        md,
        "| configuration | ms/frame | vs hardware | polygons drawn | pixels differing from hardware | mean texel error | max texel error | vertex jitter (px) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {:.3} | {:.2}x | {:.0} | {} | {:.3} | {:.2} | {:.3} |",
            r.name,
            r.frame_ms,
            r.ratio,
            r.drawn,
            r.differing_pixels,
            r.texel_mean,
            r.texel_max,
            r.jitter
        );
    }
    let _ = writeln!(md, "\n## What the columns mean\n");
    let _ = writeln!(
        md,
        "- **pixels differing from hardware**: pixels of the displayed frames whose 15-bit colour \
         differs from the hardware-exact configuration's, summed over the frames.\n\
         - **texel error**: per pixel where both the hardware pipeline and the reference renderer \
         show a textured surface, the distance in texels between the texel the GPU sampled \
         (read back by drawing the scene with textures that encode their own coordinates) and \
         the texel the reference samples (perspective-correct, sub-pixel vertices, exact \
         trigonometry and division, near-plane clipping, z-buffer). Pixels where the two show \
         different surfaces count too, so occlusion and dropped polygons add to the error.\n\
         - **vertex jitter**: for every vertex on screen, the frame-to-frame screen displacement \
         of the GTE's snapped projection minus that of the exact projection, averaged."
    );
    let _ = writeln!(md, "\n## Pictures\n");
    let _ = writeln!(
        md,
        "Hardware-exact (left) and reference (right), frame 0:\n"
    );
    let _ = writeln!(
        md,
        "![hardware vs reference](trade/hardware-vs-reference.png)\n"
    );
    let _ = writeln!(
        md,
        "Texel-error heat maps, frame 0 (black: exact, red to yellow: up to 8 texels and more, \
         dark blue: no textured surface in one of the two):\n"
    );
    for r in &rows {
        let _ = writeln!(
            md,
            "- {}: ![{}](trade/heat-{}.png)",
            r.name,
            r.name,
            slug(&r.name)
        );
    }
    let _ = writeln!(
        md,
        "\nError against cost across tessellation levels 0-4 (x: ms per frame from 0, y: mean \
         texel error from 0; one dot per level joined in level order 0 to 4; tick labels in those units):\n"
    );
    let _ = writeln!(md, "![tessellation curve](trade/tessellation-curve.png)\n");
    for r in rows.iter().filter(|r| r.knob.on_tessellation_curve()) {
        let _ = writeln!(
            md,
            "- {}: {:.3} ms, mean texel error {:.3}",
            r.name, r.frame_ms, r.texel_mean
        );
    }
    let _ = writeln!(md, "\n## Numerical stability of the GTE divide\n");
    let _ = writeln!(
        md,
        "Largest screen error of a vertex at the extreme |IR| = 7FFFh caused by each divide \
         mode's quotient against the real H*65536/SZ3, over every SZ3 and {} \
         (non-overflowing pairs), and the quotient at the edges (SZ3 = 0 and H = 2*SZ3 \
         overflow in every mode: 1FFFFh and FLAG.17, a saturated value, never garbage):\n",
        if settings.sweep_step <= 1 {
            "every H: all 2^32 pairs".to_string()
        } else {
            format!("every {}th H", settings.sweep_step)
        }
    );
    let _ = writeln!(
        md,
        "| divide | max screen error (px) | H=1000, SZ3=0 | H=1000, SZ3=500 |"
    );
    let _ = writeln!(md, "|---|---|---|---|");
    for (mode, worst, z, e) in &stability {
        let _ = writeln!(md, "| {mode:?} | {worst:.3} | {z:05X}h | {e:05X}h |");
    }
    let tess: Vec<&Row> = rows
        .iter()
        .filter(|r| matches!(r.knob, Knob::Tessellation(_)))
        .collect();
    let base = &rows[0];
    let _ = writeln!(md, "\n## Conclusion\n");
    let _ = writeln!(md, "{}", conclusion(base, &rows, &tess));
    let path = out.join("trade.md");
    std::fs::write(&path, md).map_err(|source| TradeError::Io { file: path, source })?;
    Ok(rows)
}

/// A short conclusion drawn from the figures.
fn conclusion(base: &Row, rows: &[Row], tess: &[&Row]) -> String {
    let find = |k: Knob| rows.iter().find(|r| r.knob == k);
    let mut out = String::new();
    if let (Some(e), Some(f)) = (find(Knob::DivideExact), find(Knob::DivideF32)) {
        let _ = writeln!(
            out,
            "- The GTE's UNR divide is not where the error comes from: exact and f32 division \
             change {} and {} pixels, move the mean texel error from {:.3} to {:.3} / {:.3} and \
             the jitter from {:.3} to {:.3} / {:.3} px, at {:.2}x / {:.2}x the time.",
            e.differing_pixels,
            f.differing_pixels,
            base.texel_mean,
            e.texel_mean,
            f.texel_mean,
            base.jitter,
            e.jitter,
            f.jitter,
            e.ratio,
            f.ratio
        );
    }
    if let Some(d) = find(Knob::DitherOff) {
        let _ = writeln!(
            out,
            "- Dithering changes {} pixels' colour and nothing about geometry or texels (texel \
             error {:.3}); without it a frame takes {:.2}x the time.",
            d.differing_pixels, d.texel_mean, d.ratio
        );
    }
    if let (Some(first), Some(last)) = (tess.first(), tess.last()) {
        let _ = writeln!(
            out,
            "- Tessellation is the hardware's lever: the mean texel error goes from {:.3} (level 0) \
             through {:.3} (level 1) to {:.3} (level 4) while the frame time goes from {:.3} ms \
             to {:.3} ms ({:.2}x) and the polygon count from {:.0} to {:.0}; past level 2 it buys \
             almost nothing. Affine mapping and vertex snapping, not arithmetic precision, are \
             what separate the PS1 image from the intended one.",
            base.texel_mean,
            first.texel_mean,
            last.texel_mean,
            base.frame_ms,
            last.frame_ms,
            last.ratio,
            base.drawn,
            last.drawn
        );
    }
    if let (Some(sp), Some(pc), Some(both)) = (
        find(Knob::Subpixel),
        find(Knob::PerspectiveUv),
        find(Knob::SubpixelPerspective),
    ) {
        let best_tess = tess
            .iter()
            .min_by(|a, b| a.texel_mean.total_cmp(&b.texel_mean));
        let _ = writeln!(
            out,
            "- Perspective-correct texture coordinates alone take the mean texel error from {:.3} to {:.3}{}; sub-pixel vertices alone barely move it ({:.3}) but cut the vertex jitter from {:.3} to {:.3} px; together they reach {:.3}. These two are the modern-GPU fixes, and the measurements say both are worth having in a non-hardware path: the crate's precise path is a straightforward integer rasterizer at {:.2}x / {:.2}x / {:.2}x the hardware path's time here, which a span-based implementation would reduce.",
            base.texel_mean,
            pc.texel_mean,
            best_tess.map_or(String::new(), |t| format!(
                ", better than the best tessellation level ({:.3}, {})",
                t.texel_mean, t.name
            )),
            sp.texel_mean,
            base.jitter,
            sp.jitter,
            both.texel_mean,
            sp.ratio,
            pc.ratio,
            both.ratio
        );
    }
    let _ = writeln!(
        out,
        "- On the hardware path, vertex jitter ({:.3} px a frame on average) comes from the \
         integer snapping of screen coordinates; only sub-pixel positions remove it.",
        base.jitter
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows as `measure` would return them, with distinct figures per row.
    fn synthetic_rows() -> Vec<Row> {
        configs()
            .iter()
            .zip(1..)
            .map(|(c, i)| Row {
                knob: c.knob,
                name: c.name.to_string(),
                frame_ms: f64::from(i),
                ratio: f64::from(i),
                drawn: f64::from(i),
                differing_pixels: i as usize,
                texel_mean: f64::from(i),
                texel_max: f64::from(i),
                jitter: f64::from(i),
            })
            .collect()
    }

    #[test]
    fn every_knob_has_one_row_with_a_distinct_label() {
        let rows = configs();
        assert_eq!(rows.len(), Knob::ALL.len());
        assert_eq!(rows[0].knob, Knob::Hardware);
        let labels: std::collections::HashSet<_> = rows.iter().map(|c| c.name).collect();
        assert_eq!(labels.len(), rows.len());
    }

    #[test]
    fn every_knob_yields_its_paragraph_whatever_the_labels() {
        let mut rows = synthetic_rows();
        for r in &mut rows {
            r.name = format!("renamed {:?}", r.knob);
        }
        let tess: Vec<&Row> = rows
            .iter()
            .filter(|r| matches!(r.knob, Knob::Tessellation(_)))
            .collect();
        let text = conclusion(&rows[0], &rows, &tess);
        let paragraphs: Vec<&str> = text.lines().filter(|l| l.starts_with("- ")).collect();
        // Divide (exact, f32), dithering, tessellation (1-4), sub-pixel/perspective, jitter.
        assert_eq!(paragraphs.len(), 5, "{text}");
        for needle in [
            "- The GTE's UNR divide",
            "- Dithering changes",
            "- Tessellation is the hardware's lever",
            "- Perspective-correct texture coordinates",
            "- On the hardware path",
        ] {
            assert!(text.contains(needle), "missing {needle:?} in {text}");
        }
        // The divide paragraph quotes the exact (row 2) and f32 (row 3) figures; the
        // tessellation paragraph quotes level 4 (row 11) polygons.
        assert!(text.contains("change 2 and 3 pixels"), "{text}");
        assert!(text.contains("from 1 to 11"), "{text}");
    }

    #[test]
    fn a_missing_row_drops_only_its_paragraph() {
        let rows: Vec<Row> = synthetic_rows()
            .into_iter()
            .filter(|r| r.knob != Knob::DitherOff)
            .collect();
        let tess: Vec<&Row> = rows
            .iter()
            .filter(|r| matches!(r.knob, Knob::Tessellation(_)))
            .collect();
        let text = conclusion(&rows[0], &rows, &tess);
        assert!(!text.contains("Dithering changes"));
        assert_eq!(text.lines().filter(|l| l.starts_with("- ")).count(), 4);
    }
}
