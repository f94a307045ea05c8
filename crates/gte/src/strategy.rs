//! proptest strategies (feature `proptest`, which needs `std`): generators biased towards
//! the values where the GTE's arithmetic changes behaviour, and `Arbitrary` for the types
//! with an obvious one.
//!
//! Every numeric generator mixes uniform values, values at every magnitude (a uniform value
//! shifted right by a random amount, so that saturations are hit as often as not) and edge
//! values (0, ±1, the ends of each range, the IR, screen and 44-bit limits). The typed ones
//! (feature `typed`) build `gte::typed` values; `on_screen` builds a camera
//! set-up with vertices that project inside a 320x240 screen.
//!
//! ```
//! use gte::strategy;
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::default();
//! runner
//!     .run(&(strategy::registers(), strategy::command()), |(regs, word)| {
//!         let mut gte = gte::Gte::new();
//!         let state = gte::GteState { registers: regs, ..gte.state() };
//!         gte.load_state(&state).unwrap();
//!         gte.execute(word);
//!         let flag = gte.flag().bits();
//!         prop_assert_eq!(flag >> 31 == 1, flag & 0x7F87_E000 != 0);
//!         Ok(())
//!     })
//!     .unwrap();
//! ```

use crate::{Command, Flag, MatrixSel, Opcode, Registers, TranslationSel, VectorSel};
use proptest::prelude::*;

/// 16-bit values where saturations and products change: 0, ±1, the ends of i16, 1.0 in
/// 1.3.12 (1000h) and its neighbours, the screen range's ends (±400h), IR0's top (1000h).
const EDGES_16: [i16; 22] = [
    0, 1, -1, 2, -2, 0x7FFF, -0x8000, 0x7FFE, -0x7FFF, 0x1000, -0x1000, 0x0FFF, 0x1001, 0x400,
    -0x400, 0x3FF, -0x401, 0x800, -0x800, 0x4000, -0x4000, 0x80,
];

/// 32-bit values at the ends of i32, of the 44-bit accumulator once shifted left 12 (2^31
/// minus a product's reach), of the 16.16 screen range, and small ones.
const EDGES_32: [i32; 18] = [
    0,
    1,
    -1,
    i32::MAX,
    i32::MIN,
    i32::MAX - 1,
    i32::MIN + 1,
    0x7FFF,
    -0x8000,
    0x8000,
    0x1000,
    0x3FF << 16,
    -0x400 << 16,
    0x400 << 16,
    i32::MAX - (1 << 18),
    i32::MIN + (1 << 18),
    1 << 30,
    -(1 << 30),
];

/// Unsigned 16-bit values: 0, 1, 2, the ends, the sign boundary (H is read sign-extended),
/// and the depths where 2 × SZ3 meets a typical H.
const EDGES_U16: [u16; 12] = [
    0, 1, 2, 0x7FFF, 0x8000, 0x8001, 0xFFFF, 0xFFFE, 0x1000, 0x100, 0xA0, 0x140,
];

/// A signed 16-bit value: uniform, at every magnitude, or an edge.
pub fn half() -> BoxedStrategy<i16> {
    prop_oneof![
        3 => any::<i16>(),
        3 => (any::<i16>(), 0u32..16).prop_map(|(v, s)| v >> s),
        2 => prop::sample::select(EDGES_16.to_vec()),
    ]
    .boxed()
}

/// An unsigned 16-bit value (SZ, OTZ, H): uniform, at every magnitude, or an edge.
pub fn unsigned_half() -> BoxedStrategy<u16> {
    prop_oneof![
        3 => any::<u16>(),
        3 => (any::<u16>(), 0u32..16).prop_map(|(v, s)| v >> s),
        2 => prop::sample::select(EDGES_U16.to_vec()),
    ]
    .boxed()
}

/// A signed 32-bit value (TR, BK, FC, OFX/OFY, DQB, MAC): uniform, at every magnitude, an
/// edge, or within 2^18 of either end of i32, where T << 12 plus one product crosses the
/// 44-bit range (docs/hardware/gte.md §4).
pub fn word() -> BoxedStrategy<i32> {
    prop_oneof![
        3 => any::<i32>(),
        3 => (any::<i32>(), 0u32..32).prop_map(|(v, s)| v >> s),
        2 => prop::sample::select(EDGES_32.to_vec()),
        1 => (i32::MAX - (1 << 18))..=i32::MAX,
        1 => i32::MIN..=(i32::MIN + (1 << 18)),
    ]
    .boxed()
}

/// A 32-bit register word made of two [`half`] values (a packed XY pair).
pub fn packed_halves() -> BoxedStrategy<u32> {
    (half(), half())
        .prop_map(|(lo, hi)| lo as u16 as u32 | (hi as u16 as u32) << 16)
        .boxed()
}

