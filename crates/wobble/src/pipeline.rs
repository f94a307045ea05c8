//! The PS1 rendering pipeline, using only the console's mechanisms: GTE transforms (RTPT/RTPS,
//! integer-snapped screen positions), NCLIP back-face culling, whole-polygon clipping,
//! optional GTE lighting (NCCT/NCCS) and depth cueing (NCDT/NCDS, DPCS), AVSZ3/AVSZ4 depth into an ordering table, GP0 packets
//! in a primitive buffer, the DMA walk into the GPU, and two display buffers.

use crate::quantize::Depth;
use crate::scene::Scene;
use crate::tessellate::{MAX_LEVEL, PreparedFace, PreparedVertex, SplitStack, UV_FRACTION_BITS};
use crate::vram_alloc::{Placement, VramAllocator, VramFull};
use gpu::ordering_table::OrderingTable;
use gpu::rasterizer::precise::{PreciseVertex, SUBPIXEL_BITS};
use gpu::texture::ClutCache;
use gpu::{DisplayArea, Gpu};
use gte::typed::{Geometry, I4F12, I8F8, I8F24, I16F16, Matrix, Projection, Translation, Vector3};
use gte::{DivideMode, Flag};
use std::fmt;
use std::time::{Duration, Instant};

/// Ordering-table entries.
pub const OT_DEPTH: usize = 2048;
/// OTZ to OT index: OTZ (the mean SZ) >> this.
pub const OT_SHIFT: u32 = 3;

/// Most polygons one frame can draw: sizes the scratch list and the primitive buffer (13
/// words a polygon, 6.8 MB, inside the console's 8 MB address range the OT links can reach).
pub const MAX_POLYGONS: usize = 1 << 17;

/// Default [`PipelineOptions::split_extent`]: polygons wider or taller than this many pixels
/// are split while their object's tessellation level allows.
pub const DEFAULT_SPLIT_EXTENT: u16 = 64;

/// Knobs, all defaulting to what the scene says and to hardware behaviour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PipelineOptions {
    /// Override every object's tessellation level (0..=4).
    pub tessellation: Option<u8>,
    /// A polygon whose screen bounding box is wider or taller than this many pixels is split
    /// (up to its object's tessellation level); 0 splits every polygon to the full level.
    pub split_extent: u16,
    /// Override the scene's dithering.
    pub dither: Option<bool>,
    /// GTE divide (hardware UNR by default).
    pub divide_mode: DivideMode,
    /// Non-hardware: keep 4 fractional bits of each screen position (the GTE's 16.16 result
    /// before its truncation to whole pixels) and rasterize with the precise path.
    pub subpixel: bool,
    /// Non-hardware: perspective-correct texture coordinates (the precise path with 1/SZ
    /// per vertex) instead of the GPU's affine stepping.
    pub perspective_uv: bool,
}

impl PipelineOptions {
    /// Whether polygons go through the non-hardware precise rasterizer (never, when built
    /// without the `accuracy-knobs` feature).
    pub fn precise(&self) -> bool {
        cfg!(feature = "accuracy-knobs") && (self.subpixel || self.perspective_uv)
    }
}

impl Default for PipelineOptions {
    fn default() -> Self {
        Self {
            tessellation: None,
            split_extent: DEFAULT_SPLIT_EXTENT,
            dither: None,
            divide_mode: DivideMode::default(),
            subpixel: false,
            perspective_uv: false,
        }
    }
}

/// Why a renderer could not be built.
#[derive(Debug)]
pub enum PipelineError {
    /// Textures do not fit VRAM.
    Vram(VramFull),
    /// The scene is inconsistent.
    Scene(String),
}

impl fmt::Display for PipelineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PipelineError::Vram(e) => write!(f, "{e}"),
            PipelineError::Scene(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for PipelineError {}

/// What one frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Polygons examined after splitting: each ends drawn, culled, off screen or dropped.
    pub polygons: usize,
    /// Polygons linked into the ordering table and drawn.
    pub drawn: usize,
    /// Back faces removed by NCLIP.
    pub culled: usize,
    /// Polygons entirely off screen.
    pub offscreen: usize,
    /// Polygons dropped whole: a vertex behind the near plane (SZ3 or divide overflow flag),
    /// a saturated SX/SY, or an extent the GPU would drop.
    pub dropped: usize,
    /// Time in GTE work (transform, project, cull, light, AVSZ).
    pub gte: Duration,
    /// Time building packets and linking them into the ordering table.
    pub ot: Duration,
    /// Time in the GPU (environment, OT walk, rasterization).
    pub gpu: Duration,
}

