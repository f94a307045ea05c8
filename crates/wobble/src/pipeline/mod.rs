//! The PS1 rendering pipeline, using only the console's mechanisms: GTE transforms (RTPT/RTPS,
//! integer-snapped screen positions), NCLIP back-face culling, whole-polygon clipping,
//! optional GTE lighting (NCCT/NCCS) and depth cueing (NCDT/NCDS, DPCS), AVSZ3/AVSZ4 depth into an ordering table, GP0 packets
//! in a primitive buffer, the DMA walk into the GPU, and two display buffers.
//!
//! One frame runs the stages in order: `gte_stage` (transform each shared vertex once, then
//! cull, clip, light and depth per polygon; splitting polygons as `tessellate` and `clip`
//! decide), `ot_stage` (GP0 packets linked into the ordering table), `gpu_stage` (the OT
//! walk into the GPU, or the precise path).

mod clip;
mod gpu_stage;
mod gte_stage;
mod lighting;
pub mod object;
mod options;
mod ot_stage;
mod polygon;
mod precise;
mod projection;
mod stats;
pub mod tessellate;
#[cfg(test)]
mod tests;
mod trace;
mod upload;
pub mod vram_alloc;

pub use object::{angle, object_transform};
pub use options::{DEFAULT_SPLIT_EXTENT, PipelineOptions, UnsupportedKnob};
pub use ot_stage::{MAX_POLYGONS, OT_DEPTH, OT_SHIFT};
pub use stats::{FrameStats, cap_message};
pub use trace::{DropCause, FaceFate, FaceRecord, FrameTrace};

use crate::scene::animation::Animation;
use crate::scene::{Camera, InvalidScene, Scene};
use gpu::{DisplayArea, Gpu};
use gpu::{OrderingTable, OtError};
use gpu_stage::GP1_RESET;
use gte::typed::Geometry;
use lighting::LitNormal;
use object::PreparedObject;
use polygon::ProjectedFace;
use precise::SubpixelVertex;
use projection::SharedProjection;
use std::fmt;
use std::time::Instant;
use tessellate::SplitStack;
use vram_alloc::VramAllocError;

/// Why a renderer could not be built.
#[derive(Debug)]
pub enum RenderError {
    /// Textures do not fit VRAM.
    Vram(VramAllocError),
    /// The scene is inconsistent.
    Scene(InvalidScene),
    /// An accuracy knob this build does not include (built without `accuracy-knobs`).
    Unsupported(UnsupportedKnob),
    /// The ordering table cannot be built.
    OrderingTable(OtError),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Vram(e) => write!(f, "{e}"),
            RenderError::Scene(e) => write!(f, "{e}"),
            RenderError::Unsupported(e) => write!(f, "{e}"),
            RenderError::OrderingTable(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for RenderError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            RenderError::Vram(e) => Some(e),
            RenderError::Scene(e) => Some(e),
            RenderError::Unsupported(e) => Some(e),
            RenderError::OrderingTable(e) => Some(e),
        }
    }
}

/// An animation that poses a scene out of range at one of its frames.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseError {
    /// The frame.
    pub frame: u32,
    /// What is out of range.
    pub source: InvalidScene,
}

impl fmt::Display for PoseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "animation frame {}: {}", self.frame, self.source)
    }
}

impl std::error::Error for PoseError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

/// Renders a scene frame by frame into a GPU's VRAM.
pub struct Renderer {
    scene: Scene,
    options: PipelineOptions,
    objects: Vec<PreparedObject>,
    gpu: Gpu,
    ot: OrderingTable,
    geometry: Geometry,
    scratch: Vec<ProjectedFace>,
    stack: SplitStack,
    capacity: usize,
    display: DisplayArea,
    /// CLUT cache of the precise path (the GPU's own is private to it).
    /// Sub-pixel positions (without the drawing offset) and 1/SZ of each `scratch` entry,
    /// filled only when the precise path is on, so the hardware path carries none of it.
    precise_vertices: Vec<[SubpixelVertex; 4]>,
    /// Face and packet records of a traced frame; `None` (and untouched) otherwise.
    trace: Option<Box<trace::TraceSink>>,
    /// The current object's vertices after RTPS.
    shared: Vec<SharedProjection>,
    /// The current object's distinct normals, and their colours once lit.
    lit_normals: Vec<LitNormal>,
    /// Every face through its own RTPT/RTPS (the path split faces take), no vertex shared:
    /// the reference the shared-vertex path is tested against.
    per_polygon: bool,
}

