//! Tracing one frame for the inspector (`wobble render --inspect`): what happened to each
//! polygon, and which GP0 packet draws it. The stages take an optional recorder
//! ([`FrameRecorder`]) and run the same way with or without it; without it, they only test
//! an empty `Option`.

use gpu::Gpu;
use std::fmt;

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

/// Which stage put a packet into the frame, and for which polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PacketOrigin {
    /// The frame's set-up in the back buffer: a drawing-environment word (E1h-E6h) or the
    /// fill with the background colour.
    Environment,
    /// The polygon of this face record (an index into [`FrameTrace::faces`]).
    Face(usize),
    /// The draw-mode word (E1h) carrying the blend mode of the polygon of this face record,
    /// which comes next (an untextured polygon has no texpage attribute to carry it).
    BlendMode(usize),
}

/// One GP0 packet of a traced frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TracedPacket {
    /// Its words.
    pub words: Vec<u32>,
    /// Where it comes from; `None` for a packet the frame's stages did not link (none is).
    pub origin: Option<PacketOrigin>,
}

/// A traced frame: the faces' fates and the GPU stage's GP0 packets, each tagged with where
/// it comes from.
#[derive(Clone, Debug)]
pub struct FrameTrace {
    /// The GPU before the frame (textures and the previous frame in VRAM).
    pub gpu_before: Gpu,
    /// Every polygon examined, in pipeline order.
    pub faces: Vec<FaceRecord>,
    /// The GP0 packets in the order the GPU received them (environment and background
    /// fill, then the OT walk).
    pub packets: Vec<TracedPacket>,
    /// The GP1 word that displays the frame.
    pub display_word: u32,
}

/// Why a frame cannot be traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TraceError {
    /// The precise path draws outside GP0, so its packets cannot be replayed.
    PrecisePath,
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TraceError::PrecisePath => write!(
                f,
                "tracing needs the hardware path: drop --subpixel / --perspective-uv"
            ),
        }
    }
}

impl std::error::Error for TraceError {}

/// Records one frame as its stages run: each polygon's fate (GTE stage), the node and
/// origin of each linked packet (OT stage), then the packets as the GPU receives them (GPU
/// stage).
#[derive(Debug)]
pub(super) struct FrameRecorder {
    gpu_before: Gpu,
    faces: Vec<FaceRecord>,
    /// The face record of each polygon the GTE stage emitted, in its order.
    emitted: Vec<usize>,
    /// (OT node index, origin) of each linked packet, in the order linked, which is the
    /// nodes' order in the primitive buffer.
    nodes: Vec<(usize, PacketOrigin)>,
    packets: Vec<TracedPacket>,
    display_word: u32,
}

impl FrameRecorder {
    /// A recorder for a frame drawn on `gpu` as it is now.
    pub(super) fn new(gpu: &Gpu) -> Self {
        Self {
            gpu_before: gpu.clone(),
            faces: Vec::new(),
            emitted: Vec::new(),
            nodes: Vec::new(),
            packets: Vec::new(),
            display_word: 0,
        }
    }

    /// The GTE stage examined a polygon; a drawn one was emitted, after those before it.
    pub(super) fn face(&mut self, record: FaceRecord) {
        if matches!(record.fate, FaceFate::Drawn { .. }) {
            self.emitted.push(self.faces.len());
        }
        self.faces.push(record);
    }

    /// The OT stage links a packet at node `node` for emitted polygon `polygon`: the
    /// polygon itself, or (`blend_mode`) the draw-mode word before it.
    pub(super) fn linked(&mut self, node: usize, polygon: usize, blend_mode: bool) {
        if let Some(&record) = self.emitted.get(polygon) {
            let origin = if blend_mode {
                PacketOrigin::BlendMode(record)
            } else {
                PacketOrigin::Face(record)
            };
            self.nodes.push((node, origin));
        }
    }

    /// The GPU stage sends a packet of its own (`Environment`).
    pub(super) fn sent(&mut self, words: &[u32], origin: PacketOrigin) {
        self.packets.push(TracedPacket {
            words: words.to_vec(),
            origin: Some(origin),
        });
    }

    /// The OT walk hands the GPU the packet of node `node`.
    pub(super) fn walked(&mut self, node: usize, words: &[u32]) {
        let origin = self
            .nodes
            .binary_search_by_key(&node, |&(n, _)| n)
            .ok()
            .and_then(|i| self.nodes.get(i))
            .map(|&(_, origin)| origin);
        self.packets.push(TracedPacket {
            words: words.to_vec(),
            origin,
        });
    }

    /// The GPU stage displays the frame with GP1 word `word`.
    pub(super) fn displayed(&mut self, word: u32) {
        self.display_word = word;
    }

    pub(super) fn finish(self) -> FrameTrace {
        FrameTrace {
            gpu_before: self.gpu_before,
            faces: self.faces,
            packets: self.packets,
            display_word: self.display_word,
        }
    }
}
