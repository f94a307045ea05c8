//! The PS1 rendering pipeline, using only the console's mechanisms: GTE transforms (RTPT/RTPS,
//! integer-snapped screen positions), NCLIP back-face culling, whole-polygon clipping,
//! optional GTE lighting (NCCT/NCCS) and depth cueing (NCDT/NCDS, DPCS), AVSZ3/AVSZ4 depth
//! into an ordering table, GP0 packets in a primitive buffer, the ordering-table walk into
//! the GPU, and two display buffers.
//!
//! A frame is a chain of stages, each a function of what the one before produced: the
//! scene's objects, prepared once ([`object`], from `scene::prepared`) -> `gte_stage`
//! (projected polygons, a list of `ProjectedFace`) -> `ot_stage` (their GP0 packets linked
//! into the ordering table) -> `gpu_stage` (the table walked into GP0, the frame
//! displayed). The non-hardware precise path takes the projected polygons straight to the
//! GPU's precise rasterizer in the table's order (`precise`). A traced frame runs the same
//! stages with a recorder (`trace`).

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
mod record;
mod stats;
pub mod tessellate;
#[cfg(test)]
mod tests;
mod trace;
mod upload;
pub mod vram_alloc;

pub use object::{angle, object_transform};
pub use options::{PipelineOptions, UnsupportedKnob};
pub use ot_stage::{MAX_POLYGONS, OT_DEPTH, OT_SHIFT};
pub use stats::{FrameStats, cap_message};
pub use trace::{
    DropCause, FaceFate, FaceRecord, FrameTrace, PacketOrigin, TraceError, TracedPacket,
};

use crate::scene::animation::Animation;
use crate::scene::{Camera, InvalidScene, Scene};
use gpu::gp1::Gp1;
use gpu::{DisplayArea, Gpu, OrderingTable, OtError};
use gpu_stage::FrameEnvironment;
use gte::typed::Geometry;
use gte_stage::{FrameInput, ProjectedFaces, Workspace, gte_stage};
use object::PreparedObject;
use std::fmt;
use std::time::Instant;
use trace::FrameRecorder;
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

/// Renders a scene frame by frame into a GPU's VRAM.
pub struct Renderer {
    scene: Scene,
    options: PipelineOptions,
    /// The scene's objects, prepared.
    objects: Vec<PreparedObject>,
    geometry: Geometry,
    /// The GTE stage's buffers.
    work: Workspace,
    /// The GTE stage's output.
    faces: ProjectedFaces,
    /// The ordering table and its primitive buffer.
    ot: OrderingTable,
    /// The precise path's drawing order (the table's order, without the table).
    precise_order: Vec<u32>,
    gpu: Gpu,
    display: DisplayArea,
    /// Every face through its own RTPT/RTPS, no vertex shared (the tests' reference).
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
        gpu.gp1(Gp1::Reset.word());
        gpu.set_texture_cache(options.texture_cache);
        let placements = upload::upload_textures(&mut gpu, &scene).map_err(RenderError::Vram)?;
        let objects: Vec<PreparedObject> = (0..scene.objects.len())
            .filter_map(|i| {
                PreparedObject::new(
                    &scene,
                    i,
                    &placements,
                    (options.tessellation, options.split_extent),
                )
            })
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
            scene,
            options,
            objects,
            geometry,
            work: Workspace::with_capacity(most_vertices),
            faces: ProjectedFaces::with_capacity(capacity),
            ot,
            precise_order: Vec::new(),
            gpu,
            display,
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
    /// `render_frame(frame)`): the camera on its path, drifting objects at their positions,
    /// each checked as [`Scene::validate`] checks a scene.
    pub fn pose(
        &mut self,
        animation: &Animation,
        base: &Scene,
        frame: u32,
    ) -> Result<(), InvalidScene> {
        self.set_camera(animation.camera_at(&base.camera, frame))?;
        for (i, o) in base.objects.iter().enumerate() {
            if animation.drift.iter().any(|(d, _)| *d == i) {
                self.set_object_position(i, animation.position_at(i, o.position, frame))?;
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
        self.render(frame, None)
    }

    /// Render frame `frame` like [`Renderer::render_frame`] and record what happened to
    /// every polygon and which GP0 packet draws it. The stage times include the tracing.
    /// Only the hardware path can be traced.
    pub fn render_frame_traced(
        &mut self,
        frame: u32,
    ) -> Result<(FrameStats, FrameTrace), TraceError> {
        if self.options.precise() {
            return Err(TraceError::PrecisePath);
        }
        let mut recorder = FrameRecorder::new(&self.gpu);
        let stats = self.render(frame, Some(&mut recorder));
        Ok((stats, recorder.finish()))
    }

    /// The frame's stages in order, each fed what the one before produced.
    fn render(&mut self, frame: u32, mut trace: Option<&mut FrameRecorder>) -> FrameStats {
        let mut stats = FrameStats::default();
        let dither = self.options.dither.unwrap_or(self.scene.screen.dither);
        let t0 = Instant::now();
        let input = FrameInput {
            scene: &self.scene,
            objects: &self.objects,
            options: &self.options,
            frame,
            per_polygon: self.per_polygon,
        };
        gte_stage(
            &input,
            &mut self.geometry,
            &mut self.work,
            &mut self.faces,
            &mut stats,
            trace.as_deref_mut(),
        );
        stats.capped = usize::from(self.faces.faces.len() >= MAX_POLYGONS);
        let t1 = Instant::now();
        let environment = FrameEnvironment::new(&self.scene.screen, frame, dither);
        let t2 = if self.options.precise() {
            stats.drawn = precise::depth_order(&self.faces.faces, &mut self.precise_order);
            let t2 = Instant::now();
            gpu_stage::begin_frame(&mut self.gpu, &environment, None);
            #[cfg(feature = "accuracy-knobs")]
            precise::draw(
                &mut self.gpu,
                (&self.faces.faces, &self.faces.precise),
                &self.precise_order,
                dither,
                self.options.perspective_uv,
            );
            t2
        } else {
            stats.drawn = ot_stage::link(
                &self.faces.faces,
                dither,
                &mut self.ot,
                trace.as_deref_mut(),
            );
            let t2 = Instant::now();
            gpu_stage::begin_frame(&mut self.gpu, &environment, trace.as_deref_mut());
            gpu_stage::walk(&mut self.gpu, &self.ot, trace.as_deref_mut());
            t2
        };
        self.display =
            gpu_stage::show_frame(&mut self.gpu, &environment, &self.scene.screen, trace);
        let t3 = Instant::now();
        stats.gte = t1 - t0;
        stats.ot = t2 - t1;
        stats.gpu = t3 - t2;
        stats
    }
}
