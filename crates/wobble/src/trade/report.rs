//! The trade report's markdown (`trade.md`) and the files it links to.

use super::charts::{curve_image, side_by_side};
use super::heat::{colour_words, with_colour_bar};
use super::measure::{Measurement, Skipped, divide_stability, measure};
use super::{Knob, Row, TradeError, TradeProgress, TradeSettings, configs};
use crate::pipeline::{PipelineOptions, Renderer};
use crate::reference;
use crate::scene::Scene;
use std::fmt::Write as _;
use std::path::Path;

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
    let Measurement {
        rows,
        heat,
        skipped,
    } = measure(scene, settings)?;
    let save = |img: &image::RgbImage, name: &str| -> Result<(), TradeError> {
        let p = images_dir.join(name);
        img.save_with_format(&p, image::ImageFormat::Png)
            .map_err(|source| TradeError::Image { file: p, source })
    };
    let chart_error = |name: &str| {
        let file = images_dir.join(name);
        move |message| TradeError::Chart { file, message }
    };
    let mut hw = Renderer::new(scene.clone(), PipelineOptions::default())?;
    hw.render_frame(0);
    let reference = reference::render(scene, 0);
    let pair_name = "hardware-vs-reference.png";
    let pair =
        side_by_side(&hw.image(), &reference.image(), HALVES).map_err(chart_error(pair_name))?;
    save(&pair, pair_name)?;
    for (row, img) in rows.iter().zip(&heat) {
        let name = format!("heat-{}.png", slug(&row.name));
        let map = with_colour_bar(img).map_err(chart_error(&name))?;
        save(&map, &name)?;
    }
    let curve: Vec<(u8, f64, f64)> = rows
        .iter()
        .filter_map(|r| match r.knob {
            Knob::Hardware => Some((0, r.frame_ms, r.texel_mean)),
            Knob::Tessellation(level) => Some((level, r.frame_ms, r.texel_mean)),
            _ => None,
        })
        .collect();
    let curve_name = "tessellation-curve.png";
    let chart = curve_image(&curve).map_err(chart_error(curve_name))?;
    save(&chart, curve_name)?;
    if settings.sweep_step <= 1 {
        progress(TradeProgress::FullSweep);
    }
    let stability = divide_stability(settings.sweep_step, &mut |done, total| {
        progress(TradeProgress::Sweep { done, total })
    });

    let mut md = String::new();
    let _ = writeln!(md, "# The accuracy trade, measured\n");
    let _ = writeln!(
        md,
        "Scene: {scene_name}, {}x{}, {} consecutive frames; times are the median of {} runs of \
         all frames, measured one configuration after another in the same process. Generated \
         by `wobble trade`; regenerate with `cargo run --release -- trade -o docs`.\n",
        scene.screen.width,
        scene.screen.height,
        settings.frames.max(2),
        settings.repeats.max(1)
    );
    if let Some(load) = machine_load() {
        let _ = writeln!(md, "{load}\n");
    }
    md.push_str(&figures_table(&rows, &skipped));
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
        "Frame 0: on the left the {}, on the right the {}, each half labelled in the \
         image:\n",
        HALVES[0], HALVES[1]
    );
    let _ = writeln!(
        md,
        "![hardware vs reference](trade/hardware-vs-reference.png)\n"
    );
    let _ = writeln!(
        md,
        "Texel-error heat maps, frame 0, each with its colour bar ({}):\n",
        colour_words()
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
         texel error from 0; one dot per level joined in level order 0 to 4, each labelled \
         with its level):\n"
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
    if rows.iter().any(|r| r.knob == Knob::Hardware) {
        let _ = writeln!(md, "\n## Conclusion\n");
        let _ = writeln!(md, "{}", conclusion(&rows));
    }
    let path = out.join("trade.md");
    std::fs::write(&path, md).map_err(|source| TradeError::Io { file: path, source })?;
    Ok(rows)
}

