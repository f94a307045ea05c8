//! PlayStation GPU: GP0/GP1 command processing into a 1024x512 16-bit VRAM, pixel-exact with
//! a real console. Facts are those of the GPU hardware reference (`docs/hardware/gpu.md`, cited by section); the
//! choices made where it is silent are listed in `docs/gpu.md`.
//!
//! Route the console's GP0/GP1 port writes (or DMA blocks) into [`Gpu`]; read pixels from
//! [`Gpu::vram`]. Commands may arrive split at any word boundary. Time passes through
//! [`Gpu::run`] (or [`Gpu::run_lines`], which also hands over each displayed line as the beam
//! finishes it); [`Gpu::beam`] and [`Gpu::cycles_until`] tell where the beam is and when each
//! kind of event comes, for the timers and the interrupt controller.
//!
//! An emulator's side of the chip, in a few lines (docs/emulator.md has the full wiring):
//!
//! ```
//! use gpu::{Gpu, PixelFormat};
//! let mut gpu = Gpu::new(); // NTSC console at power-on
//! gpu.gp1(0x0300_0000); // GP1(03h): display on
//! gpu.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]); // draw anywhere, offset 0
//! gpu.gp0_words(&[0x2000_00FF, 0, 64, 64 << 16]); // GP0(20h): flat red triangle
//! assert_eq!(gpu.vram().pixel(1, 1), 0x001F); // 5-bit red
//! gpu.gp0(0x1F00_0000); // GP0(1Fh): request IRQ1
//! let ev = gpu.run(600_000); // a little over one NTSC frame of CPU cycles
//! assert!(ev.vblank_start && ev.gpu_irq); // IRQ0 and IRQ1 sources
//! let size = gpu.frame_size(); // 320x240 after reset
//! let mut rgb = vec![0u8; size.bytes(PixelFormat::Rgb888)];
//! gpu.display_frame(&mut rgb, PixelFormat::Rgb888).unwrap();
//! assert_eq!(&rgb[..3], &[255, 0, 0]);
//! ```
#![no_std]
// The one `unsafe` is the call of the span loops' AVX2 build where the host has AVX2
// (`rasterizer::triangle`, `host_cpu`).
#![deny(unsafe_code)]
#![deny(missing_docs, rustdoc::broken_intra_doc_links)]

extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod bus;
mod color;
pub mod command;
pub mod command_stream;
pub mod decode;
mod display;
mod dma;
mod drawing;
pub mod dump;
pub mod encode;
mod frame;
mod gp0;
pub mod gp1;
mod host_cpu;
mod ordering_table;
#[cfg(feature = "precise")]
pub mod precise;
mod primitive;
mod rasterizer;
mod rows;
#[cfg(feature = "serde")]
mod save;
#[cfg(feature = "serde")]
mod serde_array;
mod state;
mod texture;
mod texture_cache;
mod timing;
mod transfer;

use alloc::boxed::Box;
use alloc::vec;

pub use display::{DisplayArea, DisplayState};
pub use dma::{
    DmaError, LINKED_LIST_WORD_BUDGET, LinkedListReport, ListEnd, RAM_MASK, RAM_SIZE,
    dma_clear_ordering_table,
};
pub use frame::{ChannelExpand, DisplayLine, FrameError, FrameSize, PixelFormat};
pub use gp0::PendingInput;
pub use ordering_table::{
    END_MARKER, MAX_DEPTH, MAX_PACKET_WORDS, MAX_WORDS, OrderingTable, OtError, WalkStats, walk_ram,
};
#[cfg(feature = "serde")]
pub use save::{
    SAVE_STATE_MAGIC, SAVE_STATE_OLDEST_VERSION, SAVE_STATE_VERSION, SaveState, StateError,
};
pub use state::{
    BlendMode, ClutAttr, DrawMode, DrawState, DrawingArea, MaskSettings, Texpage, TextureDepth,
    TextureWindow,
};
use texture::ClutCache;
use texture_cache::TextureCache;
pub use texture_cache::TextureCacheEntry;
pub use timing::{Beam, CPU_CLOCK_HZ, EventKind, Events, VideoStandard};

/// VRAM width in halfwords.
pub const VRAM_WIDTH: usize = 1024;
/// VRAM height in lines.
pub const VRAM_HEIGHT: usize = 512;
/// VRAM size in halfwords.
pub const VRAM_LEN: usize = VRAM_WIDTH * VRAM_HEIGHT;