impl FrameStats {
    /// Add another frame's counts and times.
    pub fn accumulate(&mut self, other: &FrameStats) {
        self.polygons += other.polygons;
        self.drawn += other.drawn;
        self.culled += other.culled;
        self.offscreen += other.offscreen;
        self.dropped += other.dropped;
        self.gte += other.gte;
        self.ot += other.ot;
        self.gpu += other.gpu;
    }
}

/// An object ready to draw: faces in GTE units with texel coordinates.
#[derive(Clone, Debug)]
struct PreparedObject {
    faces: Vec<PreparedFace>,
    level: u8,
    texture: Option<(Placement, u32)>,
}

/// A polygon after the GTE stage, waiting for its packet.
#[derive(Clone, Copy, Debug, Default)]
struct ProjectedFace {
    xy: [(i16, i16); 4],
    color: [[u8; 3]; 4],
    uv: [(u8, u8); 4],
    quad: bool,
    ot_index: u16,
    texture: Option<(u32, u32)>,
    blend: Option<u8>,
}

/// FLAG bits that discard a polygon whole: SZ3 saturated (a vertex behind the camera, SZ
/// clamped to 0), divide overflow (SZ3 <= H/2, too near), SX2/SY2 saturated (gte.md §3,
/// §5 steps 4 and 6, §6).
const DROP_FLAGS: Flag = Flag::DIVIDE_OVERFLOW
    .union(Flag::SX2_SATURATED)
    .union(Flag::SY2_SATURATED)
    .union(Flag::SZ3_OTZ_SATURATED);

/// Degrees to 1/4096 turn.
pub fn angle(deg: f64) -> i32 {
    (deg.rem_euclid(360.0) * 4096.0 / 360.0).round() as i32
}

fn to_fixed(v: f64) -> i16 {
    (v * 4096.0).round().clamp(-32768.0, 32767.0) as i16
}

fn to_i16(v: f64) -> i16 {
    v.round().clamp(-32768.0, 32767.0) as i16
}

fn vector(p: [f64; 3]) -> Vector3 {
    Vector3 {
        x: to_i16(p[0]),
        y: to_i16(p[1]),
        z: to_i16(p[2]),
    }
}

fn normal(n: [f64; 3]) -> Vector3 {
    Vector3 {
        x: to_fixed(n[0]),
        y: to_fixed(n[1]),
        z: to_fixed(n[2]),
    }
}

/// Apply a 1.3.12 matrix to a vector in f64 (CPU-side set-up only).
fn apply(m: &Matrix, v: [f64; 3]) -> [f64; 3] {
    let b = m.to_bits();
    let row = |r: usize| (0..3).map(|c| b[r][c] as f64 * v[c]).sum::<f64>() / 4096.0;
    [row(0), row(1), row(2)]
}

/// Prepare an object's faces for the GTE: positions scaled and rounded to 16-bit vertices,
/// normals in 1.3.12, per-face texel coordinates (each face's texture coordinates shifted by
/// whole texture repeats to start in the first repeat, then scaled to 0..size-1 texels and
/// clamped to 255) in 8.8 fixed point.
pub fn prepare(scene: &Scene, index: usize) -> Vec<PreparedFace> {
    let Some(o) = scene.objects.get(index) else {
        return Vec::new();
    };
    let Some(mesh) = scene.meshes.get(o.mesh).map(|m| &m.mesh) else {
        return Vec::new();
    };
    let size = o
        .texture
        .and_then(|t| scene.textures.get(t))
        .map_or((1.0, 1.0), |t| {
            (t.texture.width as f64 - 1.0, t.texture.height as f64 - 1.0)
        });
    let uv_scale = f64::from(1u32 << UV_FRACTION_BITS);
    let mut faces = Vec::with_capacity(mesh.faces.len());
    for f in &mesh.faces {
        let count = if f.quad { 4 } else { 3 };
        let mut vs = [None; 4];
        for (slot, &i) in vs.iter_mut().zip(&f.indices).take(count) {
            *slot = mesh.vertices.get(i as usize);
        }
        if vs.iter().take(count).any(Option::is_none) {
            continue;
        }
        let vs = vs.iter().take(count).flatten();
        let min_u = vs
            .clone()
            .map(|v| v.uv[0])
            .fold(f64::INFINITY, f64::min)
            .floor();
        let min_v = vs
            .clone()
            .map(|v| v.uv[1])
            .fold(f64::INFINITY, f64::min)
            .floor();
        let mut face = PreparedFace {
            quad: f.quad,
            ..Default::default()
        };
        for (slot, v) in face.v.iter_mut().zip(vs) {
            let texel = |c: f64, min: f64, size: f64| {
                (((c - min) * size).clamp(0.0, 255.0) * uv_scale).round() as u16
            };
            *slot = PreparedVertex {
                position: vector(v.position.map(|c| c * o.scale)),
                normal: normal(v.normal),
                uv: [texel(v.uv[0], min_u, size.0), texel(v.uv[1], min_v, size.1)],
            };
        }
        faces.push(face);
    }
    faces
}

