//! Every typed operation against the reference model, value and FLAG, on set-ups from the
//! shipped strategies: the properties docs/typed-api.md says a user can write. Each operation
//! is given the registers it documents writing (V0-V2, IR0-3, RGBC, RGB0-2, MAC1-3, SXY,
//! SZ); the model runs the same command word on them, and the engine then holds exactly the
//! registers the model leaves.

#![cfg(feature = "typed")]

use gte::reference::{self, Trace};
use gte::strategy;
use gte::typed::{self, Geometry, I4F12, MvmvaVector, Rgb, Vector3};
use gte::{
    Command, DivideMode, Gte, GteState, MatrixSel, Opcode, Registers, TranslationSel, VectorSel,
};
use proptest::prelude::*;

/// A geometry on any register file, or one set up through the typed calls from the typed
/// strategies (rotation or any matrix, lights, colours, projection).
fn geometry() -> impl Strategy<Value = Geometry> {
    let raw = strategy::registers().prop_map(|registers| {
        let mut gte = Gte::new();
        let state = GteState {
            registers,
            ..gte.state()
        };
        gte.load_state(&state).expect("a valid state");
        Geometry::from_gte(gte)
    });
    let typed = (
        prop_oneof![strategy::rotation(), strategy::matrix()],
        strategy::translation(),
        strategy::projection(),
        (strategy::matrix(), strategy::matrix()),
        (strategy::background_color(), strategy::far_color()),
        0i16..=0x1000,
    )
        .prop_map(|(rt, tr, p, (llm, lcm), (bk, fc), ir0)| {
            let mut g = Geometry::new();
            g.set_rotation(&rt);
            g.set_translation(tr);
            g.set_projection(&p);
            g.set_light_matrix(&llm);
            g.set_light_colors(&lcm);
            g.set_background_color(bk);
            g.set_far_color(fc);
            g.set_interpolation_factor(I4F12::from_bits(ir0));
            g
        });
    prop_oneof![raw, typed]
}

fn modes() -> Vec<DivideMode> {
    [DivideMode::Unr, DivideMode::Exact, DivideMode::F32]
        .into_iter()
        .filter(|m| m.is_supported())
        .collect()
}

fn word(op: Opcode) -> u32 {
    typed::command(op)
}

fn rgbc(c: Rgb) -> u32 {
    u32::from_le_bytes([c[0], c[1], c[2], 0])
}

fn ir(regs: &mut Registers, v: Vector3) {
    regs.ir[1..].copy_from_slice(&v.to_array());
}

