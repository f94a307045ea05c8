//! Scenes: meshes, textures, objects, camera, light and screen, from a TOML file
//! (docs/formats.md, "Scene files") or built in (the default scene).

use crate::mesh::{Mesh, MeshError};
use crate::quantize::{Depth, Texture, TextureError};
use serde::Deserialize;
use std::fmt;
use std::path::{Path, PathBuf};

/// Screen set-up.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Screen {
    /// Width: 256, 320, 368, 512 or 640 (the hardware's horizontal resolutions).
    pub width: u16,
    /// Height: 1..=256 (two buffers are stacked in VRAM).
    pub height: u16,
    /// Dithering (E1 bit 9).
    pub dither: bool,
    /// Background colour.
    pub background: [u8; 3],
}

impl Default for Screen {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            dither: true,
            background: [24, 24, 40],
        }
    }
}

/// Camera: position in world units, orientation in degrees (X pitch, then Y yaw, then Z
/// roll), projection distance H.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    /// World position.
    pub position: [f64; 3],
    /// Rotation in degrees.
    pub rotation: [f64; 3],
    /// Projection plane distance H (focal length in pixels).
    pub h: u16,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: [0.0, 0.0, -1000.0],
            rotation: [0.0; 3],
            h: 300,
        }
    }
}

/// A directional light with an ambient colour.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Light {
    /// Direction the light travels, in world space.
    pub direction: [f64; 3],
    /// Light colour.
    pub color: [u8; 3],
    /// Ambient (background) colour.
    pub ambient: [u8; 3],
}

impl Default for Light {
    fn default() -> Self {
        Self {
            direction: [0.5, 1.0, 0.7],
            color: [255, 255, 255],
            ambient: [80, 80, 80],
        }
    }
}

/// Depth cueing (fog): colours fade towards `color` with depth, through the GTE's depth-cue
/// factor IR0 = (DQB + DQA * H/SZ) / 4096 (gte.md §5 step 7) and NCDT/NCDS or DPCS (gte.md
/// §8). IR0 is linear in 1/SZ, so the fade runs from nothing at SZ = `near` to all fog at
/// SZ = `far` and beyond.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Fog {
    /// Far colour (FC).
    pub color: [u8; 3],
    /// Camera-space depth where the fade starts.
    pub near: f64,
    /// Camera-space depth where everything is `color`.
    pub far: f64,
}

impl Default for Fog {
    fn default() -> Self {
        Self {
            color: [0, 0, 0],
            near: 1000.0,
            far: 8000.0,
        }
    }
}

impl Fog {
    /// DQA (s16) and DQB (s32) for projection distance `h`: with q = H * 10000h / SZ,
    /// IR0 * 4096 = DQA * q + DQB must be 0 at SZ = near and 4096 * 4096 at SZ = far, so
    /// DQA = -K / (16 H) and DQB = 4096 K / near with K = 4096 near far / (far - near).
    /// `None` when the range does not fit the registers.
    pub fn coefficients(&self, h: u16) -> Option<(i16, i32)> {
        let (near, far) = (self.near, self.far);
        if !(near.is_finite() && far.is_finite() && near >= 1.0 && far > near) || h == 0 {
            return None;
        }
        let k = 4096.0 * near * far / (far - near);
        let dqa = (-k / (16.0 * f64::from(h))).round();
        let dqb = (4096.0 * k / near).round();
        let fits = |v: f64, lo: f64, hi: f64| v >= lo && v <= hi;
        (fits(dqa, -32768.0, 32767.0) && fits(dqb, i32::MIN as f64, i32::MAX as f64))
            .then_some((dqa as i16, dqb as i32))
    }
}