/// What the GTE stage decides for one polygon.
#[derive(Clone, Copy, Debug)]
enum Verdict {
    /// Discarded whole: a vertex behind or too near the camera (SZ3 saturated, divide
    /// overflow), a saturated SX/SY, or a size the GPU would drop (gpu.md §3).
    Drop(DropCause),
    /// Back face: NCLIP <= 0, the first three vertices not clockwise on screen (gte.md §7).
    Cull,
    /// Entirely outside the screen.
    Offscreen,
    /// To be drawn: screen positions, screen Z and the larger side of its bounding box.
    Draw {
        xy: [(i16, i16); 4],
        sz: [u16; 4],
        ir0: I4F12,
        extent: i32,
    },
}

/// Why the GTE stage discards a polygon whole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DropCause {
    /// A vertex behind or too near the camera (SZ3 saturated, divide overflow), or a
    /// saturated SX/SY (gte.md §5, §6).
    NearPlane,
    /// Bigger on screen than the GPU draws: a vertex pair 1024 or more apart in X or 512 in
    /// Y (gpu.md §3).
    SizeLimit,
}

/// What happened to one polygon (a mesh face, or a piece of one after splitting) in a
/// traced frame ([`Renderer::render_frame_traced`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceFate {
    /// Split into four by tessellation (its pieces follow with the next level).
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

/// A traced frame: the faces' fates and the GP0 packets of the GPU stage, each tagged with
/// the face it draws.
#[derive(Clone, Debug)]
pub struct FrameTrace {
    /// The GPU as it was before the GPU stage (textures and the previous frame in VRAM).
    pub gpu_before: Gpu,
    /// Every polygon examined, in pipeline order.
    pub faces: Vec<FaceRecord>,
    /// The GP0 packets in the order the GPU received them (environment and fill, then the
    /// OT walk); for each, the index into `faces` of the polygon it draws, if any.
    pub packets: Vec<(Vec<u32>, Option<usize>)>,
    /// The GP1 word that displays the frame.
    pub display_word: u32,
}

/// Per-frame trace state, kept only while tracing.
#[derive(Clone, Debug, Default)]
struct TraceSink {
    faces: Vec<FaceRecord>,
    /// Face record of each `scratch` entry.
    scratch_face: Vec<usize>,
    /// (OT node index, face record) of each linked packet.
    node_face: Vec<(usize, usize)>,
}

/// Screen bounding box (min x, max x, min y, max y) of some vertices.
fn bounds(points: &[(i16, i16)]) -> (i32, i32, i32, i32) {
    points.iter().fold(
        (i32::MAX, i32::MIN, i32::MAX, i32::MIN),
        |(x0, x1, y0, y1), &(x, y)| {
            let (x, y) = (i32::from(x), i32::from(y));
            (x0.min(x), x1.max(x), y0.min(y), y1.max(y))
        },
    )
}

/// The GPU drops a triangle with any vertex pair |dx| >= 1024 or |dy| >= 512 (gpu.md §3).
fn gpu_drops(triangle: &[(i16, i16)]) -> bool {
    let (x0, x1, y0, y1) = bounds(triangle);
    x1 - x0 >= 1024 || y1 - y0 >= 512
}

/// RTPT (and RTPS for a quad's fourth vertex), NCLIP, and the whole-polygon tests.
fn transform(g: &mut Geometry, face: &PreparedFace, (w, h): (i32, i32)) -> Verdict {
    let v = &face.v;
    let p = g.project_triangle([v[0].position, v[1].position, v[2].position]);
    let mut flag = p.flag;
    let area = g.nclip_current();
    let mut xy = [p.xy[0], p.xy[1], p.xy[2], (0, 0)];
    let mut sz = [p.sz[0], p.sz[1], p.sz[2], 0];
    let mut ir0 = p.ir0;
    if face.quad {
        let q = g.project(v[3].position);
        flag = flag.union(q.flag);
        xy[3] = (q.x, q.y);
        sz[3] = q.sz;
        ir0 = q.ir0;
    }
    if flag.intersects(DROP_FLAGS) {
        return Verdict::Drop(DropCause::NearPlane);
    }
    if area <= 0 {
        return Verdict::Cull;
    }
    let corners = if face.quad { &xy[..] } else { &xy[..3] };
    let (x0, x1, y0, y1) = bounds(corners);
    if x1 < 0 || x0 >= w || y1 < 0 || y0 >= h {
        return Verdict::Offscreen;
    }
    // A quad is drawn as the triangles v0 v1 v2 and v1 v2 v3 (gpu.md §3).
    if gpu_drops(&xy[..3]) || (face.quad && gpu_drops(&xy[1..])) {
        return Verdict::Drop(DropCause::SizeLimit);
    }
    Verdict::Draw {
        xy,
        sz,
        ir0,
        extent: (x1 - x0).max(y1 - y0),
    }
}