/// 1024x512 halfwords of 1555 MBGR pixels, row-major (`y * 1024 + x`) (docs/hardware/gpu.md §1).
#[derive(Clone, PartialEq, Eq)]
pub struct Vram {
    pixels: Box<[u16; VRAM_LEN]>,
}

impl Vram {
    /// All-zero VRAM, allocated on the heap directly (no 1 MiB stack temporary).
    pub fn new() -> Self {
        let pixels = match vec![0u16; VRAM_LEN].into_boxed_slice().try_into() {
            Ok(pixels) => pixels,
            // A slice of VRAM_LEN elements always converts; this arm is never taken.
            Err(_) => Box::new([0u16; VRAM_LEN]),
        };
        Self { pixels }
    }
    /// The whole VRAM, `VRAM_WIDTH * VRAM_HEIGHT` halfwords.
    pub fn as_slice(&self) -> &[u16] {
        &self.pixels[..]
    }
    /// The whole VRAM, mutable.
    pub fn as_mut_slice(&mut self) -> &mut [u16] {
        &mut self.pixels[..]
    }
    /// The whole VRAM as a fixed-size array: indices masked with `VRAM_LEN - 1` need no
    /// bounds check.
    pub fn as_array(&self) -> &[u16; VRAM_LEN] {
        &self.pixels
    }
    /// The whole VRAM as a fixed-size array, mutable.
    pub fn as_array_mut(&mut self) -> &mut [u16; VRAM_LEN] {
        &mut self.pixels
    }
    /// The pixel at (x, y), coordinates wrapped to the VRAM.
    pub fn pixel(&self, x: usize, y: usize) -> u16 {
        self.pixels[((y & 511) * VRAM_WIDTH + (x & 1023)) & (VRAM_LEN - 1)]
    }
    /// Set the pixel at (x, y), coordinates wrapped to the VRAM.
    pub fn set_pixel(&mut self, x: usize, y: usize, value: u16) {
        self.pixels[((y & 511) * VRAM_WIDTH + (x & 1023)) & (VRAM_LEN - 1)] = value;
    }
}

impl Default for Vram {
    fn default() -> Self {
        Self::new()
    }
}

impl core::fmt::Debug for Vram {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Vram").finish_non_exhaustive()
    }
}

/// The GPU: GP0 (rendering, VRAM transfers) and GP1 (display control) ports over a [`Vram`].
///
/// Two GPUs compare equal when their chip states are equal: everything a save state holds
/// (VRAM, registers, transfers and packets in progress, the CLUT cache, FIFO and drawing time,
/// video timing, events not yet reported), not the tables derived from it for speed.
///
/// With the `serde` feature the whole state serializes; deserializing checks every field
/// against what the hardware can reach (`StateError`); `Gpu::save_state` adds a format
/// header and version (docs/emulator.md, "Save states").
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(try_from = "save::GpuFields")
)]
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Gpu {
    draw: DrawState,
    clut: ClutCache,
    texture_cache: TextureCache,
    gp0: gp0::Gp0State,
    read: transfer::ReadTransfer,
    display: DisplayState,
    gpuread_latch: u32,
    irq: bool,
    /// GP0(1Fh) raised the IRQ and `run` has not reported it yet.
    irq_event: bool,
    texture_disable_allowed: bool,
    drawing: drawing::Drawing,
    timing: timing::Timing,
    #[cfg_attr(feature = "serde", serde(skip))]
    host: host_cpu::HostCpu,
    /// Last, so the other fields lead a serialized state.
    vram: Vram,
}

impl Gpu {
    /// An NTSC GPU in its reset state with all-zero VRAM.
    pub fn new() -> Self {
        Self::with_standard(VideoStandard::Ntsc)
    }

    /// A GPU of a console of region `standard` at power-on: reset state, all-zero VRAM, the
    /// display mode of that standard (GP1(08h) bit 3 set for PAL) and its video clock.
    pub fn with_standard(standard: VideoStandard) -> Self {
        let mut display = DisplayState::default();
        if standard == VideoStandard::Pal {
            display.mode |= 0x08;
        }
        Self {
            vram: Vram::new(),
            draw: DrawState::default(),
            clut: ClutCache::default(),
            texture_cache: TextureCache::default(),
            gp0: gp0::Gp0State::default(),
            read: transfer::ReadTransfer::default(),
            display,
            gpuread_latch: 0,
            irq: false,
            irq_event: false,
            texture_disable_allowed: false,
            drawing: drawing::Drawing::default(),
            timing: timing::Timing::new(standard),
            host: host_cpu::HostCpu::detect(),
        }
    }

