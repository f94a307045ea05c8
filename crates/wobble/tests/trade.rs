//! The accuracy-trade measurements: the reference renderer on cases with known answers and
//! the report's accuracy columns on the face-on scene (not timed). The `wobble trade`
//! command itself is tested in crates/wobble-cli/tests/trade.rs.

use std::path::PathBuf;
use wobble::reference;
use wobble::scene::Scene;
use wobble::trade::{Knob, Measurement, TradeSettings, measure};

fn scene(name: &str) -> Scene {
    Scene::load(
        &PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../../fixtures/scenes")
            .join(name),
    )
    .unwrap()
}

/// Face-on, the reference's texel at pixel (x, y) is floor((x - 97)/2 + 0.5) across the
/// front face (63 texels over 126 pixels), computed by hand from the geometry.
#[test]
fn reference_face_on_texels() {
    let s = scene("face-on.toml");
    let f = reference::render(&s, 0);
    for (x, y) in [(97, 57), (98, 60), (150, 100), (222, 182)] {
        let want = ((x - 97) / 2 + (x - 97) % 2, (y - 57) / 2 + (y - 57) % 2);
        assert_eq!(
            f.texel[y as usize * 320 + x as usize],
            Some(want),
            "({x},{y})"
        );
    }
    assert_eq!(
        f.texel[120 * 320 + 96],
        None,
        "left of the face: background"
    );
    assert_eq!(
        f.texel[120 * 320 + 223],
        None,
        "right edge excluded (top-left rule)"
    );
}

/// A known perspective case: the face turned 60 degrees about Y (yaw 683/4096 turn, so
/// cos = 0.49945, sin = 0.86634 from the 1.3.12 table rounded). The ray through pixel
/// (178, 120) has X/Z = 18/256; it meets the face at p = 512a / (cos + a sin) = 64.24 units
/// right of centre, u = 63 (p/126 + 1)/2 = 47.56 -> texel 48.
#[test]
fn reference_perspective_case() {
    let mut s = scene("face-on.toml");
    // A single square (the cube's front face alone), centred 512 units away.
    s.meshes[0].mesh = wobble::scene::mesh::Mesh {
        vertices: [
            (-1.0, -1.0, 0.0, 0.0),
            (1.0, -1.0, 1.0, 0.0),
            (-1.0, 1.0, 0.0, 1.0),
            (1.0, 1.0, 1.0, 1.0),
        ]
        .iter()
        .map(|&(x, y, u, v)| wobble::scene::mesh::MeshVertex {
            position: [x, y, 0.0],
            normal: [0.0, 0.0, -1.0],
            uv: [u, v],
        })
        .collect(),
        faces: vec![wobble::scene::mesh::MeshFace {
            indices: [0, 1, 2, 3],
            quad: true,
        }],
    };
    s.objects[0].position = [0.0, 0.0, 512.0];
    s.objects[0].rotation = [0.0, 60.0, 0.0];
    let f = reference::render(&s, 0);
    let (u, v) = f.texel[120 * 320 + 178].expect("face at (178,120)");
    assert_eq!(u, 48);
    assert_eq!(v, 32, "v = 31.5 on the centre line, ties round up");
}

