//! A typed fixed-point API over the register-level engine, for renderers that want to
//! transform, light and project vertices exactly as the PS1 does without handling registers,
//! and for property tests of fixed-point code.
//!
//! Every call writes the GTE registers a PS1 program would write, runs the same command word
//! and reads the result registers back, so results are bit-identical to the register-level
//! path (docs/hardware/gte.md §5, §7, §8). The types say what the hardware stores: 1.3.12
//! matrices ([`I4F12`]) and normals, 16-bit vertices, 32-bit translations, the 1.19.12
//! background colour ([`I20F12`]) and 1.27.4 far colour ([`I28F4`]), 16.16 screen offsets
//! ([`I16F16`]), the unsigned 16-bit projection distance H, depth-cue DQA (8.8) and DQB
//! (8.24). Each operation runs one command, so [`Geometry::last_flag`] is that command's FLAG.
//! docs/typed-api.md gives each operation's ranges, FLAG bits and rounding.

mod results;
mod rotation;
mod values;

pub use fixed::types::{I4F12, I8F8, I8F24, I16F16, I20F12, I28F4};
pub use results::{Interpolated, MacIr, Projected, ProjectedTriangle, Rgb, SubpixelProjected};
pub use rotation::{Angle, cos, sin};
pub use values::{
    BackgroundColor, FarColor, Matrix, MvmvaVector, Normal, Projection, Translation, Vector3,
};

use crate::command::{Command, MatrixSel, Opcode, TranslationSel, VectorSel};
use crate::{DivideMode, Flag, Gte, UnsupportedDivideMode};

/// The command word the typed API issues for `op`: sf = 1 (results in 1.3.12), lm as the
/// SDK's word for the command sets it (psx-spx's command list): lm = 1 for NCS, NCT, NCCS,
/// NCCT, NCDS, NCDT, CC, CDP and SQR (negative light clamps to zero), lm = 0 for the others.
/// MVMVA's word here selects RT, V0 and TR; [`Geometry::multiply_add`] builds its own.
pub const fn command(op: Opcode) -> u32 {
    let lm = matches!(
        op,
        Opcode::Ncs
            | Opcode::Nct
            | Opcode::Nccs
            | Opcode::Ncct
            | Opcode::Ncds
            | Opcode::Ncdt
            | Opcode::Cc
            | Opcode::Cdp
            | Opcode::Sqr
    );
    Command::build(
        op,
        true,
        lm,
        MatrixSel::Rotation,
        VectorSel::V0,
        TranslationSel::Translation,
    )
    .word()
}

/// The typed face of a [`Gte`]: set-up calls load control registers, operations run
/// commands with sf = 1 (results in 1.3.12) and the lm setting of the SDK's words
/// ([`command`]). Every operation runs exactly one command; [`Geometry::last_flag`] is its
/// FLAG.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Geometry {
    gte: Gte,
}

fn packed(lo: i16, hi: i16) -> u32 {
    (lo as u16 as u32) | ((hi as u16 as u32) << 16)
}

fn write_matrix(gte: &mut Gte, first: u32, m: &Matrix) {
    let b = m.to_bits();
    gte.write_control(first, packed(b[0][0], b[0][1]));
    gte.write_control(first + 1, packed(b[0][2], b[1][0]));
    gte.write_control(first + 2, packed(b[1][1], b[1][2]));
    gte.write_control(first + 3, packed(b[2][0], b[2][1]));
    gte.write_control(first + 4, b[2][2] as i32 as u32);
}

fn write_vector(gte: &mut Gte, index: u32, v: Vector3) {
    gte.write_data(index * 2, packed(v.x, v.y));
    gte.write_data(index * 2 + 1, v.z as i32 as u32);
}

fn write_ir(gte: &mut Gte, v: Vector3) {
    gte.write_data(9, v.x as i32 as u32);
    gte.write_data(10, v.y as i32 as u32);
    gte.write_data(11, v.z as i32 as u32);
}

fn unpack_xy(word: u32) -> (i16, i16) {
    (word as u16 as i16, (word >> 16) as u16 as i16)
}

fn unpack_rgb(word: u32) -> Rgb {
    [word as u8, (word >> 8) as u8, (word >> 16) as u8]
}

fn rgb_word(color: Rgb) -> u32 {
    color[0] as u32 | (color[1] as u32) << 8 | (color[2] as u32) << 16
}

