//! Exhaustive comparison of the UNR divide with exact rounded division over every
//! (H, SZ3) pair of 16-bit values: 2^32 pairs. Prints how many pairs overflow, how many
//! differ from round(H * 10000h / SZ3), the largest difference in each direction, and a
//! histogram. Run with `cargo run --release -p gte --example unr_sweep` (about a minute on
//! one core of a 2020s machine); pass a number N to sweep only H < N.

use gte::unr::{exact_divide, unr_divide};

fn main() {
    let h_limit: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0x1_0000)
        .min(0x1_0000);
    let mut overflow = 0u64;
    let mut compared = 0u64;
    let mut differing = 0u64;
    let mut histogram = [0u64; 9]; // unr - exact in -4..=4
    let (mut min_diff, mut max_diff) = (0i64, 0i64);
    let mut worst = (0u16, 0u16);
    for h in 0..h_limit {
        let h = h as u16;
        for sz3 in 0..=0xFFFFu16 {
            let (q, of) = unr_divide(h, sz3);
            if of {
                overflow += 1;
                continue;
            }
            let (e, _) = exact_divide(h, sz3);
            compared += 1;
            let d = q as i64 - e as i64;
            if d != 0 {
                differing += 1;
                if d < min_diff || d > max_diff {
                    worst = (h, sz3);
                }
                min_diff = min_diff.min(d);
                max_diff = max_diff.max(d);
            }
            if let Some(slot) = histogram.get_mut((d + 4).clamp(0, 8) as usize) {
                *slot += 1;
            }
        }
    }
    println!("H swept: 0..{h_limit:#X}, SZ3 swept: 0..=0xFFFF");
    println!("overflow (H >= 2*SZ3): {overflow}");
    println!("compared: {compared}");
    println!(
        "differing from round(H*65536/SZ3): {differing} ({:.2}%)",
        100.0 * differing as f64 / compared.max(1) as f64
    );
    println!(
        "unr - exact: min {min_diff}, max {max_diff} (an extreme at H={:#06X}, SZ3={:#06X})",
        worst.0, worst.1
    );
    for (i, n) in histogram.iter().enumerate() {
        if *n > 0 {
            println!("  diff {:+}: {n}", i as i64 - 4);
        }
    }
}
