//! Tracing one frame for the inspector (`wobble render --inspect`): what happened to each
//! polygon, and which GP0 packet draws it. Off unless [`Renderer::render_frame_traced`]
//! runs; the normal path only tests an empty `Option`.

use super::gpu_stage::{display_word, frame_environment};
use super::{FrameStats, MAX_POLYGONS, Renderer};
use gpu::Gpu;
use std::time::Instant;

/// Why the GTE stage discards a polygon whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DropCause {
    /// A vertex behind or too near the camera (SZ3 saturated, divide overflow), or a
    /// saturated SX/SY (docs/hardware/gte.md §5, §6).
    NearPlane,
    /// Bigger on screen than the GPU draws: a vertex pair 1024 or more apart in X or 512 in
    /// Y (docs/hardware/gpu.md §3).
    SizeLimit,
}

/// What happened to one polygon (a mesh face, or a piece of one after splitting).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceFate {
    /// Split into pieces by tessellation (they follow, one level deeper).
    Split,
    /// Back face removed by NCLIP.
    Culled,
    /// Dropped whole.
    Dropped(DropCause),
    /// Entirely off screen.
    Offscreen,
    /// The polygon list was full.
    Overflow,
    /// Linked into the ordering table at this slot and drawn.
    Drawn {
        /// OT entry.
        ot_slot: u16,
    },
}

/// One polygon's record in a traced frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FaceRecord {
    /// Index into the scene's objects.
    pub object: usize,
    /// Face index in the object's mesh (faces with invalid vertex indices skipped).
    pub face: usize,
    /// Tessellation level of this piece (0: the face itself).
    pub level: u8,
    /// What happened to it.
    pub fate: FaceFate,
}

/// A traced frame: the faces' fates and the GPU stage's GP0 packets, each tagged with the
/// face it draws.
#[derive(Clone, Debug)]
pub struct FrameTrace {
    /// The GPU before the GPU stage (textures and the previous frame in VRAM).
    pub gpu_before: Gpu,
    /// Every polygon examined, in pipeline order.
    pub faces: Vec<FaceRecord>,
    /// The GP0 packets in the order the GPU received them (environment and background
    /// fill, then the OT walk), each with the index into `faces` of the polygon it draws.
    pub packets: Vec<(Vec<u32>, Option<usize>)>,
    /// The GP1 word that displays the frame.
    pub display_word: u32,
}

/// Per-frame records, kept only while tracing.
#[derive(Clone, Debug, Default)]
pub(super) struct TraceSink {
    pub(super) faces: Vec<FaceRecord>,
    /// Face record of each `scratch` entry.
    pub(super) scratch_face: Vec<usize>,
    /// (OT node index, face record) of each linked packet.
    pub(super) node_face: Vec<(usize, usize)>,
}

impl TraceSink {
    pub(super) fn clear(&mut self) {
        self.faces.clear();
        self.scratch_face.clear();
        self.node_face.clear();
    }
}

impl Renderer {
    /// Render frame `frame` like [`Renderer::render_frame`] and record what happened to
    /// every polygon and which GP0 packet draws it. The stage times include the tracing.
    /// Only the hardware path can be traced.
    pub fn render_frame_traced(&mut self, frame: u32) -> Result<(FrameStats, FrameTrace), String> {
        if self.options.precise() {
            return Err(
                "tracing needs the hardware path: drop --subpixel / --perspective-uv".into(),
            );
        }
        self.trace = Some(Box::default());
        let mut stats = FrameStats::default();
        let t0 = Instant::now();
        self.gte_stage(frame, &mut stats);
        stats.capped = usize::from(self.scratch.len() >= MAX_POLYGONS);
        let t1 = Instant::now();
        self.ot_stage(&mut stats);
        let t2 = Instant::now();
        let sink = self.trace.take().unwrap_or_default();
        let gpu_before = self.gpu.clone();
        let screen = self.scene.screen;
        let buffer_y = (frame % 2) * screen.height as u32;
        let dither = self.options.dither.unwrap_or(screen.dither);
        let env = frame_environment(&screen, buffer_y, dither);
        let mut packets: Vec<(Vec<u32>, Option<usize>)> = Vec::new();
        for w in &env[..6] {
            packets.push((vec![*w], None));
        }
        packets.push((env[6..].to_vec(), None));
        let base = self.ot.ram().as_ptr() as usize;
        let _ = self.ot.walk(|words| {
            // A packet's words follow its node header in the table's RAM image.
            let node = ((words.as_ptr() as usize).saturating_sub(base) / 4).saturating_sub(1);
            let face = sink
                .node_face
                .iter()
                .find(|(n, _)| *n == node)
                .map(|&(_, f)| f);
            packets.push((words.to_vec(), face));
        });
        let t3 = Instant::now();
        self.gpu_stage(frame);
        stats.gte = t1 - t0;
        stats.ot = t2 - t1;
        stats.gpu = Instant::now() - t3;
        let trace = FrameTrace {
            gpu_before,
            faces: sink.faces,
            packets,
            display_word: display_word(buffer_y),
        };
        Ok((stats, trace))
    }
}
