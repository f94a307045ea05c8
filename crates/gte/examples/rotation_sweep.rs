//! Exhaustive measurement of `Matrix::rotation` against the rotation computed in `f64` from
//! the same angles, over every (x, y, z) triple of angles in 1/4096 turn: 2^36 triples.
//! Prints the largest distance of an entry from the exact value and the largest distance of
//! an entry of R·Rᵀ (summed exactly) from the identity's, in LSB (1/4096), with a triple
//! where each occurs. These are the figures behind `Matrix::ROTATION_ERROR` and
//! `Matrix::ROTATION_ORTHOGONALITY` (docs/typed-api.md, "Rotation accuracy").
//!
//! Run with `cargo run --release -p gte --example rotation_sweep`, or with two numbers
//! `FIRST END` to sweep only x in FIRST..END (the whole sweep is about 25 minutes of one
//! core; split, it runs on several). The angles beyond one turn are not needed: only the
//! low 12 bits of an angle count.

use gte::typed::Matrix;

#[path = "../tests/support/rotation.rs"]
mod rotation;

fn main() {
    let args: Vec<i32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (first, end) = match args[..] {
        [first, end] => (first.clamp(0, 4096), end.clamp(0, 4096)),
        _ => (0, 4096),
    };
    let sin: Vec<f64> = (0..4096).map(|a| rotation::radians(a).sin()).collect();
    let cos: Vec<f64> = (0..4096).map(|a| rotation::radians(a).cos()).collect();
    let (mut worst_entry, mut at_entry) = (0f64, (0, 0, 0));
    let (mut worst_dot, mut at_dot) = (0i64, (0, 0, 0));
    for x in first..end {
        let (sx, cx) = (sin[x as usize], cos[x as usize]);
        for y in 0..4096 {
            let (sy, cy) = (sin[y as usize], cos[y as usize]);
            for z in 0..4096 {
                let (sz, cz) = (sin[z as usize], cos[z as usize]);
                let m = Matrix::rotation(x, y, z).to_bits();
                let exact = rotation::exact([(sx, cx), (sy, cy), (sz, cz)]);
                for i in 0..3 {
                    for j in 0..3 {
                        let e = (m[i][j] as f64 - 4096.0 * exact[i][j]).abs();
                        if e > worst_entry {
                            (worst_entry, at_entry) = (e, (x, y, z));
                        }
                    }
                    for j in i..3 {
                        let d = rotation::off_identity(&m, i, j);
                        if d > worst_dot {
                            (worst_dot, at_dot) = (d, (x, y, z));
                        }
                    }
                }
            }
        }
    }
    println!("x swept: {first}..{end}, y and z: 0..4096");
    println!("worst entry of R against f64: {worst_entry:.4} LSB at (x, y, z) = {at_entry:?}");
    println!(
        "worst entry of R·Rᵀ against the identity: {worst_dot}/4096 = {:.4} LSB at {at_dot:?}",
        worst_dot as f64 / 4096.0
    );
}
