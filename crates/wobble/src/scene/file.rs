//! Scene files: the TOML schema (docs/formats.md, "Scene files") and its loading into a
//! [`Scene`], with file names resolved against the scene file's directory.

use super::mesh::Mesh;
use super::texture::{Texture, depth_from_bits_per_texel};
use super::{
    Accuracy, Camera, DEFAULT_SPLIT_EXTENT, Fog, InvalidScene, Light, MeshAsset, Object, Scene,
    SceneError, Screen, TextureAsset,
};
use gpu::TextureDepth;
use serde::Deserialize;
use std::path::{Path, PathBuf};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    #[serde(default)]
    screen: Screen,
    #[serde(default)]
    camera: Camera,
    light: Option<Light>,
    fog: Option<Fog>,
    #[serde(default)]
    accuracy: Accuracy,
    #[serde(default)]
    tessellation: u8,
    split_extent: Option<u16>,
    #[serde(default, rename = "texture")]
    textures: Vec<TextureDef>,
    #[serde(default, rename = "mesh")]
    meshes: Vec<MeshDef>,
    #[serde(default, rename = "object")]
    objects: Vec<ObjectDef>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TextureDef {
    name: String,
    /// PNG file, relative to the scene file.
    file: Option<PathBuf>,
    /// Built-in texture: "checker".
    builtin: Option<String>,
    #[serde(default = "default_depth", deserialize_with = "depth")]
    depth: TextureDepth,
}

fn default_depth() -> TextureDepth {
    TextureDepth::Clut4
}

/// `depth = 4 | 8 | 15` (16 taken as 15).
fn depth<'de, D: serde::Deserializer<'de>>(d: D) -> Result<TextureDepth, D::Error> {
    let bits = <u8 as Deserialize>::deserialize(d)?;
    depth_from_bits_per_texel(bits).map_err(serde::de::Error::custom)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MeshDef {
    name: String,
    /// OBJ file, relative to the scene file.
    file: Option<PathBuf>,
    /// Built-in mesh: "cube", "grid", "sphere".
    builtin: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ObjectDef {
    mesh: String,
    texture: Option<String>,
    #[serde(default)]
    position: [f64; 3],
    #[serde(default)]
    rotation: [f64; 3],
    #[serde(default)]
    spin: [f64; 3],
    #[serde(default = "one")]
    scale: f64,
    #[serde(default = "grey")]
    color: [u8; 3],
    semi_transparent: Option<u8>,
    tessellation: Option<u8>,
    split_extent: Option<u16>,
}

fn one() -> f64 {
    1.0
}

fn grey() -> [u8; 3] {
    [128, 128, 128]
}

impl Scene {
    /// Load a TOML scene; relative file names are resolved against its directory.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Io {
            file: path.to_path_buf(),
            source,
        })?;
        let file: SceneFile = toml::from_str(&text).map_err(|source| SceneError::Syntax {
            file: path.to_path_buf(),
            source,
        })?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let invalid = |source: InvalidScene| SceneError::Invalid {
            file: path.to_path_buf(),
            source,
        };
        let mut textures = Vec::new();
        for t in &file.textures {
            let texture = match (&t.file, &t.builtin) {
                (Some(f), None) => {
                    Texture::load_png(&dir.join(f), t.depth).map_err(SceneError::Texture)?
                }
                (None, Some(b)) if b == "checker" => {
                    Texture::checker(64, 8, [232, 232, 224], [200, 40, 48])
                }
                (None, Some(b)) => {
                    return Err(invalid(InvalidScene::UnknownTextureBuiltin {
                        texture: t.name.clone(),
                        builtin: b.clone(),
                    }));
                }
                _ => {
                    return Err(invalid(InvalidScene::TextureSource {
                        texture: t.name.clone(),
                    }));
                }
            };
            textures.push(TextureAsset {
                name: t.name.clone(),
                texture,
            });
        }
        let mut meshes = Vec::new();
        for m in &file.meshes {
            let mesh = match (&m.file, &m.builtin) {
                (Some(f), None) => Mesh::load_obj(&dir.join(f)).map_err(SceneError::Mesh)?,
                (None, Some(b)) => match b.as_str() {
                    "cube" => Mesh::cube(1.0),
                    "grid" => Mesh::grid(2.0, 8, 4.0),
                    "sphere" => Mesh::sphere(1.0, 16, 24),
                    _ => {
                        return Err(invalid(InvalidScene::UnknownMeshBuiltin {
                            mesh: m.name.clone(),
                            builtin: b.clone(),
                        }));
                    }
                },
                _ => {
                    return Err(invalid(InvalidScene::MeshSource {
                        mesh: m.name.clone(),
                    }));
                }
            };
            meshes.push(MeshAsset {
                name: m.name.clone(),
                mesh,
            });
        }
        let mut objects = Vec::new();
        for (i, o) in file.objects.iter().enumerate() {
            let mesh = meshes
                .iter()
                .position(|m| m.name == o.mesh)
                .ok_or_else(|| {
                    invalid(InvalidScene::NoMesh {
                        object: i + 1,
                        mesh: o.mesh.clone(),
                    })
                })?;
            let texture = match &o.texture {
                None => None,
                Some(name) => Some(textures.iter().position(|t| &t.name == name).ok_or_else(
                    || {
                        invalid(InvalidScene::NoTexture {
                            object: i + 1,
                            texture: name.clone(),
                        })
                    },
                )?),
            };
            super::check_number(
                || format!("object {}: scale", i + 1),
                o.scale,
                super::NumberRule::Positive,
            )
            .map_err(invalid)?;
            meshes[mesh]
                .mesh
                .check_scale(&format!("object {} (mesh `{}`)", i + 1, o.mesh), o.scale)
                .map_err(SceneError::Mesh)?;
            if let Some(b) = o.semi_transparent
                && b > 3
            {
                return Err(invalid(InvalidScene::BlendMode {
                    object: i + 1,
                    mode: b,
                }));
            }
            objects.push(Object {
                mesh,
                texture,
                position: o.position,
                rotation: o.rotation,
                spin: o.spin,
                scale: o.scale,
                color: o.color,
                blend: o.semi_transparent,
                tessellation: o.tessellation.unwrap_or(file.tessellation),
                split_extent: o
                    .split_extent
                    .or(file.split_extent)
                    .unwrap_or(DEFAULT_SPLIT_EXTENT),
            });
        }
        let scene = Scene {
            screen: file.screen,
            camera: file.camera,
            light: file.light,
            fog: file.fog,
            accuracy: file.accuracy,
            textures,
            meshes,
            objects,
        };
        scene.validate().map_err(invalid)?;
        Ok(scene)
    }
}
