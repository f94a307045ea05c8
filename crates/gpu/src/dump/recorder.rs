//! Recording a dump while an emulator drives the GPU: a prologue that restores the GPU's
//! state, then the port writes, GPUREAD reads and VSyncs as they happen.

use super::{Dialect, GpuVersion, Sink, VsyncTime, WriteError, Writer};
use crate::dma::linked_list_walk;
use crate::encode;
use crate::gp1::Gp1;
use crate::{Gpu, LinkedListReport, PendingInput};
use alloc::vec::Vec;
use core::fmt;

/// Single GP0 words gathered into one packet before it is written (more go into the next).
pub const GP0_PACKET_WORDS: usize = 1 << 16;

/// What a recording says about itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RecordInfo<'a> {
    /// The dialect written ([`Dialect::Spec`] by default; [`Dialect::DuckStation`] for a
    /// dump DuckStation opens).
    pub dialect: Dialect,
    /// The game's ID (e.g. `SLUS-00001`), if known.
    pub game_id: Option<&'a str>,
    /// A comment, e.g. the emulator's name and version.
    pub comment: Option<&'a str>,
}

/// Why a recording could not start or went wrong.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordError<E> {
    /// The GPU is in the middle of GP0 input (a packet, a CPU-to-VRAM transfer or a
    /// polyline): the dump could not restore it. Start between commands, e.g. at a VSync.
    Busy(PendingInput),
    /// Writing failed.
    Write(WriteError<E>),
}

impl<E> From<WriteError<E>> for RecordError<E> {
    fn from(e: WriteError<E>) -> Self {
        RecordError::Write(e)
    }
}

impl<E: fmt::Display> fmt::Display for RecordError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RecordError::Busy(p) => write!(
                f,
                "the GPU is in the middle of GP0 input ({p:?}); start recording between commands"
            ),
            RecordError::Write(e) => write!(f, "{e}"),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> core::error::Error for RecordError<E> {}

/// Records a dump of what an emulator sends a [`Gpu`].
///
/// [`Recorder::start`] writes the information packets (GPU version: the v2 GPU the crate
/// models; game ID; `PAL` or `NTSC` from GP1(08h) bit 3; comment) and the state-restore
/// prologue: all of VRAM as one GP0(A0h) transfer of size 0 (1024x512, docs/hardware/gpu.md
/// §8), the display registers as GP1(03h), (05h), (06h), (07h), (09h) and (08h), the drawing
/// environment as GP0(E1h)-(E6h), then the trace-begin mark. VRAM comes first so that the
/// replaying GPU's mask settings are still their reset values (nothing forced or tested,
/// §6) while it loads.
///
/// Then route the GPU's inputs through the recorder ([`Recorder::gp0`], [`Recorder::gp1`],
/// [`Recorder::gpuread`], the DMA methods) and call [`Recorder::vsync`] at each vertical
/// blank; or call the `record_*` methods beside your own calls into the GPU. Each block of
/// GP0 words (a [`Recorder::gp0_words`] or DMA block, a linked-list node) is one packet, as
/// DuckStation writes a packet per command, so a dump lists the program's packets;
/// single-word writes are gathered into packets of up to [`GP0_PACKET_WORDS`] words, and
/// consecutive GPUREAD reads of a VRAM-to-CPU transfer into one discard packet. GP1(04h) (DMA direction) and GP1(10h) and
/// above (information reads, which change no drawing state) are not recorded, as DuckStation
/// leaves them out.
///
/// Recording never changes what the GPU does. A write error is kept: later calls only drive
/// the GPU, and [`Recorder::finish`] returns the error.
///
/// ```
/// use gpu::dump::{Dialect, Packet, Reader, RecordInfo, Recorder, VsyncTime};
/// let mut gpu = gpu::Gpu::new();
/// let info = RecordInfo { dialect: Dialect::DuckStation, ..RecordInfo::default() };
/// let mut rec = Recorder::start(Vec::new(), &gpu, &info).unwrap();
/// rec.gp0_words(&mut gpu, &[0x0200_00FF, 0, 0x0001_0010]); // fill 16x1 with red
/// rec.vsync(VsyncTime::Cycles64(564_480));
/// let bytes = rec.finish().unwrap();
/// assert_eq!(gpu.vram().pixel(0, 0), 0x001F);
/// let packets: Vec<_> = Reader::new(&bytes).unwrap().map(|p| p.unwrap().1).collect();
/// assert!(matches!(packets.last(), Some(Packet::VSync(VsyncTime::Cycles64(564_480)))));
/// ```
#[derive(Debug)]
pub struct Recorder<S: Sink> {
    writer: Writer<S>,
    gp0: Vec<u32>,
    reads: u32,
    error: Option<RecordError<S::Error>>,
}

