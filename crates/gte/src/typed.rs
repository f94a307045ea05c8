//! A typed fixed-point API over the register-level engine, for renderers that want to
//! transform, light and project vertices exactly as the PS1 does without handling registers.
//!
//! Every call writes the GTE registers a PS1 program would write, runs the same command word
//! and reads the result registers back, so results are bit-identical to the register-level
//! path (docs/hardware/gte.md §5, §7, §8). The types say what the hardware stores: 1.3.12 matrices
//! ([`I4F12`]), 16-bit vertices, 32-bit translations, 16.16 screen offsets ([`I16F16`]), the
//! unsigned 16-bit projection distance H, depth-cue DQA (8.8) and DQB (8.24).

use crate::command::{Command, MatrixSel, Opcode, TranslationSel, VectorSel};
use crate::{DivideMode, Flag, Gte, UnsupportedDivideMode};
pub use fixed::types::{I4F12, I8F8, I8F24, I16F16};

/// A 3x3 matrix of 1.3.12 entries (rotation RT, light LLM or light colour LCM), row-major.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Matrix(pub [[I4F12; 3]; 3]);

/// A 16-bit vertex or normal (V0-V2). Normals use 1.3.12 (4096 = 1.0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vector3 {
    /// X.
    pub x: i16,
    /// Y.
    pub y: i16,
    /// Z.
    pub z: i16,
}

/// A 32-bit translation (TR), in the same units as vertices.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Translation {
    /// X.
    pub x: i32,
    /// Y.
    pub y: i32,
    /// Z.
    pub z: i32,
}

/// Projection set-up: screen offsets OFX/OFY (16.16), distance H, depth cue DQA/DQB and the
/// AVSZ scale factors ZSF3/ZSF4 (1.3.12).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Projection {
    /// Screen X of the optical axis (OFX).
    pub offset_x: I16F16,
    /// Screen Y of the optical axis (OFY).
    pub offset_y: I16F16,
    /// Projection plane distance H (unsigned in the maths).
    pub h: u16,
    /// Depth-cue coefficient DQA (8.8).
    pub dqa: I8F8,
    /// Depth-cue offset DQB (8.24).
    pub dqb: I8F24,
    /// AVSZ3 scale ZSF3.
    pub zsf3: I4F12,
    /// AVSZ4 scale ZSF4.
    pub zsf4: I4F12,
}

impl Default for Projection {
    /// A 320x240 screen centred at (160, 120), H = 320, no depth cue, ZSF3 = 1/3, ZSF4 = 1/4
    /// (so OTZ is the mean SZ).
    fn default() -> Self {
        Self {
            offset_x: I16F16::from_num(160),
            offset_y: I16F16::from_num(120),
            h: 320,
            dqa: I8F8::ZERO,
            dqb: I8F24::ZERO,
            zsf3: I4F12::from_bits(0x1000 / 3),
            zsf4: I4F12::from_bits(0x1000 / 4),
        }
    }
}

/// One projected vertex (RTPS).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Projected {
    /// Screen X, integer-snapped and saturated to -400h..3FFh as the GPU receives it.
    pub x: i16,
    /// Screen Y.
    pub y: i16,
    /// Screen Z (SZ3), 0..FFFFh.
    pub sz: u16,
    /// Depth-cue interpolation factor IR0, 0..1.0.
    pub ir0: I4F12,
    /// FLAG after the command.
    pub flag: Flag,
}

/// One projected vertex (RTPS) with its screen position before the integer truncation.
///
/// `x`/`y` are the 16.16 values of docs/hardware/gte.md §5 step 6 (`quotient * IR1 + OFX`, resp.
/// `quotient * IR2 + OFY`, from the divide mode in use), saturated to -400h..=3FFh.FFFFh: the
/// range whose integer parts are the -400h..3FFh that SXY saturates to, with the fraction kept.
/// So `x.floor()` is always `projected.x` (and likewise for y).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SubpixelProjected {
    /// What [`Geometry::project`] returns for the same state and vertex.
    pub projected: Projected,
    /// Screen X in 16.16, before truncation.
    pub x: I16F16,
    /// Screen Y in 16.16, before truncation.
    pub y: I16F16,
}

/// Three projected vertices (RTPT).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ProjectedTriangle {
    /// Screen X, Y of each vertex (SXY0-2).
    pub xy: [(i16, i16); 3],
    /// Screen Z of each vertex (SZ1-3).
    pub sz: [u16; 3],
    /// Depth-cue IR0 from the last vertex.
    pub ir0: I4F12,
    /// FLAG after the command.
    pub flag: Flag,
}

/// An 8-bit-per-channel colour as the colour FIFO stores it.
pub type Rgb = [u8; 3];

