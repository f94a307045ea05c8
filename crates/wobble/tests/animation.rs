//! The default animation (docs/animation.md): deterministic, and each artefact it is built
//! to show is measurably there in the hardware pipeline and (nearly) absent where the
//! artefact's cause is removed: the precise path (sub-pixel vertices, perspective-correct
//! texture coordinates) or the f64 reference renderer.

use gte::typed::{Geometry, I16F16, Projection, Vector3};
use wobble::pipeline::{PipelineOptions, Renderer, object_transform};
use wobble::reference;
use wobble::scene::animation::Animation;
use wobble::scene::default::{CUBE, FLOOR, SPHERE, WALL, default_animation};
use wobble::scene::prepared::prepare;
use wobble::scene::{InvalidScene, Scene};
use wobble::trade::{coordinate_scene, texel_errors};

/// The hardware path with every non-hardware knob off.
fn hardware() -> PipelineOptions {
    PipelineOptions::default()
}

/// The precise path: sub-pixel vertices and perspective-correct texture coordinates.
fn precise() -> PipelineOptions {
    PipelineOptions {
        subpixel: true,
        perspective_uv: true,
        ..PipelineOptions::default()
    }
}

/// The default scene posed at `frame` with only object `keep` left in it.
fn alone(animation: &Animation, keep: usize, frame: u32) -> Scene {
    let mut s = animation.scene_at(&Scene::default_scene(), frame);
    s.objects = vec![s.objects[keep].clone()];
    s
}

/// One frame of `scene` (already posed) as 15-bit colours.
fn render(scene: &Scene, options: PipelineOptions, frame: u32) -> Vec<u16> {
    let mut r = Renderer::new(scene.clone(), options).unwrap();
    r.render_frame(frame);
    r.image().pixels().map(|p| rgb15(p.0)).collect()
}

fn rgb15(p: [u8; 3]) -> u16 {
    u16::from(p[0] >> 3) | u16::from(p[1] >> 3) << 5 | u16::from(p[2] >> 3) << 10
}

