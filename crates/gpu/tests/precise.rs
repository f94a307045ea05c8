//! The non-hardware precise triangle path (sub-pixel positions, perspective-correct texture
//! coordinates), on hand-worked cases.

use gpu::Vram;
use gpu::primitive::{Texture, Triangle, Vertex};
use gpu::rasterizer::draw_triangle_precise;
use gpu::rasterizer::precise::PreciseVertex;
use gpu::state::{DrawState, DrawingArea, TextureDepth};
use gpu::texture::ClutCache;

fn state() -> DrawState {
    DrawState {
        area: DrawingArea {
            left: 0,
            top: 0,
            right: 1023,
            bottom: 511,
        },
        ..DrawState::default()
    }
}

fn vertex(u: u8, v: u8) -> Vertex {
    Vertex {
        color: [255, 0, 0],
        u,
        v,
        ..Vertex::default()
    }
}

fn at(x: i32, y: i32, inv_z: u32) -> PreciseVertex {
    PreciseVertex {
        x: x * 16,
        y: y * 16,
        inv_z,
    }
}

/// Integer positions: the right triangle (0,0) (4,0) (0,4) covers x in [0, 4-y) on rows
/// 0..3, the top-left rule of the hardware (10 pixels).
#[test]
fn coverage_top_left() {
    let mut vram = Vram::new();
    let tri = Triangle {
        vertices: [vertex(0, 0); 3],
        ..Triangle::default()
    };
    draw_triangle_precise(
        &mut vram,
        &state(),
        &mut ClutCache::default(),
        &tri,
        &[at(0, 0, 1), at(4, 0, 1), at(0, 4, 1)],
        false,
    );
    let mut covered = Vec::new();
    for y in 0..6 {
        for x in 0..6 {
            if vram.pixel(x, y) != 0 {
                covered.push((x, y));
            }
        }
    }
    let expected: Vec<(usize, usize)> = (0..4)
        .flat_map(|y| (0..4 - y).map(move |x| (x, y)))
        .collect();
    assert_eq!(covered, expected);
    assert_eq!(vram.pixel(0, 0), 31);
}

/// A sub-pixel shift moves coverage: the same triangle moved right by 8/16 pixel no longer
/// covers column 0 (samples at x = 0 lie left of its edge x = 0.5).
#[test]
fn subpixel_shift() {
    let mut vram = Vram::new();
    let tri = Triangle {
        vertices: [vertex(0, 0); 3],
        ..Triangle::default()
    };
    let p = [
        PreciseVertex {
            x: 8,
            y: 0,
            inv_z: 1,
        },
        PreciseVertex {
            x: 8 + 64,
            y: 0,
            inv_z: 1,
        },
        PreciseVertex {
            x: 8,
            y: 64,
            inv_z: 1,
        },
    ];
    draw_triangle_precise(
        &mut vram,
        &state(),
        &mut ClutCache::default(),
        &tri,
        &p,
        false,
    );
    assert_eq!(vram.pixel(0, 0), 0);
    assert_eq!(vram.pixel(1, 0), 31);
}

/// Texture coordinates, with a 15-bit texture row whose texel u holds the value u + 1:
/// (0,0) u=0, (64,0) u=64, (0,8) u=0. Affine: u(x) = x, so pixel (32, 0) samples texel 32.
/// Perspective with the right vertex four times as far (inv_z 4 : 1): at screen x the
/// weights are (64 - x) * 4 and x, so u = 64 x / (4 (64 - x) + x); at x = 32,
/// u = 2048 / 160 = 12.8 -> texel 13.
#[test]
fn perspective_texture_coordinates() {
    for (perspective, want) in [(false, 32u16), (true, 13)] {
        let mut vram = Vram::new();
        for u in 0..256usize {
            vram.set_pixel(768 + u, 0, (u + 1) as u16);
        }
        let tri = Triangle {
            vertices: [vertex(0, 0), vertex(64, 0), vertex(0, 0)],
            texture: Some(Texture {
                page_x: 768,
                page_y: 0,
                depth: TextureDepth::Direct15,
                raw: true,
                ..Texture::default()
            }),
            ..Triangle::default()
        };
        let p = [
            at(0, 100, 4 << 20),
            at(64, 100, 1 << 20),
            at(0, 108, 4 << 20),
        ];
        draw_triangle_precise(
            &mut vram,
            &state(),
            &mut ClutCache::default(),
            &tri,
            &p,
            perspective,
        );
        assert_eq!(vram.pixel(32, 100), want + 1, "perspective {perspective}");
    }
}
