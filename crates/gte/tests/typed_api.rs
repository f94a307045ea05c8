//! The typed API gives exactly what the register-level path gives: each property performs
//! the same operation by hand (register writes, command words assembled from the fact
//! sheet's bit layout, docs/hardware/gte.md §1) and compares.

#![cfg(feature = "typed")]

use gte::reference;
use gte::typed::{Geometry, I4F12, I8F8, I8F24, I16F16, Matrix, Projection, Translation, Vector3};
use gte::{DivideMode, Gte};
use proptest::prelude::*;

/// sf = 1 (bit 19), lm = 0, no MVMVA selectors.
const SF: u32 = 1 << 19;

fn packed(lo: i16, hi: i16) -> u32 {
    (lo as u16 as u32) | ((hi as u16 as u32) << 16)
}

/// The divide modes this build runs: all three with `divide-modes`, UNR alone without.
fn supported_modes() -> Vec<DivideMode> {
    [DivideMode::Unr, DivideMode::Exact, DivideMode::F32]
        .into_iter()
        .filter(|m| m.is_supported())
        .collect()
}

fn matrix() -> impl Strategy<Value = [[i16; 3]; 3]> {
    prop::array::uniform3(prop::array::uniform3(any::<i16>()))
}

fn vector() -> impl Strategy<Value = Vector3> {
    (any::<i16>(), any::<i16>(), any::<i16>()).prop_map(|(x, y, z)| Vector3 { x, y, z })
}

fn load_matrix(gte: &mut Gte, first: u32, m: &[[i16; 3]; 3]) {
    gte.write_control(first, packed(m[0][0], m[0][1]));
    gte.write_control(first + 1, packed(m[0][2], m[1][0]));
    gte.write_control(first + 2, packed(m[1][1], m[1][2]));
    gte.write_control(first + 3, packed(m[2][0], m[2][1]));
    gte.write_control(first + 4, m[2][2] as u16 as u32);
}

#[derive(Debug, Clone)]
struct Setup {
    rt: [[i16; 3]; 3],
    tr: [i32; 3],
    ofx: i32,
    ofy: i32,
    h: u16,
    dqa: i16,
    dqb: i32,
    zsf3: i16,
    zsf4: i16,
}

fn setup() -> impl Strategy<Value = Setup> {
    (
        matrix(),
        prop::array::uniform3(any::<i32>()),
        any::<i32>(),
        any::<i32>(),
        any::<u16>(),
        any::<i16>(),
        any::<i32>(),
        (any::<i16>(), any::<i16>()),
    )
        .prop_map(|(rt, tr, ofx, ofy, h, dqa, dqb, (zsf3, zsf4))| Setup {
            rt,
            tr,
            ofx,
            ofy,
            h,
            dqa,
            dqb,
            zsf3,
            zsf4,
        })
}

fn typed(s: &Setup) -> Geometry {
    let mut g = Geometry::new();
    g.set_rotation(&Matrix::from_bits(s.rt));
    g.set_translation(Translation {
        x: s.tr[0],
        y: s.tr[1],
        z: s.tr[2],
    });
    g.set_projection(&Projection {
        offset_x: I16F16::from_bits(s.ofx),
        offset_y: I16F16::from_bits(s.ofy),
        h: s.h,
        dqa: I8F8::from_bits(s.dqa),
        dqb: I8F24::from_bits(s.dqb),
        zsf3: I4F12::from_bits(s.zsf3),
        zsf4: I4F12::from_bits(s.zsf4),
    });
    g
}