/// The object's rotation in degrees at `frame`.
pub fn object_rotation(object: &crate::scene::Object, frame: u32) -> [f64; 3] {
    let f = frame as f64;
    [
        object.rotation[0] + object.spin[0] * f,
        object.rotation[1] + object.spin[1] * f,
        object.rotation[2] + object.spin[2] * f,
    ]
}

/// RT and TR for an object at `frame`: the camera rotation times the object rotation, and
/// the object's position in camera space (what the pipeline loads into the GTE).
pub fn object_transform(
    scene: &Scene,
    object: &crate::scene::Object,
    frame: u32,
) -> (Matrix, Translation) {
    let cam = &scene.camera;
    let view = Matrix::rotation(
        angle(cam.rotation[0]),
        angle(cam.rotation[1]),
        angle(cam.rotation[2]),
    );
    let r = object_rotation(object, frame);
    let rot = Matrix::rotation(angle(r[0]), angle(r[1]), angle(r[2]));
    let relative = [
        object.position[0] - cam.position[0],
        object.position[1] - cam.position[1],
        object.position[2] - cam.position[2],
    ];
    let t = apply(&view, relative);
    let clamp32 = |v: f64| v.round().clamp(i32::MIN as f64, i32::MAX as f64) as i32;
    (
        view.multiply(&rot),
        Translation {
            x: clamp32(t[0]),
            y: clamp32(t[1]),
            z: clamp32(t[2]),
        },
    )
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
    /// Face and packet records of a traced frame; `None` (and untouched) otherwise.
    trace: Option<Box<TraceSink>>,
    /// CLUT cache of the precise path (the GPU's own is private to it).
    clut: ClutCache,
    /// Sub-pixel positions (without the drawing offset) and 1/SZ of each `scratch` entry,
    /// filled only when the precise path is on, so the hardware path carries none of it.
    precise_vertices: Vec<[PreciseVertex; 4]>,
}

/// Frame-wide settings of the precise path.
#[derive(Clone, Copy)]
struct PreciseFrame {
    /// Drawing offset Y of the back buffer.
    offset_y: i32,
    /// E1 dithering.
    dither: bool,
    /// Perspective-correct texture coordinates.
    perspective: bool,
}

/// Draw one polygon through the non-hardware precise rasterizer: the same colours, texture,
/// blending and dithering a GP0 packet would carry, at sub-pixel positions.
fn draw_precise(
    gpu: &mut Gpu,
    state: &gpu::state::DrawState,
    clut: &mut ClutCache,
    f: &ProjectedFace,
    precise: &[PreciseVertex; 4],
    place: PreciseFrame,
) {
    let PreciseFrame {
        offset_y,
        dither,
        perspective,
    } = place;
    let texture = f.texture.map(|(clut_attr, tpage)| gpu::primitive::Texture {
        page_x: ((tpage & 0xF) * 64) as u16,
        page_y: (((tpage >> 4) & 1) * 256) as u16,
        depth: match (tpage >> 7) & 3 {
            0 => gpu::state::TextureDepth::Clut4,
            1 => gpu::state::TextureDepth::Clut8,
            _ => gpu::state::TextureDepth::Direct15,
        },
        clut_x: ((clut_attr & 0x3F) * 16) as u16,
        clut_y: ((clut_attr >> 6) & 0x1FF) as u16,
        raw: false,
    });
    let n = if f.quad { 4 } else { 3 };
    let gouraud = f.color[1..n].iter().any(|c| *c != f.color[0]);
    let blend = f.blend.map(|b| match b {
        0 => gpu::state::BlendMode::Average,
        1 => gpu::state::BlendMode::Add,
        2 => gpu::state::BlendMode::Subtract,
        _ => gpu::state::BlendMode::AddQuarter,
    });
    let vertex = |k: usize| gpu::primitive::Vertex {
        x: f.xy[k].0 as i32,
        y: f.xy[k].1 as i32,
        color: f.color[k],
        u: f.uv[k].0,
        v: f.uv[k].1,
    };
    let at = |k: usize| PreciseVertex {
        y: precise[k].y + (offset_y << SUBPIXEL_BITS),
        ..precise[k]
    };
    let triangles: &[[usize; 3]] = if f.quad {
        &[[0, 1, 2], [1, 2, 3]]
    } else {
        &[[0, 1, 2]]
    };
    for t in triangles {
        let tri = gpu::primitive::Triangle {
            vertices: t.map(vertex),
            gouraud,
            texture,
            blend,
            dither: dither && gpu::primitive::dither_applies(gouraud, texture.is_some(), false),
        };
        gpu::rasterizer::draw_triangle_precise(
            gpu.vram_mut(),
            state,
            clut,
            &tri,
            &t.map(at),
            perspective,
        );
    }
}