/// A scene object: a mesh instance with a transform and material.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    /// Index into [`Scene::meshes`].
    pub mesh: usize,
    /// Index into [`Scene::textures`]; untextured (Gouraud/flat) when `None`.
    pub texture: Option<usize>,
    /// World position.
    pub position: [f64; 3],
    /// Rotation in degrees at frame 0.
    pub rotation: [f64; 3],
    /// Rotation added per frame, degrees.
    pub spin: [f64; 3],
    /// Scale from mesh units to GTE units.
    pub scale: f64,
    /// Material colour (modulates the texture; 128 = unchanged).
    pub color: [u8; 3],
    /// Semi-transparency mode 0-3, when semi-transparent.
    pub blend: Option<u8>,
    /// Tessellation level 0..=4: how many times a large or near polygon may be split into
    /// four before projection (`pipeline.rs`, `tessellate.rs`).
    pub tessellation: u8,
}

/// A named texture.
#[derive(Clone, Debug, PartialEq)]
pub struct TextureAsset {
    /// Name used by objects.
    pub name: String,
    /// The prepared texture.
    pub texture: Texture,
}

/// A named mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAsset {
    /// Name used by objects.
    pub name: String,
    /// The mesh.
    pub mesh: Mesh,
}

/// The GTE divide a scene asks for (`[accuracy] divide`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum Divide {
    /// The console's UNR divide.
    #[default]
    Unr,
    /// Exact rounded division (non-hardware).
    Exact,
    /// f32 division (non-hardware).
    F32,
}

impl From<Divide> for gte::DivideMode {
    fn from(d: Divide) -> gte::DivideMode {
        match d {
            Divide::Unr => gte::DivideMode::Unr,
            Divide::Exact => gte::DivideMode::Exact,
            Divide::F32 => gte::DivideMode::F32,
        }
    }
}

/// Accuracy knobs beyond the hardware (docs/trade.md), from the `[accuracy]` table; all off
/// by default, which is exactly the hardware. Dithering and tessellation, which the hardware
/// has, live in `[screen]` and the objects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Accuracy {
    /// GTE divide for RTPS/RTPT.
    pub divide: Divide,
    /// Keep 1/16-pixel screen positions instead of whole pixels.
    pub subpixel: bool,
    /// Perspective-correct texture coordinates instead of affine ones.
    pub perspective_uv: bool,
}

/// A complete scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Screen.
    pub screen: Screen,
    /// Camera.
    pub camera: Camera,
    /// Light; unlit objects use their colour as is.
    pub light: Option<Light>,
    /// Depth cueing; none when `None`.
    pub fog: Option<Fog>,
    /// Non-hardware accuracy knobs (all off: the hardware).
    pub accuracy: Accuracy,
    /// Textures.
    pub textures: Vec<TextureAsset>,
    /// Meshes.
    pub meshes: Vec<MeshAsset>,
    /// Objects.
    pub objects: Vec<Object>,
}

/// Why a scene could not be loaded.
#[derive(Debug)]
pub enum SceneError {
    /// Reading a file failed.
    Io(PathBuf, std::io::Error),
    /// The TOML is malformed or has a bad field (the message names line and field).
    Syntax(PathBuf, String),
    /// A mesh failed to load or does not fit.
    Mesh(MeshError),
    /// A texture failed to load.
    Texture(TextureError),
    /// A value is out of range or refers to nothing.
    Invalid(PathBuf, String),
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Io(p, e) => write!(f, "{}: {e}", p.display()),
            SceneError::Syntax(p, e) => write!(f, "{}: {e}", p.display()),
            SceneError::Mesh(e) => write!(f, "{e}"),
            SceneError::Texture(e) => write!(f, "{e}"),
            SceneError::Invalid(p, e) => write!(f, "{}: {e}", p.display()),
        }
    }
}

impl std::error::Error for SceneError {}

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
    #[serde(default = "default_depth")]
    depth: Depth,
}

fn default_depth() -> Depth {
    Depth::Clut4
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
}

fn one() -> f64 {
    1.0
}

fn grey() -> [u8; 3] {
    [128, 128, 128]
}

/// The horizontal resolutions the GPU offers (GP1(08h)).
pub const WIDTHS: [u16; 5] = [256, 320, 368, 512, 640];
/// Largest tessellation level.
pub const MAX_TESSELLATION: u8 = 4;

