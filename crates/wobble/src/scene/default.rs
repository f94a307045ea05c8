//! The built-in default scene and its animation (docs/animation.md): no files needed. The
//! camera travels low over a floor of large checkerboard quads and turns, so the quads slide
//! into grazing angles where the affine texture warp is strongest, the nearest ones split
//! where they would be dropped whole; a textured cube drifts slowly (vertex jitter); a
//! Gouraud-lit sphere shows the dither pattern; a wall of mortared bricks laid in running
//! bond, whose pieces share no vertices, opens seams at its T-junctions; fog fades the
//! distance into the background colour.
//! 4-bit CLUT textures, one directional light (NCCT/NCCS, NCDT/NCDS with fog), dithering on.

use super::animation::Animation;
use super::mesh::{Mesh, MeshFace, MeshVertex};
use super::texture::Texture;
use super::{
    Camera, DEFAULT_SPLIT_EXTENT, Fog, Light, MeshAsset, Object, Scene, Screen, TextureAsset,
};
use gpu::TextureDepth;

/// Index of the drifting textured cube in the default scene's objects.
pub const CUBE: usize = 0;
/// Index of the floor.
pub const FLOOR: usize = 1;
/// Index of the Gouraud-lit, untextured sphere.
pub const SPHERE: usize = 2;
/// Index of the brick wall.
pub const WALL: usize = 3;

/// Background and fog colour.
const DUSK: [u8; 3] = [40, 36, 64];

/// Projection distance H of the default camera.
const H: u16 = 300;

/// How many times a floor quad may be split: a 500-unit quad becomes pieces of 62.5 units,
/// small enough that every piece wholly in front of the near plane covers the floor on
/// screen (at level 2 a dropped 125-unit piece still opens a hole at the bottom edge).
const FLOOR_LEVEL: u8 = 3;

/// The floor's split extent: above any screen size, so the floor is split only where a
/// polygon would be dropped whole (near the camera), as games split near geometry; the
/// quads that are drawn keep their full size and their affine swim.
const NEAR_ONLY: u16 = u16::MAX;

/// Bricks per row and rows of the wall.
const WALL_BRICKS: u32 = 6;
const WALL_ROWS: u32 = 6;

/// The built-in scene at frame 0 of its animation.
pub fn default_scene() -> Scene {
    let checker = Texture::checker(64, 8, [232, 232, 224], [200, 40, 48]);
    let floor = Texture::checker(64, 4, [96, 176, 96], [32, 72, 40]);
    let object = |mesh, texture, position, scale| Object {
        mesh,
        texture,
        position,
        rotation: [0.0; 3],
        spin: [0.0; 3],
        scale,
        color: [128, 128, 128],
        blend: None,
        tessellation: 0,
        split_extent: DEFAULT_SPLIT_EXTENT,
    };
    let mut objects = vec![
        object(0, Some(0), [-420.0, -190.0, 650.0], 110.0),
        object(1, Some(1), [0.0, 0.0, 600.0], 2000.0),
        object(2, None, [520.0, -180.0, 1250.0], 170.0),
        object(3, Some(2), [0.0, 0.0, 2600.0], 100.0),
    ];
    objects[CUBE].rotation = [20.0, 30.0, 0.0];
    objects[CUBE].spin = [0.4, 0.9, 0.2];
    objects[SPHERE].color = [210, 150, 90];
    objects[SPHERE].spin = [0.0, 1.0, 0.0];
    objects[FLOOR].tessellation = FLOOR_LEVEL;
    objects[FLOOR].split_extent = NEAR_ONLY;
    let mut scene = Scene {
        screen: Screen {
            background: DUSK,
            ..Screen::default()
        },
        accuracy: Default::default(),
        camera: Camera::default(),
        light: Some(Light {
            direction: [0.6, 1.0, 0.8],
            color: [255, 240, 220],
            ambient: [60, 60, 84],
        }),
        fog: Some(Fog {
            color: DUSK,
            near: 1800.0,
            far: 6000.0,
        }),
        textures: vec![
            TextureAsset {
                name: "checker".into(),
                texture: checker,
            },
            TextureAsset {
                name: "floor".into(),
                texture: floor,
            },
            TextureAsset {
                name: "stone".into(),
                texture: stone(),
            },
        ],
        meshes: vec![
            MeshAsset {
                name: "cube".into(),
                mesh: Mesh::cube(1.0),
            },
            MeshAsset {
                name: "floor".into(),
                mesh: Mesh::grid(2.0, 8, 8.0),
            },
            MeshAsset {
                name: "sphere".into(),
                mesh: Mesh::sphere(1.0, 10, 16),
            },
            MeshAsset {
                name: "wall".into(),
                mesh: brick_wall(WALL_BRICKS, WALL_ROWS),
            },
        ],
        objects,
    };
    scene.camera = default_animation().camera_at(&scene.camera, 0);
    scene
}

