//! Properties of the decode API: every pixel a command changes lies inside its decoded write
//! bounds, and a command whose primitives the rasterizer drops changes no pixel.

use gpu::Gpu;
use gpu::decode::Coverage;
use gpu::encode::{self, Line, Polygon, Rectangle, Vertex};
use proptest::prelude::*;

/// A vertex at x, y in -1100..1100 (the packet keeps 11 bits: wrapping exercised) of
/// colour `color`.
fn vertex(x: i32, y: i32, color: [u8; 3]) -> Vertex {
    Vertex {
        x: x as i16,
        y: y as i16,
        color,
        ..Vertex::default()
    }
}

/// Yellow, the colour of the primitives.
const YELLOW: [u8; 3] = [0xFF, 0xFF, 0];

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
        encode::area_top_left(l as u16, t as u16),
        encode::area_bottom_right(r as u16, b as u16),
        encode::drawing_offset(offset.0 as i16, offset.1 as i16),
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
        color in any::<[u8; 3]>().prop_filter("not black", |c| *c != [0; 3]),
    ) {
        let mut gpu = setup(a, off);
        let polygon = Polygon {
            vertices: v.map(|(x, y)| vertex(x, y, color)),
            quad,
            ..Polygon::default()
        };
        check(&mut gpu, &polygon.packet())?;
    }

    #[test]
    fn small_polygons_stay_in_their_bounds(
        a in area(),
        base in (0i32..1000, 0i32..500),
        v in prop::array::uniform3((-40i32..40, -40i32..40)),
    ) {
        let mut gpu = setup(a, (0, 0));
        let v = v.map(|(x, y)| vertex(base.0 + x, base.1 + y, YELLOW));
        check(&mut gpu, &Polygon::triangle(v).packet())?;
    }

    #[test]
    fn lines_stay_in_their_bounds(
        a in area(),
        p in prop::array::uniform2((-1100i32..1100, -600i32..600)),
    ) {
        let mut gpu = setup(a, (0, 0));
        let line = Line {
            vertices: p.map(|(x, y)| vertex(x, y, YELLOW)),
            ..Line::default()
        };
        check(&mut gpu, &line.packet())?;
    }

    #[test]
    fn rectangles_stay_in_their_bounds(
        a in area(),
        p in (-1100i32..1100, -600i32..600),
        size in (0u32..1100, 0u32..600),
    ) {
        let mut gpu = setup(a, (0, 0));
        let rectangle = Rectangle {
            x: p.0 as i16,
            y: p.1 as i16,
            color: YELLOW,
            width: size.0 as u16,
            height: size.1 as u16,
            ..Rectangle::default()
        };
        check(&mut gpu, &rectangle.packet())?;
    }
}
