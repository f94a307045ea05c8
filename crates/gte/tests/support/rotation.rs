//! The rotation `Matrix::rotation` approximates, computed in `f64` from the same angles, and
//! how far an integer rotation is from orthogonal (docs/typed-api.md, "Rotation accuracy"):
//! shared by the error-bound property (tests/typed_docs.rs) and the exhaustive sweep behind
//! the bound (examples/rotation_sweep.rs).

/// An angle in 1/4096 turn (only the low 12 bits count) in radians.
pub fn radians(angle: i32) -> f64 {
    (angle & 0xFFF) as f64 / 4096.0 * std::f64::consts::TAU
}

/// The rotation about X, then Y, then Z (the order `Matrix::rotation` multiplies in), from
/// each angle's (sine, cosine).
#[inline(always)]
pub fn exact([(sx, cx), (sy, cy), (sz, cz)]: [(f64, f64); 3]) -> [[f64; 3]; 3] {
    [
        [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
        [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
        [-sy, cy * sx, cy * cx],
    ]
}

/// Entry (i, j) of R·Rᵀ, summed exactly, minus the identity's (1.0 in 1.3.12 squared is
/// 2^24), in 1/2^24.
#[inline(always)]
pub fn off_identity(m: &[[i16; 3]; 3], i: usize, j: usize) -> i64 {
    let dot: i64 = (0..3).map(|k| m[i][k] as i64 * m[j][k] as i64).sum();
    let identity = if i == j { 1 << 24 } else { 0 };
    (dot - identity).abs()
}