/// A rotation angle in 1/4096 of a turn (4096 = 360 degrees), the PS1 SDK convention.
pub type Angle = i32;

impl Matrix {
    /// The identity (4096 on the diagonal).
    pub const IDENTITY: Matrix = Matrix([
        [I4F12::ONE, I4F12::ZERO, I4F12::ZERO],
        [I4F12::ZERO, I4F12::ONE, I4F12::ZERO],
        [I4F12::ZERO, I4F12::ZERO, I4F12::ONE],
    ]);

    /// From raw 1.3.12 bit patterns.
    pub const fn from_bits(m: [[i16; 3]; 3]) -> Matrix {
        let mut out = [[I4F12::ZERO; 3]; 3];
        let mut r = 0;
        while r < 3 {
            let mut c = 0;
            while c < 3 {
                out[r][c] = I4F12::from_bits(m[r][c]);
                c += 1;
            }
            r += 1;
        }
        Matrix(out)
    }

    /// Raw 1.3.12 bit patterns.
    pub fn to_bits(&self) -> [[i16; 3]; 3] {
        self.0.map(|row| row.map(I4F12::to_bits))
    }

    /// Rotation by `x`, then `y`, then `z` (angles in 1/4096 turn, any `i32`: only the low
    /// 12 bits matter, a whole turn being 4096): R = Rz * Ry * Rx, each
    /// entry rounded to 1.3.12 from an integer sine table, products truncated by >> 12 as PS1
    /// SDK rotation functions do.
    pub fn rotation(x: Angle, y: Angle, z: Angle) -> Matrix {
        let (sx, cx) = (sin(x), cos(x));
        let (sy, cy) = (sin(y), cos(y));
        let (sz, cz) = (sin(z), cos(z));
        let m = [
            [
                (cz * cy) >> 12,
                ((((cz * sy) >> 12) * sx) >> 12) - ((sz * cx) >> 12),
                ((((cz * sy) >> 12) * cx) >> 12) + ((sz * sx) >> 12),
            ],
            [
                (sz * cy) >> 12,
                ((((sz * sy) >> 12) * sx) >> 12) + ((cz * cx) >> 12),
                ((((sz * sy) >> 12) * cx) >> 12) - ((cz * sx) >> 12),
            ],
            [-sy, (cy * sx) >> 12, (cy * cx) >> 12],
        ];
        Matrix::from_bits(m.map(|row| row.map(|v| v.clamp(-0x8000, 0x7FFF) as i16)))
    }

    /// Matrix product `self * other` in 1.3.12, truncated, saturated to 16 bits.
    pub fn multiply(&self, other: &Matrix) -> Matrix {
        let a = self.to_bits();
        let b = other.to_bits();
        let mut out = [[0i16; 3]; 3];
        for (r, row) in out.iter_mut().enumerate() {
            for (c, slot) in row.iter_mut().enumerate() {
                let sum: i64 = (0..3).map(|k| a[r][k] as i64 * b[k][c] as i64).sum();
                *slot = (sum >> 12).clamp(-0x8000, 0x7FFF) as i16;
            }
        }
        Matrix::from_bits(out)
    }
}

/// sin(angle) in 1.3.12 for an angle in 1/4096 turn (any `i32`; only the low 12 bits
/// matter), from a compile-time quarter-wave table.
pub fn sin(angle: Angle) -> i32 {
    let a = (angle & 0xFFF) as usize;
    let q = a % 1024;
    let v = match a / 1024 {
        0 => SINE_QUARTER[q],
        1 => SINE_QUARTER[1024 - q],
        2 => -SINE_QUARTER[q],
        _ => -SINE_QUARTER[1024 - q],
    };
    v as i32
}

/// cos(angle) in 1.3.12 (any `i32`; a quarter turn ahead of [`sin`], wrapping).
pub fn cos(angle: Angle) -> i32 {
    sin(angle.wrapping_add(1024))
}

/// sin for 0..=1024 (a quarter turn) in 1.3.12, rounded, from a Taylor series evaluated in
/// 64.64 fixed point at compile time.
const SINE_QUARTER: [i16; 1025] = build_sine();

const fn build_sine() -> [i16; 1025] {
    // pi/2 in Q60.
    const HALF_PI_Q60: i128 = 1_811_004_864_519_280_711;
    let mut table = [0i16; 1025];
    let mut i = 0;
    while i <= 1024 {
        let x = HALF_PI_Q60 * i as i128 / 1024; // Q60
        let x2 = (x * x) >> 60;
        let mut term = x;
        let mut sum = x;
        let mut k = 1;
        while k <= 9 {
            term = -((term * x2) >> 60) / ((2 * k) * (2 * k + 1)) as i128;
            sum += term;
            k += 1;
        }
        table[i] = ((sum * 4096 + (1i128 << 59)) >> 60) as i16;
        i += 1;
    }
    table
}