    /// The console region this GPU was built for (its video clock).
    pub fn video_standard(&self) -> VideoStandard {
        self.timing.standard()
    }

    /// Ask for the build of the textured triangles' span loops compiled for x86-64 with AVX2
    /// (`true`, the x86-64-v3 level: AVX2, BMI1, BMI2, FMA, LZCNT, POPCNT) or for the
    /// baseline instruction set; returns whether the AVX2 build now runs. It runs only where
    /// the host has those instructions, found at run time with the `std` feature (without
    /// it, or off x86-64, never). A new GPU starts with it wherever it can run. Both builds
    /// are the same source: the pixels, texture cache misses and drawing times are the
    /// same; only the host's time differs (docs/performance.md).
    pub fn set_avx2(&mut self, on: bool) -> bool {
        self.host.set_avx2(on)
    }

    /// Whether the textured triangles' span loops run in their AVX2 build ([`Gpu::set_avx2`]).
    pub fn avx2(&self) -> bool {
        self.host.avx2()
    }

    /// Advance time by `cpu_cycles` CPU cycles (33.8688 MHz) and report what happened: dot
    /// clocks and hblanks for the timers, vblank edges for IRQ0 (`docs/gpu.md`, "Video
    /// timing"). Any split of a span of time into calls reports the same totals.
    ///
    /// ```
    /// // One NTSC frame: 263 lines of 3413 GPU cycles, the GPU clock 11/7 of the CPU's
    /// // (docs/hardware/timing.md): 571,212 CPU cycles hold exactly one vblank start.
    /// let mut gpu = gpu::Gpu::new();
    /// let (mut vblanks, mut hblanks) = (0, 0);
    /// for _ in 0..1000 {
    ///     let ev = gpu.run(571);
    ///     vblanks += ev.vblank_start as u32;
    ///     hblanks += ev.hblanks;
    /// }
    /// let ev = gpu.run(212);
    /// vblanks += ev.vblank_start as u32;
    /// hblanks += ev.hblanks;
    /// assert_eq!((vblanks, hblanks), (1, 263));
    /// ```
    pub fn run(&mut self, cpu_cycles: u32) -> Events {
        let video = self.timing.convert(cpu_cycles);
        let mut events = self.timing.advance(video, &self.display.video_mode());
        let (gpu_irq, drawing_done) =
            self.advance_drawing(u32::try_from(video).unwrap_or(u32::MAX));
        events.gpu_irq = gpu_irq;
        events.drawing_done = drawing_done;
        events
    }

    /// CPU cycles until [`Gpu::run`] would report an event: an hblank or vblank edge, the GPU
    /// IRQ or the end of drawing (rounded up, so running exactly this many reaches it); 0 when
    /// one awaits delivery. Every line has an hblank, so one always comes within a line. Dot
    /// counts are not events ([`Gpu::cycles_until_dots`] gives their deadlines).
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// let n = gpu.cycles_until_next_event();
    /// assert!(n > 0 && !gpu.run(n - 1).any()); // nothing happens before it
    /// assert!(gpu.run(1).any());
    /// ```
    pub fn cycles_until_next_event(&self) -> u32 {
        let video = self
            .timing
            .cycles_until_next_event(&self.display.video_mode());
        match self.drawing_cycles_until_event() {
            None => video,
            Some(gpu) => video.min(self.timing.cpu_cycles_for(gpu as u64)),
        }
    }

    /// CPU cycles until the GPU has finished every command it has received (drawing, fills,
    /// copies, transfer units), counted from the clock [`Gpu::run`] keeps; 0 when it has
    /// nothing left to do.
    pub fn drawing_cycles_left(&self) -> u32 {
        let gpu = self
            .drawing
            .ahead()
            .saturating_add(self.drawing.cycles_until_idle());
        if gpu == 0 {
            0
        } else {
            self.timing.cpu_cycles_for(gpu as u64)
        }
    }