/// An iterator known to yield exactly `.1` items.
struct Counted<I>(I, usize);

impl<I: Iterator<Item = u32>> Iterator for Counted<I> {
    type Item = u32;
    fn next(&mut self) -> Option<u32> {
        let item = self.0.next()?;
        self.1 = self.1.saturating_sub(1);
        Some(item)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.1, Some(self.1))
    }
}

impl<I: Iterator<Item = u32>> ExactSizeIterator for Counted<I> {}

/// GP1 words a dump carries: 00h-09h except 04h.
fn recorded_gp1(word: u32) -> bool {
    !matches!(
        Gp1::from_word(word),
        Gp1::DmaDirection(_) | Gp1::GetInfo(_) | Gp1::Unused(_)
    )
}

/// GP1(03h), (05h), (06h), (07h), (09h), (08h) words restoring `gpu`'s display state
/// (docs/hardware/gpu.md §9).
fn display_words(gpu: &Gpu) -> [u32; 6] {
    let d = gpu.display_state();
    [
        Gp1::DisplayEnabled(!d.disabled),
        Gp1::DisplayStart {
            x: d.start_x,
            y: d.start_y,
        },
        Gp1::HorizontalRange {
            x1: d.h_range.0,
            x2: d.h_range.1,
        },
        Gp1::VerticalRange {
            y1: d.v_range.0,
            y2: d.v_range.1,
        },
        Gp1::AllowTextureDisable(gpu.texture_disable_allowed()),
        Gp1::DisplayMode(d.mode),
    ]
    .map(Gp1::word)
}

impl<S: Sink> Recorder<S> {
    /// Start recording `gpu` into `sink`: the information packets, the state-restore
    /// prologue and the trace-begin mark. Fails when the GPU is in the middle of GP0 input.
    pub fn start(sink: S, gpu: &Gpu, info: &RecordInfo<'_>) -> Result<Self, RecordError<S::Error>> {
        if let Some(pending) = gpu.pending_input() {
            return Err(RecordError::Busy(pending));
        }
        let mut w = Writer::new(sink, info.dialect)?;
        w.gpu_version(GpuVersion::V2)?;
        if let Some(id) = info.game_id {
            w.game_id(id.as_bytes())?;
        }
        let pal = gpu.display_state().mode & 0x08 != 0;
        w.video_format(if pal { b"PAL" } else { b"NTSC" })?;
        if let Some(comment) = info.comment {
            w.comment(comment.as_bytes())?;
        }
        let vram = gpu
            .vram()
            .as_slice()
            .chunks_exact(2)
            .map(|p| p[0] as u32 | (p[1] as u32) << 16);
        // GP0(A0h) at (0, 0), size 0 = 1024x512 (docs/hardware/gpu.md §8), then the pixels.
        let transfer = encode::cpu_to_vram(0, 0, 0, 0).into_iter().chain(vram);
        w.words(
            super::PacketType::Gp0.byte(),
            Counted(transfer, 3 + crate::VRAM_LEN / 2),
        )?;
        w.gp1(&display_words(gpu))?;
        w.gp0(&encode::environment(gpu.draw_state()))?;
        w.trace_begin()?;
        Ok(Recorder {
            writer: w,
            gp0: Vec::new(),
            reads: 0,
            error: None,
        })
    }

    fn keep<T>(&mut self, result: Result<T, WriteError<S::Error>>) {
        if let Err(e) = result
            && self.error.is_none()
        {
            self.error = Some(RecordError::Write(e));
        }
    }

    fn flush_gp0(&mut self) {
        if !self.gp0.is_empty() && self.error.is_none() {
            let r = self.writer.gp0(&self.gp0);
            self.keep(r);
        }
        self.gp0.clear();
    }

    fn flush_reads(&mut self) {
        if self.reads > 0 && self.error.is_none() {
            let r = self.writer.discard(self.reads);
            self.keep(r);
        }
        self.reads = 0;
    }

    fn push_gp0(&mut self, word: u32) {
        if self.error.is_some() {
            return;
        }
        if self.gp0.len() >= GP0_PACKET_WORDS {
            self.flush_gp0();
        }
        self.gp0.push(word);
    }

