//! Properties of the decode API: every pixel a command changes lies inside its decoded write
//! bounds, and a command whose primitives the rasterizer drops changes no pixel.

use gpu::Gpu;
use gpu::decode::Coverage;
use proptest::prelude::*;

/// A signed 11-bit vertex word from x, y in -1100..1100 (wrapping exercised).
fn vertex(x: i32, y: i32) -> u32 {
    (x as u32 & 0x7FF) | (y as u32 & 0x7FF) << 16
}

fn check(gpu: &mut Gpu, words: &[u32]) -> Result<(), TestCaseError> {
    let d = gpu.decode_gp0(words);
    let before = gpu.vram().clone();
    gpu.gp0_words(words);
    let mut changed = 0usize;
    for y in 0..512 {
        for x in 0..1024 {
            if before.pixel(x, y) != gpu.vram().pixel(x, y) {
                changed += 1;
                let b = d
                    .writes
                    .ok_or_else(|| TestCaseError::fail("changed without bounds"))?;
                prop_assert!(
                    (b.left as usize..=b.right as usize).contains(&x)
                        && (b.top as usize..=b.bottom as usize).contains(&y),
                    "({x}, {y}) outside {b:?} for {words:x?}"
                );
                // The pixel lies in the bounds of some drawn primitive.
                let inside = d.primitives.iter().any(|p| match p.coverage() {
                    Coverage::Drawn(b) => {
                        (b.left as usize..=b.right as usize).contains(&x)
                            && (b.top as usize..=b.bottom as usize).contains(&y)
                    }
                    Coverage::Dropped(_) => false,
                });
                prop_assert!(inside, "({}, {}) outside every drawn primitive", x, y);
            }
        }
    }
    if d.all_dropped() {
        prop_assert_eq!(changed, 0, "dropped but drew: {:x?}", words);
    }
    Ok(())
}

fn setup(area: (u32, u32, u32, u32), offset: (i32, i32)) -> Gpu {
    let (l, t, r, b) = area;
    let mut gpu = Gpu::new();
    gpu.gp0_words(&[
        0xE300_0000 | l | t << 10,
        0xE400_0000 | r | b << 10,
        0xE500_0000 | (offset.0 as u32 & 0x7FF) | (offset.1 as u32 & 0x7FF) << 11,
    ]);
    gpu
}

fn area() -> impl Strategy<Value = (u32, u32, u32, u32)> {
    (0u32..1024, 0u32..512, 0u32..1024, 0u32..512)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn polygons_stay_in_their_bounds(
        a in area(),
        off in (-64i32..64, -64i32..64),
        v in prop::array::uniform4((-1100i32..1100, -600i32..600)),
        quad in any::<bool>(),
        color in 1u32..0xFF_FFFF,
    ) {
        let mut gpu = setup(a, off);
        let mut words = vec![(if quad { 0x28 } else { 0x20 }) << 24 | color];
        for (x, y) in v.iter().take(if quad { 4 } else { 3 }) {
            words.push(vertex(*x, *y));
        }
        check(&mut gpu, &words)?;
    }

    #[test]
    fn small_polygons_stay_in_their_bounds(
        a in area(),
        base in (0i32..1000, 0i32..500),
        v in prop::array::uniform3((-40i32..40, -40i32..40)),
    ) {
        let mut gpu = setup(a, (0, 0));
        let mut words = vec![0x2000_FFFF];
        for (x, y) in v {
            words.push(vertex(base.0 + x, base.1 + y));
        }
        check(&mut gpu, &words)?;
    }

    #[test]
    fn lines_stay_in_their_bounds(
        a in area(),
        p in prop::array::uniform2((-1100i32..1100, -600i32..600)),
    ) {
        let mut gpu = setup(a, (0, 0));
        check(&mut gpu, &[0x4000_FFFF, vertex(p[0].0, p[0].1), vertex(p[1].0, p[1].1)])?;
    }

    #[test]
    fn rectangles_stay_in_their_bounds(
        a in area(),
        p in (-1100i32..1100, -600i32..600),
        size in (0u32..1100, 0u32..600),
    ) {
        let mut gpu = setup(a, (0, 0));
        check(&mut gpu, &[0x6000_FFFF, vertex(p.0, p.1), size.0 | size.1 << 16])?;
    }
}