    /// Where the video beam is now: the scanline of the field, the video clock cycle in it,
    /// whether that lies in hblank or vblank, and the interlace field
    /// (docs/hardware/timing.md §2-§7). Timer synchronisation modes (pause or reset during
    /// hblank or vblank) read `hblank` and `vblank`; the edges come from [`Gpu::run`]'s
    /// [`Events`] and [`Gpu::cycles_until`]. After a GP1(08h) change that leaves the beam past
    /// the end of a now shorter field, the beam is at the start of the next field, where the
    /// next `run` continues.
    ///
    /// ```
    /// // NTSC at reset: 3413 video cycles a line, 11 for every 7 CPU cycles
    /// // (docs/hardware/timing.md §1, §2); 3000 CPU cycles are 4714 video cycles.
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.run(3000);
    /// let beam = gpu.beam();
    /// assert_eq!((beam.line, beam.cycle), (1, 4714 - 3413));
    /// assert!(!beam.hblank); // the GP1(06h) reset range shows cycles 512..3072
    /// assert!(beam.vblank); // the GP1(07h) reset range shows lines 16..256
    /// assert_eq!(beam.field, 0);
    /// ```
    pub fn beam(&self) -> Beam {
        self.timing.beam(&self.display.video_mode())
    }

    /// CPU cycles until [`Gpu::run`] would report an event of `kind`, rounded up: `run(n - 1)`
    /// does not report it, `run(n)` does (as long as no GP0/GP1 write changes the timing in
    /// between). 0 when a [`EventKind::DrawingDone`] awaits delivery; `u32::MAX` when none
    /// comes: no vblank edges while GP1(07h) Y2 lies past the last line or Y1 >= Y2, no
    /// drawing end while the GPU is idle. An emulator that only needs IRQ0 stops at
    /// `cycles_until(EventKind::VblankStart)` once a field instead of at every line's edges.
    ///
    /// ```
    /// use gpu::EventKind;
    /// let mut gpu = gpu::Gpu::new();
    /// // The first vblank starts at line 256 (GP1(07h) reset Y2): 256 * 3413 video cycles,
    /// // at 7 CPU cycles for 11 (docs/hardware/timing.md §1, §6).
    /// let n = gpu.cycles_until(EventKind::VblankStart);
    /// assert_eq!(n, (256 * 3413 * 7u32).div_ceil(11));
    /// assert!(!gpu.run(n - 1).vblank_start);
    /// assert!(gpu.run(1).vblank_start);
    /// // The next hblank starts at cycle 3072 of the line (GP1(06h) reset X2).
    /// let beam = gpu.beam();
    /// let n = gpu.cycles_until(EventKind::HblankStart);
    /// assert_eq!(n, ((3072 - beam.cycle) * 7).div_ceil(11));
    /// // Drawing: a 256x256 fill keeps the GPU busy; it ends within the frame.
    /// assert_eq!(gpu.cycles_until(EventKind::DrawingDone), u32::MAX); // idle
    /// gpu.gp0_words(&[0x0200_0000, 0, 256 << 16 | 256]);
    /// let n = gpu.cycles_until(EventKind::DrawingDone);
    /// assert!(n > 0 && n < 571_212);
    /// assert!(!gpu.run(n - 1).drawing_done);
    /// assert!(gpu.run(1).drawing_done);
    /// ```
    pub fn cycles_until(&self, kind: EventKind) -> u32 {
        match kind {
            EventKind::DrawingDone => {
                if self.drawing.done_pending() {
                    0
                } else if self.drawing.idle() {
                    u32::MAX
                } else {
                    let gpu = self
                        .drawing
                        .ahead()
                        .saturating_add(self.drawing.cycles_until_idle());
                    self.timing.cpu_cycles_for(gpu as u64)
                }
            }
            _ => self.timing.cycles_until(&self.display.video_mode(), kind),
        }
    }