/// A colour word (RGBC, RGB0-2): four bytes, each uniform or 0 or FFh.
pub fn color_word() -> BoxedStrategy<u32> {
    let byte = prop_oneof![3 => any::<u8>(), 1 => Just(0u8), 1 => Just(0xFFu8)];
    prop::array::uniform4(byte)
        .prop_map(u32::from_le_bytes)
        .boxed()
}

fn matrix_bits() -> BoxedStrategy<[[i16; 3]; 3]> {
    prop::array::uniform3(prop::array::uniform3(half())).boxed()
}

/// Leading bits equal to bit 31 (docs/hardware/gte.md §2, LZCR).
fn leading_sign_bits(v: u32) -> u32 {
    if v >> 31 == 1 {
        v.leading_ones()
    } else {
        v.leading_zeros()
    }
}

/// A raw register file any register writes can leave: every field from the edge-biased
/// generators above, LZCR consistent with LZCS, FLAG as the register can hold it. Load it
/// with [`Gte::load_state`](crate::Gte::load_state), or give it to the reference model.
pub fn registers() -> BoxedStrategy<Registers> {
    let data = (
        prop::array::uniform3(prop::array::uniform3(half())),
        color_word(),
        unsigned_half(),
        prop::array::uniform4(half()),
        prop::array::uniform3(packed_halves()),
        prop::array::uniform4(unsigned_half()),
        prop::array::uniform3(color_word()),
        any::<u32>(),
        prop::array::uniform4(word()),
        word(),
    );
    let control = (
        matrix_bits(),
        prop::array::uniform3(word()),
        matrix_bits(),
        prop::array::uniform3(word()),
        matrix_bits(),
        prop::array::uniform3(word()),
        (word(), word()),
        unsigned_half(),
        half(),
        word(),
        (half(), half()),
        any::<u32>(),
    );
    (data, control)
        .prop_map(
            |(
                (v, rgbc, otz, ir, sxy, sz, rgb, res1, mac, lzcs),
                (rt, tr, llm, bk, lcm, fc, (ofx, ofy), h, dqa, dqb, (zsf3, zsf4), flag),
            )| Registers {
                v,
                rgbc,
                otz,
                ir,
                sxy,
                sz,
                rgb,
                res1,
                mac,
                lzcs: lzcs as u32,
                lzcr: leading_sign_bits(lzcs as u32),
                rt,
                tr,
                llm,
                bk,
                lcm,
                fc,
                ofx,
                ofy,
                h,
                dqa,
                dqb,
                zsf3,
                zsf4,
                flag: Flag::from_bits(flag),
            },
        )
        .boxed()
}

/// A COP2 command word: mostly one of the 22 commands with random sf, lm and MVMVA fields
/// (and random ignored bits 20-24), sometimes any 32-bit word (undefined opcodes included).
pub fn command() -> BoxedStrategy<u32> {
    prop_oneof![
        4 => (prop::sample::select(Opcode::ALL.to_vec()), any::<u32>())
            .prop_map(|(op, bits)| (bits & 0x01FF_FFC0) | op.bits()),
        1 => any::<u32>(),
    ]
    .boxed()
}

/// A command word for `op` with every combination of sf, lm and the MVMVA fields.
pub fn command_for(op: Opcode) -> BoxedStrategy<u32> {
    (
        any::<bool>(),
        any::<bool>(),
        0usize..4,
        0usize..4,
        0usize..4,
    )
        .prop_map(move |(sf, lm, mx, v, cv)| {
            let mx = [
                MatrixSel::Rotation,
                MatrixSel::Light,
                MatrixSel::LightColor,
                MatrixSel::Garbage,
            ][mx];
            let v = [VectorSel::V0, VectorSel::V1, VectorSel::V2, VectorSel::Ir][v];
            let cv = [
                TranslationSel::Translation,
                TranslationSel::Background,
                TranslationSel::FarColor,
                TranslationSel::None,
            ][cv];
            Command::build(op, sf, lm, mx, v, cv).word()
        })
        .boxed()
}

impl Arbitrary for Registers {
    type Parameters = ();
    type Strategy = BoxedStrategy<Registers>;
    /// [`registers`].
    fn arbitrary_with(_: ()) -> Self::Strategy {
        registers().boxed()
    }
}

impl Arbitrary for Flag {
    type Parameters = ();
    type Strategy = BoxedStrategy<Flag>;
    /// Any value FLAG can hold ([`Flag::from_bits`] of any word).
    fn arbitrary_with(_: ()) -> Self::Strategy {
        any::<u32>().prop_map(Flag::from_bits).boxed()
    }
}

