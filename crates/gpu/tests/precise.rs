//! The non-hardware precise path (`precise` feature: sub-pixel positions, perspective-correct
//! texture coordinates), on hand-worked cases, through `Gpu::draw_polygon_precise`.

use gpu::Gpu;
use gpu::precise::{PreciseError, PreciseVertex};

/// A GPU drawing anywhere in VRAM with offset (0, 0).
fn gpu() -> Gpu {
    let mut g = Gpu::new();
    g.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]);
    g
}

fn at(x: i32, y: i32, inv_z: u32) -> PreciseVertex {
    PreciseVertex {
        x: x * 16,
        y: y * 16,
        inv_z,
    }
}

/// A flat red triangle packet (GP0 20h) whose whole-pixel vertices are all (0, 0): only the
/// sub-pixel positions place it.
const FLAT_RED: [u32; 4] = [0x2000_00FF, 0, 0, 0];

fn covered(g: &Gpu) -> Vec<(usize, usize)> {
    let mut v = Vec::new();
    for y in 0..6 {
        for x in 0..6 {
            if g.vram().pixel(x, y) != 0 {
                v.push((x, y));
            }
        }
    }
    v
}

/// Integer positions: the right triangle (0,0) (4,0) (0,4) covers x in [0, 4-y) on rows
/// 0..3, the top-left rule of the hardware (10 pixels).
#[test]
fn coverage_top_left() {
    let mut g = gpu();
    g.draw_polygon_precise(&FLAT_RED, &[at(0, 0, 1), at(4, 0, 1), at(0, 4, 1)], false)
        .unwrap();
    let expected: Vec<(usize, usize)> = (0..4)
        .flat_map(|y| (0..4 - y).map(move |x| (x, y)))
        .collect();
    assert_eq!(covered(&g), expected);
    assert_eq!(g.vram().pixel(0, 0), 31);
}

/// A sub-pixel shift moves coverage: the same triangle moved right by 8/16 pixel no longer
/// covers column 0 (samples at x = 0 lie left of its edge x = 0.5).
#[test]
fn subpixel_shift() {
    let mut g = gpu();
    let p = [(8, 0), (8 + 64, 0), (8, 64)].map(|(x, y)| PreciseVertex { x, y, inv_z: 1 });
    g.draw_polygon_precise(&FLAT_RED, &p, false).unwrap();
    assert_eq!(g.vram().pixel(0, 0), 0);
    assert_eq!(g.vram().pixel(1, 0), 31);
}

/// Positions are relative to the drawing offset (E5h), as packet vertices are.
#[test]
fn drawing_offset_applies() {
    let mut g = gpu();
    g.gp0(0xE500_0000 | 100 << 11 | 200);
    g.draw_polygon_precise(&FLAT_RED, &[at(0, 0, 1), at(4, 0, 1), at(0, 4, 1)], false)
        .unwrap();
    assert_eq!(g.vram().pixel(200, 100), 31);
    assert_eq!(g.vram().pixel(0, 0), 0);
}

/// Texture coordinates, with a 15-bit texture row whose texel u holds the value u + 1:
/// (0,0) u=0, (64,0) u=64, (0,8) u=0. Affine: u(x) = x, so pixel (32, 0) samples texel 32.
/// Perspective with the right vertex four times as far (inv_z 4 : 1): at screen x the
/// weights are (64 - x) * 4 and x, so u = 64 x / (4 (64 - x) + x); at x = 32,
/// u = 2048 / 160 = 12.8 -> texel 13.
#[test]
fn perspective_texture_coordinates() {
    for (perspective, want) in [(false, 32u16), (true, 13)] {
        let mut g = gpu();
        for u in 0..256usize {
            g.vram_mut().set_pixel(768 + u, 0, (u + 1) as u16);
        }
        // Raw-textured triangle (25h); texpage attribute: page x 768 / 64 = 12, 15-bit (2 << 7).
        let texpage = 12 | 2 << 7;
        let packet = [0x2500_0000, 0, 0, 0, 64 | texpage << 16, 0, 0];
        let p = [
            at(0, 100, 4 << 20),
            at(64, 100, 1 << 20),
            at(0, 108, 4 << 20),
        ];
        g.draw_polygon_precise(&packet, &p, perspective).unwrap();
        assert_eq!(
            g.vram().pixel(32, 100),
            want + 1,
            "perspective {perspective}"
        );
    }
}

/// A quad packet (28h) draws both triangles (v0 v1 v2 and v1 v2 v3): a 4x4 square.
#[test]
fn quad_covers_both_halves() {
    let mut g = gpu();
    let p = [at(0, 0, 1), at(4, 0, 1), at(0, 4, 1), at(4, 4, 1)];
    g.draw_polygon_precise(&[0x2800_00FF, 0, 0, 0, 0], &p, false)
        .unwrap();
    let expected: Vec<(usize, usize)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
    assert_eq!(covered(&g), expected);
}

/// Packets that are not polygons, of the wrong length, or with the wrong number of
/// positions are refused and draw nothing.
#[test]
fn bad_input_is_refused() {
    let mut g = gpu();
    let p = [at(0, 0, 1), at(4, 0, 1), at(0, 4, 1)];
    assert_eq!(
        g.draw_polygon_precise(&[0x6000_00FF, 0, 0], &p, false),
        Err(PreciseError::NotPolygon(0x6000_00FF))
    );
    assert_eq!(
        g.draw_polygon_precise(&[], &p, false),
        Err(PreciseError::NotPolygon(0))
    );
    assert_eq!(
        g.draw_polygon_precise(&FLAT_RED[..3], &p, false),
        Err(PreciseError::PacketLength {
            expected: 4,
            got: 3
        })
    );
    assert_eq!(
        g.draw_polygon_precise(&FLAT_RED, &p[..2], false),
        Err(PreciseError::VertexCount {
            expected: 3,
            got: 2
        })
    );
    assert_eq!(covered(&g), []);
}