fn by_hand(s: &Setup) -> Gte {
    let mut gte = Gte::new();
    load_matrix(&mut gte, 0, &s.rt);
    for i in 0..3 {
        gte.write_control((5 + i) as u32, s.tr[i] as u32);
    }
    gte.write_control(24, s.ofx as u32);
    gte.write_control(25, s.ofy as u32);
    gte.write_control(26, s.h as u32);
    gte.write_control(27, s.dqa as u16 as u32);
    gte.write_control(28, s.dqb as u32);
    gte.write_control(29, s.zsf3 as u16 as u32);
    gte.write_control(30, s.zsf4 as u16 as u32);
    gte
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn project_equals_rtps(s in setup(), v in vector(), mode in prop::sample::select(supported_modes())) {
        let mut g = typed(&s);
        g.set_divide_mode(mode).unwrap();
        let p = g.project(v);
        let mut gte = by_hand(&s);
        gte.set_divide_mode(mode).unwrap();
        gte.write_data(0, packed(v.x, v.y));
        gte.write_data(1, v.z as u16 as u32);
        gte.execute(0x01 | SF);
        prop_assert_eq!(packed(p.x, p.y), gte.read_data(14));
        prop_assert_eq!(p.sz as u32, gte.read_data(19));
        prop_assert_eq!(p.ir0.to_bits() as i32 as u32, gte.read_data(8));
        prop_assert_eq!(p.flag.bits(), gte.read_control(31));
        prop_assert_eq!(g.gte(), &gte);
    }

    #[test]
    fn project_triangle_equals_rtpt(s in setup(), v in prop::array::uniform3(vector())) {
        let mut g = typed(&s);
        let p = g.project_triangle(v);
        let mut gte = by_hand(&s);
        for (i, v) in v.iter().enumerate() {
            gte.write_data((2 * i) as u32, packed(v.x, v.y));
            gte.write_data((2 * i + 1) as u32, v.z as u16 as u32);
        }
        gte.execute(0x30 | SF);
        for i in 0..3 {
            prop_assert_eq!(packed(p.xy[i].0, p.xy[i].1), gte.read_data((12 + i) as u32));
            prop_assert_eq!(p.sz[i] as u32, gte.read_data((17 + i) as u32));
        }
        prop_assert_eq!(p.flag.bits(), gte.read_control(31));
        prop_assert_eq!(g.gte(), &gte);
        // NCLIP and AVSZ3 on the result, typed and by hand.
        let area = g.nclip_current();
        gte.execute(0x06);
        prop_assert_eq!(area as u32, gte.read_data(24));
        let otz = g.average_z3(p.sz);
        gte.execute(0x2D);
        prop_assert_eq!(otz as u32, gte.read_data(7));
    }

    #[test]
    fn average_z4_equals_avsz4(s in setup(), sz in prop::array::uniform4(any::<u16>())) {
        let mut g = typed(&s);
        let otz = g.average_z4(sz);
        let mut gte = by_hand(&s);
        for (i, z) in sz.iter().enumerate() {
            gte.write_data((16 + i) as u32, *z as u32);
        }
        gte.execute(0x2E);
        prop_assert_eq!(otz as u32, gte.read_data(7));
        prop_assert_eq!(g.gte(), &gte);
    }

    #[test]
    fn lighting_equals_register_path(
        llm in matrix(), lcm in matrix(), bk in prop::array::uniform3(any::<i32>()),
        fc in prop::array::uniform3(any::<i32>()), n in prop::array::uniform3(vector()),
        color in prop::array::uniform3(any::<u8>()), ir0 in 0i16..=0x1000, op in 0usize..7
    ) {
        let mut g = Geometry::new();
        g.set_light_matrix(&Matrix::from_bits(llm));
        g.set_light_colors(&Matrix::from_bits(lcm));
        g.set_background_color(bk);
        g.set_far_color(fc);
        g.gte_mut().write_data(8, ir0 as u16 as u32);
        let mut gte = Gte::new();
        load_matrix(&mut gte, 8, &llm);
        load_matrix(&mut gte, 16, &lcm);
        for i in 0..3 {
            gte.write_control((13 + i) as u32, bk[i] as u32);
            gte.write_control((21 + i) as u32, fc[i] as u32);
        }
        gte.write_data(8, ir0 as u16 as u32);
        let rgbc = color[0] as u32 | (color[1] as u32) << 8 | (color[2] as u32) << 16;
        let triple = op % 2 == 1;
        let got: Vec<[u8; 3]> = match op {
            0 => vec![g.normal_color(n[0])],
            1 => g.normal_color_triple(n).to_vec(),
            2 => vec![g.normal_color_color(n[0], color)],
            3 => g.normal_color_color_triple(n, color).to_vec(),
            4 => vec![g.normal_color_depth(n[0], color)],
            5 => g.normal_color_depth_triple(n, color).to_vec(),
            _ => vec![g.depth_cue(color, I4F12::from_bits(ir0))],
        };
        let opcode = [0x1E, 0x20, 0x1B, 0x3F, 0x13, 0x16, 0x10][op];
        if op >= 2 {
            gte.write_data(6, rgbc);
        }
        for (i, v) in n.iter().enumerate() {
            gte.write_data((2 * i) as u32, packed(v.x, v.y));
            gte.write_data((2 * i + 1) as u32, v.z as u16 as u32);
        }
        // The SDK's lighting words set lm (bit 10); DPCS does not.
        let lm = if op < 6 { 1 << 10 } else { 0 };
        gte.execute(opcode | SF | lm);
        let fifo: Vec<[u8; 3]> = (20..23)
            .map(|r| {
                let w = gte.read_data(r);
                [w as u8, (w >> 8) as u8, (w >> 16) as u8]
            })
            .collect();
        let expected = if triple { fifo } else { fifo[2..].to_vec() };
        prop_assert_eq!(got, expected);
    }
}

