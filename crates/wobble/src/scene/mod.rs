//! Scenes: meshes, textures, objects, camera, light and screen, from a TOML file
//! (docs/formats.md, "Scene files") or built in (the default scene), and their validation.

pub mod animation;
pub mod default;
mod file;
pub mod mesh;
pub mod prepared;
pub mod quantize;
pub mod texel;
pub mod texture;

use mesh::{Mesh, MeshError};
use serde::Deserialize;
use std::fmt;
use std::path::PathBuf;
use texture::{InvalidTexture, Texture, TextureError};

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
/// factor IR0 = (DQB + DQA * H/SZ) / 4096 (docs/hardware/gte.md §5 step 7) and NCDT/NCDS or DPCS (docs/hardware/gte.md
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

/// Default split extent of an object ([`Object::split_extent`]): polygons wider or taller than
/// this many pixels are split while their object's tessellation level allows.
pub const DEFAULT_SPLIT_EXTENT: u16 = 64;

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
    /// four before projection (`pipeline/mod.rs`, `pipeline/tessellate.rs`).
    pub tessellation: u8,
    /// A polygon of this object whose screen bounding box is wider or taller than this many
    /// pixels is split, while its tessellation level allows (0: every polygon to the full
    /// level; `u16::MAX`: only polygons that would be dropped whole, the near ones). Default
    /// [`DEFAULT_SPLIT_EXTENT`].
    pub split_extent: u16,
}

impl Object {
    /// The rotation in degrees at `frame`: the frame-0 rotation plus `frame` times the spin.
    pub fn rotation_at(&self, frame: u32) -> [f64; 3] {
        let f = f64::from(frame);
        std::array::from_fn(|i| self.rotation[i] + self.spin[i] * f)
    }
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

/// `[accuracy] divide = "unr" | "exact" | "f32"`.
/// A file named by a scene, for an error message: the path as resolved against the scene
/// file's directory, followed by its absolute form when that differs (the current directory
/// made explicit).
pub(crate) fn file_shown(path: &std::path::Path) -> String {
    match std::path::absolute(path) {
        Ok(abs) if abs != path => format!("{} ({})", path.display(), abs.display()),
        _ => path.display().to_string(),
    }
}

fn divide_mode<'de, D: serde::Deserializer<'de>>(d: D) -> Result<gte::DivideMode, D::Error> {
    let name = <String as Deserialize>::deserialize(d)?;
    match name.as_str() {
        "unr" => Ok(gte::DivideMode::Unr),
        "exact" => Ok(gte::DivideMode::Exact),
        "f32" => Ok(gte::DivideMode::F32),
        _ => Err(serde::de::Error::unknown_variant(
            &name,
            &["unr", "exact", "f32"],
        )),
    }
}

/// Accuracy knobs beyond the hardware (docs/trade.md), from the `[accuracy]` table; all off
/// by default, which is exactly the hardware. Dithering and tessellation, which the hardware
/// has, live in `[screen]` and the objects.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Accuracy {
    /// GTE divide for RTPS/RTPT.
    #[serde(deserialize_with = "divide_mode")]
    pub divide: gte::DivideMode,
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
    /// Reading the scene file failed.
    Io {
        /// The scene file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The TOML is malformed or has a bad field (the message names line and field).
    Syntax {
        /// The scene file.
        file: PathBuf,
        /// The parser's error.
        source: toml::de::Error,
    },
    /// A mesh failed to load or does not fit.
    Mesh(MeshError),
    /// A texture failed to load.
    Texture(TextureError),
    /// A value is out of range or refers to nothing.
    Invalid {
        /// The scene file.
        file: PathBuf,
        /// What is wrong.
        source: InvalidScene,
    },
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneError::Io { file, source } => write!(f, "{}: {source}", file.display()),
            SceneError::Syntax { file, source } => write!(f, "{}: {source}", file.display()),
            SceneError::Mesh(e) => write!(f, "{e}"),
            SceneError::Texture(e) => write!(f, "{e}"),
            SceneError::Invalid { file, source } => write!(f, "{}: {source}", file.display()),
        }
    }
}

impl std::error::Error for SceneError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SceneError::Io { source, .. } => Some(source),
            SceneError::Syntax { source, .. } => Some(source),
            SceneError::Mesh(e) => Some(e),
            SceneError::Texture(e) => Some(e),
            SceneError::Invalid { source, .. } => Some(source),
        }
    }
}