/// The default scene's animation: 90 frames at 30 per second. The camera starts at the
/// near edge of the floor looking slightly right (every object in view), travels forward at
/// 170 down to 120 units above the floor while turning left, then right (a positive Y
/// rotation turns the view left), and ends 1500 units from the wall; the cube drifts 2
/// units a frame.
pub fn default_animation() -> Animation {
    let key = |position, rotation| Camera {
        position,
        rotation,
        h: H,
    };
    Animation {
        frames: 90,
        fps: 30,
        camera: vec![
            key([-300.0, -170.0, -1250.0], [7.0, -8.0, 0.0]),
            key([0.0, -140.0, -300.0], [5.0, 14.0, 0.0]),
            key([250.0, -120.0, 1100.0], [3.0, -12.0, 0.0]),
        ],
        drift: vec![(CUBE, [2.0, 0.0, -0.6])],
    }
}

/// Light mortar between the bricks, far from the background so a seam reads as a crack.
const MORTAR: [u8; 3] = [214, 206, 188];

/// A 32x16 brick (one brick face of the wall): a one-texel mortar border on every side, so
/// two bricks meet in a two-texel mortar joint, around a fired-clay face of four tones
/// scattered by an integer hash (4-bit CLUT).
fn stone() -> Texture {
    let tones = [[150, 62, 44], [136, 54, 40], [164, 74, 52], [122, 48, 36]];
    let pixels: Vec<[u8; 4]> = (0u32..32 * 16)
        .map(|i| {
            let (x, y) = (i % 32, i / 32);
            let c = if x == 0 || x == 31 || y == 0 || y == 15 {
                MORTAR
            } else {
                let h = i.wrapping_mul(0x9E37_79B1).rotate_left(7) ^ i.wrapping_mul(0x85EB_CA77);
                tones[(h >> 29) as usize % tones.len()]
            };
            [c[0], c[1], c[2], 255]
        })
        .collect();
    Texture::from_rgba(32, 16, &pixels, TextureDepth::Clut4)
        .unwrap_or_else(|_| Texture::checker(16, 2, [150, 62, 44], MORTAR))
}

/// A single-sided wall of `bricks` x `rows` brick faces, each 2 x 1 units, laid in running
/// bond (odd rows shifted by half a brick, with half bricks at the ends), in the XY plane
/// facing -Z, standing on Y = 0 and rising towards -Y. Every brick has its own four vertices:
/// the corners of one row's bricks fall in the middle of the next row's edges (T-junctions).
pub fn brick_wall(bricks: u32, rows: u32) -> Mesh {
    let mut mesh = Mesh::default();
    let half_width = f64::from(bricks);
    for row in 0..rows {
        let (top, bottom) = (-f64::from(row + 1), -f64::from(row));
        let mut edges = vec![-half_width];
        let shift = if row % 2 == 1 { 1.0 } else { 0.0 };
        let mut x = -half_width + shift;
        while x < half_width {
            if x > -half_width {
                edges.push(x);
            }
            x += 2.0;
        }
        edges.push(half_width);
        for pair in edges.windows(2) {
            let (left, right) = (pair[0], pair[1]);
            let base = mesh.vertices.len() as u32;
            let u_right = (right - left) / 2.0;
            for (x, y, u, v) in [
                (left, top, 0.0, 0.0),
                (right, top, u_right, 0.0),
                (left, bottom, 0.0, 1.0),
                (right, bottom, u_right, 1.0),
            ] {
                mesh.vertices.push(MeshVertex {
                    position: [x, y, 0.0],
                    normal: [0.0, 0.0, -1.0],
                    uv: [u, v],
                });
            }
            mesh.faces.push(MeshFace {
                indices: [base, base + 1, base + 2, base + 3],
                quad: true,
            });
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Running bond: even rows hold `bricks` whole bricks, odd rows `bricks - 1` whole and
    /// two halves; no vertex is shared; each odd row's inner joints sit at the middle of the
    /// even rows' bricks (a T-junction on every brick edge between rows).
    #[test]
    fn wall_is_running_bond_without_shared_vertices() {
        let m = brick_wall(6, 4);
        assert_eq!(m.faces.len(), 6 + 7 + 6 + 7);
        assert_eq!(m.vertices.len(), 4 * m.faces.len());
        let mut used: Vec<u32> = m.faces.iter().flat_map(|f| f.indices).collect();
        used.sort_unstable();
        used.dedup();
        assert_eq!(used.len(), m.vertices.len());
        let left_edges = |row: usize| -> Vec<f64> {
            m.faces
                .iter()
                .map(|f| m.vertices[f.indices[2] as usize].position)
                .filter(|p| p[1] == -(row as f64))
                .map(|p| p[0])
                .collect()
        };
        assert_eq!(left_edges(0), vec![-6.0, -4.0, -2.0, 0.0, 2.0, 4.0]);
        assert_eq!(left_edges(1), vec![-6.0, -5.0, -3.0, -1.0, 1.0, 3.0, 5.0]);
    }
}