impl Arbitrary for Opcode {
    type Parameters = ();
    type Strategy = BoxedStrategy<Opcode>;
    /// One of the 22 commands.
    fn arbitrary_with(_: ()) -> Self::Strategy {
        prop::sample::select(Opcode::ALL.to_vec()).boxed()
    }
}

impl Arbitrary for Command {
    type Parameters = ();
    type Strategy = BoxedStrategy<Command>;
    /// [`command`].
    fn arbitrary_with(_: ()) -> Self::Strategy {
        command().prop_map(Command::new).boxed()
    }
}

#[cfg(feature = "typed")]
pub use typed::*;

#[cfg(feature = "typed")]
mod typed {
    use super::{half, matrix_bits, unsigned_half, word};
    use crate::typed::{
        Angle, BackgroundColor, FarColor, I4F12, I8F8, I8F24, I16F16, Matrix, Normal, Projection,
        Translation, Vector3, cos, sin,
    };
    use proptest::prelude::*;
    use std::vec::Vec;

    /// A vertex: each component from [`half`](super::half).
    pub fn vertex() -> BoxedStrategy<Vector3> {
        prop::array::uniform3(half())
            .prop_map(Vector3::from)
            .boxed()
    }

    /// A normal in 1.3.12: mostly unit length (from two angles, through the sine table),
    /// sometimes along an axis (±1.0), sometimes any bits.
    pub fn normal() -> BoxedStrategy<Normal> {
        let unit = (any::<Angle>(), any::<Angle>()).prop_map(|(a, b)| {
            let xy = cos(b);
            Normal::from_bits([
                ((cos(a) * xy) >> 12) as i16,
                ((sin(a) * xy) >> 12) as i16,
                sin(b) as i16,
            ])
        });
        let axis = (0usize..3, any::<bool>()).prop_map(|(axis, negative)| {
            let mut bits = [0i16; 3];
            bits[axis] = if negative { -0x1000 } else { 0x1000 };
            Normal::from_bits(bits)
        });
        prop_oneof![
            3 => unit,
            1 => axis,
            1 => prop::array::uniform3(half()).prop_map(Normal::from_bits),
        ]
        .boxed()
    }

    /// A matrix of any 1.3.12 entries, each from [`half`](super::half).
    pub fn matrix() -> BoxedStrategy<Matrix> {
        matrix_bits().prop_map(Matrix::from_bits).boxed()
    }

    /// An angle in 1/4096 turn: any `i32` (only the low 12 bits count), a multiple of an
    /// eighth of a turn, or within a few units of one.
    pub fn angle() -> BoxedStrategy<Angle> {
        let eighths: Vec<Angle> = (0..8).map(|k| k * 512).collect();
        prop_oneof![
            2 => any::<Angle>(),
            1 => prop::sample::select(eighths.clone()),
            1 => (prop::sample::select(eighths), -4i32..=4).prop_map(|(a, d)| a + d),
        ]
        .boxed()
    }

    /// A pure rotation: [`Matrix::rotation`] of three [`angle`]s.
    pub fn rotation() -> BoxedStrategy<Matrix> {
        (angle(), angle(), angle())
            .prop_map(|(x, y, z)| Matrix::rotation(x, y, z))
            .boxed()
    }

    /// A translation: each component from [`word`](super::word), so near the 44-bit edges
    /// too.
    pub fn translation() -> BoxedStrategy<Translation> {
        prop::array::uniform3(word())
            .prop_map(|[x, y, z]| Translation { x, y, z })
            .boxed()
    }

    /// A projection set-up with every field edge-biased (any H, offsets, DQA/DQB, ZSF3/4).
    pub fn projection() -> BoxedStrategy<Projection> {
        (
            word(),
            word(),
            unsigned_half(),
            half(),
            word(),
            half(),
            half(),
        )
            .prop_map(|(ofx, ofy, h, dqa, dqb, zsf3, zsf4)| Projection {
                offset_x: I16F16::from_bits(ofx),
                offset_y: I16F16::from_bits(ofy),
                h,
                dqa: I8F8::from_bits(dqa),
                dqb: I8F24::from_bits(dqb),
                zsf3: I4F12::from_bits(zsf3),
                zsf4: I4F12::from_bits(zsf4),
            })
            .boxed()
    }

    /// A background colour BK (1.19.12): each channel from [`word`](super::word), or in
    /// 0..=1.0 (the range that lights a channel from black to saturated).
    pub fn background_color() -> BoxedStrategy<BackgroundColor> {
        let channel = prop_oneof![word(), 0i32..=0x1000];
        prop::array::uniform3(channel)
            .prop_map(BackgroundColor::from_bits)
            .boxed()
    }

