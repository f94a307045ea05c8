//! GPU dumps (`.psxgpu`, docs/formats.md "GPU dumps") and command streams replayed frame by
//! frame: what a dump holds ([`DumpSummary`]), a [`Player`] that runs it on a [`Gpu`] one
//! frame at a time (frames end at VSync packets), and the commands of one frame for the
//! inspector.
//!
//! A command stream (`.gpu` text) is turned into a dump of the spec's dialect first
//! ([`Dump::from_text`]), so both replay through the same code; its packets keep the text's
//! line numbers.

use gpu::command::Command;
use gpu::command_stream::{self, Entry, Port, StreamCommand, StreamError};
use gpu::decode::{self, Class};
use gpu::dump::{
    Dialect, DumpError, GpuVersion, Header, MAX_PACKET_WORDS, Packet, Reader, VsyncTime, Writer,
};
use gpu::{DisplayArea, Gpu, PendingInput, VideoStandard};
use image::RgbImage;
use std::fmt;

use crate::vram_image::{self, Expand};

/// A dump held in memory, from a `.psxgpu` file or converted from a command stream.
#[derive(Clone, Debug)]
pub struct Dump {
    bytes: Vec<u8>,
    header: Header,
    /// For a dump made from text: the text line of each packet.
    lines: Option<Vec<usize>>,
}

impl Dump {
    /// A dump from its bytes (already decompressed); the magic header is checked.
    pub fn from_bytes(bytes: Vec<u8>) -> Result<Dump, DumpError> {
        let header = Header::parse(&bytes)?;
        Ok(Dump {
            bytes,
            header,
            lines: None,
        })
    }

    /// A command stream's text as a dump of the spec's dialect: one packet per line.
    pub fn from_text(text: &str) -> Result<Dump, StreamError> {
        let entries = command_stream::parse_entries(text)?;
        Dump::from_entries(&entries).map_err(|message| StreamError {
            line: entries.last().map_or(1, Entry::line),
            message,
        })
    }

    /// Parsed stream entries as a dump of the spec's dialect.
    pub fn from_entries(entries: &[Entry]) -> Result<Dump, String> {
        let mut writer = Writer::new(Vec::new(), Dialect::Spec).map_err(|e| e.to_string())?;
        command_stream::to_dump(entries, &mut writer).map_err(|e| e.to_string())?;
        let mut lines = Vec::new();
        for e in entries {
            let packets = match e {
                Entry::Command(c) => c.words.len().div_ceil(MAX_PACKET_WORDS).max(1),
                Entry::Directive { .. } => 1,
            };
            lines.extend(std::iter::repeat_n(e.line(), packets));
        }
        let mut dump = Dump::from_bytes(writer.into_inner()).map_err(|e| e.to_string())?;
        dump.lines = Some(lines);
        Ok(dump)
    }

    /// The dump's bytes.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// The magic header.
    pub fn header(&self) -> Header {
        self.header
    }

    /// Whether the dump was made from a command stream's text.
    pub fn from_stream_text(&self) -> bool {
        self.lines.is_some()
    }

    /// The packets from the start.
    pub fn reader(&self) -> Reader<'_> {
        Reader::with_header(&self.bytes, self.header)
    }

    /// Where packet `index` (0-based) came from: its text line for a stream, else its
    /// 1-based number in the dump. The inspector shows it in its line column.
    pub fn packet_line(&self, index: usize) -> usize {
        match &self.lines {
            Some(lines) => lines.get(index).copied().unwrap_or(index + 1),
            None => index + 1,
        }
    }

    /// What the dump holds, read without replaying it. `progress` gets the bytes read so
    /// far now and then.
    pub fn summary(&self, progress: &mut dyn FnMut(usize)) -> Result<DumpSummary, DumpError> {
        let mut s = DumpSummary {
            header: self.header,
            frames: Vec::new(),
            packets: 0,
            trace_begin: None,
            gpu_version: None,
            game_id: None,
            video_format: None,
            comments: Vec::new(),
            unknown_packets: 0,
        };
        let mut frame = FrameInfo::default();
        let mut port_data = false;
        for (index, item) in self.reader().enumerate() {
            let (offset, packet) = item?;
            if frame.packets == 0 {
                frame.first_packet = index;
                frame.offset = offset;
            }
            frame.packets += 1;
            s.packets += 1;
            if index % 4096 == 0 {
                progress(offset);
            }
            match packet {
                Packet::Gp0(w) => {
                    frame.gp0_words += w.len() as u64;
                    port_data = true;
                }
                Packet::Gp1(w) => {
                    frame.gp1_words += w.len() as u64;
                    port_data = true;
                }
                Packet::Discard(n) | Packet::Readback(n) => {
                    frame.read_words += u64::from(n);
                    port_data = true;
                }
                Packet::VSync(t) => {
                    frame.vsync = Some(t);
                    s.frames.push(std::mem::take(&mut frame));
                    port_data = false;
                }
                Packet::TraceBegin => {
                    s.trace_begin.get_or_insert(index);
                }
                Packet::GpuVersion { word, version } => s.gpu_version = Some((word, version)),
                Packet::GameId(t) => s.game_id = Some(t.to_string()),
                Packet::VideoFormat(t) => s.video_format = Some(t.to_string()),
                Packet::Comment(t) => s.comments.push(t.to_string()),
                Packet::Unknown { .. } => s.unknown_packets += 1,
            }
        }
        if port_data {
            s.frames.push(frame);
        }
        progress(self.bytes.len());
        Ok(s)
    }
}