/// The typed face of a [`Gte`]: set-up calls load control registers, operations run
/// commands with sf = 1 (results in 1.3.12) and the lm setting of the SDK's words
/// ([`command`]).
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

fn unpack_xy(word: u32) -> (i16, i16) {
    (word as u16 as i16, (word >> 16) as u16 as i16)
}

fn unpack_rgb(word: u32) -> Rgb {
    [word as u8, (word >> 8) as u8, (word >> 16) as u8]
}

/// The command word the typed API issues: sf = 1; lm = 1 for the normal-colour lighting
/// commands (negative light clamps to zero, as the SDK's NCS/NCT/NCCS/NCCT/NCDS/NCDT words
/// do), lm = 0 otherwise.
pub const fn command(op: Opcode) -> u32 {
    let lm = matches!(
        op,
        Opcode::Ncs | Opcode::Nct | Opcode::Nccs | Opcode::Ncct | Opcode::Ncds | Opcode::Ncdt
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

    /// Load the background (ambient) colour BK (c13-c15), 1.19.12 per channel (4096 = 1.0).
    pub fn set_background_color(&mut self, bk: [i32; 3]) {
        for (r, v) in (13..).zip(bk) {
            self.gte.write_control(r, v as u32);
        }
    }

    /// Load the far colour FC (c21-c23) that depth cueing fades towards, 1.27.4 per channel.
    pub fn set_far_color(&mut self, fc: [i32; 3]) {
        for (r, v) in (21..).zip(fc) {
            self.gte.write_control(r, v as u32);
        }
    }

    /// RTPS: rotate, translate and project one vertex.
    pub fn project(&mut self, v: Vector3) -> Projected {
        write_vector(&mut self.gte, 0, v);
        self.gte.execute(command(Opcode::Rtps));
        let (x, y) = unpack_xy(self.gte.read_data(14));
        Projected {
            x,
            y,
            sz: self.gte.read_data(19) as u16,
            ir0: I4F12::from_bits(self.gte.read_data(8) as i16),
            flag: self.gte.flag(),
        }
    }

    /// RTPS with the sub-pixel screen position: one command, the same register effects and
    /// [`Projected`] as [`Geometry::project`], plus the 16.16 screen X/Y before the integer
    /// truncation (docs/hardware/gte.md §5 step 6), saturated as [`SubpixelProjected`] says.
    pub fn project_subpixel(&mut self, v: Vector3) -> SubpixelProjected {
        let projected = self.project(v);
        let regs = &self.gte.regs;
        // The quotient RTPS used: H and the saturated SZ3 it pushed
        // (docs/hardware/gte.md §5 steps 4-5).
        let (q, _) = crate::unr::divide(self.gte.divide_mode(), regs.h(), projected.sz);
        let q = q as i64;
        let fine = |ir: i16, offset: i32| {
            let value = q * ir as i64 + offset as i64;
            I16F16::from_bits(value.clamp(-0x400 << 16, (0x400 << 16) - 1) as i32)
        };
        SubpixelProjected {
            projected,
            x: fine(regs.ir(1), regs.offset().0),
            y: fine(regs.ir(2), regs.offset().1),
        }
    }

    /// RTPT: rotate, translate and project three vertices.
    pub fn project_triangle(&mut self, v: [Vector3; 3]) -> ProjectedTriangle {
        for (i, v) in (0..).zip(v) {
            write_vector(&mut self.gte, i, v);
        }
        self.gte.execute(command(Opcode::Rtpt));
        ProjectedTriangle {
            xy: [12, 13, 14].map(|r| unpack_xy(self.gte.read_data(r))),
            sz: [17, 18, 19].map(|r| self.gte.read_data(r) as u16),
            ir0: I4F12::from_bits(self.gte.read_data(8) as i16),
            flag: self.gte.flag(),
        }
    }

    /// NCLIP on the screen XY FIFO as it stands (after a projection): twice the signed area
    /// of SXY0, SXY1, SXY2; positive when they run clockwise as seen on a Y-down screen
    /// (top-left, top-right, bottom-left).
    pub fn nclip_current(&mut self) -> i32 {
        self.gte.execute(command(Opcode::Nclip));
        self.gte.read_data(24) as i32
    }

    /// NCLIP of three screen points.
    pub fn nclip(&mut self, xy: [(i16, i16); 3]) -> i32 {
        for (r, (x, y)) in (12..).zip(xy) {
            self.gte.write_data(r, packed(x, y));
        }
        self.nclip_current()
    }

    /// AVSZ3 of three screen Z values: OTZ = ZSF3 * (SZ1 + SZ2 + SZ3) >> 12.
    pub fn average_z3(&mut self, sz: [u16; 3]) -> u16 {
        for (r, z) in (17..).zip(sz) {
            self.gte.write_data(r, z as u32);
        }
        self.gte.execute(command(Opcode::Avsz3));
        self.gte.read_data(7) as u16
    }

    /// AVSZ4 of four screen Z values: OTZ = ZSF4 * (SZ0 + ... + SZ3) >> 12.
    pub fn average_z4(&mut self, sz: [u16; 4]) -> u16 {
        for (r, z) in (16..).zip(sz) {
            self.gte.write_data(r, z as u32);
        }
        self.gte.execute(command(Opcode::Avsz4));
        self.gte.read_data(7) as u16
    }

    fn set_color(&mut self, color: Rgb, code: u8) {
        let word = color[0] as u32
            | (color[1] as u32) << 8
            | (color[2] as u32) << 16
            | (code as u32) << 24;
        self.gte.write_data(6, word);
    }

    fn single(&mut self, op: Opcode, normal: Vector3) -> Rgb {
        write_vector(&mut self.gte, 0, normal);
        self.gte.execute(command(op));
        unpack_rgb(self.gte.read_data(22))
    }

    fn triple(&mut self, op: Opcode, normals: [Vector3; 3]) -> [Rgb; 3] {
        for (i, n) in (0..).zip(normals) {
            write_vector(&mut self.gte, i, n);
        }
        self.gte.execute(command(op));
        [20, 21, 22].map(|r| unpack_rgb(self.gte.read_data(r)))
    }

    /// NCS: the light colour at a normal (BK + LCM * (LLM * N)).
    pub fn normal_color(&mut self, normal: Vector3) -> Rgb {
        self.single(Opcode::Ncs, normal)
    }

    /// NCT: NCS for three normals.
    pub fn normal_color_triple(&mut self, normals: [Vector3; 3]) -> [Rgb; 3] {
        self.triple(Opcode::Nct, normals)
    }

    /// NCCS: the light colour at a normal multiplied by a material colour.
    pub fn normal_color_color(&mut self, normal: Vector3, color: Rgb) -> Rgb {
        self.set_color(color, 0);
        self.single(Opcode::Nccs, normal)
    }

    /// NCCT: NCCS for three normals with one material colour.
    pub fn normal_color_color_triple(&mut self, normals: [Vector3; 3], color: Rgb) -> [Rgb; 3] {
        self.set_color(color, 0);
        self.triple(Opcode::Ncct, normals)
    }

    /// NCDS: NCCS then depth cueing towards FC by IR0 (set by the last projection).
    pub fn normal_color_depth(&mut self, normal: Vector3, color: Rgb) -> Rgb {
        self.set_color(color, 0);
        self.single(Opcode::Ncds, normal)
    }

    /// NCDT: NCDS for three normals.
    pub fn normal_color_depth_triple(&mut self, normals: [Vector3; 3], color: Rgb) -> [Rgb; 3] {
        self.set_color(color, 0);
        self.triple(Opcode::Ncdt, normals)
    }

    /// DPCS: fade a colour towards FC by `ir0` (0 = the colour, 1.0 = FC).
    pub fn depth_cue(&mut self, color: Rgb, ir0: I4F12) -> Rgb {
        self.set_color(color, 0);
        self.gte.write_data(8, ir0.to_bits() as i32 as u32);
        self.gte.execute(command(Opcode::Dpcs));
        unpack_rgb(self.gte.read_data(22))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sine_table_known_values() {
        // sin 0 = 0, sin 30deg = 0.5 = 2048, sin 90deg = 4096, sin 45deg = 2896.3 -> 2896.
        assert_eq!(sin(0), 0);
        // 341/4096 turn = 29.97 degrees: 4096 * sin = 2046.19 -> 2046.
        assert_eq!(sin(4096 / 12), 2046);
        assert_eq!(sin(1024), 4096);
        assert_eq!(sin(512), 2896);
        assert_eq!(sin(2048), 0);
        assert_eq!(sin(3072), -4096);
        assert_eq!(cos(0), 4096);
        // 982/4096 turn: 4096 * sin = 4087.502 -> 4088 (a wrong pi/2 constant once gave 4087).
        assert_eq!(sin(982), 4088);
    }

    #[test]
    fn identity_rotation() {
        assert_eq!(Matrix::rotation(0, 0, 0), Matrix::IDENTITY);
    }
}
