//! Three properties a user of `gte::typed` writes with the shipped strategies
//! (`gte::strategy`) and the reference model (`gte::reference`): run with
//! `cargo run -p gte --example properties --features reference,proptest`.
//!
//! 1. A projection gives exactly the screen position, depth, quotient and FLAG the reference
//!    model computes, for any set-up: an exact property, value and FLAG.
//! 2. A camera set-up that sees a scene projects all of it on screen with FLAG clear: a
//!    renderer's property, on generated on-screen set-ups.
//! 3. Lighting gives the reference model's colour and FLAG for any normal, lights and
//!    colours, and no colour byte comes out of a negative light.

use gte::reference::{self, Trace};
use gte::strategy;
use gte::typed::{
    BackgroundColor, FarColor, Geometry, I4F12, Matrix, Normal, Projection, Translation, Vector3,
};
use gte::{DivideMode, Opcode};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    fn projection_matches_the_reference(
        rotation in strategy::rotation(),
        translation in strategy::translation(),
        projection in strategy::projection(),
        v in strategy::vertex(),
    ) {
        let mut g = Geometry::new();
        g.set_rotation(&rotation);
        g.set_translation(translation);
        g.set_projection(&projection);
        // `project` writes V0 and runs RTPS: the model runs RTPS on the same registers.
        let mut regs = g.gte().registers();
        regs.v[0] = v.to_array();
        let expected = reference::rtps(&mut regs, true, false, DivideMode::Unr);
        let p = g.project(v);
        prop_assert_eq!([p.x, p.y], expected.vertex.sxy);
        prop_assert_eq!(p.sz, expected.vertex.sz3);
        prop_assert_eq!(p.quotient, expected.vertex.quotient);
        prop_assert_eq!(p.camera.mac, expected.vertex.camera.mac());
        prop_assert_eq!(p.ir0.to_bits(), expected.depth_cue.ir0);
        prop_assert_eq!(p.flag, expected.flag);
        // And the screen position is the exact one whenever it is on the screen range.
        if !p.flag.intersects(gte::Flag::SX2_SATURATED) {
            prop_assert_eq!(p.x as i64, expected.vertex.screen[0] >> 16);
        }
    }

    fn on_screen_set_ups_stay_on_screen(s in strategy::on_screen()) {
        let mut g = Geometry::new();
        g.set_rotation(&s.rotation);
        g.set_translation(s.translation);
        g.set_projection(&s.projection);
        let t = g.project_triangle(s.vertices);
        for (x, y) in t.xy {
            prop_assert!((10..=310).contains(&x) && (10..=230).contains(&y), "({}, {})", x, y);
        }
        prop_assert!(t.flag.is_empty(), "{}", t.flag);
        prop_assert!(g.nclip_current() != i32::MIN);
    }

    fn lighting_matches_the_reference(
        light in strategy::matrix(),
        colors in strategy::matrix(),
        bk in strategy::background_color(),
        fc in strategy::far_color(),
        n in strategy::normal(),
        rgb in any::<[u8; 3]>(),
        ir0 in 0i16..=0x1000,
    ) {
        let mut g = Geometry::new();
        g.set_light_matrix(&light);
        g.set_light_colors(&colors);
        g.set_background_color(bk);
        g.set_far_color(fc);
        g.set_interpolation_factor(I4F12::from_bits(ir0));
        // NCDS writes V0 and RGBC (CODE 0) and runs with lm = 1.
        let mut regs = g.gte().registers();
        regs.v[0] = n.to_bits();
        regs.rgbc = u32::from_le_bytes([rgb[0], rgb[1], rgb[2], 0]);
        let Trace::Lit(expected) =
            reference::execute(&mut regs, gte::typed::command(Opcode::Ncds))
        else {
            unreachable!()
        };
        let got = g.normal_color_depth(n, rgb);
        prop_assert_eq!(got, expected.push.rgb);
        prop_assert_eq!(g.last_flag(), expected.flag);
        // lm = 1: the light step never goes below zero.
        prop_assert!(expected.light.is_some_and(|l| l.ir().iter().all(|&i| i >= 0)));
    }
}

fn main() {
    projection_matches_the_reference();
    on_screen_set_ups_stay_on_screen();
    lighting_matches_the_reference();
    println!("3 properties held, 2000 cases each");
    // The types the strategies produce can also be built by hand.
    let _ = (
        Matrix::IDENTITY,
        Translation::default(),
        Projection::default(),
        Vector3::new(0, 0, 0),
        Normal::default(),
        BackgroundColor::default(),
        FarColor::default(),
    );
}

#[test]
fn properties_hold() {
    main();
}