    /// CPU cycles until [`Gpu::run`] has reported `dots` more dot clock ticks, rounded up: the
    /// deadline of timer 0 counting the dot clock to a target. The dot divider restarts at
    /// each line, so a line holds `cycles_per_line / divider` dots, rounded down
    /// (docs/hardware/timing.md §4); 0 for 0 dots. Valid while no GP1(08h) write changes the
    /// divider or the line length.
    ///
    /// ```
    /// // 320 wide (GP1(08h) = 1): 8 video cycles a dot, 426 dots a 3413-cycle NTSC line.
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp1(0x0800_0001);
    /// let n = gpu.cycles_until_dots(426);
    /// // Dot 426 of line 0 ticks at video cycle 426 * 8 = 3408, CPU cycle 3408 * 7 / 11.
    /// assert_eq!(n, (3408 * 7u32).div_ceil(11));
    /// assert_eq!(gpu.clone().run(n - 1).dots, 425);
    /// assert_eq!(gpu.run(n).dots, 426);
    /// ```
    pub fn cycles_until_dots(&self, dots: u32) -> u32 {
        self.timing
            .cycles_until_dots(&self.display.video_mode(), dots)
    }

    /// A block of GP0 words, each received as [`Gpu::gp0`] receives it, with no time passing:
    /// the words never wait for FIFO room (a FIFO overfilled this way holds the excess with
    /// the newest command). For timing, send words with [`Gpu::gp0`] or
    /// [`Gpu::dma_block_write`].
    pub fn gp0_words(&mut self, mut words: &[u32]) {
        while let Some((&first, rest)) = words.split_first() {
            let taken = self.gp0_packet(words);
            if taken == 0 {
                self.gp0_word(first);
                words = rest;
            } else {
                words = words.get(taken..).unwrap_or_default();
            }
        }
    }

    /// GPUREAD: the next two pixels of a VRAM-to-CPU transfer (GP0 C0h), or the latched
    /// value of the last GP1(10h) info read.
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.vram_mut().set_pixel(10, 20, 0x1234);
    /// gpu.vram_mut().set_pixel(11, 20, 0x5678);
    /// gpu.gp0_words(&[0xC000_0000, 20 << 16 | 10, 1 << 16 | 2]); // GP0(C0h): 2x1 at (10, 20)
    /// assert_ne!(gpu.gpustat() & 1 << 27, 0); // ready to send VRAM to the CPU
    /// assert_eq!(gpu.gpuread(), 0x5678_1234); // first pixel in the low half
    /// ```
    pub fn gpuread(&mut self) -> u32 {
        if self.read.active() {
            let word = self.read.next_word(&self.vram);
            self.gpuread_latch = word;
        }
        self.gpuread_latch
    }

    /// A CPU load from GPUREAD, timed: the word [`Gpu::gpuread`] returns and the CPU cycles
    /// the load waited for it. During a GP0(C0h) transfer the GPU fetches the rectangle from
    /// VRAM at its own rate (docs/emulator.md, "Drawing time"), and a load of a word not yet
    /// fetched waits: the drawing side runs ahead through the wait, which the caller adds to
    /// the CPU's time and passes to [`Gpu::run`] as usual.
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp0_words(&[0xC000_0000, 0, 1 << 16 | 64]); // GP0(C0h): 64x1, 32 words
    /// let (_, wait) = gpu.gpuread_timed();
    /// assert!(wait > 0); // the first word was not fetched yet: the load waited
    /// gpu.run(wait); // the CPU's time passes as usual (the GPU side is not run twice)
    /// gpu.run(1_000); // far longer than fetching 32 words
    /// assert_eq!(gpu.gpuread_timed().1, 0); // every word is there
    /// ```
    pub fn gpuread_timed(&mut self) -> (u32, u32) {
        let wait = self.wait_for_read();
        (self.gpuread(), self.gpu_to_cpu_cycles(wait))
    }

    /// Run the drawing side until the next GPUREAD word of a VRAM-to-CPU transfer is
    /// fetched; returns the GPU cycles waited.
    pub(crate) fn wait_for_read(&mut self) -> u32 {
        let wait = self
            .read
            .cycles_until_ready(self.drawing.cycles_until_idle());
        self.drawing.run_ahead(wait);
        wait
    }

    /// GPU cycles in CPU cycles at this console's clock ratio, rounded up.
    pub(crate) fn gpu_to_cpu_cycles(&self, gpu: u32) -> u32 {
        let (num, den) = drawing::clock_ratio(self.timing.standard());
        u32::try_from((gpu as u64 * den).div_ceil(num)).unwrap_or(u32::MAX)
    }