impl Renderer {
    /// Prepare a scene: tessellate meshes, place and upload textures (GP0 A0h), set up the
    /// GPU's display.
    pub fn new(scene: Scene, options: PipelineOptions) -> Result<Renderer, PipelineError> {
        scene.validate().map_err(PipelineError::Scene)?;
        let (width, height) = (scene.screen.width, scene.screen.height);
        let mut gpu = Gpu::new();
        gpu.gp1(0x0000_0000);
        let mut alloc = VramAllocator::new(width, height);
        let mut placements = Vec::new();
        for (index, t) in scene.textures.iter().enumerate() {
            let p = alloc
                .place(&t.name, &t.texture)
                .map_err(PipelineError::Vram)?;
            // A textured polygon blends only the texels with bit 15 set (gpu.md §1): a texture
            // worn by a semi-transparent material gets bit 15 on every texel colour except
            // transparent 0000h.
            let blended = scene
                .objects
                .iter()
                .any(|o| o.texture == Some(index) && o.blend.is_some());
            let mark = |c: u16| if blended && c != 0 { c | 0x8000 } else { c };
            let (texels, clut) = match t.texture.depth {
                Depth::Direct15 => {
                    let texels: Vec<u16> = t.texture.halfwords().into_iter().map(mark).collect();
                    (texels, Vec::new())
                }
                _ => {
                    let clut: Vec<u16> = t.texture.clut.iter().map(|&c| mark(c)).collect();
                    (t.texture.halfwords(), clut)
                }
            };
            upload(
                &mut gpu,
                p.page_x,
                p.page_y,
                t.texture.row_halfwords(),
                &texels,
            );
            if let Some((x, y)) = p.clut {
                upload(&mut gpu, x, y, clut.len(), &clut);
            }
            placements.push(p);
        }
        let mut objects = Vec::new();
        let mut capacity = 0;
        for (i, o) in scene.objects.iter().enumerate() {
            let level = options
                .tessellation
                .unwrap_or(o.tessellation)
                .min(MAX_LEVEL);
            let faces = prepare(&scene, i);
            capacity = faces
                .len()
                .saturating_mul(1 << (2 * level))
                .saturating_add(capacity)
                .min(MAX_POLYGONS);
            let texture = o.texture.and_then(|t| {
                let depth = scene.textures.get(t)?.texture.depth.bits();
                Some((*placements.get(t)?, depth))
            });
            objects.push(PreparedObject {
                faces,
                level,
                texture,
            });
        }
        // GP1: display mode for the width, 240 lines, display on.
        let mode = match width {
            256 => 0,
            320 => 1,
            512 => 2,
            640 => 3,
            _ => 0x40,
        };
        gpu.gp1(0x0800_0000 | mode);
        gpu.gp1(0x0300_0000);
        let display = DisplayArea {
            x: 0,
            y: 0,
            width,
            height,
            color_24bit: false,
        };
        let mut geometry = Geometry::new();
        geometry.set_divide_mode(options.divide_mode);
        Ok(Renderer {
            ot: OrderingTable::new(OT_DEPTH, capacity * 13 + 64),
            scratch: Vec::with_capacity(capacity),
            stack: SplitStack::default(),
            capacity,
            scene,
            options,
            objects,
            gpu,
            geometry,
            display,
            clut: ClutCache::default(),
            precise_vertices: Vec::new(),
            trace: None,
        })
    }