    /// Log words written to GP0 (by the CPU or DMA) without sending them anywhere: a single
    /// word joins the words gathered, a block is a packet of its own.
    pub fn record_gp0(&mut self, words: &[u32]) {
        self.flush_reads();
        match words {
            [] => {}
            [word] => self.push_gp0(*word),
            block => {
                self.flush_gp0();
                for chunk in block.chunks(super::MAX_PACKET_WORDS) {
                    if self.error.is_none() {
                        let r = self.writer.gp0(chunk);
                        self.keep(r);
                    }
                }
            }
        }
    }

    /// Log a word written to GP1 (left out when it is GP1(04h) or GP1(10h) and above).
    pub fn record_gp1(&mut self, word: u32) {
        if !recorded_gp1(word) {
            return;
        }
        self.flush_reads();
        self.flush_gp0();
        if self.error.is_none() {
            let r = self.writer.gp1(&[word]);
            self.keep(r);
        }
    }

    /// Log `words` GPUREAD reads of a VRAM-to-CPU transfer.
    pub fn record_gpuread(&mut self, words: u32) {
        if words == 0 {
            return;
        }
        self.flush_gp0();
        match self.reads.checked_add(words) {
            Some(n) => self.reads = n,
            None => {
                self.flush_reads();
                self.reads = words;
            }
        }
    }

    /// A vertical sync: a frame ends. `time` is the CPU cycle count, if the emulator keeps
    /// one ([`VsyncTime::Cycles64`] never wraps).
    pub fn vsync(&mut self, time: VsyncTime) {
        self.flush_reads();
        self.flush_gp0();
        if self.error.is_none() {
            let r = self.writer.vsync(time);
            self.keep(r);
        }
    }

    /// [`Gpu::gp0`], recorded; returns the CPU cycles the store waited.
    pub fn gp0(&mut self, gpu: &mut Gpu, word: u32) -> u32 {
        self.record_gp0(&[word]);
        gpu.gp0(word)
    }

    /// [`Gpu::gp0_words`], recorded.
    pub fn gp0_words(&mut self, gpu: &mut Gpu, words: &[u32]) {
        self.record_gp0(words);
        gpu.gp0_words(words);
    }

    /// [`Gpu::gp1`], recorded.
    pub fn gp1(&mut self, gpu: &mut Gpu, word: u32) {
        self.record_gp1(word);
        gpu.gp1(word);
    }

    /// [`Gpu::gpuread`], recorded when it reads VRAM (a GP0(C0h) transfer in progress).
    pub fn gpuread(&mut self, gpu: &mut Gpu) -> u32 {
        if gpu.read.active() {
            self.record_gpuread(1);
        }
        gpu.gpuread()
    }

    /// [`Gpu::gpuread_timed`], recorded as [`Recorder::gpuread`] is.
    pub fn gpuread_timed(&mut self, gpu: &mut Gpu) -> (u32, u32) {
        if gpu.read.active() {
            self.record_gpuread(1);
        }
        gpu.gpuread_timed()
    }

    /// [`Gpu::dma_block_write`], recorded.
    pub fn dma_block_write(&mut self, gpu: &mut Gpu, words: &[u32]) -> u32 {
        self.record_gp0(words);
        gpu.dma_block_write(words)
    }

    /// [`Gpu::dma_block_read`], recorded: the words read while the transfer lasts.
    pub fn dma_block_read(&mut self, gpu: &mut Gpu, out: &mut [u32]) -> u32 {
        let left = gpu.read.remaining_words();
        self.record_gpuread(left.min(u32::try_from(out.len()).unwrap_or(u32::MAX)));
        gpu.dma_block_read(out)
    }

    /// [`Gpu::dma_linked_list`], recorded: each node's data words the walk sends, a packet
    /// per node.
    pub fn dma_linked_list(&mut self, gpu: &mut Gpu, ram: &[u8], start: u32) -> LinkedListReport {
        linked_list_walk(ram, start, |node| self.record_gp0(node));
        gpu.dma_linked_list(ram, start)
    }

    /// Write what is gathered (GP0 words, GPUREAD counts) to the sink now.
    pub fn flush(&mut self) {
        self.flush_reads();
        self.flush_gp0();
    }

    /// The first write error, if one happened.
    pub fn error(&self) -> Option<&RecordError<S::Error>> {
        self.error.as_ref()
    }

    /// Write what is gathered and hand back the sink, or the first error.
    pub fn finish(mut self) -> Result<S, RecordError<S::Error>> {
        self.flush();
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(self.writer.into_inner()),
        }
    }
}