    /// GPU cycles of all the work the GPU has received since power-on: every command's
    /// modelled time (drawing, fills, copies, transfers), whether or not it has run yet. The
    /// difference across a command is that command's time; debuggers and profilers show it
    /// per draw (docs/emulator.md, "Drawing time").
    pub fn work_cycles(&self) -> u64 {
        self.drawing.total()
    }

    /// The GPU interrupt line, GPUSTAT.24: set by GP0(1Fh), cleared by GP1(02h) (psx-spx
    /// "GPU Other Commands").
    pub fn irq_pending(&self) -> bool {
        self.irq
    }

    /// VRAM.
    pub fn vram(&self) -> &Vram {
        &self.vram
    }

    /// VRAM, mutable (for loading state or tests). Texels the texture cache holds keep the
    /// values they were loaded with, as after any other write (docs/gpu.md, "Texture cache").
    pub fn vram_mut(&mut self) -> &mut Vram {
        self.texture_cache.keep_copies(self.vram.as_array());
        &mut self.vram
    }

    /// The drawing environment set by E1-E6.
    pub fn draw_state(&self) -> &DrawState {
        &self.draw
    }

    /// The display state set by GP1.
    pub fn display_state(&self) -> &DisplayState {
        &self.display
    }

    /// Whether textured primitives read their texels through the texture cache (on at
    /// power-on; docs/gpu.md, "Texture cache").
    pub fn texture_cache_enabled(&self) -> bool {
        self.texture_cache.enabled()
    }

    /// Turn the texture cache on or off (docs/gpu.md, "Texture cache"); either way it starts
    /// empty. On, as on the console, texels are read through the 2 KB cache
    /// (docs/hardware/gpu.md §10): VRAM drawn or filled under cached texels is not seen until
    /// the cache reloads them, and each miss adds to the drawing time. Off, texels are read
    /// straight from VRAM and misses cost nothing.
    ///
    /// ```
    /// let mut gpu = gpu::Gpu::new();
    /// gpu.gp0_words(&[0xE300_0000, 0xE407_FFFF, 0xE500_0000]); // draw anywhere, no offset
    /// gpu.gp0(0xE100_0108); // texture page (512, 0), 15-bit
    /// let fill = |rgb: u32| [0x0200_0000 | rgb, 512, 1 << 16 | 16]; // GP0(02h): 16x1 at (512, 0)
    /// let sprite = [0x6D00_0000, 0, 0]; // GP0(6Dh): 1x1 raw-textured sprite at (0, 0), UV (0, 0)
    /// gpu.gp0_words(&fill(0x00FF00)); // green
    /// gpu.gp0_words(&sprite);
    /// assert_eq!(gpu.vram().pixel(0, 0), 0x03E0); // the texel, loaded into the cache
    /// gpu.gp0_words(&fill(0xFF0000)); // blue: a fill leaves the cache as it is
    /// gpu.gp0_words(&sprite);
    /// assert_eq!(gpu.vram().pixel(0, 0), 0x03E0); // the cached (stale) green texel
    /// gpu.set_texture_cache(false);
    /// gpu.gp0_words(&sprite);
    /// assert_eq!(gpu.vram().pixel(0, 0), 0x7C00); // off: VRAM as it is now
    /// ```
    pub fn set_texture_cache(&mut self, on: bool) {
        self.texture_cache.set_enabled(on);
    }

    /// Texture cache misses since power-on (docs/gpu.md, "Texture cache"): the difference
    /// before and after a command is that command's count. Nothing is counted while the cache
    /// is off.
    pub fn texture_cache_misses(&self) -> u64 {
        self.texture_cache.total_misses()
    }

    /// Texture cache entry `index` (0-255), for debuggers: where its four halfwords were
    /// loaded from and their values then; `None` when the entry holds nothing (and always
    /// while the cache is off). Entries are numbered as docs/hardware/gpu.md §10 describes.
    pub fn texture_cache_entry(&self, index: u8) -> Option<TextureCacheEntry> {
        self.texture_cache.entry(index, self.vram.as_array())
    }

    /// The display area the current GP1 state selects (docs/hardware/gpu.md §9): position, size in
    /// pixels from the display ranges, colour depth ([`DisplayState::area`]).
    pub fn display_area(&self) -> DisplayArea {
        self.display.area()
    }
}

impl Default for Gpu {
    fn default() -> Self {
        Self::new()
    }
}