/// FNV-1a, 64 bits.
fn fnv(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Frames 0, 30, 60 and 89 of the whole default animation rendered twice give the same
/// bytes, and their hash is the recorded one. Regenerate the hash on purpose (a deliberate
/// change of the scene or the pipeline) from the failure message.
#[test]
fn default_animation_is_deterministic() {
    let animation = default_animation();
    let base = Scene::default_scene();
    let run = || {
        let mut r = Renderer::new(base.clone(), hardware()).unwrap();
        let mut bytes = Vec::new();
        for frame in [0, 30, 60, 89] {
            r.pose(&animation, &base, frame).unwrap();
            r.render_frame(frame);
            bytes.extend_from_slice(r.image().as_raw());
        }
        bytes
    };
    let (a, b) = (run(), run());
    assert!(a == b, "two runs differ");
    let hash = fnv(&a);
    assert_eq!(hash, GOLDEN_HASH, "hash {hash:#018x}");
}

const GOLDEN_HASH: u64 = 0x2d9e_1910_0bbd_eaa5;

/// Mean texel error (texels) of the floor alone over frames 0, 15, ..., 75.
fn floor_texel_error(options: PipelineOptions) -> f64 {
    let animation = default_animation();
    let mut errors = Vec::new();
    for frame in (0..animation.frames).step_by(15) {
        let coords = coordinate_scene(&alone(&animation, FLOOR, frame));
        let hw = render(&coords, options, frame);
        errors.extend(texel_errors(&hw, &reference::render(&coords, frame), 1));
    }
    assert!(
        errors.len() > 10_000,
        "{} floor pixels compared",
        errors.len()
    );
    errors.iter().sum::<f64>() / errors.len() as f64
}

/// Texture swim on the floor. Its 500-unit quads (a 64-texel texture over each) are drawn
/// affinely: across a quad seen at a grazing angle the depth changes by a factor of 2 to 5,
/// and the affine texel coordinate misses the perspective one by up to a quarter of the
/// texel span in the middle of the split diagonal (a texel span of 64 there: up to 16
/// texels), so a mean error above 3 texels over the floor is a conservative bound. The
/// precise path interpolates u/z, v/z and 1/z from sub-pixel vertices: what is left is
/// rounding (1/16-pixel vertices, integer SZ in 1/Z) and, towards the horizon, where one
/// pixel spans 8 texels and more, a texel or two from any sub-pixel difference: under 2
/// texels on average, and under a quarter of the hardware's.
#[test]
fn floor_texture_swims_in_hardware_only() {
    let hw = floor_texel_error(hardware());
    let fixed = floor_texel_error(precise());
    eprintln!("floor mean texel error: hardware {hw:.3}, precise path {fixed:.3}");
    assert!(hw > 3.0, "hardware {hw}");
    assert!(
        fixed < 2.0 && fixed * 4.0 < hw,
        "precise path {fixed}, hardware {hw}"
    );
}

/// A vertex's GTE screen position and its exact one.
type Positions = ([f64; 2], [f64; 2]);

/// Mean frame-to-frame vertex displacement of the GTE's projection minus the exact f64
/// motion, in pixels, over the cube's vertices on screen, frames 0..30.
fn cube_jitter(subpixel: bool) -> f64 {
    let animation = default_animation();
    let base = Scene::default_scene();
    let vertices: Vec<Vector3> = prepare(&base, CUBE)
        .faces
        .iter()
        .flat_map(|f| f.v.map(|v| v.position))
        .collect();
    let (w, h) = (f64::from(base.screen.width), f64::from(base.screen.height));
    let mut last: Option<Vec<Option<Positions>>> = None;
    let (mut sum, mut count) = (0.0, 0usize);
    for frame in 0..30 {
        let s = animation.scene_at(&base, frame);
        let object = &s.objects[CUBE];
        let mut g = Geometry::new();
        g.set_projection(&Projection {
            offset_x: I16F16::from_num(s.screen.width / 2),
            offset_y: I16F16::from_num(s.screen.height / 2),
            h: s.camera.h,
            ..Projection::default()
        });
        let (rt, tr) = object_transform(&s, object, frame);
        g.set_rotation(&rt);
        g.set_translation(tr);
        // The exact motion of the same transform: RT and TR as loaded into the GTE (so the
        // 1/4096-turn angle steps, a hardware effect of their own, are left out), applied
        // and divided in f64.
        let m = rt.to_bits().map(|row| row.map(|c| f64::from(c) / 4096.0));
        let t = [f64::from(tr.x), f64::from(tr.y), f64::from(tr.z)];
        let hp = f64::from(s.camera.h);
        let now: Vec<_> = vertices
            .iter()
            .map(|v| {
                let q = g.project_subpixel(*v);
                let p = [f64::from(v.x), f64::from(v.y), f64::from(v.z)];
                let cam: [f64; 3] =
                    std::array::from_fn(|r| (0..3).map(|c| m[r][c] * p[c]).sum::<f64>() + t[r]);
                let exact = [
                    w / 2.0 + hp * cam[0] / cam[2],
                    h / 2.0 + hp * cam[1] / cam[2],
                ];
                let gte = if subpixel {
                    [q.x.to_num::<f64>(), q.y.to_num::<f64>()]
                } else {
                    [f64::from(q.projected.x), f64::from(q.projected.y)]
                };
                let on =
                    cam[2] > hp && (0.0..w).contains(&exact[0]) && (0.0..h).contains(&exact[1]);
                on.then_some((gte, exact))
            })
            .collect();
        if let Some(prev) = &last {
            for (a, b) in prev.iter().zip(&now) {
                if let (Some((g0, e0)), Some((g1, e1))) = (a, b) {
                    let d = [
                        (g1[0] - g0[0]) - (e1[0] - e0[0]),
                        (g1[1] - g0[1]) - (e1[1] - e0[1]),
                    ];
                    sum += (d[0] * d[0] + d[1] * d[1]).sqrt();
                    count += 1;
                }
            }
        }
        last = Some(now);
    }
    assert!(count > 100, "{count} vertex steps measured");
    sum / count as f64
}

/// Vertex jitter on the drifting cube. A vertex moving v pixels a frame (v < 1) on an axis
/// jumps a whole pixel in a fraction v of the frames and stands still in the rest, so its
/// step misses the smooth one by 1 - v or by v: 2v(1 - v) on average, 1/3 over speeds spread
/// evenly in 0..1; two axes give about 0.45 px, and more than 0.3 px is required. With the
/// GTE's 16.16 screen positions what is left comes from its whole-unit camera-space
/// coordinates (IR1, IR2 and SZ truncated: H/Z is 0.2 px a unit at the cube's distance of
/// 1500 and more), under 0.2 px on average and under a third of the whole-pixel jitter.
#[test]
fn drifting_cube_jitters_in_hardware_only() {
    let whole = cube_jitter(false);
    let fine = cube_jitter(true);
    eprintln!("cube vertex jitter: whole pixels {whole:.3} px, sub-pixel {fine:.3} px");
    assert!(whole > 0.3, "whole-pixel jitter {whole}");
    assert!(
        fine < 0.2 && fine * 3.0 < whole,
        "sub-pixel {fine}, whole pixels {whole}"
    );
}

/// Background pixels inside the wall: where `frame` shows the background colour but the
/// reference renderer has no background pixel within 2 pixels (so a silhouette that is a
/// pixel off does not count).
fn holes(frame: &[u16], reference: &[u16], background: u16, width: usize) -> usize {
    let height = frame.len() / width;
    let mut n = 0;
    for y in 2..height.saturating_sub(2) {
        for x in 2..width - 2 {
            if frame[y * width + x] != background {
                continue;
            }
            let solid = (y - 2..=y + 2)
                .all(|yy| (x - 2..=x + 2).all(|xx| reference[yy * width + xx] != background));
            n += usize::from(solid);
        }
    }
    n
}

/// `scene` without fog (so the background is one colour), its reference image at `frame` in
/// 15-bit colour, and that background colour.
fn unfogged(scene: &Scene, frame: u32) -> (Scene, Vec<u16>, u16) {
    let mut s = scene.clone();
    s.fog = None;
    let background = rgb15(s.screen.background);
    let reference = reference::render(&s, frame)
        .rgb
        .iter()
        .map(|&p| rgb15(p))
        .collect();
    (s, reference, background)
}

/// Seam pixels of the wall alone (no fog, so the background is one colour) per frame,
/// every third frame.
fn wall_seams(options: PipelineOptions) -> Vec<usize> {
    let animation = default_animation();
    (0..animation.frames)
        .step_by(3)
        .map(|frame| {
            let (s, reference, background) = unfogged(&alone(&animation, WALL, frame), frame);
            let hw = render(&s, options, frame);
            holes(&hw, &reference, background, usize::from(s.screen.width))
        })
        .collect()
}

/// Seams: the wall's bricks share no vertices and meet the next row at T-junctions, where
/// a corner snapped to a whole pixel leaves the long edge's rasterized line: gaps of
/// background open and close. Some frames must show them, and the whole animation a few
/// dozen such pixels at least (one T-junction gap is a pixel or two; the wall has 30 of
/// them). The precise path keeps the corners to 1/16 pixel, so a gap needs a pixel centre
/// within 1/16 pixel of a joint: a handful over the animation.
#[test]
fn brick_wall_seams_flash_in_hardware_only() {
    let hw = wall_seams(hardware());
    let fine = wall_seams(precise());
    let (hw_total, fine_total): (usize, usize) = (hw.iter().sum(), fine.iter().sum());
    eprintln!("wall seam pixels per frame, hardware {hw:?}\nprecise path {fine:?}");
    assert!(hw.iter().filter(|&&n| n > 0).count() >= 5, "{hw:?}");
    assert!(hw_total >= 30, "{hw:?}");
    assert!(
        fine_total * 10 <= hw_total,
        "precise {fine_total} vs hardware {hw_total}"
    );
}

/// The near floor stays on screen. Every frame, the floor alone (no fog): background
/// pixels where the reference draws floor all around (`holes`), against the reference's
/// floor pixels. Unsplit, a near quad is dropped whole and a band of background opens at
/// the bottom of the screen (a third of the floor and more); split where it would be dropped
/// (docs/pipeline.md step 8), what is left are T-junction cracks, one pixel wide, where a
/// split quad meets a whole neighbour: under 1% of the floor in every frame.
#[test]
fn near_floor_is_split_not_dropped() {
    let animation = default_animation();
    let floor_holes = |scene: &Scene, frame: u32| {
        let (s, reference, background) = unfogged(scene, frame);
        let floor = reference.iter().filter(|&&p| p != background).count();
        let hw = render(&s, hardware(), frame);
        (
            holes(&hw, &reference, background, usize::from(s.screen.width)),
            floor,
        )
    };
    let (mut worst_split, mut worst_unsplit) = (0.0f64, 0.0f64);
    for frame in 0..animation.frames {
        let s = alone(&animation, FLOOR, frame);
        let (n, floor) = floor_holes(&s, frame);
        worst_split = worst_split.max(n as f64 / floor as f64);
        assert!(floor > 10_000, "frame {frame}: {floor} floor pixels");
        assert!(
            n * 100 < floor,
            "frame {frame}: {n} holes in {floor} floor pixels"
        );
        let mut unsplit = s.clone();
        unsplit.objects[0].tessellation = 0;
        let (n, floor) = floor_holes(&unsplit, frame);
        worst_unsplit = worst_unsplit.max(n as f64 / floor as f64);
    }
    eprintln!("worst frame's floor holes: split {worst_split:.4}, unsplit {worst_unsplit:.4}");
    assert!(worst_unsplit > 0.3, "unsplit floor loses {worst_unsplit}");
}

/// Fraction of the object's pixels (those not of the background colour) that differ from
/// both horizontal neighbours in the same direction in some channel: a 1-pixel ripple,
/// which a smooth Gouraud gradient quantized to 5 bits has only where its bands are under
/// a pixel wide, and the 4x4 dither pattern (offsets -4..+3 before truncation to 5 bits,
/// docs/hardware/gpu.md §1) has everywhere the offset carries a channel across a step.
fn ripple(frame: &[u16], background: u16, width: usize) -> f64 {
    let (mut inside, mut ripples) = (0usize, 0usize);
    for row in frame.chunks(width) {
        for x in 1..width - 1 {
            let (a, b, c) = (row[x - 1], row[x], row[x + 1]);
            if a == background || b == background || c == background {
                continue;
            }
            inside += 1;
            let ch = |p: u16, k: u16| i32::from((p >> (5 * k)) & 31);
            let extreme = (0..3).any(|k| {
                let (l, m, r) = (ch(a, k), ch(b, k), ch(c, k));
                (m > l && m > r) || (m < l && m < r)
            });
            ripples += usize::from(extreme);
        }
    }
    assert!(inside > 1000, "{inside} object pixels");
    ripples as f64 / inside as f64
}

/// Dithering on the lit sphere, at frame 89 (passing the camera, large on screen). With the
/// dither offsets a channel crosses a 5-bit step in a quarter of the pixels on average (the
/// mean |offset| is 2 of the 8 units a step spans), and half of those crossings stand out
/// from both neighbours: over 10% of the pixels ripple. Undithered, or in the reference,
/// only band edges narrower than a pixel do: under 2%.
#[test]
fn lit_sphere_is_dithered() {
    let animation = default_animation();
    let frame = 89;
    let mut s = alone(&animation, SPHERE, frame);
    s.fog = None;
    let background = rgb15(s.screen.background);
    let width = usize::from(s.screen.width);
    let dithered = ripple(&render(&s, hardware(), frame), background, width);
    let plain = ripple(
        &render(
            &s,
            PipelineOptions {
                dither: Some(false),
                ..hardware()
            },
            frame,
        ),
        background,
        width,
    );
    let reference: Vec<u16> = reference::render(&s, frame)
        .rgb
        .iter()
        .map(|&p| rgb15(p))
        .collect();
    let smooth = ripple(&reference, background, width);
    eprintln!(
        "sphere ripple: dithered {dithered:.3}, undithered {plain:.3}, reference {smooth:.3}"
    );
    assert!(dithered > 0.10, "dithered {dithered}");
    assert!(plain < 0.02, "undithered {plain}");
    assert!(smooth < 0.02, "reference {smooth}");
}

/// Posing checks each frame's positions as `Scene::validate` checks a scene's (within
/// +-1000000, docs/formats.md, "Limits"): an object drifting past the limit is refused at the
/// first frame beyond it, with the field named; the frame before is posed.
#[test]
fn pose_refuses_the_first_frame_out_of_range() {
    let base = Scene::default_scene();
    let step = 100_000.0;
    let animation = Animation {
        drift: vec![(0, [0.0, 0.0, step])],
        ..Animation::still(100)
    };
    let z = base.objects[0].position[2];
    let first_bad = ((1e6 - z) / step).floor() as u32 + 1;
    let mut r = Renderer::new(base.clone(), hardware()).unwrap();
    assert!(r.pose(&animation, &base, first_bad - 1).is_ok());
    let e = r.pose(&animation, &base, first_bad).unwrap_err();
    assert!(
        matches!(&e, InvalidScene::Number { field, .. } if field == "object 1: position[2]"),
        "{e:?}"
    );
}
