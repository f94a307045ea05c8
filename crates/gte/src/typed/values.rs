//! The values a PS1 program loads into the GTE, typed by what the hardware stores
//! (docs/hardware/gte.md §2): 1.3.12 matrices and normals, 16-bit vertices, 32-bit
//! translations, the 1.19.12 background colour and 1.27.4 far colour, the projection set-up.

use fixed::types::{I4F12, I8F8, I8F24, I16F16, I20F12, I28F4};

/// A 3x3 matrix of 1.3.12 entries (rotation RT, light LLM or light colour LCM), row-major.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Matrix(pub [[I4F12; 3]; 3]);

/// A 16-bit vertex (V0-V2), or a 16-bit vector written to IR1-3.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Vector3 {
    /// X.
    pub x: i16,
    /// Y.
    pub y: i16,
    /// Z.
    pub z: i16,
}

/// A surface normal in 1.3.12 (1.0 = 4096), written to V0-V2 for the lighting commands.
/// [`Vector3`] converts into it bit for bit, so the lighting calls take either.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Normal {
    /// X.
    pub x: I4F12,
    /// Y.
    pub y: I4F12,
    /// Z.
    pub z: I4F12,
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

/// The background (ambient) colour BK (c13-c15): R, G, B in 1.19.12, as the second lighting
/// step adds it (BK << 12 + LCM × IR, docs/hardware/gte.md §8). With no light, a colour byte
/// is BK SAR 4 saturated to 0..=FFh, so 1.0 (4096) gives 256, saturated to 255 with its FLAG
/// bit set; 255 takes FF0h..=FFFh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct BackgroundColor(pub [I20F12; 3]);

/// The far colour FC (c21-c23) that depth cueing fades towards: R, G, B in 1.27.4, so the
/// integer part is the colour byte (FC << 12 enters the sum, docs/hardware/gte.md §8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FarColor(pub [I28F4; 3]);

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
    /// A 320x240 screen centred at (160, 120), H = 320, no depth cue, ZSF3 = 555h and
    /// ZSF4 = 400h. ZSF4 is 1/4 exactly, so AVSZ4's OTZ is the mean of four SZ rounded down;
    /// ZSF3 is 1365/4096, a little under 1/3, so AVSZ3's OTZ is floor(ΣSZ × 1365 / 4096):
    /// the mean of three SZ rounded down, or up to 16 below it (16 at ΣSZ = 3 × FFFFh)
    /// (docs/typed-api.md).
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

    /// The transpose (for a rotation, its inverse up to the rounding of the entries).
    pub fn transpose(&self) -> Matrix {
        let m = self.0;
        Matrix([0, 1, 2].map(|r| [m[0][r], m[1][r], m[2][r]]))
    }
}

impl Vector3 {
    /// From X, Y, Z.
    pub const fn new(x: i16, y: i16, z: i16) -> Vector3 {
        Vector3 { x, y, z }
    }

    /// X, Y, Z as an array.
    pub const fn to_array(self) -> [i16; 3] {
        [self.x, self.y, self.z]
    }
}

impl From<[i16; 3]> for Vector3 {
    fn from([x, y, z]: [i16; 3]) -> Vector3 {
        Vector3 { x, y, z }
    }
}

impl Normal {
    /// From raw 1.3.12 bit patterns X, Y, Z.
    pub const fn from_bits([x, y, z]: [i16; 3]) -> Normal {
        Normal {
            x: I4F12::from_bits(x),
            y: I4F12::from_bits(y),
            z: I4F12::from_bits(z),
        }
    }

    /// Raw 1.3.12 bit patterns X, Y, Z.
    pub const fn to_bits(self) -> [i16; 3] {
        [self.x.to_bits(), self.y.to_bits(), self.z.to_bits()]
    }
}

impl From<Vector3> for Normal {
    /// The vector's components read as 1.3.12 bit patterns.
    fn from(v: Vector3) -> Normal {
        Normal::from_bits(v.to_array())
    }
}

impl From<Normal> for Vector3 {
    /// The normal's 1.3.12 bit patterns.
    fn from(n: Normal) -> Vector3 {
        Vector3::from(n.to_bits())
    }
}

impl BackgroundColor {
    /// From raw 1.19.12 bit patterns R, G, B (the words CTC2 writes).
    pub const fn from_bits(bits: [i32; 3]) -> BackgroundColor {
        BackgroundColor([
            I20F12::from_bits(bits[0]),
            I20F12::from_bits(bits[1]),
            I20F12::from_bits(bits[2]),
        ])
    }

    /// Raw 1.19.12 bit patterns R, G, B.
    pub fn to_bits(self) -> [i32; 3] {
        self.0.map(I20F12::to_bits)
    }
}

impl From<[i32; 3]> for BackgroundColor {
    /// As [`BackgroundColor::from_bits`].
    fn from(bits: [i32; 3]) -> BackgroundColor {
        BackgroundColor::from_bits(bits)
    }
}

impl FarColor {
    /// From raw 1.27.4 bit patterns R, G, B (the words CTC2 writes).
    pub const fn from_bits(bits: [i32; 3]) -> FarColor {
        FarColor([
            I28F4::from_bits(bits[0]),
            I28F4::from_bits(bits[1]),
            I28F4::from_bits(bits[2]),
        ])
    }

    /// Raw 1.27.4 bit patterns R, G, B.
    pub fn to_bits(self) -> [i32; 3] {
        self.0.map(I28F4::to_bits)
    }
}

impl From<[i32; 3]> for FarColor {
    /// As [`FarColor::from_bits`].
    fn from(bits: [i32; 3]) -> FarColor {
        FarColor::from_bits(bits)
    }
}

/// The vector MVMVA multiplies (its `v` field, docs/hardware/gte.md §1): a vector written to
/// V0, V1 or V2, or to IR1-3, and selected there.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MvmvaVector {
    /// Written to V0 (`v` = 0).
    V0(Vector3),
    /// Written to V1 (`v` = 1).
    V1(Vector3),
    /// Written to V2 (`v` = 2).
    V2(Vector3),
    /// Written to IR1-3 (`v` = 3).
    Ir(Vector3),
}