impl Geometry {
    /// A GTE with all registers zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// Wrap an existing engine.
    pub fn from_gte(gte: Gte) -> Self {
        Self { gte }
    }

    /// The engine underneath.
    pub fn gte(&self) -> &Gte {
        &self.gte
    }

    /// The engine underneath, mutable.
    pub fn gte_mut(&mut self) -> &mut Gte {
        &mut self.gte
    }

    /// FLAG as the last operation left it. Every operation runs one command, which clears
    /// FLAG first and sets bit 31 from its error sources at the end (docs/hardware/gte.md §3),
    /// so this is exactly that operation's FLAG; the set-up calls leave it as it was.
    pub fn last_flag(&self) -> Flag {
        self.gte.flag()
    }

    /// Select the divide used by projection (non-hardware modes are accuracy knobs), as
    /// [`Gte::set_divide_mode`]: refused without the `divide-modes` feature.
    pub fn set_divide_mode(&mut self, mode: DivideMode) -> Result<(), UnsupportedDivideMode> {
        self.gte.set_divide_mode(mode)
    }

    /// Load the rotation matrix RT (c0-c4).
    pub fn set_rotation(&mut self, m: &Matrix) {
        write_matrix(&mut self.gte, 0, m);
    }

    /// Load the translation TR (c5-c7).
    pub fn set_translation(&mut self, t: Translation) {
        self.gte.write_control(5, t.x as u32);
        self.gte.write_control(6, t.y as u32);
        self.gte.write_control(7, t.z as u32);
    }

    /// Load OFX, OFY, H, DQA, DQB, ZSF3, ZSF4 (c24-c30).
    pub fn set_projection(&mut self, p: &Projection) {
        self.gte.write_control(24, p.offset_x.to_bits() as u32);
        self.gte.write_control(25, p.offset_y.to_bits() as u32);
        self.gte.write_control(26, p.h as u32);
        self.gte.write_control(27, p.dqa.to_bits() as i32 as u32);
        self.gte.write_control(28, p.dqb.to_bits() as u32);
        self.gte.write_control(29, p.zsf3.to_bits() as i32 as u32);
        self.gte.write_control(30, p.zsf4.to_bits() as i32 as u32);
    }

    /// Load the light direction matrix LLM (c8-c12): one light direction per row.
    pub fn set_light_matrix(&mut self, m: &Matrix) {
        write_matrix(&mut self.gte, 8, m);
    }

    /// Load the light colour matrix LCM (c16-c20): one light's colour per column.
    pub fn set_light_colors(&mut self, m: &Matrix) {
        write_matrix(&mut self.gte, 16, m);
    }

    /// Load the background (ambient) colour BK (c13-c15), 1.19.12 per channel (4096 = 1.0,
    /// which lights a channel to 256, saturated to 255: [`BackgroundColor`]). Raw
    /// `[i32; 3]` bit patterns convert into it.
    pub fn set_background_color(&mut self, bk: impl Into<BackgroundColor>) {
        for (r, v) in (13..).zip(bk.into().to_bits()) {
            self.gte.write_control(r, v as u32);
        }
    }

    /// Load the far colour FC (c21-c23) that depth cueing fades towards, 1.27.4 per channel
    /// (the integer part is the colour byte). Raw `[i32; 3]` bit patterns convert into it.
    pub fn set_far_color(&mut self, fc: impl Into<FarColor>) {
        for (r, v) in (21..).zip(fc.into().to_bits()) {
            self.gte.write_control(r, v as u32);
        }
    }

    /// Load the interpolation factor IR0 (r8), which NCDS, NCDT and CDP read: a projection
    /// sets it too (its depth cue).
    pub fn set_interpolation_factor(&mut self, ir0: I4F12) {
        self.gte.write_data(8, ir0.to_bits() as i32 as u32);
    }

    /// MAC1-3 and IR1-3 from the registers.
    fn mac_ir(&self) -> MacIr {
        let regs = &self.gte.regs;
        MacIr {
            mac: [regs.mac(1), regs.mac(2), regs.mac(3)],
            ir: [regs.ir(1), regs.ir(2), regs.ir(3)],
        }
    }

    /// The quotient RTPS/RTPT computed for a pushed SZ3 (docs/hardware/gte.md §5.5): the
    /// divide of H by it, in the engine's divide mode.
    #[inline]
    fn quotient(&self, sz3: u16) -> u32 {
        let h = self.gte.regs.h();
        match self.gte.divide_mode() {
            DivideMode::Unr => crate::unr::unr_divide(h, sz3).0,
            mode => crate::unr::divide(mode, h, sz3).0,
        }
    }