/// The report's accuracy columns on the face-on scene: the hardware configuration samples
/// exactly the reference's texels (error 0), differs from itself in 0 pixels, and the
/// exact-divide row equals it (H/SZ3 = 1/2 is exact in every mode).
#[test]
fn trade_face_on_accuracy_columns() {
    let s = scene("face-on.toml");
    let Measurement {
        rows,
        heat,
        skipped,
    } = measure(
        &s,
        TradeSettings {
            frames: 2,
            repeats: 1,
            sweep_step: 4099,
        },
    )
    .unwrap();
    assert_eq!(rows.len(), heat.len());
    assert_eq!(rows.len() + skipped.len(), Knob::ALL.len());
    let hw = &rows[0];
    assert_eq!(hw.knob, Knob::Hardware);
    assert_eq!(hw.texel_mean, 0.0);
    assert_eq!(hw.texel_max, 0.0);
    assert_eq!(hw.differing_pixels, 0);
    assert_eq!(hw.ratio, 1.0);
    assert_eq!(hw.drawn, 1.0, "only the front face survives NCLIP");
    assert_eq!(hw.jitter, 0.0, "nothing moves");
    for r in &rows {
        for (what, v) in [
            ("ms", r.frame_ms),
            ("ratio", r.ratio),
            ("drawn", r.drawn),
            ("texel mean", r.texel_mean),
            ("texel max", r.texel_max),
            ("jitter", r.jitter),
        ] {
            assert!(v.is_finite(), "{:?} {what} = {v}", r.knob);
        }
    }
    let non_hardware = [
        Knob::DivideExact,
        Knob::DivideF32,
        Knob::Subpixel,
        Knob::PerspectiveUv,
        Knob::SubpixelPerspective,
    ];
    if cfg!(feature = "accuracy-knobs") {
        assert!(skipped.is_empty(), "{skipped:?}");
        let exact = rows.iter().find(|r| r.knob == Knob::DivideExact).unwrap();
        assert_eq!((exact.differing_pixels, exact.texel_max), (0, 0.0));
        // Face-on with whole-pixel corners, the precise path agrees too: sub-pixel positions
        // equal the snapped ones and perspective weights are all equal.
        for knob in [
            Knob::Subpixel,
            Knob::PerspectiveUv,
            Knob::SubpixelPerspective,
        ] {
            let r = rows.iter().find(|r| r.knob == knob).unwrap();
            assert_eq!(r.texel_max, 0.0, "{knob:?}");
        }
    } else {
        // Without the knobs, exactly the non-hardware rows are skipped, each naming the
        // feature that would build it.
        let knobs: Vec<Knob> = skipped.iter().map(|s| s.knob).collect();
        assert_eq!(knobs, non_hardware);
        for s in &skipped {
            assert!(s.reason.contains("accuracy-knobs"), "{s:?}");
        }
        assert!(rows.iter().all(|r| !non_hardware.contains(&r.knob)));
    }
}

/// The committed report, docs/trade.md, holds what `wobble trade -o docs` measures today: the
/// deterministic columns of its table (all but the two timing columns, ms/frame and vs
/// hardware) equal a fresh measurement of the default scene over the same number of frames,
/// formatted as the report formats them. A change to the default scene or the pipeline that
/// moves a figure fails here until the report is regenerated.
#[test]
fn committed_report_matches_a_measurement() {
    let doc = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/trade.md"),
    )
    .unwrap();
    let frames: u32 = doc
        .split("Scene: the default scene, ")
        .nth(1)
        .and_then(|t| t.split(" consecutive frames").next())
        .and_then(|t| t.rsplit(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the report names the default scene and its frame count");
    let Measurement { rows, skipped, .. } = measure(
        &Scene::default_scene(),
        TradeSettings {
            frames,
            repeats: 1,
            sweep_step: 1,
        },
    )
    .unwrap();
    // A table line without its timing cells: label, polygons, pixels, texel mean and max,
    // jitter.
    let deterministic = |line: &str| -> Vec<String> {
        let cells: Vec<String> = line
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect();
        cells
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != 1 && *i != 2)
            .map(|(_, c)| c.clone())
            .collect()
    };
    let table = |text: &str| -> Vec<Vec<String>> {
        text.lines()
            .skip_while(|l| !l.starts_with("| configuration |"))
            .skip(2)
            .take_while(|l| l.starts_with("| "))
            .map(deterministic)
            .collect()
    };
    let fresh = table(&wobble::trade::figures_table(&rows, &skipped));
    let committed = table(&doc);
    assert_eq!(fresh.len(), rows.len());
    for line in &fresh {
        let found = committed.iter().find(|c| c[0] == line[0]);
        assert_eq!(
            found,
            Some(line),
            "docs/trade.md differs from a measurement (regenerate it: cargo run --release -- \
             trade -o docs)"
        );
    }
    if skipped.is_empty() {
        assert_eq!(committed.len(), fresh.len(), "rows in docs/trade.md");
    }
}
