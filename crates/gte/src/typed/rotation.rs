//! Rotation matrices from angles, built the way PS1 SDK rotation functions build them: an
//! integer sine table and products truncated by >> 12, with no floating point.

use super::values::Matrix;

/// A rotation angle in 1/4096 of a turn (4096 = 360 degrees), the PS1 SDK convention.
pub type Angle = i32;

impl Matrix {
    /// The largest distance, in LSB (1/4096), of an entry of [`Matrix::rotation`] from the
    /// exact rotation of the same angles: 4.4628 at (x, y, z) = (42, 982, 2090), the worst
    /// of all 2^36 angle triples (docs/typed-api.md, "Rotation accuracy").
    pub const ROTATION_ERROR: f64 = 4.463;

    /// The largest distance, in LSB, of an entry of R·Rᵀ (summed exactly, then divided by
    /// 4096) from the identity's, for R from [`Matrix::rotation`]: 37294 / 4096 at (127, 788,
    /// 2162), the worst of all 2^36 angle triples (docs/typed-api.md, "Rotation accuracy").
    pub const ROTATION_ORTHOGONALITY: f64 = 37294.0 / 4096.0;

    /// Rotation by `x`, then `y`, then `z` (angles in 1/4096 turn, any `i32`: only the low
    /// 12 bits matter, a whole turn being 4096): R = Rz * Ry * Rx, each
    /// entry rounded to 1.3.12 from an integer sine table, products truncated by >> 12 as PS1
    /// SDK rotation functions do.
    ///
    /// Each entry is within [`Matrix::ROTATION_ERROR`] LSB (1/4096) of the exact rotation of
    /// the same angles, and R·Rᵀ within [`Matrix::ROTATION_ORTHOGONALITY`] LSB of the
    /// identity, for every angle triple (measured over all of them by the example
    /// `rotation_sweep`).
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
