//! The statements of docs/typed-api.md, each held by a property or an exhaustive check:
//! the four that the typed docs once had wrong (RTPT's FLAG, NCLIP's wrap, AVSZ3's OTZ, the
//! colour scale of BK), RTPT against RTPS, the rotation's error bound, the on-screen
//! strategy, and `Flag`'s names.

#![cfg(feature = "typed")]

use gte::reference;
use gte::strategy;
use gte::typed::{
    BackgroundColor, Geometry, I8F8, I8F24, I16F16, Matrix, Normal, Projection, Translation,
    Vector3,
};
use gte::{DivideMode, Flag};
use proptest::prelude::*;

#[path = "support/rotation.rs"]
mod rotation;

/// The FLAG bits of RTPS/RTPT's depth cue (docs/hardware/gte.md §5.7): IR0 and MAC0.
const DEPTH_CUE_BITS: u32 = 0x1000 | 0x8000 | 0x1_0000;

fn set_up(rt: &Matrix, tr: Translation, p: &Projection) -> Geometry {
    let mut g = Geometry::new();
    g.set_rotation(rt);
    g.set_translation(tr);
    g.set_projection(p);
    g
}

/// The RTPT example of docs/typed-api.md: V0 at depth 60 gives a quotient near 1.67
/// (H = 100), whose depth cue with DQA = -128.0 and DQB just under 1.0 leaves MAC0's range
/// and IR0's; V1 and V2 at depth 20000 give about 328/65536, whose depth cue stays in range. RTPS on each vertex sets
/// 0x80009000 in all; RTPT, whose depth cue is V2's alone, sets nothing.
#[test]
fn rtpt_flag_example() {
    let p = Projection {
        offset_x: I16F16::ZERO,
        offset_y: I16F16::ZERO,
        h: 100,
        dqa: I8F8::from_bits(-0x8000),
        dqb: I8F24::from_bits(0xFF_FFFF),
        ..Projection::default()
    };
    let mut g = set_up(&Matrix::IDENTITY, Translation::default(), &p);
    let v = [
        Vector3::new(0, 0, 60),
        Vector3::new(0, 0, 20000),
        Vector3::new(0, 0, 20000),
    ];
    let rtps = v.map(|v| g.clone().project(v).flag);
    assert_eq!(rtps[0].bits(), 0x8000_9000);
    assert!(rtps[1].is_empty() && rtps[2].is_empty());
    let rtpt = g.project_triangle(v);
    assert!(rtpt.flag.is_empty(), "{}", rtpt.flag);
    // 100 × 65536 / 60 = 109226.7 and 100 × 65536 / 20000 = 327.7: UNR within 3 of both
    // (docs/gte.md, "The UNR divide").
    assert!(rtpt.quotient[0].abs_diff(109_227) <= 3);
    assert!(rtpt.quotient[2].abs_diff(328) <= 3);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// RTPT against RTPS on each vertex: the same screen points, depths and quotients, V2's
    /// camera space, IR0 and MAC0; FLAG the OR of the three RTPS FLAGs with V0's and V1's
    /// depth-cue bits taken out (the reference model's `vertex.flag` is a vertex's FLAG
    /// without them), so within the plain OR and holding V2's FLAG whole.
    #[test]
    fn rtpt_is_rtps_three_times_but_for_the_depth_cue(
        rt in strategy::rotation(),
        tr in strategy::translation(),
        p in strategy::projection(),
        v in prop::array::uniform3(strategy::vertex()),
    ) {
        let mut g = set_up(&rt, tr, &p);
        let singles = v.map(|v| g.clone().project(v));
        let t = g.project_triangle(v);
        for (k, single) in singles.iter().enumerate() {
            prop_assert_eq!(t.xy[k], (single.x, single.y));
            prop_assert_eq!(t.sz[k], single.sz);
            prop_assert_eq!(t.quotient[k], single.quotient);
        }
        prop_assert_eq!(t.camera, singles[2].camera);
        prop_assert_eq!(t.ir0, singles[2].ir0);
        prop_assert_eq!(t.mac0, singles[2].mac0);
        let or = singles[0].flag | singles[1].flag | singles[2].flag;
        prop_assert_eq!(t.flag.bits() & !or.bits(), 0);
        prop_assert!(t.flag.contains(singles[2].flag));
        let without_depth_cue = |k: usize| {
            let mut regs = set_up(&rt, tr, &p).gte().registers();
            regs.v[0] = v[k].to_array();
            reference::rtps(&mut regs, true, false, DivideMode::Unr).vertex.flag
        };
        prop_assert_eq!(t.flag, without_depth_cue(0) | without_depth_cue(1) | singles[2].flag);
        // The depth cue's bits are where the two can differ.
        prop_assert_eq!((or.bits() ^ t.flag.bits()) & !DEPTH_CUE_BITS & 0x7FFF_FFFF, 0);
    }

    /// NCLIP of any 16-bit points is twice the signed area wrapped to 32 bits, with FLAG bit
    /// 16 or 15 (and 31) exactly when it does not fit; inside -400h..=3FFh it always fits.
    #[test]
    fn nclip_wraps_to_32_bits(p in prop::array::uniform3((strategy::half(), strategy::half()))) {
        let mut g = Geometry::new();
        let got = g.nclip(p);
        let [(x0, y0), (x1, y1), (x2, y2)] = p.map(|(x, y)| (x as i64, y as i64));
        let area = x0 * y1 + x1 * y2 + x2 * y0 - x0 * y2 - x1 * y0 - x2 * y1;
        prop_assert_eq!(got, area as i32);
        let expected = if area > i32::MAX as i64 {
            0x8001_0000
        } else if area < i32::MIN as i64 {
            0x8000_8000
        } else {
            0
        };
        prop_assert_eq!(g.last_flag().bits(), expected);
        let screen = p.map(|(x, y)| (x.clamp(-0x400, 0x3FF), y.clamp(-0x400, 0x3FF)));
        g.nclip(screen);
        prop_assert!(g.last_flag().is_empty());
    }

    /// The colour scale of BK: with no light (LLM = 0), NCS lights a channel to BK SAR 4
    /// saturated to 0..=FFh, with the channel's FLAG bit (21, 20, 19) exactly when
    /// saturated.
    #[test]
    fn background_color_scale(bk in strategy::background_color(), n in strategy::normal(), lcm in strategy::matrix()) {
        let mut g = Geometry::new();
        g.set_light_colors(&lcm);
        g.set_background_color(bk);
        let got = g.normal_color(n);
        let bits = bk.to_bits();
        for c in 0..3 {
            let scaled = bits[c] >> 4;
            prop_assert_eq!(got[c] as i32, scaled.clamp(0, 0xFF));
            let bit = Flag::from_bits(1 << (21 - c));
            prop_assert_eq!(g.last_flag().contains(bit), !(0..=0xFF).contains(&scaled));
        }
    }

    /// Projection's result fields are the registers RTPS leaves: SXY2, SZ3, IR0, MAC0,
    /// MAC1-3, IR1-3 and FLAG; `quotient` is the divide of H by SZ3.
    #[test]
    fn projected_reads_the_registers(
        rt in strategy::matrix(), tr in strategy::translation(), p in strategy::projection(), v in strategy::vertex(),
    ) {
        let mut g = set_up(&rt, tr, &p);
        let r = g.project(v);
        let regs = g.gte().registers();
        prop_assert_eq!(regs.sxy[2], r.x as u16 as u32 | (r.y as u16 as u32) << 16);
        prop_assert_eq!(regs.sz[3], r.sz);
        prop_assert_eq!(regs.ir[0], r.ir0.to_bits());
        prop_assert_eq!(regs.mac[0], r.mac0);
        prop_assert_eq!(&regs.mac[1..], &r.camera.mac[..]);
        prop_assert_eq!(&regs.ir[1..], &r.camera.ir[..]);
        prop_assert_eq!(regs.flag, r.flag);
        prop_assert_eq!(r.quotient, reference::unr(p.h, r.sz).value);
    }

    /// `Matrix::rotation`'s error bound (docs/typed-api.md, "Rotation accuracy"): every
    /// entry within `ROTATION_ERROR` LSB of the f64 rotation of the same angles, every entry
    /// of R·Rᵀ within `ROTATION_ORTHOGONALITY` LSB of the identity's.
    #[test]
    fn rotation_error_bound(x in strategy::angle(), y in strategy::angle(), z in strategy::angle()) {
        let m = Matrix::rotation(x, y, z).to_bits();
        let exact = rotation::exact([x, y, z].map(|a| rotation::radians(a).sin_cos()));
        for i in 0..3 {
            for j in 0..3 {
                let error = (m[i][j] as f64 - 4096.0 * exact[i][j]).abs();
                prop_assert!(error <= Matrix::ROTATION_ERROR, "entry {},{}: {}", i, j, error);
                let off = rotation::off_identity(&m, i, j) as f64 / 4096.0;
                prop_assert!(off <= Matrix::ROTATION_ORTHOGONALITY, "R·Rᵀ {},{}: {}", i, j, off);
            }
        }
    }

    /// `strategy::on_screen` set-ups project every vertex inside 10..=310, 10..=230 with
    /// FLAG clear, through RTPS and RTPT alike.
    #[test]
    fn on_screen_set_ups_project_on_screen(s in strategy::on_screen()) {
        let mut g = set_up(&s.rotation, s.translation, &s.projection);
        for v in s.vertices {
            prop_assert!(v.to_array().iter().all(|c| c.abs() <= s.radius));
            let p = g.project(v);
            prop_assert!((10..=310).contains(&p.x) && (10..=230).contains(&p.y), "({}, {})", p.x, p.y);
            prop_assert!(p.flag.is_empty(), "{}", p.flag);
        }
        let t = g.project_triangle(s.vertices);
        prop_assert!(t.flag.is_empty(), "{}", t.flag);
    }

    /// Normals and raw vectors are the same bits to the lighting calls.
    #[test]
    fn normal_and_vector_light_alike(n in strategy::normal(), lcm in strategy::matrix(), llm in strategy::matrix(), bk in strategy::background_color()) {
        let mut a = Geometry::new();
        a.set_light_matrix(&llm);
        a.set_light_colors(&lcm);
        a.set_background_color(bk);
        let mut b = a.clone();
        prop_assert_eq!(a.normal_color(n), b.normal_color(Vector3::from(n)));
        prop_assert_eq!(Normal::from(Vector3::from(n)), n);
        prop_assert_eq!(a.gte(), b.gte());
    }
}