/// After the operation: the engine holds the model's registers, FLAG the model's.
fn same_state(g: &Geometry, regs: &Registers, trace: Trace) -> Result<(), TestCaseError> {
    prop_assert_eq!(&g.gte().registers(), regs);
    prop_assert_eq!(g.last_flag(), trace.flag());
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    /// RTPS: `project` and `project_subpixel` write V0.
    #[test]
    fn project(mut g in geometry(), v in strategy::vertex(), mode in prop::sample::select(modes())) {
        g.set_divide_mode(mode).unwrap();
        let mut regs = g.gte().registers();
        regs.v[0] = v.to_array();
        let t = reference::rtps(&mut regs, true, false, mode);
        let mut h = g.clone();
        let p = g.project(v);
        prop_assert_eq!([p.x, p.y], t.vertex.sxy);
        prop_assert_eq!(p.sz, t.vertex.sz3);
        prop_assert_eq!(p.ir0.to_bits(), t.depth_cue.ir0);
        prop_assert_eq!(p.flag, t.flag);
        prop_assert_eq!(p.camera.mac, t.vertex.camera.mac());
        prop_assert_eq!(p.camera.ir, t.vertex.camera.ir());
        prop_assert_eq!(p.mac0, t.depth_cue.mac0);
        prop_assert_eq!(p.quotient, t.vertex.quotient);
        same_state(&g, &regs, Trace::Rtps(t))?;
        let s = h.project_subpixel(v);
        prop_assert_eq!(s.projected, p);
        let limit = 0x400i64 << 16;
        prop_assert_eq!(s.x.to_bits() as i64, t.vertex.screen[0].clamp(-limit, limit - 1));
        prop_assert_eq!(s.y.to_bits() as i64, t.vertex.screen[1].clamp(-limit, limit - 1));
    }

    /// RTPT: `project_triangle` writes V0-V2.
    #[test]
    fn project_triangle(mut g in geometry(), v in prop::array::uniform3(strategy::vertex()), mode in prop::sample::select(modes())) {
        g.set_divide_mode(mode).unwrap();
        let mut regs = g.gte().registers();
        regs.v = v.map(Vector3::to_array);
        let t = reference::rtpt(&mut regs, true, false, mode);
        let p = g.project_triangle(v);
        for k in 0..3 {
            prop_assert_eq!([p.xy[k].0, p.xy[k].1], t.vertices[k].sxy);
            prop_assert_eq!(p.sz[k], t.vertices[k].sz3);
            prop_assert_eq!(p.quotient[k], t.vertices[k].quotient);
        }
        prop_assert_eq!(p.ir0.to_bits(), t.depth_cue.ir0);
        prop_assert_eq!(p.flag, t.flag);
        prop_assert_eq!(p.camera.mac, t.vertices[2].camera.mac());
        prop_assert_eq!(p.camera.ir, t.vertices[2].camera.ir());
        prop_assert_eq!(p.mac0, t.depth_cue.mac0);
        same_state(&g, &regs, Trace::Rtpt(t))?;
    }

    /// NCLIP: `nclip` writes SXY0-2; `nclip_current` nothing.
    #[test]
    fn nclip(mut g in geometry(), xy in prop::array::uniform3((strategy::half(), strategy::half()))) {
        let mut regs = g.gte().registers();
        let t = reference::nclip(&mut regs.clone());
        let mut current = g.clone();
        prop_assert_eq!(current.nclip_current(), t.mac0);
        prop_assert_eq!(current.last_flag(), t.flag);
        regs.sxy = xy.map(|(x, y)| x as u16 as u32 | (y as u16 as u32) << 16);
        let t = reference::nclip(&mut regs);
        prop_assert_eq!(g.nclip(xy), t.mac0);
        same_state(&g, &regs, Trace::Nclip(t))?;
    }

    /// AVSZ3 writes SZ1-3, AVSZ4 SZ0-3.
    #[test]
    fn average_z(mut g in geometry(), sz in prop::array::uniform4(strategy::unsigned_half()), four in any::<bool>()) {
        let mut regs = g.gte().registers();
        let (otz, t) = if four {
            regs.sz = sz;
            (g.average_z4(sz), reference::avsz4(&mut regs))
        } else {
            regs.sz[1..].copy_from_slice(&sz[..3]);
            (g.average_z3([sz[0], sz[1], sz[2]]), reference::avsz3(&mut regs))
        };
        prop_assert_eq!(otz, t.otz);
        same_state(&g, &regs, Trace::AverageZ(t))?;
    }

    /// NCS/NCCS/NCDS write V0 (and RGBC); NCT/NCCT/NCDT V0-V2 (and RGBC).
    #[test]
    fn normal_colors(
        mut g in geometry(),
        n in prop::array::uniform3(strategy::normal()),
        color in any::<[u8; 3]>(),
        which in 0usize..6,
    ) {
        let mut regs = g.gte().registers();
        let op = [Opcode::Ncs, Opcode::Nccs, Opcode::Ncds, Opcode::Nct, Opcode::Ncct, Opcode::Ncdt][which];
        if which % 3 != 0 {
            regs.rgbc = rgbc(color);
        }
        let trace = if which < 3 {
            regs.v[0] = n[0].to_bits();
            let trace = reference::execute(&mut regs, word(op));
            let Trace::Lit(t) = trace else { unreachable!() };
            let got = match which {
                0 => g.normal_color(n[0]),
                1 => g.normal_color_color(n[0], color),
                _ => g.normal_color_depth(n[0], color),
            };
            prop_assert_eq!(got, t.push.rgb);
            trace
        } else {
            regs.v = n.map(|n| n.to_bits());
            let trace = reference::execute(&mut regs, word(op));
            let Trace::LitTriple(t) = trace else { unreachable!() };
            let got = match which {
                3 => g.normal_color_triple(n),
                4 => g.normal_color_color_triple(n, color),
                _ => g.normal_color_depth_triple(n, color),
            };
            prop_assert_eq!(got, t.vertices.map(|v| v.push.rgb));
            trace
        };
        same_state(&g, &regs, trace)?;
    }

    /// CC and CDP write IR1-3 and RGBC.
    #[test]
    fn color_color_and_depth(mut g in geometry(), light in strategy::vertex(), color in any::<[u8; 3]>(), depth in any::<bool>()) {
        let mut regs = g.gte().registers();
        regs.rgbc = rgbc(color);
        ir(&mut regs, light);
        let (got, t) = if depth {
            (g.color_depth(light, color), reference::cdp(&mut regs, true, true))
        } else {
            (g.color_color(light, color), reference::cc(&mut regs, true, true))
        };
        prop_assert_eq!(got, t.push.rgb);
        same_state(&g, &regs, Trace::Lit(t))?;
    }

    /// DPCS writes RGBC and IR0; DPCT RGB0-2 and IR0; DCPL RGBC, IR1-3 and IR0.
    #[test]
    fn depth_cues(
        mut g in geometry(),
        colors in any::<[[u8; 3]; 3]>(),
        light in strategy::vertex(),
        ir0 in strategy::half(),
        which in 0usize..3,
    ) {
        let mut regs = g.gte().registers();
        let ir0 = I4F12::from_bits(ir0);
        regs.ir[0] = ir0.to_bits();
        let trace = match which {
            0 => {
                regs.rgbc = rgbc(colors[0]);
                let t = reference::dpcs(&mut regs, true, false);
                prop_assert_eq!(g.depth_cue(colors[0], ir0), t.push.rgb);
                Trace::DepthCued(t)
            }
            1 => {
                regs.rgb = colors.map(rgbc);
                let t = reference::dpct(&mut regs, true, false);
                prop_assert_eq!(g.depth_cue_triple(colors, ir0), t.entries.map(|e| e.push.rgb));
                Trace::DepthCuedTriple(t)
            }
            _ => {
                regs.rgbc = rgbc(colors[0]);
                ir(&mut regs, light);
                let t = reference::dcpl(&mut regs, true, false);
                prop_assert_eq!(g.depth_cue_light(light, colors[0], ir0), t.push.rgb);
                Trace::DepthCued(t)
            }
        };
        same_state(&g, &regs, trace)?;
    }

    /// INTPL and GPF write IR1-3 and IR0; GPL also MAC1-3.
    #[test]
    fn interpolations(
        mut g in geometry(),
        v in strategy::vertex(),
        ir0 in strategy::half(),
        base in prop::array::uniform3(strategy::word()),
        which in 0usize..3,
    ) {
        let mut regs = g.gte().registers();
        let ir0 = I4F12::from_bits(ir0);
        regs.ir[0] = ir0.to_bits();
        ir(&mut regs, v);
        let (got, step, push, trace) = match which {
            0 => {
                let t = reference::intpl(&mut regs, true, false);
                (g.interpolate(v, ir0), t.interpolation.near, t.push, Trace::DepthCued(t))
            }
            1 => {
                let t = reference::gpf(&mut regs, true, false);
                (g.general_interpolate(v, ir0), t.step, t.push, Trace::General(t))
            }
            _ => {
                regs.mac[1..].copy_from_slice(&base);
                let t = reference::gpl(&mut regs, true, false);
                (g.general_interpolate_with_base(base, v, ir0), t.step, t.push, Trace::General(t))
            }
        };
        prop_assert_eq!(got.mac_ir.mac, step.mac());
        prop_assert_eq!(got.mac_ir.ir, step.ir());
        prop_assert_eq!(got.rgb, push.rgb);
        same_state(&g, &regs, trace)?;
    }

    /// MVMVA writes the chosen vector to V0, V1, V2 or IR1-3; every matrix, add vector and
    /// lm, the hardware's garbage matrix and far-colour bug included.
    #[test]
    fn multiply_add(
        mut g in geometry(),
        v in strategy::vertex(),
        (mx, which, cv) in (0usize..4, 0usize..4, 0usize..4),
        lm in any::<bool>(),
    ) {
        let mut regs = g.gte().registers();
        let matrix = [MatrixSel::Rotation, MatrixSel::Light, MatrixSel::LightColor, MatrixSel::Garbage][mx];
        let add = [TranslationSel::Translation, TranslationSel::Background, TranslationSel::FarColor, TranslationSel::None][cv];
        let (vector, selector) = match which {
            0 => (MvmvaVector::V0(v), VectorSel::V0),
            1 => (MvmvaVector::V1(v), VectorSel::V1),
            2 => (MvmvaVector::V2(v), VectorSel::V2),
            _ => (MvmvaVector::Ir(v), VectorSel::Ir),
        };
        if which < 3 {
            regs.v[which] = v.to_array();
        } else {
            ir(&mut regs, v);
        }
        let t = reference::mvmva(&mut regs, Command::build(Opcode::Mvmva, true, lm, matrix, selector, add));
        let got = g.multiply_add(matrix, vector, add, lm);
        prop_assert_eq!(got.mac, t.step.mac());
        prop_assert_eq!(got.ir, t.step.ir());
        same_state(&g, &regs, Trace::Mvmva(t))?;
    }

    /// OP and SQR write IR1-3.
    #[test]
    fn outer_product_and_square(mut g in geometry(), v in strategy::vertex(), square in any::<bool>()) {
        let mut regs = g.gte().registers();
        ir(&mut regs, v);
        let (got, t) = if square {
            (g.square(v), reference::sqr(&mut regs, true, true))
        } else {
            (g.outer_product(v), reference::op(&mut regs, true, false))
        };
        prop_assert_eq!(got.mac, t.step.mac());
        prop_assert_eq!(got.ir, t.step.ir());
        same_state(&g, &regs, Trace::Vector(t))?;
    }
}