impl Renderer {
    /// Prepare a scene: check it, place and upload its textures (GP0 A0h), prepare its
    /// objects (meshes in GTE units, tessellation, texture attributes), size the polygon
    /// list and the ordering table, and turn the GPU's display on.
    pub fn new(scene: Scene, options: PipelineOptions) -> Result<Renderer, RenderError> {
        options.check().map_err(RenderError::Unsupported)?;
        scene.validate().map_err(RenderError::Scene)?;
        let mut gpu = Gpu::new();
        gpu.gp1(GP1_RESET);
        let placements = upload::upload_textures(&mut gpu, &scene).map_err(RenderError::Vram)?;
        let objects: Vec<PreparedObject> = (0..scene.objects.len())
            .filter_map(|i| PreparedObject::new(&scene, i, &placements, options.tessellation))
            .collect();
        let capacity = objects.iter().fold(0, |sum: usize, o| {
            sum.saturating_add(o.most_polygons()).min(MAX_POLYGONS)
        });
        let ot = OrderingTable::new(OT_DEPTH, ot_stage::primitive_words(capacity))
            .map_err(RenderError::OrderingTable)?;
        let display = gpu_stage::start_display(&mut gpu, &scene.screen);
        let mut geometry = Geometry::new();
        geometry
            .set_divide_mode(options.divide_mode)
            .map_err(|e| RenderError::Unsupported(UnsupportedKnob::Divide(e.0)))?;
        let most_vertices = objects
            .iter()
            .map(|o| o.mesh.vertices.len())
            .max()
            .unwrap_or(0);
        Ok(Renderer {
            ot,
            scratch: Vec::with_capacity(capacity),
            stack: SplitStack::default(),
            capacity,
            scene,
            options,
            objects,
            gpu,
            geometry,
            display,
            precise_vertices: Vec::new(),
            trace: None,
            shared: Vec::with_capacity(most_vertices),
            lit_normals: Vec::with_capacity(most_vertices),
            per_polygon: false,
        })
    }

    /// The scene being rendered.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Move the camera (an animation's path); checked as the scene's camera is.
    pub fn set_camera(&mut self, camera: Camera) -> Result<(), InvalidScene> {
        self.scene.validate_camera(&camera)?;
        self.scene.camera = camera;
        Ok(())
    }

    /// Move object `object` (index into the scene's objects) to `position`.
    pub fn set_object_position(
        &mut self,
        object: usize,
        position: [f64; 3],
    ) -> Result<(), InvalidScene> {
        self.scene.validate_position(object, position)?;
        if let Some(o) = self.scene.objects.get_mut(object) {
            o.position = position;
        }
        Ok(())
    }

    /// Pose the renderer, built from `base`, for frame `frame` of `animation` (before
    /// `render_frame(frame)`): the camera on its path, drifting objects at their positions.
    pub fn pose(
        &mut self,
        animation: &Animation,
        base: &Scene,
        frame: u32,
    ) -> Result<(), PoseError> {
        let err = |source| PoseError { frame, source };
        self.set_camera(animation.camera_at(&base.camera, frame))
            .map_err(err)?;
        for (i, o) in base.objects.iter().enumerate() {
            if animation.drift.iter().any(|(d, _)| *d == i) {
                self.set_object_position(i, animation.position_at(i, o.position, frame))
                    .map_err(err)?;
            }
        }
        Ok(())
    }

    /// The GPU (VRAM holds both buffers and the textures).
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The display area of the last frame drawn.
    pub fn display_area(&self) -> DisplayArea {
        self.display
    }

    /// The last frame as an RGB image.
    pub fn image(&self) -> image::RgbImage {
        crate::vram_image::display_image(
            self.gpu.vram().as_slice(),
            self.display,
            crate::vram_image::Expand::Replicate,
        )
    }

    /// Render frame `frame` (objects at their frame-`frame` rotation) into the back buffer
    /// and display it.
    pub fn render_frame(&mut self, frame: u32) -> FrameStats {
        let mut stats = FrameStats::default();
        let t0 = Instant::now();
        self.gte_stage(frame, &mut stats);
        stats.capped = usize::from(self.scratch.len() >= MAX_POLYGONS);
        let t1 = Instant::now();
        self.ot_stage(&mut stats);
        let t2 = Instant::now();
        self.gpu_stage(frame);
        let t3 = Instant::now();
        stats.gte = t1 - t0;
        stats.ot = t2 - t1;
        stats.gpu = t3 - t2;
        stats
    }
}