/// A scene value out of range or a reference to nothing. Objects are numbered from 1.
#[derive(Clone, Debug, PartialEq)]
pub enum InvalidScene {
    /// A built-in texture name that does not exist.
    UnknownTextureBuiltin {
        /// The texture's name.
        texture: String,
        /// The built-in asked for.
        builtin: String,
    },
    /// A texture with both or neither of `file` and `builtin`.
    TextureSource {
        /// The texture's name.
        texture: String,
    },
    /// A built-in mesh name that does not exist.
    UnknownMeshBuiltin {
        /// The mesh's name.
        mesh: String,
        /// The built-in asked for.
        builtin: String,
    },
    /// A mesh with both or neither of `file` and `builtin`.
    MeshSource {
        /// The mesh's name.
        mesh: String,
    },
    /// An object names a mesh that does not exist.
    NoMesh {
        /// Object number.
        object: usize,
        /// The name given.
        mesh: String,
    },
    /// An object names a texture that does not exist.
    NoTexture {
        /// Object number.
        object: usize,
        /// The name given.
        texture: String,
    },
    /// A semi-transparency mode above 3.
    BlendMode {
        /// Object number.
        object: usize,
        /// The mode given.
        mode: u8,
    },
    /// `screen.width` is not one of the GPU's horizontal resolutions.
    ScreenWidth(u16),
    /// `screen.height` outside 1..=256.
    ScreenHeight(u16),
    /// `camera.h` is 0.
    CameraH,
    /// The fog range does not fit DQA/DQB.
    Fog {
        /// Near distance.
        near: f64,
        /// Far distance.
        far: f64,
    },
    /// An object's tessellation level above [`MAX_TESSELLATION`].
    Tessellation {
        /// Object number.
        object: usize,
        /// The level given.
        level: u8,
    },
    /// A number outside what its field allows (docs/formats.md, "Limits"); `field` names
    /// it as in the scene file, e.g. `light.direction[0]` or `object 2: scale`.
    Number {
        /// The field.
        field: String,
        /// The value given.
        value: f64,
        /// What the field allows.
        rule: NumberRule,
    },
    /// An object's mesh or texture index is past the lists.
    ObjectIndex {
        /// Object number.
        object: usize,
    },
    /// A texture's fields do not agree.
    Texture {
        /// The texture's name.
        texture: String,
        /// What is wrong.
        source: InvalidTexture,
    },
}

/// What a numeric scene field allows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NumberRule {
    /// Finite and within +-[`MAX_NUMBER`].
    Finite,
    /// Finite, within +-[`MAX_NUMBER`] and above zero.
    Positive,
    /// A direction: every component finite and within +-[`MAX_NUMBER`], and not all of them
    /// below [`MIN_DIRECTION`] in size (the direction must have a length).
    Direction,
}

/// Largest size of any number in a scene (docs/formats.md, "Limits").
pub const MAX_NUMBER: f64 = 1e6;
/// A direction (the light's) needs a component at least this large.
pub const MIN_DIRECTION: f64 = 1e-6;

impl fmt::Display for NumberRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NumberRule::Finite => write!(f, "a finite number within +-1000000"),
            NumberRule::Positive => write!(f, "a finite number above 0 and at most 1000000"),
            NumberRule::Direction => write!(
                f,
                "a direction: finite numbers within +-1000000, not all zero (some component \
                 at least 0.000001 in size)"
            ),
        }
    }
}

/// Check one number against `rule`; `field` names it in the error.
fn check_number(
    field: impl Fn() -> String,
    value: f64,
    rule: NumberRule,
) -> Result<(), InvalidScene> {
    let ok = value.is_finite()
        && value.abs() <= MAX_NUMBER
        && (rule != NumberRule::Positive || value > 0.0);
    if ok {
        Ok(())
    } else {
        Err(InvalidScene::Number {
            field: field(),
            value,
            rule,
        })
    }
}

/// Check every component of `values`; `name` is the field, components are shown as `[i]`.
fn check_numbers(name: &str, values: &[f64], rule: NumberRule) -> Result<(), InvalidScene> {
    let component_rule = match rule {
        NumberRule::Direction => NumberRule::Finite,
        r => r,
    };
    for (i, &v) in values.iter().enumerate() {
        check_number(|| format!("{name}[{i}]"), v, component_rule).map_err(|e| match e {
            InvalidScene::Number { field, value, .. } => {
                InvalidScene::Number { field, value, rule }
            }
            e => e,
        })?;
    }
    if rule == NumberRule::Direction && values.iter().all(|v| v.abs() < MIN_DIRECTION) {
        let value = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        return Err(InvalidScene::Number {
            field: name.to_string(),
            value,
            rule,
        });
    }
    Ok(())
}