impl Scene {
    /// Load a TOML scene; relative file names are resolved against its directory.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let text =
            std::fs::read_to_string(path).map_err(|e| SceneError::Io(path.to_path_buf(), e))?;
        let file: SceneFile = toml::from_str(&text)
            .map_err(|e| SceneError::Syntax(path.to_path_buf(), e.to_string()))?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let invalid = |m: String| SceneError::Invalid(path.to_path_buf(), m);
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
                    return Err(invalid(format!(
                        "texture `{}`: unknown builtin `{b}` (known: checker)",
                        t.name
                    )));
                }
                _ => {
                    return Err(invalid(format!(
                        "texture `{}`: give exactly one of `file` and `builtin`",
                        t.name
                    )));
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
                        return Err(invalid(format!(
                            "mesh `{}`: unknown builtin `{b}` (known: cube, grid, sphere)",
                            m.name
                        )));
                    }
                },
                _ => {
                    return Err(invalid(format!(
                        "mesh `{}`: give exactly one of `file` and `builtin`",
                        m.name
                    )));
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
                .ok_or_else(|| invalid(format!("object {}: no mesh named `{}`", i + 1, o.mesh)))?;
            let texture = match &o.texture {
                None => None,
                Some(name) => Some(textures.iter().position(|t| &t.name == name).ok_or_else(
                    || invalid(format!("object {}: no texture named `{name}`", i + 1)),
                )?),
            };
            meshes[mesh]
                .mesh
                .check_scale(&format!("object {} (mesh `{}`)", i + 1, o.mesh), o.scale)
                .map_err(SceneError::Mesh)?;
            if let Some(b) = o.semi_transparent
                && b > 3
            {
                return Err(invalid(format!(
                    "object {}: semi_transparent must be a mode 0-3, got {b}",
                    i + 1
                )));
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

    /// Check ranges: screen size, tessellation, camera H, finite numbers.
    pub fn validate(&self) -> Result<(), String> {
        if !WIDTHS.contains(&self.screen.width) {
            return Err(format!(
                "screen.width must be one of 256, 320, 368, 512, 640, got {}",
                self.screen.width
            ));
        }
        if self.screen.height == 0 || self.screen.height > 256 {
            return Err(format!(
                "screen.height must be 1..=256 (two buffers share VRAM), got {}",
                self.screen.height
            ));
        }
        if self.camera.h == 0 {
            return Err("camera.h must be positive".into());
        }
        if let Some(fog) = &self.fog
            && fog.coefficients(self.camera.h).is_none()
        {
            return Err(format!(
                "fog: need 1 <= near < far with the range wide enough for DQA (16 bits), got \
                 near = {}, far = {}",
                fog.near, fog.far
            ));
        }
        for (i, o) in self.objects.iter().enumerate() {
            if o.tessellation > MAX_TESSELLATION {
                return Err(format!(
                    "object {}: tessellation must be 0..=4, got {}",
                    i + 1,
                    o.tessellation
                ));
            }
            let numbers = o.position.iter().chain(&o.rotation).chain(&o.spin);
            if numbers.clone().any(|v| !v.is_finite()) {
                return Err(format!("object {}: numbers must be finite", i + 1));
            }
            if o.position.iter().any(|v| v.abs() > 1e6) {
                return Err(format!("object {}: position beyond +-1000000 units", i + 1));
            }
            if o.mesh >= self.meshes.len() || o.texture.is_some_and(|t| t >= self.textures.len()) {
                return Err(format!(
                    "object {}: mesh or texture index out of range",
                    i + 1
                ));
            }
        }
        for t in &self.textures {
            t.texture
                .check()
                .map_err(|e| format!("texture `{}`: {e}", t.name))?;
        }
        let cam = self.camera.position.iter().chain(&self.camera.rotation);
        if cam.clone().any(|v| !v.is_finite() || v.abs() > 1e6) {
            return Err("camera: numbers must be finite and within +-1000000".into());
        }
        Ok(())
    }

    /// The built-in scene (`default_scene.rs`).
    pub fn default_scene() -> Scene {
        crate::default_scene::default_scene()
    }
}
