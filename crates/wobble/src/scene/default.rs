//! The built-in default scene: no files needed. A spinning cube with a two-colour
//! checkerboard over a large checkerboard floor seen at a grazing angle, so the affine
//! texture warp along the floor quads' split diagonals is plain to see; 4-bit CLUT textures,
//! one directional light (Gouraud through NCCT/NCCS), dithering on.

use super::mesh::Mesh;
use super::texture::Texture;
use super::{Camera, Light, MeshAsset, Object, Scene, Screen, TextureAsset};

/// The built-in scene.
pub fn default_scene() -> Scene {
    let checker = Texture::checker(64, 8, [232, 232, 224], [200, 40, 48]);
    let floor = Texture::checker(64, 4, [96, 176, 96], [32, 72, 40]);
    Scene {
        screen: Screen::default(),
        accuracy: Default::default(),
        camera: Camera {
            position: [0.0, -300.0, -1500.0],
            rotation: [12.0, 0.0, 0.0],
            h: 300,
        },
        light: Some(Light {
            direction: [0.6, 1.0, 0.8],
            color: [255, 240, 220],
            ambient: [70, 70, 90],
        }),
        fog: None,
        textures: vec![
            TextureAsset {
                name: "checker".into(),
                texture: checker,
            },
            TextureAsset {
                name: "floor".into(),
                texture: floor,
            },
        ],
        meshes: vec![
            MeshAsset {
                name: "cube".into(),
                mesh: Mesh::cube(1.0),
            },
            MeshAsset {
                name: "floor".into(),
                mesh: Mesh::grid(2.0, 6, 6.0),
            },
        ],
        objects: vec![
            Object {
                mesh: 0,
                texture: Some(0),
                position: [0.0, -190.0, -450.0],
                rotation: [20.0, 30.0, 0.0],
                spin: [1.0, 2.0, 0.5],
                scale: 120.0,
                color: [128, 128, 128],
                blend: None,
                tessellation: 0,
            },
            Object {
                mesh: 1,
                texture: Some(1),
                position: [0.0, 0.0, 160.0],
                rotation: [0.0; 3],
                spin: [0.0; 3],
                scale: 1500.0,
                color: [128, 128, 128],
                blend: None,
                tessellation: 0,
            },
        ],
    }
}