/// How busy the machine was when the report was measured, from the Linux load average
/// (`/proc/loadavg`, the one-minute figure) against the processors available: timings taken
/// on a loaded machine are only indicative. `None` where the load cannot be read.
fn machine_load() -> Option<String> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    let load: f64 = text.split_whitespace().next()?.parse().ok()?;
    let cpus = std::thread::available_parallelism().ok()?.get();
    let verdict = if load < 0.5 * cpus as f64 {
        "a quiet machine"
    } else {
        "a busy machine: the time columns (ms/frame, vs hardware) are only indicative, the \
         other columns do not depend on it"
    };
    Some(format!(
        "Measured at a load average of {load:.1} on {cpus} processors, {verdict}."
    ))
}

/// The labels of the two halves of `hardware-vs-reference.png`.
pub const HALVES: [&str; 2] = ["PS1 hardware path (GTE + GPU)", "f64 reference renderer"];

/// The figures table of `trade.md`, then a note listing the rows this build did not measure.
pub fn figures_table(rows: &[Row], skipped: &[Skipped]) -> String {
    let mut md = String::new();
    let _ = writeln!(
        md,
        "| configuration | ms/frame | vs hardware | polygons drawn | pixels differing from hardware | mean texel error | max texel error | vertex jitter (px) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|");
    for r in rows {
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
    if !skipped.is_empty() {
        let _ = writeln!(md, "\nNot measured in this build:\n");
        for s in skipped {
            let _ = writeln!(md, "- {}: {}", s.knob.label(), s.reason);
        }
    }
    md
}

/// A change from the hardware figure of at most this fraction of it (5%) is called no real
/// change: "barely", "not where the error comes from", "buys almost nothing".
pub const SMALL_CHANGE: f64 = 0.05;

/// Whether going from `from` to `to` is a [`SMALL_CHANGE`].
fn small(from: f64, to: f64) -> bool {
    (to - from).abs() <= SMALL_CHANGE * from.abs()
}

/// `a` against `b` as the report prints them (three decimals): less, equal or greater.
fn printed_cmp(a: f64, b: f64) -> std::cmp::Ordering {
    let r = |v: f64| (v * 1000.0).round();
    r(a).total_cmp(&r(b))
}

/// "1 pixel", "2 pixels", "no pixel".
fn pixels(n: usize) -> String {
    match n {
        0 => "no pixel".to_string(),
        1 => "1 pixel".to_string(),
        n => format!("{n} pixels"),
    }
}

/// The conclusion of `trade.md`: one paragraph per group of rows present, every comparison
/// in it (better, worse, barely, only, not where the error comes from, ...) decided from the
/// figures of `rows`, which must hold the hardware row.
pub fn conclusion(rows: &[Row]) -> String {
    use std::cmp::Ordering::{Equal, Greater, Less};
    let find = |k: Knob| rows.iter().find(|r| r.knob == k);
    let Some(base) = find(Knob::Hardware) else {
        return String::new();
    };
    let mut tess: Vec<(u8, &Row)> = rows
        .iter()
        .filter_map(|r| match r.knob {
            Knob::Tessellation(level) => Some((level, r)),
            _ => None,
        })
        .collect();
    tess.sort_by_key(|t| t.0);
    let mut out = String::new();
    let divide = find(Knob::DivideExact).zip(find(Knob::DivideF32));
    if let Some((e, f)) = divide {
        let negligible = [e, f]
            .iter()
            .all(|r| small(base.texel_mean, r.texel_mean) && small(base.jitter, r.jitter));
        let lead = if negligible {
            "The GTE's UNR divide is not where the error comes from"
        } else {
            "The GTE's UNR divide matters on this scene"
        };
        let changed = if e.differing_pixels == f.differing_pixels {
            format!("each change {}", pixels(e.differing_pixels))
        } else {
            format!(
                "change {} and {} pixels",
                e.differing_pixels, f.differing_pixels
            )
        };
        let _ = writeln!(
            out,
            "- {lead}: exact and f32 division {changed}, move the mean texel error from {:.3} \
             to {:.3} / {:.3} and the jitter from {:.3} to {:.3} / {:.3} px{}, at {:.2}x / \
             {:.2}x the time.",
            base.texel_mean,
            e.texel_mean,
            f.texel_mean,
            base.jitter,
            e.jitter,
            f.jitter,
            if negligible {
                format!(" (each within {:.0}%)", SMALL_CHANGE * 100.0)
            } else {
                String::new()
            },
            e.ratio,
            f.ratio
        );
    }
    if let Some(d) = find(Knob::DitherOff) {
        let geometry = if d.texel_mean == base.texel_mean
            && d.texel_max == base.texel_max
            && d.jitter == base.jitter
        {
            format!(
                " and nothing about geometry or texels (mean texel error {:.3}, as with it)",
                d.texel_mean
            )
        } else {
            format!(
                " and also moves the mean texel error from {:.3} to {:.3}",
                base.texel_mean, d.texel_mean
            )
        };
        let _ = writeln!(
            out,
            "- Dithering changes the colour of {}{geometry}; without it a frame takes {:.2}x \
             the time.",
            pixels(d.differing_pixels),
            d.ratio
        );
    }
    if let Some(&(_, last)) = tess.last() {
        let levels: Vec<(u8, &Row)> = std::iter::once((0, base))
            .chain(tess.iter().copied())
            .collect();
        let list: Vec<String> = levels
            .iter()
            .map(|(l, r)| format!("{:.3} (level {l})", r.texel_mean))
            .collect();
        let best = levels
            .iter()
            .min_by(|a, b| a.1.texel_mean.total_cmp(&b.1.texel_mean))
            .copied()
            .unwrap_or((0, base));
        let costs = format!(
            "the frame time goes from {:.3} ms to {:.3} ms ({:.2}x) and the polygon count from \
             {:.0} to {:.0}",
            base.frame_ms, last.frame_ms, last.ratio, base.drawn, last.drawn
        );
        let mut text = if printed_cmp(best.1.texel_mean, base.texel_mean) == Less {
            format!(
                "- Tessellation is the hardware's lever: the mean texel error goes {} while {costs}",
                list.join(", ")
            )
        } else {
            format!(
                "- Tessellation does not lower the mean texel error here ({}), while {costs}",
                list.join(", ")
            )
        };
        let gain = base.texel_mean - best.1.texel_mean;
        if gain > 0.0
            && let Some(&(k, at)) = levels
                .iter()
                .find(|(_, r)| r.texel_mean - best.1.texel_mean <= SMALL_CHANGE * gain)
            && k < levels.last().map_or(0, |l| l.0)
        {
            let _ = write!(
                text,
                "; past level {k} it buys almost nothing (level {k} is {:.3} above the best, \
                 {:.3}, of a {:.3} gain)",
                at.texel_mean - best.1.texel_mean,
                best.1.texel_mean,
                gain
            );
        }
        let same: Vec<String> = levels
            .windows(2)
            .filter(|w| w[0].1.drawn == w[1].1.drawn && w[0].0 > 0)
            .map(|w| format!("levels {} and {}", w[0].0, w[1].0))
            .collect();
        if !same.is_empty() {
            let _ = write!(
                text,
                "; {} draw the same number of polygons",
                same.join(", ")
            );
        }
        let _ = writeln!(out, "{text}.");
    }
    let precise = find(Knob::Subpixel)
        .zip(find(Knob::PerspectiveUv))
        .zip(find(Knob::SubpixelPerspective))
        .map(|((sp, pc), both)| (sp, pc, both));
    if let (Some((e, f)), Some((sp, pc, both))) = (divide, precise) {
        let arithmetic = e.texel_mean.min(f.texel_mean);
        let geometry = [sp, pc, both]
            .iter()
            .map(|r| r.texel_mean)
            .fold(f64::INFINITY, f64::min);
        let figures = format!(
            "perspective-correct coordinates and sub-pixel vertices take the mean texel error \
             from {:.3} to {geometry:.3}, exact or f32 division to {arithmetic:.3}",
            base.texel_mean
        );
        let lead = match printed_cmp(geometry, arithmetic) {
            Less => {
                "Affine mapping and vertex snapping, not arithmetic precision, are what \
                     separate the PS1 image from the reference"
            }
            Greater => {
                "Arithmetic precision, more than affine mapping and vertex snapping, \
                        separates the PS1 image from the reference"
            }
            Equal => {
                "Arithmetic precision and affine mapping with vertex snapping weigh the \
                      same here"
            }
        };
        let _ = writeln!(out, "- {lead}: {figures}.");
    }
    if let Some((sp, pc, both)) = precise {
        let best_tess = tess
            .iter()
            .map(|t| t.1)
            .min_by(|a, b| a.texel_mean.total_cmp(&b.texel_mean));
        let against_tess = best_tess.map_or(String::new(), |t| {
            let word = match printed_cmp(pc.texel_mean, t.texel_mean) {
                Less => "better than",
                Equal => "as good as",
                Greater => "worse than",
            };
            format!(
                ", {word} the best tessellation level ({:.3}, {})",
                t.texel_mean, t.name
            )
        });
        let sp_texels = if small(base.texel_mean, sp.texel_mean) {
            format!("barely move it ({:.3})", sp.texel_mean)
        } else {
            format!("move it to {:.3}", sp.texel_mean)
        };
        let sp_jitter = if small(base.jitter, sp.jitter) {
            format!("leave the vertex jitter at {:.3} px", sp.jitter)
        } else if sp.jitter < base.jitter {
            format!(
                "cut the vertex jitter from {:.3} to {:.3} px",
                base.jitter, sp.jitter
            )
        } else {
            format!(
                "raise the vertex jitter from {:.3} to {:.3} px",
                base.jitter, sp.jitter
            )
        };
        let joint = if small(base.texel_mean, sp.texel_mean) != small(base.jitter, sp.jitter) {
            "but"
        } else {
            "and"
        };
        let better_alone = if pc.texel_mean <= sp.texel_mean {
            ("perspective-correct coordinates", pc.texel_mean)
        } else {
            ("sub-pixel vertices", sp.texel_mean)
        };
        let together = match printed_cmp(both.texel_mean, better_alone.1) {
            Less => "lower than either alone".to_string(),
            _ => format!("no lower than {} alone", better_alone.0),
        };
        let mut text = format!(
            "- Perspective-correct texture coordinates alone take the mean texel error from \
             {:.3} to {:.3}{against_tess}; sub-pixel vertices alone {sp_texels} {joint} \
             {sp_jitter}; together they reach {:.3}, {together}.",
            base.texel_mean, pc.texel_mean, both.texel_mean
        );
        let pc_fixes_texels =
            pc.texel_mean < base.texel_mean && !small(base.texel_mean, pc.texel_mean);
        let sp_fixes_jitter = sp.jitter < base.jitter && !small(base.jitter, sp.jitter);
        if pc_fixes_texels && sp_fixes_jitter && small(base.jitter, pc.jitter) {
            text.push_str(
                " Each fixes what the other leaves: perspective-correct coordinates the texels, \
                 sub-pixel vertices the jitter.",
            );
        }
        let _ = writeln!(
            out,
            "{text} The precise path that draws them runs at {:.2}x / {:.2}x / {:.2}x the \
             hardware path's time here.",
            sp.ratio, pc.ratio, both.ratio
        );
    }
    let reducing: Vec<&Row> = rows
        .iter()
        .filter(|r| {
            r.knob != Knob::Hardware && r.jitter < base.jitter && !small(base.jitter, r.jitter)
        })
        .collect();
    let lowest = reducing
        .iter()
        .map(|r| r.jitter)
        .fold(base.jitter, f64::min);
    let jitter = if base.jitter == 0.0 {
        "no vertex jitters here (0.000 px)".to_string()
    } else if reducing.is_empty() {
        format!(
            "vertices jitter {:.3} px a frame on average against their exact motion, and no \
             configuration measured here reduces it",
            base.jitter
        )
    } else if reducing.iter().all(|r| r.knob.options().subpixel) {
        format!(
            "vertices jitter {:.3} px a frame on average against their exact motion; only \
             sub-pixel vertex positions reduce it (to {lowest:.3} px), so it comes from the \
             integer snapping of screen coordinates",
            base.jitter
        )
    } else {
        let names: Vec<&str> = reducing.iter().map(|r| r.name.as_str()).collect();
        format!(
            "vertices jitter {:.3} px a frame on average against their exact motion; {} \
             reduce it (to {lowest:.3} px at best)",
            base.jitter,
            names.join(", ")
        )
    };
    let _ = writeln!(out, "- On the hardware path {jitter}.");
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

    /// The figures of a past run of the default scene (ms, ratio, polygons, pixels, mean and
    /// max texel error, jitter), in `Knob::ALL` order.
    fn measured_rows() -> Vec<Row> {
        let figures: [(f64, f64, f64, usize, f64, f64, f64); 11] = [
            (0.271, 1.00, 31.0, 0, 6.267, 45.25, 0.114),
            (0.270, 1.00, 31.0, 0, 6.267, 45.25, 0.114),
            (0.267, 0.99, 31.0, 0, 6.267, 45.25, 0.114),
            (0.256, 0.94, 31.0, 430006, 6.267, 45.25, 0.114),
            (1.313, 4.85, 31.0, 136833, 6.215, 44.55, 0.033),
            (1.480, 5.46, 31.0, 392050, 1.894, 45.25, 0.114),
            (1.498, 5.53, 31.0, 434475, 0.816, 45.25, 0.033),
            (0.314, 1.16, 106.0, 364230, 2.634, 45.25, 0.114),
            (0.352, 1.30, 166.0, 412787, 1.988, 45.25, 0.114),
            (0.383, 1.41, 206.0, 412667, 1.979, 45.25, 0.114),
            (0.408, 1.51, 206.0, 412667, 1.979, 45.25, 0.114),
        ];
        configs()
            .iter()
            .zip(figures)
            .map(|(c, f)| Row {
                knob: c.knob,
                name: c.name.to_string(),
                frame_ms: f.0,
                ratio: f.1,
                drawn: f.2,
                differing_pixels: f.3,
                texel_mean: f.4,
                texel_max: f.5,
                jitter: f.6,
            })
            .collect()
    }

    fn row(rows: &mut [Row], knob: Knob) -> &mut Row {
        rows.iter_mut().find(|r| r.knob == knob).unwrap()
    }

    #[test]
    fn every_knob_has_one_row_with_a_distinct_label() {
        let rows = configs();
        assert_eq!(rows.len(), Knob::ALL.len());
        assert_eq!(rows[0].knob, Knob::Hardware);
        let labels: std::collections::HashSet<_> = rows.iter().map(|c| c.name).collect();
        assert_eq!(labels.len(), rows.len());
    }

    /// On measured figures, each comparison is the one worked out by hand from the rules
    /// (5% is a small change; three decimals decide better / worse).
    #[test]
    fn conclusion_of_measured_figures() {
        let text = conclusion(&measured_rows());
        for sentence in [
            // Exact and f32: 0 pixels and no change of texel error or jitter.
            "- The GTE's UNR divide is not where the error comes from: exact and f32 division \
             each change no pixel, move the mean texel error from 6.267 to 6.267 / 6.267 and \
             the jitter from 0.114 to 0.114 / 0.114 px (each within 5%), at 1.00x / 0.99x the \
             time.",
            "- Dithering changes the colour of 430006 pixels and nothing about geometry or \
             texels (mean texel error 6.267, as with it); without it a frame takes 0.94x the \
             time.",
            // Gain 6.267 - 1.979 = 4.288; level 2 is 0.009 above the best, within 5% of it.
            "- Tessellation is the hardware's lever: the mean texel error goes 6.267 (level 0), \
             2.634 (level 1), 1.988 (level 2), 1.979 (level 3), 1.979 (level 4) while the frame \
             time goes from 0.271 ms to 0.408 ms (1.51x) and the polygon count from 31 to 206; \
             past level 2 it buys almost nothing (level 2 is 0.009 above the best, 1.979, of a \
             4.288 gain); levels 3 and 4 draw the same number of polygons.",
            "- Affine mapping and vertex snapping, not arithmetic precision, are what separate \
             the PS1 image from the reference: perspective-correct coordinates and sub-pixel \
             vertices take the mean texel error from 6.267 to 0.816, exact or f32 division to \
             6.267.",
            // 1.894 < 1.979; sub-pixel: 6.215 within 5% of 6.267, jitter 0.114 -> 0.033.
            "- Perspective-correct texture coordinates alone take the mean texel error from \
             6.267 to 1.894, better than the best tessellation level (1.979, tessellation 3); \
             sub-pixel vertices alone barely move it (6.215) but cut the vertex jitter from \
             0.114 to 0.033 px; together they reach 0.816, lower than either alone. Each fixes \
             what the other leaves: perspective-correct coordinates the texels, sub-pixel \
             vertices the jitter. The precise path that draws them runs at 4.85x / 5.46x / \
             5.53x the hardware path's time here.",
            "- On the hardware path vertices jitter 0.114 px a frame on average against their \
             exact motion; only sub-pixel vertex positions reduce it (to 0.033 px), so it \
             comes from the integer snapping of screen coordinates.",
        ] {
            assert!(text.contains(sentence), "missing\n{sentence}\nin\n{text}");
        }
        assert_eq!(text.lines().count(), 6, "{text}");
    }

    /// Change one figure and the sentence that compares it changes with it.
    #[test]
    fn a_changed_figure_changes_its_sentence() {
        let base = measured_rows();
        let with = |change: &dyn Fn(&mut Vec<Row>)| {
            let mut rows = base.clone();
            change(&mut rows);
            conclusion(&rows)
        };
        // Perspective-correct UVs worse than, then as good as, tessellation level 3.
        let text = with(&|r| row(r, Knob::PerspectiveUv).texel_mean = 2.5);
        assert!(
            text.contains(
                "to 2.500, worse than the best tessellation level (1.979, tessellation 3)"
            ),
            "{text}"
        );
        let text = with(&|r| row(r, Knob::PerspectiveUv).texel_mean = 1.9794);
        assert!(
            text.contains("as good as the best tessellation level"),
            "{text}"
        );
        // Exact division removing a fifth of the texel error: the divide matters.
        let text = with(&|r| row(r, Knob::DivideExact).texel_mean = 5.0);
        assert!(
            text.contains("- The GTE's UNR divide matters on this scene:"),
            "{text}"
        );
        assert!(!text.contains("not where the error comes from"), "{text}");
        // Different pixel counts are both given.
        let text = with(&|r| row(r, Knob::DivideF32).differing_pixels = 12);
        assert!(
            text.contains("exact and f32 division change 0 and 12 pixels"),
            "{text}"
        );
        // Dithering off moving the texel error.
        let text = with(&|r| row(r, Knob::DitherOff).texel_mean = 6.3);
        assert!(
            text.contains("and also moves the mean texel error from 6.267 to 6.300"),
            "{text}"
        );
        // Level 2 further from the best: the plateau starts at level 3.
        let text = with(&|r| row(r, Knob::Tessellation(2)).texel_mean = 2.5);
        assert!(
            text.contains("past level 3 it buys almost nothing"),
            "{text}"
        );
        // No level below level 0: no lever.
        let text = with(&|r| {
            for level in 1..=4 {
                row(r, Knob::Tessellation(level)).texel_mean = 6.5;
            }
        });
        assert!(
            text.contains("- Tessellation does not lower the mean texel error here"),
            "{text}"
        );
        assert!(!text.contains("buys almost nothing"), "{text}");
        // Sub-pixel vertices moving the texel error by more than 5%.
        let text = with(&|r| row(r, Knob::Subpixel).texel_mean = 5.0);
        assert!(
            text.contains("sub-pixel vertices alone move it to 5.000 and cut"),
            "{text}"
        );
        // Exact division also reducing jitter: no longer "only sub-pixel".
        let text = with(&|r| row(r, Knob::DivideExact).jitter = 0.05);
        assert!(
            text.contains(
                "divide: exact, sub-pixel vertices (non-hardware), sub-pixel + perspective \
                 (non-hardware) reduce it (to 0.033 px at best)"
            ),
            "{text}"
        );
        // Arithmetic beating geometry.
        let text = with(&|r| {
            row(r, Knob::DivideF32).texel_mean = 0.5;
        });
        assert!(
            text.contains("- Arithmetic precision, more than affine mapping"),
            "{text}"
        );
    }

    #[test]
    fn every_knob_yields_its_paragraph_whatever_the_labels() {
        let mut rows = synthetic_rows();
        for r in &mut rows {
            r.name = format!("renamed {:?}", r.knob);
        }
        let text = conclusion(&rows);
        let paragraphs: Vec<&str> = text.lines().filter(|l| l.starts_with("- ")).collect();
        // Divide, dithering, tessellation, precision against geometry, sub-pixel /
        // perspective, jitter.
        assert_eq!(paragraphs.len(), 6, "{text}");
        // The divide paragraph quotes the exact (row 2) and f32 (row 3) figures; the
        // tessellation paragraph quotes level 4 (row 11) polygons.
        assert!(text.contains("change 2 and 3 pixels"), "{text}");
        assert!(text.contains("from 1 to 11"), "{text}");
    }

    #[test]
    fn a_missing_row_drops_only_its_paragraph() {
        let rows: Vec<Row> = measured_rows()
            .into_iter()
            .filter(|r| r.knob != Knob::DitherOff)
            .collect();
        let text = conclusion(&rows);
        assert!(!text.contains("Dithering changes"));
        assert_eq!(text.lines().filter(|l| l.starts_with("- ")).count(), 5);
        // Without the non-hardware rows (a build without `accuracy-knobs`), the divide,
        // precision and sub-pixel paragraphs go.
        let rows: Vec<Row> = measured_rows()
            .into_iter()
            .filter(|r| {
                !matches!(
                    r.knob,
                    Knob::DivideExact
                        | Knob::DivideF32
                        | Knob::Subpixel
                        | Knob::PerspectiveUv
                        | Knob::SubpixelPerspective
                )
            })
            .collect();
        let text = conclusion(&rows);
        assert_eq!(
            text.lines().filter(|l| l.starts_with("- ")).count(),
            3,
            "{text}"
        );
        assert!(
            text.contains("no configuration measured here reduces it"),
            "{text}"
        );
    }

    #[test]
    fn skipped_rows_are_left_out_of_the_table_with_a_note() {
        let rows: Vec<Row> = synthetic_rows()
            .into_iter()
            .filter(|r| r.knob != Knob::Subpixel)
            .collect();
        let skipped = [Skipped {
            knob: Knob::Subpixel,
            reason: "needs the `accuracy-knobs` feature".to_string(),
        }];
        let text = figures_table(&rows, &skipped);
        let table_lines = text.lines().filter(|l| l.starts_with("| ")).count();
        // The header plus one line per measured row.
        assert_eq!(table_lines, 1 + rows.len(), "{text}");
        assert!(!text.contains("| sub-pixel vertices"), "{text}");
        assert!(
            text.contains(
                "Not measured in this build:\n\n- sub-pixel vertices (non-hardware): needs the \
                 `accuracy-knobs` feature"
            ),
            "{text}"
        );
        assert!(!text.contains("NaN"), "{text}");
        assert!(!figures_table(&rows, &[]).contains("Not measured"));
    }
}
