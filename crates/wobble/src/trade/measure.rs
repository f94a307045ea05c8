//! The measurements of the trade report: timing, differing pixels, texel error against the
//! reference renderer, vertex jitter, and the divide sweep.

use super::heat::heat_map;
use super::texel_error::{coordinate_scene, texel_errors};
use super::{Knob, Row, TradeSettings, configs};
use crate::pipeline::{PipelineOptions, RenderError, Renderer, UnsupportedKnob, object_transform};
use crate::reference::{self, ReferenceFrame, rotation};
use crate::scene::Scene;
use crate::scene::prepared::prepare;
use gte::typed::{Geometry, I16F16, Projection, Vector3};
use gte::{DivideMode, UnsupportedDivideMode};
use std::time::Instant;

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

/// A vertex's screen position, when it is on screen.
type ScreenPoint = Option<(f64, f64)>;

/// Mean frame-to-frame vertex displacement of the hardware projection minus the reference's
/// smooth motion, in pixels, over every mesh vertex in front of the camera. A divide mode
/// this build does not include is an error.
pub fn vertex_jitter(
    scene: &Scene,
    mode: DivideMode,
    subpixel: bool,
    frames: u32,
) -> Result<f64, UnsupportedDivideMode> {
    let (w, h) = (scene.screen.width as f64, scene.screen.height as f64);
    let hp = scene.camera.h as f64;
    let mut g = Geometry::new();
    g.set_divide_mode(mode)?;
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
            .faces
            .iter()
            .flat_map(|f| f.v[..if f.quad { 4 } else { 3 }].to_vec())
            .map(|v| v.position)
            .collect();
        let mut last: Option<(Vec<ScreenPoint>, Vec<ScreenPoint>)> = None;
        for frame in 0..frames {
            let (rt, tr) = object_transform(scene, object, frame);
            g.set_rotation(&rt);
            g.set_translation(tr);
            let rot = rotation(object.rotation_at(frame));
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
    Ok(if count == 0 { 0.0 } else { sum / count as f64 })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// The figures of every configuration this build can run, the frame-0 heat map of each
/// (same order), and the rows it cannot run.
#[derive(Clone, Debug, Default)]
pub struct Measurement {
    /// Measured rows, hardware first, in [`Knob::ALL`] order.
    pub rows: Vec<Row>,
    /// Texel-error heat map of frame 0, one per row of `rows`.
    pub heat: Vec<image::RgbImage>,
    /// Rows left out because this build or mode cannot run them.
    pub skipped: Vec<Skipped>,
}

/// A report row that was not measured.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// The knob of the row.
    pub knob: Knob,
    /// Why it was not measured (names the missing feature).
    pub reason: String,
}

/// Measure every configuration on `scene`. Configurations this build cannot run (a knob
/// behind the `accuracy-knobs` feature) are listed in [`Measurement::skipped`]; any other
/// renderer error ends the measurement.
pub fn measure(scene: &Scene, settings: TradeSettings) -> Result<Measurement, RenderError> {
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
    let mut out = Measurement::default();
    let mut baseline: Vec<Vec<u16>> = Vec::new();
    let mut baseline_ms = 0.0;
    for config in configs() {
        let mut renderer = match Renderer::new(scene.clone(), config.options) {
            Ok(r) => r,
            Err(RenderError::Unsupported(e)) => {
                out.skipped.push(Skipped {
                    knob: config.knob,
                    reason: e.to_string(),
                });
                continue;
            }
            Err(e) => return Err(e),
        };
        let jitter = match vertex_jitter(
            scene,
            config.options.divide_mode,
            config.options.subpixel,
            frames,
        ) {
            Ok(j) => j,
            Err(e) => {
                out.skipped.push(Skipped {
                    knob: config.knob,
                    reason: UnsupportedKnob::Divide(e.0).to_string(),
                });
                continue;
            }
        };
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
        if config.knob == Knob::Hardware {
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
                out.heat.push(heat_map(&hw, reference, scale));
            }
        }
        let texel_mean = if errors.is_empty() {
            0.0
        } else {
            errors.iter().sum::<f64>() / errors.len() as f64
        };
        let texel_max = errors.iter().copied().fold(0.0, f64::max);
        out.rows.push(Row {
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
            jitter,
        });
    }
    Ok(out)
}

/// Largest |screen error| in pixels, for a vertex at the extreme |IR| = 7FFFh, over a sweep
/// of every SZ3 and every `h_step`-th H (non-overflowing pairs), for each divide mode against
/// the real quotient H*65536/SZ3; and the quotient at the SZ3 -> 0 and H >= 2*SZ3 edges.
/// `progress(done, total)` is called after each row (one mode, one H, every SZ3).
pub fn divide_stability(
    h_step: usize,
    progress: &mut dyn FnMut(u64, u64),
) -> Vec<(DivideMode, f64, u32, u32)> {
    const MODES: [DivideMode; 3] = [DivideMode::Unr, DivideMode::Exact, DivideMode::F32];
    let step = h_step.max(1);
    let rows_per_mode = 0xFFFF / step as u64 + 1;
    let total = rows_per_mode * MODES.len() as u64;
    let mut done = 0u64;
    MODES
        .into_iter()
        .map(|mode| {
            let mut worst = 0.0f64;
            for h in (0..=0xFFFFu32).step_by(step) {
                for sz3 in 1..=0xFFFFu32 {
                    if h >= 2 * sz3 {
                        continue;
                    }
                    let (q, _) = gte::unr::divide(mode, h as u16, sz3 as u16);
                    let real = (h as f64 * 65536.0 / sz3 as f64).min(0x1FFFF as f64);
                    worst = worst.max((q as f64 - real).abs() * 32767.0 / 65536.0);
                }
                done += 1;
                progress(done, total);
            }
            let (at_zero, _) = gte::unr::divide(mode, 1000, 0);
            let (at_edge, _) = gte::unr::divide(mode, 1000, 500);
            (mode, worst, at_zero, at_edge)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep reports every row once, in order, against the total: H = 0, 30000, 60000
    /// (three values of 0..=FFFFh at step 30000) in each of three modes, nine rows.
    #[test]
    fn divide_sweep_reports_each_row() {
        let mut seen = Vec::new();
        let result = divide_stability(30000, &mut |done, total| seen.push((done, total)));
        assert_eq!(result.len(), 3);
        let want: Vec<(u64, u64)> = (1..=9).map(|d| (d, 9)).collect();
        assert_eq!(seen, want);
    }
}
