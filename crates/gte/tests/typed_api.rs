//! The typed API gives exactly what the register-level path gives: each property performs
//! the same operation by hand (register writes, command words assembled from the fact
//! sheet's bit layout, gte.md §1) and compares.

use gte::typed::{Geometry, I4F12, I8F8, I8F24, I16F16, Matrix, Projection, Translation, Vector3};
use gte::{DivideMode, Gte};
use proptest::prelude::*;

/// sf = 1 (bit 19), lm = 0, no MVMVA selectors.
const SF: u32 = 1 << 19;

fn packed(lo: i16, hi: i16) -> u32 {
    (lo as u16 as u32) | ((hi as u16 as u32) << 16)
}

fn matrix() -> impl Strategy<Value = [[i16; 3]; 3]> {
    prop::array::uniform3(prop::array::uniform3(any::<i16>()))
}

fn vector() -> impl Strategy<Value = Vector3> {
    (any::<i16>(), any::<i16>(), any::<i16>()).prop_map(|(x, y, z)| Vector3 { x, y, z })
}

fn load_matrix(gte: &mut Gte, first: usize, m: &[[i16; 3]; 3]) {
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
        gte.write_control(5 + i, s.tr[i] as u32);
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
    fn project_equals_rtps(s in setup(), v in vector(), mode in prop::sample::select(vec![DivideMode::Unr, DivideMode::Exact, DivideMode::F32])) {
        let mut g = typed(&s);
        g.set_divide_mode(mode);
        let p = g.project(v);
        let mut gte = by_hand(&s);
        gte.set_divide_mode(mode);
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
            gte.write_data(2 * i, packed(v.x, v.y));
            gte.write_data(2 * i + 1, v.z as u16 as u32);
        }
        gte.execute(0x30 | SF);
        for i in 0..3 {
            prop_assert_eq!(packed(p.xy[i].0, p.xy[i].1), gte.read_data(12 + i));
            prop_assert_eq!(p.sz[i] as u32, gte.read_data(17 + i));
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
            gte.write_data(16 + i, *z as u32);
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
            gte.write_control(13 + i, bk[i] as u32);
            gte.write_control(21 + i, fc[i] as u32);
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
            gte.write_data(2 * i, packed(v.x, v.y));
            gte.write_data(2 * i + 1, v.z as u16 as u32);
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
    /// registers sign-extended, gte.md §2).
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
            prop_assert_eq!(gte.read_control(i), w);
        }
        for i in 0..3 {
            prop_assert_eq!(gte.read_control(5 + i), s.tr[i] as u32);
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