    /// A far colour FC (1.27.4): each channel from [`word`](super::word), or a colour byte
    /// 0..=FFh with a fraction.
    pub fn far_color() -> BoxedStrategy<FarColor> {
        let channel = prop_oneof![word(), 0i32..=0xFFF];
        prop::array::uniform3(channel)
            .prop_map(FarColor::from_bits)
            .boxed()
    }

    /// A camera set-up and three vertices that project inside a 320x240 screen.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub struct OnScreen {
        /// A pure rotation ([`rotation`]).
        pub rotation: Matrix,
        /// The translation, in front of the camera.
        pub translation: Translation,
        /// H 64..=1000, offsets (160, 120) with a random fraction, no depth cue (DQA = DQB =
        /// 0), ZSF3/ZSF4 as [`Projection::default`].
        pub projection: Projection,
        /// Three vertices within `radius` of the origin on each axis.
        pub vertices: [Vector3; 3],
        /// The vertices' bound on each axis, 1..=1000.
        pub radius: i16,
    }

    /// [`OnScreen`] set-ups. A rotated vertex lies within 2 × radius of the translation on
    /// each axis (a rotation row sums to at most √3 in magnitude), and the depth and the
    /// translation's X/Y are drawn so that even then the camera-space depth is at least H
    /// (no divide overflow), X, Y and the depth fit IR1-3 (no saturation), and X, Y land
    /// within 140 of 160, within 100 of 120; the
    /// rounding of the rotation and of the divide moves a vertex by under 10 pixels more,
    /// so every vertex projects inside 10..=310, 10..=230 and FLAG stays 0 (held by the
    /// property `on_screen_set_ups_project_on_screen`).
    pub fn on_screen() -> BoxedStrategy<OnScreen> {
        (
            64i32..=1000,
            1i32..=1000,
            rotation(),
            any::<u16>(),
            any::<u16>(),
        )
            .prop_flat_map(|(h, r, rotation, fx, fy)| {
                let near = (h + 2 * r + 1).max(2 * r + (h * 4 * r + 139) / 140);
                let far = 0x7FFF - 2 * r;
                (Just((h, r, rotation, fx, fy)), near..=far)
            })
            .prop_flat_map(|((h, r, rotation, fx, fy), tz)| {
                // X and Y also stay inside IR1 and IR2's range.
                let bx = (140 * (tz - 2 * r) / h - 2 * r).min(0x7FFE - 2 * r);
                let by = (100 * (tz - 2 * r) / h - 2 * r).min(0x7FFE - 2 * r);
                let coordinate = -(r as i16)..=(r as i16);
                (
                    Just((h, r, rotation, fx, fy, tz)),
                    -bx..=bx,
                    -by..=by,
                    prop::array::uniform3(prop::array::uniform3(coordinate)),
                )
            })
            .prop_map(
                |((h, r, rotation, fx, fy, tz), tx, ty, vertices)| OnScreen {
                    rotation,
                    translation: Translation {
                        x: tx,
                        y: ty,
                        z: tz,
                    },
                    projection: Projection {
                        offset_x: I16F16::from_bits((160 << 16) | fx as i32),
                        offset_y: I16F16::from_bits((120 << 16) | fy as i32),
                        h: h as u16,
                        ..Projection::default()
                    },
                    vertices: vertices.map(Vector3::from),
                    radius: r as i16,
                },
            )
            .boxed()
    }

    impl Arbitrary for Vector3 {
        type Parameters = ();
        type Strategy = BoxedStrategy<Vector3>;
        /// [`vertex`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            vertex().boxed()
        }
    }

    impl Arbitrary for Normal {
        type Parameters = ();
        type Strategy = BoxedStrategy<Normal>;
        /// [`normal`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            normal().boxed()
        }
    }

    impl Arbitrary for Matrix {
        type Parameters = ();
        type Strategy = BoxedStrategy<Matrix>;
        /// [`matrix`]: any entries (for rotations, [`rotation`]).
        fn arbitrary_with(_: ()) -> Self::Strategy {
            matrix().boxed()
        }
    }

    impl Arbitrary for Translation {
        type Parameters = ();
        type Strategy = BoxedStrategy<Translation>;
        /// [`translation`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            translation().boxed()
        }
    }

    impl Arbitrary for Projection {
        type Parameters = ();
        type Strategy = BoxedStrategy<Projection>;
        /// [`projection`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            projection().boxed()
        }
    }

    impl Arbitrary for BackgroundColor {
        type Parameters = ();
        type Strategy = BoxedStrategy<BackgroundColor>;
        /// [`background_color`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            background_color().boxed()
        }
    }

    impl Arbitrary for FarColor {
        type Parameters = ();
        type Strategy = BoxedStrategy<FarColor>;
        /// [`far_color`].
        fn arbitrary_with(_: ()) -> Self::Strategy {
            far_color().boxed()
        }
    }
}