impl fmt::Display for InvalidScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InvalidScene::UnknownTextureBuiltin { texture, builtin } => write!(
                f,
                "texture `{texture}`: unknown builtin `{builtin}` (known: checker)"
            ),
            InvalidScene::TextureSource { texture } => write!(
                f,
                "texture `{texture}`: give exactly one of `file` and `builtin`"
            ),
            InvalidScene::UnknownMeshBuiltin { mesh, builtin } => write!(
                f,
                "mesh `{mesh}`: unknown builtin `{builtin}` (known: cube, grid, sphere)"
            ),
            InvalidScene::MeshSource { mesh } => {
                write!(f, "mesh `{mesh}`: give exactly one of `file` and `builtin`")
            }
            InvalidScene::NoMesh { object, mesh } => {
                write!(f, "object {object}: no mesh named `{mesh}`")
            }
            InvalidScene::NoTexture { object, texture } => {
                write!(f, "object {object}: no texture named `{texture}`")
            }
            InvalidScene::BlendMode { object, mode } => write!(
                f,
                "object {object}: semi_transparent must be a mode 0-3, got {mode}"
            ),
            InvalidScene::ScreenWidth(w) => write!(
                f,
                "screen.width must be one of 256, 320, 368, 512, 640, got {w}"
            ),
            InvalidScene::ScreenHeight(h) => write!(
                f,
                "screen.height must be 1..=256 (two buffers share VRAM), got {h}"
            ),
            InvalidScene::CameraH => write!(f, "camera.h must be positive"),
            InvalidScene::Fog { near, far } => write!(
                f,
                "fog: need 1 <= near < far with the range wide enough for DQA (16 bits), got \
                 near = {near}, far = {far}"
            ),
            InvalidScene::Tessellation { object, level } => write!(
                f,
                "object {object}: tessellation must be 0..=4, got {level}"
            ),
            InvalidScene::Number { field, value, rule } => {
                write!(f, "{field} must be {rule}, got {value}")
            }
            InvalidScene::ObjectIndex { object } => {
                write!(f, "object {object}: mesh or texture index out of range")
            }
            InvalidScene::Texture { texture, source } => {
                write!(f, "texture `{texture}`: {source}")
            }
        }
    }
}

impl std::error::Error for InvalidScene {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            InvalidScene::Texture { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// The horizontal resolutions the GPU offers (GP1(08h)).
pub const WIDTHS: [u16; 5] = [256, 320, 368, 512, 640];
/// Largest tessellation level.
pub const MAX_TESSELLATION: u8 = 4;

impl Scene {
    /// Check ranges: screen size, tessellation, camera H, and every number (finite, within
    /// +-1000000; scales positive; the light direction not zero).
    pub fn validate(&self) -> Result<(), InvalidScene> {
        use NumberRule::{Direction, Finite, Positive};
        if !WIDTHS.contains(&self.screen.width) {
            return Err(InvalidScene::ScreenWidth(self.screen.width));
        }
        if self.screen.height == 0 || self.screen.height > 256 {
            return Err(InvalidScene::ScreenHeight(self.screen.height));
        }
        if self.camera.h == 0 {
            return Err(InvalidScene::CameraH);
        }
        check_numbers("camera.position", &self.camera.position, Finite)?;
        check_numbers("camera.rotation", &self.camera.rotation, Finite)?;
        if let Some(light) = &self.light {
            check_numbers("light.direction", &light.direction, Direction)?;
        }
        if let Some(fog) = &self.fog {
            check_number(|| "fog.near".into(), fog.near, Positive)?;
            check_number(|| "fog.far".into(), fog.far, Positive)?;
            if fog.coefficients(self.camera.h).is_none() {
                return Err(InvalidScene::Fog {
                    near: fog.near,
                    far: fog.far,
                });
            }
        }
        for (i, o) in self.objects.iter().enumerate() {
            let object = i + 1;
            if o.tessellation > MAX_TESSELLATION {
                return Err(InvalidScene::Tessellation {
                    object,
                    level: o.tessellation,
                });
            }
            check_numbers(&format!("object {object}: position"), &o.position, Finite)?;
            check_numbers(&format!("object {object}: rotation"), &o.rotation, Finite)?;
            check_numbers(&format!("object {object}: spin"), &o.spin, Finite)?;
            check_number(|| format!("object {object}: scale"), o.scale, Positive)?;
            if o.mesh >= self.meshes.len() || o.texture.is_some_and(|t| t >= self.textures.len()) {
                return Err(InvalidScene::ObjectIndex { object });
            }
        }
        for t in &self.textures {
            t.texture.check().map_err(|source| InvalidScene::Texture {
                texture: t.name.clone(),
                source,
            })?;
        }
        Ok(())
    }

    /// Check a camera as [`Scene::validate`] does (H, finite numbers, the fog range for its
    /// H).
    pub fn validate_camera(&self, camera: &Camera) -> Result<(), InvalidScene> {
        use NumberRule::Finite;
        if camera.h == 0 {
            return Err(InvalidScene::CameraH);
        }
        check_numbers("camera.position", &camera.position, Finite)?;
        check_numbers("camera.rotation", &camera.rotation, Finite)?;
        if let Some(fog) = &self.fog
            && fog.coefficients(camera.h).is_none()
        {
            return Err(InvalidScene::Fog {
                near: fog.near,
                far: fog.far,
            });
        }
        Ok(())
    }

    /// Check an object position as [`Scene::validate`] does; `object` numbered from 0.
    pub fn validate_position(&self, object: usize, position: [f64; 3]) -> Result<(), InvalidScene> {
        if object >= self.objects.len() {
            return Err(InvalidScene::ObjectIndex { object: object + 1 });
        }
        check_numbers(
            &format!("object {}: position", object + 1),
            &position,
            NumberRule::Finite,
        )
    }

    /// The built-in scene (`scene/default.rs`).
    pub fn default_scene() -> Scene {
        default::default_scene()
    }
}