    /// RTPS: rotate, translate and project one vertex (docs/hardware/gte.md §5).
    pub fn project(&mut self, v: Vector3) -> Projected {
        write_vector(&mut self.gte, 0, v);
        self.gte.execute(command(Opcode::Rtps));
        self.projected()
    }

    /// What RTPS left in the registers, and its quotient.
    fn projected(&self) -> Projected {
        let (x, y) = unpack_xy(self.gte.read_data(14));
        let sz = self.gte.read_data(19) as u16;
        Projected {
            x,
            y,
            sz,
            ir0: I4F12::from_bits(self.gte.read_data(8) as i16),
            flag: self.gte.flag(),
            camera: self.mac_ir(),
            mac0: self.gte.regs.mac(0),
            quotient: self.quotient(sz),
        }
    }

    /// RTPS with the sub-pixel screen position: one command, the same register effects and
    /// [`Projected`] as [`Geometry::project`], plus the 16.16 screen X/Y before the integer
    /// truncation (docs/hardware/gte.md §5 step 6), saturated as [`SubpixelProjected`] says.
    pub fn project_subpixel(&mut self, v: Vector3) -> SubpixelProjected {
        let projected = self.project(v);
        let q = projected.quotient as i64;
        let (ofx, ofy) = self.gte.regs.offset();
        let fine = |ir: i16, offset: i32| {
            let value = q * ir as i64 + offset as i64;
            I16F16::from_bits(value.clamp(-0x400 << 16, (0x400 << 16) - 1) as i32)
        };
        SubpixelProjected {
            projected,
            x: fine(projected.camera.ir[0], ofx),
            y: fine(projected.camera.ir[1], ofy),
        }
    }

    /// RTPT: rotate, translate and project three vertices (docs/hardware/gte.md §5).
    pub fn project_triangle(&mut self, v: [Vector3; 3]) -> ProjectedTriangle {
        for (i, v) in (0..).zip(v) {
            write_vector(&mut self.gte, i, v);
        }
        self.gte.execute(command(Opcode::Rtpt));
        let sz = [17, 18, 19].map(|r| self.gte.read_data(r) as u16);
        ProjectedTriangle {
            xy: [12, 13, 14].map(|r| unpack_xy(self.gte.read_data(r))),
            sz,
            ir0: I4F12::from_bits(self.gte.read_data(8) as i16),
            flag: self.gte.flag(),
            camera: self.mac_ir(),
            mac0: self.gte.regs.mac(0),
            quotient: [
                self.quotient(sz[0]),
                self.quotient(sz[1]),
                self.quotient(sz[2]),
            ],
        }
    }

    /// NCLIP on the screen XY FIFO as it stands (after a projection): twice the signed area
    /// of SXY0, SXY1, SXY2, positive when they run clockwise as seen on a Y-down screen
    /// (top-left, top-right, bottom-left). The area is exact while it fits 32 bits, always
    /// for points in the projection's -400h..=3FFh range; beyond, MAC0 keeps its low 32 bits
    /// (it wraps) and FLAG bit 16 or 15 is set (docs/hardware/gte.md §7).
    pub fn nclip_current(&mut self) -> i32 {
        self.gte.execute(command(Opcode::Nclip));
        self.gte.read_data(24) as i32
    }

    /// NCLIP of three screen points, as [`Geometry::nclip_current`].
    pub fn nclip(&mut self, xy: [(i16, i16); 3]) -> i32 {
        for (r, (x, y)) in (12..).zip(xy) {
            self.gte.write_data(r, packed(x, y));
        }
        self.nclip_current()
    }

    /// AVSZ3 of three screen Z values: OTZ = ZSF3 × (SZ1 + SZ2 + SZ3) SAR 12, saturated to
    /// 0..=FFFFh (docs/hardware/gte.md §7). SAR rounds down, and ZSF3 = 1/3 is not exact in
    /// 1.3.12: with [`Projection::default`]'s 555h this is not the mean (docs/typed-api.md).
    pub fn average_z3(&mut self, sz: [u16; 3]) -> u16 {
        for (r, z) in (17..).zip(sz) {
            self.gte.write_data(r, z as u32);
        }
        self.gte.execute(command(Opcode::Avsz3));
        self.gte.read_data(7) as u16
    }