/// BK = 1.0 (4096) is 256 after SAR 4, saturated to 255 with the three colour bits set;
/// FF0h is the smallest BK that gives 255 unsaturated.
#[test]
fn background_color_one_saturates() {
    for (bk, rgb, flag) in [
        (0x1000, 0xFF, 0x38_0000),
        (0xFF0, 0xFF, 0),
        (0xFEF, 0xFE, 0),
    ] {
        let mut g = Geometry::new();
        g.set_background_color(BackgroundColor::from_bits([bk; 3]));
        assert_eq!(g.normal_color(Vector3::default()), [rgb; 3], "BK {bk:X}");
        assert_eq!(g.last_flag().bits(), flag, "BK {bk:X}");
    }
}

/// AVSZ3 with `Projection::default`'s ZSF3 = 555h, over every sum of three SZ values
/// (0..=3 × FFFFh): OTZ = floor(ΣSZ × 1365 / 4096), which is floor(ΣSZ / 3) or up to 16
/// below it, 16 only at the top; AVSZ4 with ZSF4 = 400h is floor(ΣSZ / 4) exactly.
#[test]
fn average_z_against_the_mean() {
    let mut g = Geometry::new();
    g.set_projection(&Projection::default());
    let mut worst = 0;
    for sum in 0..=3 * 0xFFFFu32 {
        let a = sum.min(0xFFFF);
        let b = (sum - a).min(0xFFFF);
        let c = sum - a - b;
        let otz = g.average_z3([a as u16, b as u16, c as u16]) as u32;
        assert_eq!(otz, sum * 1365 / 4096, "sum {sum}");
        let below = sum / 3 - otz;
        assert!(below <= 16, "sum {sum}");
        worst = worst.max(below);
        let four = g.average_z4([a as u16, b as u16, c as u16, 0]) as u32;
        assert_eq!(four, sum / 4, "sum {sum}");
    }
    assert_eq!(worst, 16);
    assert_eq!(g.average_z3([0, 3892, 1889]), 1926); // the mean is 1927
    assert_eq!(g.average_z3([0xFFFF; 3]), 0xFFFF - 16);
}