/// One frame of a dump: the packets up to and including a VSync (or, for the last frame,
/// to the end of the dump when port data follows the last VSync).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameInfo {
    /// Index of its first packet.
    pub first_packet: usize,
    /// Byte offset of its first packet.
    pub offset: usize,
    /// Packets in it, the VSync included.
    pub packets: usize,
    /// GP0 words.
    pub gp0_words: u64,
    /// GP1 words.
    pub gp1_words: u64,
    /// GPUREAD words discarded or read back.
    pub read_words: u64,
    /// The VSync that ends it; `None` for an unfinished last frame.
    pub vsync: Option<VsyncTime>,
}

/// What a dump holds.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DumpSummary {
    /// Its magic header.
    pub header: Header,
    /// Its frames, in order.
    pub frames: Vec<FrameInfo>,
    /// Packets in all.
    pub packets: usize,
    /// Index of the trace-begin packet, if any.
    pub trace_begin: Option<usize>,
    /// The GPU-version packet's word and meaning, if any.
    pub gpu_version: Option<(u32, Option<GpuVersion>)>,
    /// The game ID, if given.
    pub game_id: Option<String>,
    /// The video format text, if given.
    pub video_format: Option<String>,
    /// Comment packets.
    pub comments: Vec<String>,
    /// Packets of types the format does not define (skipped).
    pub unknown_packets: usize,
}

impl DumpSummary {
    /// The console region the video-format packet names (NTSC when absent or unknown).
    pub fn video_standard(&self) -> VideoStandard {
        match &self.video_format {
            Some(f) if f.trim().eq_ignore_ascii_case("PAL") => VideoStandard::Pal,
            _ => VideoStandard::Ntsc,
        }
    }

    /// GP0 words in all frames.
    pub fn gp0_words(&self) -> u64 {
        self.frames.iter().map(|f| f.gp0_words).sum()
    }

    /// GP1 words in all frames.
    pub fn gp1_words(&self) -> u64 {
        self.frames.iter().map(|f| f.gp1_words).sum()
    }

    /// A warning when the dump was recorded on a GPU other than the modelled v2 with 1 MB.
    pub fn version_warning(&self) -> Option<String> {
        match self.gpu_version {
            Some((_, Some(GpuVersion::V2))) | None => None,
            Some((_, Some(v))) => Some(format!(
                "the dump was recorded on a {} GPU; wobble models the v2 GPU with 1 MB of \
                 VRAM (docs/gpu.md, \"Modelled GPU version\"), so version-dependent \
                 behaviour may differ",
                v.describe()
            )),
            Some((w, None)) => Some(format!(
                "the dump's GPU version word {w} is reserved in the {} dialect; replayed on \
                 the modelled v2 GPU",
                self.header.dialect.name()
            )),
        }
    }
}

/// A dump's description on one line: frames, packets, words, game, video format, GPU.
impl fmt::Display for DumpSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} frame(s), {} packets ({} GP0 words, {} GP1 words)",
            self.frames.len(),
            self.packets,
            self.gp0_words(),
            self.gp1_words()
        )?;
        if let Some(id) = &self.game_id {
            write!(f, ", game {id}")?;
        }
        if let Some(v) = &self.video_format {
            write!(f, ", {v}")?;
        }
        match self.gpu_version {
            Some((_, Some(v))) => write!(f, ", GPU {}", v.describe())?,
            Some((w, None)) => write!(f, ", GPU version word {w} (reserved)")?,
            None => {}
        }
        write!(
            f,
            ", {} dialect (v{}{})",
            self.header.dialect.name(),
            self.header.major,
            self.header
                .minor
                .map(|m| format!("r{m}"))
                .unwrap_or_default()
        )
    }
}