    /// AVSZ4 of four screen Z values: OTZ = ZSF4 × (SZ0 + ... + SZ3) SAR 12, saturated to
    /// 0..=FFFFh (docs/hardware/gte.md §7).
    pub fn average_z4(&mut self, sz: [u16; 4]) -> u16 {
        for (r, z) in (16..).zip(sz) {
            self.gte.write_data(r, z as u32);
        }
        self.gte.execute(command(Opcode::Avsz4));
        self.gte.read_data(7) as u16
    }

    fn set_color(&mut self, color: Rgb) {
        self.gte.write_data(6, rgb_word(color));
    }

    fn single(&mut self, op: Opcode, normal: Normal) -> Rgb {
        write_vector(&mut self.gte, 0, normal.into());
        self.gte.execute(command(op));
        unpack_rgb(self.gte.read_data(22))
    }

    fn triple(&mut self, op: Opcode, normals: [Normal; 3]) -> [Rgb; 3] {
        for (i, n) in (0..).zip(normals) {
            write_vector(&mut self.gte, i, n.into());
        }
        self.gte.execute(command(op));
        self.fifo()
    }

    /// RGB0-2.
    fn fifo(&self) -> [Rgb; 3] {
        [20, 21, 22].map(|r| unpack_rgb(self.gte.read_data(r)))
    }

    /// NCS: the light colour at a normal (BK + LCM × (LLM × N)).
    pub fn normal_color(&mut self, normal: impl Into<Normal>) -> Rgb {
        self.single(Opcode::Ncs, normal.into())
    }

    /// NCT: NCS for three normals.
    pub fn normal_color_triple<N: Into<Normal>>(&mut self, normals: [N; 3]) -> [Rgb; 3] {
        self.triple(Opcode::Nct, normals.map(Into::into))
    }

    /// NCCS: the light colour at a normal multiplied by a material colour.
    pub fn normal_color_color(&mut self, normal: impl Into<Normal>, color: Rgb) -> Rgb {
        self.set_color(color);
        self.single(Opcode::Nccs, normal.into())
    }

    /// NCCT: NCCS for three normals with one material colour.
    pub fn normal_color_color_triple<N: Into<Normal>>(
        &mut self,
        normals: [N; 3],
        color: Rgb,
    ) -> [Rgb; 3] {
        self.set_color(color);
        self.triple(Opcode::Ncct, normals.map(Into::into))
    }

    /// NCDS: NCCS then depth cueing towards FC by IR0 (set by the last projection or
    /// [`Geometry::set_interpolation_factor`]).
    pub fn normal_color_depth(&mut self, normal: impl Into<Normal>, color: Rgb) -> Rgb {
        self.set_color(color);
        self.single(Opcode::Ncds, normal.into())
    }

    /// NCDT: NCDS for three normals.
    pub fn normal_color_depth_triple<N: Into<Normal>>(
        &mut self,
        normals: [N; 3],
        color: Rgb,
    ) -> [Rgb; 3] {
        self.set_color(color);
        self.triple(Opcode::Ncdt, normals.map(Into::into))
    }

    /// CC: a light intensity vector (written to IR1-3, 1.3.12) through BK + LCM × IR,
    /// multiplied by a material colour.
    pub fn color_color(&mut self, light: Vector3, color: Rgb) -> Rgb {
        self.set_color(color);
        write_ir(&mut self.gte, light);
        self.gte.execute(command(Opcode::Cc));
        unpack_rgb(self.gte.read_data(22))
    }

    /// CDP: CC, then depth cueing towards FC by IR0 (set by the last projection or
    /// [`Geometry::set_interpolation_factor`]).
    pub fn color_depth(&mut self, light: Vector3, color: Rgb) -> Rgb {
        self.set_color(color);
        write_ir(&mut self.gte, light);
        self.gte.execute(command(Opcode::Cdp));
        unpack_rgb(self.gte.read_data(22))
    }

    /// DPCS: fade a colour towards FC by `ir0` (0 = the colour, 1.0 = FC).
    pub fn depth_cue(&mut self, color: Rgb, ir0: I4F12) -> Rgb {
        self.set_color(color);
        self.set_interpolation_factor(ir0);
        self.gte.execute(command(Opcode::Dpcs));
        unpack_rgb(self.gte.read_data(22))
    }