    /// The scene being rendered.
    pub fn scene(&self) -> &Scene {
        &self.scene
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

    /// Render frame `frame` like [`Renderer::render_frame`] and record what happened to
    /// every polygon and which GP0 packet draws it. Only the hardware path can be traced
    /// (an error names the precise-path knobs otherwise).
    pub fn render_frame_traced(&mut self, frame: u32) -> Result<(FrameStats, FrameTrace), String> {
        if self.options.precise() {
            return Err(
                "tracing needs the hardware path: drop --subpixel / --perspective-uv".into(),
            );
        }
        self.trace = Some(Box::default());
        let mut stats = FrameStats::default();
        self.gte_stage(frame, &mut stats);
        self.ot_stage(&mut stats);
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
        let ram = self.ot.ram();
        let base = ram.as_ptr() as usize;
        let _ = self.ot.walk(|words| {
            // A packet's words follow its node header in the OT's RAM image.
            let node = (words.as_ptr() as usize - base) / 4 - 1;
            let face = sink
                .node_face
                .iter()
                .find(|(n, _)| *n == node)
                .map(|&(_, f)| f);
            packets.push((words.to_vec(), face));
        });
        self.gpu_stage(frame);
        Ok((
            stats,
            FrameTrace {
                gpu_before,
                faces: sink.faces,
                packets,
                display_word: display_word(buffer_y),
            },
        ))
    }

    fn gte_stage(&mut self, frame: u32, stats: &mut FrameStats) {
        self.scratch.clear();
        let scene = &self.scene;
        let (w, h) = (scene.screen.width as i32, scene.screen.height as i32);
        let cam = &scene.camera;
        let g = &mut self.geometry;
        let stack = &mut self.stack;
        let scratch = &mut self.scratch;
        let precise_vertices = &mut self.precise_vertices;
        precise_vertices.clear();
        let capacity = self.capacity;
        let split_extent = i32::from(self.options.split_extent);
        let options = self.options;
        let (dqa, dqb) = scene
            .fog
            .and_then(|f| f.coefficients(cam.h))
            .unwrap_or((0, 0));
        g.set_projection(&Projection {
            offset_x: I16F16::from_num(w / 2),
            offset_y: I16F16::from_num(h / 2),
            h: cam.h,
            dqa: I8F8::from_bits(dqa),
            dqb: I8F24::from_bits(dqb),
            ..Projection::default()
        });
        if let Some(fog) = &scene.fog {
            // FC is in colour units of 1/16: a colour C pushes as MAC >> 4 (gte.md §8).
            g.set_far_color(fog.color.map(|c| i32::from(c) << 4));
        }
        let mut trace = self.trace.as_deref_mut();
        if let Some(t) = trace.as_deref_mut() {
            t.faces.clear();
            t.scratch_face.clear();
            t.node_face.clear();
        }
        for (object_index, (object, prepared)) in
            scene.objects.iter().zip(&self.objects).enumerate()
        {
            let r = object_rotation(object, frame);
            let rot = Matrix::rotation(angle(r[0]), angle(r[1]), angle(r[2]));
            let (rt, tr) = object_transform(scene, object, frame);
            g.set_rotation(&rt);
            g.set_translation(tr);
            if let Some(light) = &scene.light {
                // LLM row = -(light direction) in object space: (R^T (-d))^T.
                let d = light.direction;
                let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
                let to_light = [-d[0] / len, -d[1] / len, -d[2] / len];
                let rb = rot.to_bits();
                let obj: [f64; 3] = std::array::from_fn(|c| {
                    (0..3).map(|r| rb[r][c] as f64 * to_light[r]).sum::<f64>() / 4096.0
                });
                let zero = [0i16; 3];
                g.set_light_matrix(&Matrix::from_bits([obj.map(to_fixed), zero, zero]));
                let col = light.color.map(|c| to_fixed(c as f64 / 255.0));
                g.set_light_colors(&Matrix::from_bits([
                    [col[0], 0, 0],
                    [col[1], 0, 0],
                    [col[2], 0, 0],
                ]));
                g.set_background_color(light.ambient.map(|c| (c as i32 * 4096) / 255));
            }
            let blend = object.blend;
            let texture = prepared.texture.map(|(p, depth)| {
                let tpage = p.texpage(depth) | (blend.unwrap_or(0) as u32) << 5;
                (p.clut_attr(), tpage)
            });
            for (face_index, face) in prepared.faces.iter().enumerate() {
                stack.push(*face, 0);
                while let Some((face, level)) = stack.pop() {
                    let verdict = transform(g, &face, (w, h));
                    let split = level < prepared.level
                        && match verdict {
                            Verdict::Drop(_) => true,
                            Verdict::Draw { extent, .. } => extent > split_extent,
                            Verdict::Cull | Verdict::Offscreen => false,
                        };
                    if let Some(t) = trace.as_deref_mut() {
                        let fate = match verdict {
                            _ if split => FaceFate::Split,
                            Verdict::Drop(c) => FaceFate::Dropped(c),
                            Verdict::Cull => FaceFate::Culled,
                            Verdict::Offscreen => FaceFate::Offscreen,
                            Verdict::Draw { .. } if scratch.len() >= capacity => FaceFate::Overflow,
                            // The slot is filled in below.
                            Verdict::Draw { .. } => FaceFate::Drawn { ot_slot: 0 },
                        };
                        t.faces.push(FaceRecord {
                            object: object_index,
                            face: face_index,
                            level,
                            fate,
                        });
                    }
                    if split {
                        stack.push_split(&face, level + 1);
                        continue;
                    }
                    stats.polygons += 1;
                    let (xy, sz, ir0) = match verdict {
                        Verdict::Drop(_) => {
                            stats.dropped += 1;
                            continue;
                        }
                        Verdict::Cull => {
                            stats.culled += 1;
                            continue;
                        }
                        Verdict::Offscreen => {
                            stats.offscreen += 1;
                            continue;
                        }
                        Verdict::Draw { xy, sz, ir0, .. } => (xy, sz, ir0),
                    };
                    if scratch.len() >= capacity {
                        stats.dropped += 1;
                        continue;
                    }
                    let v = &face.v;
                    let mut color = [object.color; 4];
                    let normals = [v[0].normal, v[1].normal, v[2].normal];
                    match (scene.light.is_some(), scene.fog.is_some()) {
                        (true, false) => {
                            let c = g.normal_color_color_triple(normals, object.color);
                            color[..3].copy_from_slice(&c);
                            if face.quad {
                                color[3] = g.normal_color_color(v[3].normal, object.color);
                            }
                        }
                        // NCDT/NCDS fade by IR0 as the last RTPT/RTPS left it: one factor
                        // for the whole polygon, from its last vertex (gte.md §5 step 7).
                        (true, true) => {
                            let c = g.normal_color_depth_triple(normals, object.color);
                            color[..3].copy_from_slice(&c);
                            if face.quad {
                                color[3] = g.normal_color_depth(v[3].normal, object.color);
                            }
                        }
                        (false, true) => color = [g.depth_cue(object.color, ir0); 4],
                        (false, false) => {}
                    }
                    let otz = if face.quad {
                        g.average_z4(sz)
                    } else {
                        g.average_z3([sz[0], sz[1], sz[2]])
                    };
                    if options.precise() {
                        let mut precise = [PreciseVertex::default(); 4];
                        let n = if face.quad { 4 } else { 3 };
                        for k in 0..n {
                            let (mut x, mut y) = (
                                (xy[k].0 as i32) << SUBPIXEL_BITS,
                                (xy[k].1 as i32) << SUBPIXEL_BITS,
                            );
                            if options.subpixel {
                                // The GTE's screen position before truncation: q*IR + OF
                                // in 16.16, kept to 1/16 pixel.
                                let q = g.project(v[k].position);
                                let ir1 = g.gte().read_data(9) as i32 as i64;
                                let ir2 = g.gte().read_data(10) as i32 as i64;
                                let (qd, _) = gte::unr::divide(options.divide_mode, cam.h, q.sz);
                                let fx = qd as i64 * ir1 + ((w as i64 / 2) << 16);
                                let fy = qd as i64 * ir2 + ((h as i64 / 2) << 16);
                                let limit = 0x400i64 << SUBPIXEL_BITS;
                                x = (fx >> (16 - SUBPIXEL_BITS)).clamp(-limit, limit - 1) as i32;
                                y = (fy >> (16 - SUBPIXEL_BITS)).clamp(-limit, limit - 1) as i32;
                            }
                            precise[k] = PreciseVertex {
                                x,
                                y,
                                inv_z: (1u32 << 24) / (sz[k] as u32).max(1),
                            };
                        }
                        precise_vertices.push(precise);
                    }
                    let ot_index = ((otz >> OT_SHIFT) as usize).min(OT_DEPTH - 1) as u16;
                    if let Some(t) = trace.as_deref_mut() {
                        let record = t.faces.len() - 1;
                        if let Some(r) = t.faces.last_mut() {
                            r.fate = FaceFate::Drawn { ot_slot: ot_index };
                        }
                        t.scratch_face.push(record);
                    }
                    scratch.push(ProjectedFace {
                        xy,
                        color,
                        uv: v.map(|p| p.texel()),
                        quad: face.quad,
                        ot_index,
                        texture,
                        blend,
                    });
                }
            }
        }
    }

    fn ot_stage(&mut self, stats: &mut FrameStats) {
        let dither = self.options.dither.unwrap_or(self.scene.screen.dither);
        self.ot.clear();
        let mut packet = [0u32; 12];
        if self.options.precise() {
            // The precise path links each polygon's index instead of a GP0 packet: the same
            // depth order, drawn by the non-hardware rasterizer in `gpu_stage`.
            for (i, f) in self.scratch.iter().enumerate() {
                if self.ot.insert(f.ot_index as usize, &[i as u32]).is_ok() {
                    stats.drawn += 1;
                }
            }
            return;
        }
        for (k, f) in self.scratch.iter().enumerate() {
            if let Some(t) = self.trace.as_deref_mut()
                && let Some(&record) = t.scratch_face.get(k)
            {
                // The packet's node goes where the primitive buffer's free space starts.
                t.node_face
                    .push((self.ot.depth() + self.ot.used_words(), record));
            }
            let n = if f.quad { 4 } else { 3 };
            // Gouraud (G3/G4/GT3/GT4) only when the vertex colours differ; otherwise the flat
            // packet, which the GPU draws without colour interpolation.
            let gouraud = f.color[1..n].iter().any(|c| *c != f.color[0]);
            let mut op = 0x20u32 | if f.quad { 0x08 } else { 0 };
            if gouraud {
                op |= 0x10;
            }
            if f.texture.is_some() {
                op |= 0x04;
            }
            if f.blend.is_some() {
                op |= 0x02;
            }
            let mut len = 0;
            for i in 0..n {
                let [r, g, b] = f.color[i];
                let rgb = r as u32 | (g as u32) << 8 | (b as u32) << 16;
                if i == 0 {
                    packet[len] = op << 24 | rgb;
                    len += 1;
                } else if gouraud {
                    packet[len] = rgb;
                    len += 1;
                }
                let (x, y) = f.xy[i];
                packet[len] = (x as u16 as u32 & 0x7FF) | (y as u16 as u32 & 0x7FF) << 16;
                len += 1;
                if let Some((clut, tpage)) = f.texture {
                    let (u, v) = f.uv[i];
                    let attr = match i {
                        0 => clut,
                        1 => tpage,
                        _ => 0,
                    };
                    packet[len] = u as u32 | (v as u32) << 8 | attr << 16;
                    len += 1;
                }
            }
            if self.ot.insert(f.ot_index as usize, &packet[..len]).is_ok() {
                stats.drawn += 1;
            }
            // An untextured polygon has no texpage attribute to carry its blend mode: a
            // draw-mode packet (E1) linked after it at the same entry comes out just before
            // it (gpu.md §2, §6).
            if let (None, Some(mode)) = (f.texture, f.blend) {
                let e1 = 0xE100_0000 | (dither as u32) << 9 | u32::from(mode & 3) << 5;
                // A full primitive buffer leaves the polygon in the default mode.
                let _ = self.ot.insert(f.ot_index as usize, &[e1]);
            }
        }
    }

    fn gpu_stage(&mut self, frame: u32) {
        let screen = self.scene.screen;
        let buffer_y = (frame % 2) * screen.height as u32;
        let dither = self.options.dither.unwrap_or(screen.dither);
        let gpu = &mut self.gpu;
        gpu.gp0_words(&frame_environment(&screen, buffer_y, dither));
        // Bad links cannot occur in a table this renderer built; a walk error leaves the
        // frame partly drawn rather than stopping the renderer.
        if self.options.precise() {
            let state = *gpu.draw_state();
            let (scratch, at, clut, perspective) = (
                &self.scratch,
                &self.precise_vertices,
                &mut self.clut,
                self.options.perspective_uv,
            );
            let _ = self.ot.walk(|words| {
                let i = words.first().map_or(usize::MAX, |&i| i as usize);
                if let (Some(f), Some(at)) = (scratch.get(i), at.get(i)) {
                    let place = PreciseFrame {
                        offset_y: buffer_y as i32,
                        dither,
                        perspective,
                    };
                    draw_precise(gpu, &state, clut, f, at, place);
                }
            });
        } else {
            let _ = self.ot.walk_into(gpu);
        }
        gpu.gp1(display_word(buffer_y));
        self.display = gpu.display_area();
        self.display.height = screen.height;
    }
}

/// The GP0 words that start a frame in the back buffer at line `buffer_y`: draw mode,
/// texture window, drawing area, offset, mask, and a fill with the background colour.
fn frame_environment(screen: &crate::scene::Screen, buffer_y: u32, dither: bool) -> [u32; 9] {
    let (w, h) = (screen.width as u32, screen.height as u32);
    let [r, g, b] = screen.background;
    [
        0xE100_0000 | (dither as u32) << 9,
        0xE200_0000,
        0xE300_0000 | buffer_y << 10,
        0xE400_0000 | (buffer_y + h - 1) << 10 | (w - 1),
        0xE500_0000 | (buffer_y & 0x7FF) << 11,
        0xE600_0000,
        0x0200_0000 | r as u32 | (g as u32) << 8 | (b as u32) << 16,
        buffer_y << 16,
        h << 16 | w,
    ]
}

/// GP1(05h): display the buffer at line `buffer_y`.
fn display_word(buffer_y: u32) -> u32 {
    0x0500_0000 | buffer_y << 10
}

/// Upload halfwords into a `width`-halfword-wide VRAM rectangle at (x, y) with GP0(A0h).
fn upload(gpu: &mut Gpu, x: u16, y: u16, width: usize, halfwords: &[u16]) {
    if width == 0 || halfwords.is_empty() {
        return;
    }
    let height = halfwords.len() / width;
    gpu.gp0_words(&[
        0xA000_0000,
        (y as u32) << 16 | x as u32,
        (height as u32) << 16 | width as u32,
    ]);
    for pair in halfwords.chunks(2) {
        let lo = pair[0] as u32;
        let hi = pair.get(1).copied().unwrap_or(0) as u32;
        gpu.gp0(hi << 16 | lo);
    }
}