/// What replaying one frame did, and the display it ends with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameResult {
    /// The frame's index.
    pub index: usize,
    /// GP0 commands started (a transfer's data and a polyline's vertices belong to theirs).
    pub commands: u64,
    /// Of those, drawing commands (GP0 20h-7Fh).
    pub draws: u64,
    /// GP0 words.
    pub gp0_words: u64,
    /// GP1 words.
    pub gp1_words: u64,
    /// GPUREAD words read (discard and readback packets).
    pub read_words: u64,
    /// The VSync that ended it (`None`: the dump ended first).
    pub vsync: Option<VsyncTime>,
    /// The display area GP1 selects at the frame's end.
    pub display: DisplayArea,
    /// The display is on (GP1(03h)); a disabled display shows black.
    pub display_enabled: bool,
}

impl fmt::Display for FrameResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let d = &self.display;
        write!(
            f,
            "frame {}: {} commands ({} draws), {} GP0 words, {} GP1 words",
            self.index, self.commands, self.draws, self.gp0_words, self.gp1_words
        )?;
        if self.read_words > 0 {
            write!(f, ", {} GPUREAD words", self.read_words)?;
        }
        write!(
            f,
            "; display {}x{} at ({}, {}){}{}",
            d.width,
            d.height,
            d.x,
            d.y,
            if d.color_24bit { " 24-bit" } else { "" },
            if self.display_enabled { "" } else { " (off)" }
        )?;
        match self.vsync {
            Some(VsyncTime::None) => Ok(()),
            Some(VsyncTime::Cycles32(t)) => write!(f, "; vsync at cycle {t}"),
            Some(VsyncTime::Cycles64(t)) => write!(f, "; vsync at cycle {t}"),
            None => write!(f, "; no vsync (the dump ends)"),
        }
    }
}

/// Input a replay left unfinished: what, and where it started.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unfinished {
    /// The input in progress.
    pub pending: PendingInput,
    /// The line ([`Dump::packet_line`]) of the packet holding its first word.
    pub line: usize,
}

/// Runs a dump on a GPU frame by frame.
///
/// GP0 and GP1 packets go to their ports; discard and readback packets read GPUREAD that
/// many times, consuming a VRAM-to-CPU transfer's words as the console's CPU did; at each
/// VSync the GPU's video timing runs to its next vblank, so fields alternate as they did
/// (docs/formats.md, "Replaying a dump").
pub struct Player<'a> {
    dump: &'a Dump,
    reader: Reader<'a>,
    gpu: Gpu,
    frame: usize,
    packet: usize,
    pending_packet: usize,
}

/// CPU cycles of two PAL frames: the most [`Player`] runs looking for a vblank.
const VBLANK_SEARCH_CYCLES: u32 = 1_400_000;

impl<'a> Player<'a> {
    /// Start at the dump's first packet with a fresh GPU of `standard` (all-zero VRAM).
    pub fn new(dump: &'a Dump, standard: VideoStandard) -> Self {
        Player {
            dump,
            reader: dump.reader(),
            gpu: Gpu::with_standard(standard),
            frame: 0,
            packet: 0,
            pending_packet: 0,
        }
    }

    /// Switch the GPU's texture cache on (as on the console, the default) or off
    /// ([`Gpu::set_texture_cache`]); either way it starts empty.
    pub fn set_texture_cache(&mut self, on: bool) {
        self.gpu.set_texture_cache(on);
    }