    /// DPCT: DPCS for three colours, written to the colour FIFO RGB0-2 (DPCT reads its
    /// bottom three times, docs/hardware/gte.md §8); returns them faded, in order.
    pub fn depth_cue_triple(&mut self, colors: [Rgb; 3], ir0: I4F12) -> [Rgb; 3] {
        for (r, c) in (20..).zip(colors) {
            self.gte.write_data(r, rgb_word(c));
        }
        self.set_interpolation_factor(ir0);
        self.gte.execute(command(Opcode::Dpct));
        self.fifo()
    }

    /// DCPL: a light intensity vector (written to IR1-3, 1.3.12) times a material colour,
    /// faded towards FC by `ir0`.
    pub fn depth_cue_light(&mut self, light: Vector3, color: Rgb, ir0: I4F12) -> Rgb {
        self.set_color(color);
        write_ir(&mut self.gte, light);
        self.set_interpolation_factor(ir0);
        self.gte.execute(command(Opcode::Dcpl));
        unpack_rgb(self.gte.read_data(22))
    }

    fn interpolated(&mut self, op: Opcode, v: Vector3, ir0: I4F12) -> Interpolated {
        write_ir(&mut self.gte, v);
        self.set_interpolation_factor(ir0);
        self.gte.execute(command(op));
        Interpolated {
            mac_ir: self.mac_ir(),
            rgb: unpack_rgb(self.gte.read_data(22)),
        }
    }

    /// INTPL: a vector (written to IR1-3) interpolated towards FC by `ir0`:
    /// IR + (FC - IR) × IR0, in IR's units with FC's integer part as the far value.
    pub fn interpolate(&mut self, v: Vector3, ir0: I4F12) -> Interpolated {
        self.interpolated(Opcode::Intpl, v, ir0)
    }

    /// GPF: a vector (written to IR1-3) scaled by `ir0`: MAC = (IR × IR0) SAR 12.
    pub fn general_interpolate(&mut self, v: Vector3, ir0: I4F12) -> Interpolated {
        self.interpolated(Opcode::Gpf, v, ir0)
    }

    /// GPL: `base` (written to MAC1-3) plus a vector (written to IR1-3) scaled by `ir0`:
    /// MAC = ((MAC << 12) + IR × IR0) SAR 12.
    pub fn general_interpolate_with_base(
        &mut self,
        base: [i32; 3],
        v: Vector3,
        ir0: I4F12,
    ) -> Interpolated {
        for (r, m) in (25..).zip(base) {
            self.gte.write_data(r, m as u32);
        }
        self.interpolated(Opcode::Gpl, v, ir0)
    }

    /// MVMVA: `matrix` × `vector` + `add` (docs/hardware/gte.md §8), sf = 1, IR saturated to
    /// 0..=7FFFh with `lm`, -8000h..=7FFFh without. The hardware's quirks apply:
    /// [`MatrixSel::Garbage`] multiplies by the rows of §8, and [`TranslationSel::FarColor`]
    /// adds nothing and drops each row's first product (its flags stay).
    pub fn multiply_add(
        &mut self,
        matrix: MatrixSel,
        vector: MvmvaVector,
        add: TranslationSel,
        lm: bool,
    ) -> MacIr {
        let selector = match vector {
            MvmvaVector::V0(v) => {
                write_vector(&mut self.gte, 0, v);
                VectorSel::V0
            }
            MvmvaVector::V1(v) => {
                write_vector(&mut self.gte, 1, v);
                VectorSel::V1
            }
            MvmvaVector::V2(v) => {
                write_vector(&mut self.gte, 2, v);
                VectorSel::V2
            }
            MvmvaVector::Ir(v) => {
                write_ir(&mut self.gte, v);
                VectorSel::Ir
            }
        };
        let word = Command::build(Opcode::Mvmva, true, lm, matrix, selector, add).word();
        self.gte.execute(word);
        self.mac_ir()
    }

    /// OP: the outer product D × `v` of D = (RT11, RT22, RT33), the rotation matrix's
    /// diagonal, and `v` (written to IR1-3), SAR 12 (docs/hardware/gte.md §8).
    pub fn outer_product(&mut self, v: Vector3) -> MacIr {
        write_ir(&mut self.gte, v);
        self.gte.execute(command(Opcode::Op));
        self.mac_ir()
    }

    /// SQR: each component of `v` (written to IR1-3) squared, SAR 12.
    pub fn square(&mut self, v: Vector3) -> MacIr {
        write_ir(&mut self.gte, v);
        self.gte.execute(command(Opcode::Sqr));
        self.mac_ir()
    }
}