/// A vertex on the optical axis lands exactly on (OFX, OFY).
#[test]
fn on_axis_vertex_lands_on_offset() {
    let mut g = Geometry::new();
    g.set_rotation(&Matrix::IDENTITY);
    g.set_translation(Translation {
        x: 0,
        y: 0,
        z: 1000,
    });
    g.set_projection(&Projection::default());
    let p = g.project(Vector3 { x: 0, y: 0, z: 0 });
    assert_eq!((p.x, p.y, p.sz), (160, 120, 1000));
    assert!(p.flag.is_empty());
}

/// X at distance Z with H = Z projects to OFX + X (H/Z = 1.0 exactly in UNR: 10000h).
#[test]
fn similar_triangles() {
    let mut g = Geometry::new();
    g.set_rotation(&Matrix::IDENTITY);
    g.set_translation(Translation { x: 0, y: 0, z: 512 });
    g.set_projection(&Projection {
        h: 512,
        ..Projection::default()
    });
    let p = g.project(Vector3 {
        x: 100,
        y: -50,
        z: 0,
    });
    assert_eq!((p.x, p.y), (260, 70));
    // Twice as far: half the offset. 512/1024 * 65536 = 32768 exactly, 100 * 0.5 = 50.
    g.set_translation(Translation {
        x: 0,
        y: 0,
        z: 1024,
    });
    let p = g.project(Vector3 {
        x: 100,
        y: -50,
        z: 0,
    });
    assert_eq!((p.x, p.y), (210, 95));
}

proptest! {
    /// Matrix, translation and projection types survive the trip through the registers: what
    /// the set-up calls write reads back through CFC2 as the same bits (H and the 16-bit
    /// registers sign-extended, docs/hardware/gte.md §2).
    #[test]
    fn setup_round_trips_through_registers(s in setup()) {
        let g = typed(&s);
        prop_assert_eq!(Matrix::from_bits(s.rt).to_bits(), s.rt);
        let gte = g.gte();
        let rt = [
            packed(s.rt[0][0], s.rt[0][1]),
            packed(s.rt[0][2], s.rt[1][0]),
            packed(s.rt[1][1], s.rt[1][2]),
            packed(s.rt[2][0], s.rt[2][1]),
            s.rt[2][2] as i32 as u32,
        ];
        for (i, w) in rt.into_iter().enumerate() {
            prop_assert_eq!(gte.read_control((i) as u32), w);
        }
        for i in 0..3 {
            prop_assert_eq!(gte.read_control((5 + i) as u32), s.tr[i] as u32);
        }
        prop_assert_eq!(gte.read_control(24), s.ofx as u32);
        prop_assert_eq!(gte.read_control(25), s.ofy as u32);
        prop_assert_eq!(gte.read_control(26), s.h as i16 as i32 as u32);
        prop_assert_eq!(gte.read_control(27), s.dqa as i32 as u32);
        prop_assert_eq!(gte.read_control(28), s.dqb as u32);
        prop_assert_eq!(gte.read_control(29), s.zsf3 as i32 as u32);
        prop_assert_eq!(gte.read_control(30), s.zsf4 as i32 as u32);
    }

    /// NCLIP of explicit screen points equals the doubled signed area computed in i64.
    #[test]
    fn nclip_of_points(p in prop::array::uniform3((-1024i16..1024, -1024i16..1024))) {
        let mut g = Geometry::new();
        let got = g.nclip(p);
        let [(x0, y0), (x1, y1), (x2, y2)] = p.map(|(x, y)| (x as i64, y as i64));
        let area = x0 * y1 + x1 * y2 + x2 * y0 - x0 * y2 - x1 * y0 - x2 * y1;
        prop_assert_eq!(got as i64, area);
    }
}