/// The rotation's bounds are reached: at the triples the exhaustive sweep (example
/// `rotation_sweep`) found, the entry error is within 0.001 of `ROTATION_ERROR` and R·Rᵀ's
/// distance is `ROTATION_ORTHOGONALITY` exactly.
#[test]
fn rotation_bounds_are_reached() {
    let turn = |a: i32| a as f64 / 4096.0 * std::f64::consts::TAU;
    let m = Matrix::rotation(42, 982, 2090).to_bits();
    let (sx, cx, sy, cy, sz, cz) = (
        turn(42).sin(),
        turn(42).cos(),
        turn(982).sin(),
        turn(982).cos(),
        turn(2090).sin(),
        turn(2090).cos(),
    );
    let exact = [
        [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
        [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
        [-sy, cy * sx, cy * cx],
    ];
    let worst = (0..9)
        .map(|k| (m[k / 3][k % 3] as f64 - 4096.0 * exact[k / 3][k % 3]).abs())
        .fold(0.0, f64::max);
    assert!(
        worst <= Matrix::ROTATION_ERROR && worst > Matrix::ROTATION_ERROR - 0.001,
        "{worst}"
    );
    let m = Matrix::rotation(127, 788, 2162).to_bits();
    let worst = (0..9)
        .map(|k| {
            let (i, j) = (k / 3, k % 3);
            let dot: i64 = (0..3).map(|c| m[i][c] as i64 * m[j][c] as i64).sum();
            (dot - if i == j { 1 << 24 } else { 0 }).abs()
        })
        .max();
    assert_eq!(worst, Some(37294));
    assert_eq!(Matrix::ROTATION_ORTHOGONALITY, 37294.0 / 4096.0);
}

/// `Flag`'s names: one per bit FLAG can hold, in bit order, and Display/Debug built from
/// them.
#[test]
fn flag_names() {
    let bits: Vec<u32> = Flag::NAMED.iter().map(|(f, _)| f.bits()).collect();
    let expected: Vec<u32> = (12..32).rev().map(|b| 1u32 << b).collect();
    assert_eq!(bits, expected);
    let all = Flag::from_bits(u32::MAX);
    let names: Vec<&str> = Flag::NAMED.iter().map(|(_, n)| *n).collect();
    assert_eq!(all.to_string(), names.join(" | "));
    assert_eq!(
        format!("{all:?}"),
        format!("Flag(0xFFFFF000: {})", names.join(" | "))
    );
    assert_eq!(Flag::EMPTY.to_string(), "EMPTY");
    assert_eq!(format!("{:?}", Flag::EMPTY), "Flag(0x00000000: EMPTY)");
    assert_eq!(Flag::from_bits(0x1000).to_string(), "IR0_SATURATED");
}