    /// The GPU as the packets so far left it.
    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }

    /// The GPU, to continue from it elsewhere.
    pub fn into_gpu(self) -> Gpu {
        self.gpu
    }

    /// The index of the frame the next packet belongs to.
    pub fn frame(&self) -> usize {
        self.frame
    }

    /// Bytes of the dump consumed so far.
    pub fn offset(&self) -> usize {
        self.reader.offset()
    }

    /// What the GPU is in the middle of, if anything, and where that input started.
    pub fn unfinished(&self) -> Option<Unfinished> {
        self.gpu.pending_input().map(|pending| Unfinished {
            pending,
            line: self.dump.packet_line(self.pending_packet),
        })
    }

    /// Replay the next frame: its packets up to and including the VSync that ends it.
    /// `None` when no frame is left (only packets without port data remain).
    pub fn run_frame(&mut self) -> Result<Option<FrameResult>, DumpError> {
        let mut r = FrameResult {
            index: self.frame,
            commands: 0,
            draws: 0,
            gp0_words: 0,
            gp1_words: 0,
            read_words: 0,
            vsync: None,
            display: self.gpu.display_area(),
            display_enabled: false,
        };
        let mut port_data = false;
        for item in self.reader.by_ref() {
            let (_, packet) = item?;
            let index = self.packet;
            self.packet += 1;
            match packet {
                Packet::Gp0(words) => {
                    port_data = true;
                    r.gp0_words += words.len() as u64;
                    for w in words.iter() {
                        if self.gpu.pending_input().is_none() {
                            self.pending_packet = index;
                            r.commands += 1;
                            let kind = decode::Kind::Gp0(Command::of(w).kind);
                            r.draws += u64::from(kind.class() == Class::Draw);
                        }
                        self.gpu.gp0(w);
                    }
                }
                Packet::Gp1(words) => {
                    port_data = true;
                    r.gp1_words += words.len() as u64;
                    for w in words.iter() {
                        self.gpu.gp1(w);
                    }
                }
                Packet::Discard(n) | Packet::Readback(n) => {
                    port_data = true;
                    r.read_words += u64::from(n);
                    for _ in 0..n {
                        self.gpu.gpuread();
                    }
                }
                Packet::VSync(t) => {
                    r.vsync = Some(t);
                    self.run_to_vblank();
                    break;
                }
                _ => {}
            }
        }
        if r.vsync.is_none() && !port_data {
            return Ok(None);
        }
        r.display = self.gpu.display_area();
        r.display_enabled = !self.gpu.display_state().disabled;
        self.frame += 1;
        Ok(Some(r))
    }

    /// Run the GPU's video timing to its next vblank start.
    fn run_to_vblank(&mut self) {
        let mut budget = VBLANK_SEARCH_CYCLES;
        while budget > 0 {
            let n = self.gpu.cycles_until_next_event().clamp(1, budget);
            budget -= n;
            if self.gpu.run(n).vblank_start {
                return;
            }
        }
    }

    /// Replay frames until the next one is `frame`. `progress` gets each frame replayed.
    /// Fails with the number of frames when the dump ends first.
    pub fn skip_to(
        &mut self,
        frame: usize,
        progress: &mut dyn FnMut(&FrameResult),
    ) -> Result<(), String> {
        while self.frame < frame {
            match self.run_frame().map_err(|e| e.to_string())? {
                Some(r) => progress(&r),
                None => {
                    return Err(format!(
                        "frame {frame} does not exist: the dump has {} frame(s) (0..={})",
                        self.frame,
                        self.frame.saturating_sub(1)
                    ));
                }
            }
        }
        Ok(())
    }

    /// The next frame's port writes as stream commands (one per GP0 packet and per GP1
    /// word; [`Dump::packet_line`] as their line), without running them: the input of
    /// `write_report` for one frame. GPUREAD packets in it, which change no VRAM, are
    /// counted, not listed. The player moves past the frame; its GPU stays as it was.
    pub fn take_frame_commands(&mut self) -> Result<Option<FrameCommands>, DumpError> {
        let mut out = FrameCommands {
            index: self.frame,
            commands: Vec::new(),
            read_words: 0,
            vsync: None,
        };
        let mut port_data = false;
        for item in self.reader.by_ref() {
            let (_, packet) = item?;
            let line = self.dump.packet_line(self.packet);
            self.packet += 1;
            match packet {
                Packet::Gp0(words) if !words.is_empty() => {
                    port_data = true;
                    out.commands.push(StreamCommand {
                        line,
                        port: Port::Gp0,
                        words: words.iter().collect(),
                    });
                }
                Packet::Gp1(words) => {
                    port_data = true;
                    out.commands.extend(words.iter().map(|w| StreamCommand {
                        line,
                        port: Port::Gp1,
                        words: vec![w],
                    }));
                }
                Packet::Discard(n) | Packet::Readback(n) => {
                    port_data = true;
                    out.read_words += u64::from(n);
                }
                Packet::VSync(t) => {
                    out.vsync = Some(t);
                    break;
                }
                _ => {}
            }
        }
        if out.vsync.is_none() && !port_data {
            return Ok(None);
        }
        self.frame += 1;
        Ok(Some(out))
    }

    /// The picture the frame just replayed shows: the display area of VRAM, black when
    /// GP1(03h) turned the display off. `None` when the area is empty (GP1(06h)/(07h)
    /// ranges of zero size).
    pub fn displayed_image(&self, expand: Expand) -> Option<RgbImage> {
        displayed_image(&self.gpu, expand)
    }
}

/// The picture `gpu` shows: the display area of VRAM, black when GP1(03h) turned the
/// display off; `None` when the area is empty.
pub fn displayed_image(gpu: &Gpu, expand: Expand) -> Option<RgbImage> {
    let area = gpu.display_area();
    if area.width == 0 || area.height == 0 {
        return None;
    }
    if gpu.display_state().disabled {
        return Some(RgbImage::new(u32::from(area.width), u32::from(area.height)));
    }
    Some(vram_image::display_image(
        gpu.vram().as_slice(),
        area,
        expand,
    ))
}

/// One frame's port writes, for the inspector.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameCommands {
    /// The frame's index.
    pub index: usize,
    /// Its GP0 packets and GP1 words, in order.
    pub commands: Vec<StreamCommand>,
    /// GPUREAD words its discard/readback packets read (not listed).
    pub read_words: u64,
    /// The VSync that ends it.
    pub vsync: Option<VsyncTime>,
}