/// A set-up whose projections mostly land on screen, so the unsaturated case is exercised.
fn on_screen_setup() -> impl Strategy<Value = Setup> {
    (
        prop::array::uniform3(prop::array::uniform3(-4096i16..=4096)),
        (-2000i32..2000, -2000i32..2000, 200i32..20000),
        any::<i32>().prop_map(|f| (160 << 16) + (f & 0xFFFF)),
        any::<i32>().prop_map(|f| (120 << 16) + (f & 0xFFFF)),
        100u16..1000,
    )
        .prop_map(|(rt, (x, y, z), ofx, ofy, h)| Setup {
            rt,
            tr: [x, y, z],
            ofx,
            ofy,
            h,
            dqa: 0,
            dqb: 0,
            zsf3: 0,
            zsf4: 0,
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn project_subpixel_properties(
        s in prop_oneof![setup(), on_screen_setup()],
        v in prop_oneof![vector(), prop::array::uniform3(-1000i16..1000).prop_map(|[x, y, z]| Vector3 { x, y, z })],
        mode in prop::sample::select(supported_modes()),
    ) {
        let mut g = typed(&s);
        g.set_divide_mode(mode).unwrap();
        let mut reference = g.clone();
        let p = reference.project(v);
        let sp = g.project_subpixel(v);
        // One RTPS: the same result and the same register file as `project`.
        prop_assert_eq!(sp.projected, p);
        prop_assert_eq!(g.gte(), reference.gte());
        let sat_x = p.flag.contains(gte::Flag::SX2_SATURATED);
        let sat_y = p.flag.contains(gte::Flag::SY2_SATURATED);
        if !sat_x {
            prop_assert_eq!(sp.x.floor().to_num::<i32>(), p.x as i32);
        }
        if !sat_y {
            prop_assert_eq!(sp.y.floor().to_num::<i32>(), p.y as i32);
        }
        // The screen values the reference model computes before SXY's truncation, in the
        // same divide mode, saturated to the range whose integer parts are SXY's.
        let mut regs = typed(&s).gte().registers();
        regs.v[0] = [v.x, v.y, v.z];
        let t = reference::rtps(&mut regs, true, false, mode);
        let limit = 0x400i64 << 16;
        let [x, y] = t.vertex.screen.map(|s| s.clamp(-limit, limit - 1));
        prop_assert_eq!(sp.x.to_bits() as i64, x);
        prop_assert_eq!(sp.y.to_bits() as i64, y);
        prop_assert_eq!(sp.projected.quotient, t.vertex.quotient);
    }
}

#[test]
fn subpixel_on_axis_keeps_the_offset_fraction() {
    // A vertex on the optical axis: IR1 = IR2 = 0, so the screen position is OFX/OFY exactly
    // (docs/hardware/gte.md §5 step 6), fraction included, while SXY holds the integer parts.
    let mut g = Geometry::new();
    g.set_rotation(&Matrix::IDENTITY);
    g.set_translation(Translation {
        x: 0,
        y: 0,
        z: 1000,
    });
    g.set_projection(&Projection {
        offset_x: I16F16::from_bits((160 << 16) | 0xC000),
        offset_y: I16F16::from_bits((120 << 16) | 0x4000),
        ..Projection::default()
    });
    let sp = g.project_subpixel(Vector3::default());
    assert_eq!(sp.x, I16F16::from_num(160.75));
    assert_eq!(sp.y, I16F16::from_num(120.25));
    assert_eq!((sp.projected.x, sp.projected.y), (160, 120));
}

fn fixed_matrix() -> impl Strategy<Value = Matrix> {
    matrix().prop_map(Matrix::from_bits)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Angles are 1/4096 turn: only the low 12 bits matter, for every i32 (no overflow near
    /// i32::MIN/MAX), and the table is within one unit of 4096 * sin computed in f64.
    #[test]
    fn rotation_uses_low_12_bits(x in any::<i32>(), y in any::<i32>(), z in any::<i32>()) {
        prop_assert_eq!(Matrix::rotation(x, y, z), Matrix::rotation(x & 0xFFF, y & 0xFFF, z & 0xFFF));
        let turn = (x & 0xFFF) as f64 / 4096.0 * std::f64::consts::TAU;
        prop_assert!((gte::typed::sin(x) as f64 - 4096.0 * turn.sin()).abs() <= 0.5 + 1e-9);
        prop_assert!((gte::typed::cos(x) as f64 - 4096.0 * turn.cos()).abs() <= 0.5 + 1e-9);
    }

    /// Every typed entry point with full-range inputs (every i32/i16/u16/u8 and fixed-point
    /// bit pattern; the projection from `gte::strategy`, full range and its edges) in one
    /// sequence, run with overflow checks: no panic, and every result keeps the documented
    /// ranges.
    #[test]
    fn every_entry_point_full_range(
        angles in prop::array::uniform3(any::<i32>()),
        m in prop::array::uniform3(fixed_matrix()),
        tr in prop::array::uniform3(any::<i32>()),
        p in gte::strategy::projection(),
        colors in (prop::array::uniform3(any::<i32>()), prop::array::uniform3(any::<i32>())),
        v in prop::array::uniform3(vector()),
        xy in prop::array::uniform3((any::<i16>(), any::<i16>())),
        sz in prop::array::uniform4(any::<u16>()),
        rgb in prop::array::uniform3(any::<u8>()),
        ir0 in any::<i16>(),
        mode in prop::sample::select(supported_modes()),
    ) {
        let r = Matrix::rotation(angles[0], angles[1], angles[2]);
        let product = r.multiply(&m[0]).multiply(&m[1]);
        prop_assert_eq!(Matrix::from_bits(product.to_bits()), product);
        let mut g = Geometry::from_gte(Gte::new());
        g.set_divide_mode(mode).unwrap();
        g.set_rotation(&product);
        g.set_translation(Translation { x: tr[0], y: tr[1], z: tr[2] });
        g.set_projection(&p);
        g.set_light_matrix(&m[1]);
        g.set_light_colors(&m[2]);
        g.set_background_color(colors.0);
        g.set_far_color(colors.1);
        let one = g.project(v[0]);
        let sub = g.project_subpixel(v[1]);
        prop_assert_eq!(sub.x.floor().to_num::<i32>(), sub.projected.x as i32);
        prop_assert_eq!(sub.y.floor().to_num::<i32>(), sub.projected.y as i32);
        let three = g.project_triangle(v);
        for (x, y) in [(one.x, one.y)].into_iter().chain(three.xy) {
            prop_assert!((-0x400..=0x3FF).contains(&x) && (-0x400..=0x3FF).contains(&y));
        }
        prop_assert!((0..=0x1000).contains(&three.ir0.to_bits()));
        let _ = g.nclip_current();
        let _ = g.nclip(xy);
        let _ = g.average_z3([sz[0], sz[1], sz[2]]);
        let _ = g.average_z4(sz);
        let _ = g.normal_color(v[0]);
        let _ = g.normal_color_triple(v);
        let _ = g.normal_color_color(v[1], rgb);
        let _ = g.normal_color_color_triple(v, rgb);
        let _ = g.normal_color_depth(v[2], rgb);
        let _ = g.normal_color_depth_triple(v, rgb);
        let _ = g.depth_cue(rgb, I4F12::from_bits(ir0));
        let flag = g.gte().flag().bits();
        prop_assert_eq!(flag & 0xFFF, 0);
        prop_assert_eq!(flag >> 31 == 1, flag & 0x7F87_E000 != 0);
        let _ = g.gte_mut().execute(gte::typed::command(gte::Opcode::Mvmva));
    }
}
