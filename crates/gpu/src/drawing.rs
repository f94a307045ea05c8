//! Drawing time and the GP0 command FIFO (docs/emulator.md, "Drawing time, FIFO and DMA").
//!
//! Commands still execute into VRAM the moment their last word arrives; this module keeps the
//! time they would take on the console. Each command (or, for long commands, each unit the
//! GPU consumes: one CPU-to-VRAM data word, one polyline vertex) gets a cost from [`Cost`].
//! While the GPU is busy, arriving words wait in the 16-word FIFO (psx-spx "GPU I/O Ports":
//! "a 64-byte (16-word) command FIFO buffer"); the queue below replays that: the GPU pulls
//! the next unit once the current one's time is spent.
//!
//! Costs are counted in draw units of 1/256 CPU cycle and converted to GPU cycles at the
//! console's own clock ratio (docs/hardware/timing.md §1), the fraction of a cycle carried to
//! the next unit, so that a long run of small units keeps the exact total.

use crate::VideoStandard;
use crate::rasterizer::DrawCount;

/// Words the GP0 FIFO holds (psx-spx "GPU I/O Ports").
pub(crate) const FIFO_WORDS: u32 = 16;

/// Queue entries kept; a command needs at least one FIFO word, so 16 are enough unless the
/// FIFO is overfilled, in which case the newest entries merge.
const QUEUE_LEN: usize = FIFO_WORDS as usize;

/// Draw units per CPU cycle.
pub(crate) const UNITS_PER_CYCLE: u32 = 256;

/// GPU clock over CPU clock of each console, reduced (docs/hardware/timing.md §1): NTSC 11/7,
/// PAL 53,203,425 / 33,868,800.
const NTSC_RATIO: (u64, u64) = VideoStandard::Ntsc.clock_ratio();
const PAL_RATIO: (u64, u64) = VideoStandard::Pal.clock_ratio();

/// The GPU-to-CPU clock ratio of `standard`'s console.
pub(crate) const fn clock_ratio(standard: VideoStandard) -> (u64, u64) {
    match standard {
        VideoStandard::Ntsc => NTSC_RATIO,
        VideoStandard::Pal => PAL_RATIO,
    }
}

/// `cycles` CPU cycles in draw units, saturating.
pub(crate) const fn cycles(cycles: u32) -> u32 {
    cycles.saturating_mul(UNITS_PER_CYCLE)
}

/// The drawing-cost model, in draw units (1/256 CPU cycle). docs/emulator.md, "Drawing time",
/// gives the table with the source of every figure: the per-pixel, per-row, read-back,
/// texture-miss, fill, copy and transfer figures are calibrated against a console (ps1-tests
/// `gpu/bandwidth`, docs/hardware/timing.md §12); the set-up figures are Mednafen's.
pub(crate) struct Cost;

impl Cost {
    /// Polygon set-up of a triangle, or of the first triangle of a quad (Mednafen: 41 CPU
    /// cycles).
    pub const TRIANGLE_SETUP: u32 = cycles(41);
    /// Set-up of the second triangle of a quad (Mednafen: 23 CPU cycles).
    pub const QUAD_SECOND_SETUP: u32 = cycles(23);
    /// Extra set-up per triangle: Gouraud and textured (Mednafen).
    pub const GOURAUD_TEXTURED_SETUP: u32 = cycles(225);
    /// Extra set-up per triangle: Gouraud only (Mednafen).
    pub const GOURAUD_SETUP: u32 = cycles(144);
    /// Extra set-up per triangle: textured only (Mednafen).
    pub const TEXTURED_SETUP: u32 = cycles(90);
    /// Each pixel a triangle or rectangle writes (calibrated: Rectangle, Polygon quad).
    pub const PIXEL: u32 = 136;
    /// Each row a triangle or rectangle walks inside the drawing area (calibrated:
    /// Rectangle, Polygon quad).
    pub const ROW: u32 = 615;
    /// Each even-aligned pixel pair a blending or mask-checking span reads back
    /// (calibrated: Rectangle (semitransparent)).
    pub const PAIR: u32 = 140;
    /// Extra per pixel of a Gouraud-shaded or textured triangle (Mednafen: half a cycle).
    pub const SHADED_PIXEL: u32 = UNITS_PER_CYCLE / 2;
    /// Rectangle set-up (Mednafen).
    pub const RECTANGLE_SETUP: u32 = cycles(8);
    /// Line (and polyline segment) set-up (Mednafen's sprite figure).
    pub const LINE_SETUP: u32 = cycles(8);
    /// Per step along a line's major axis (Mednafen).
    pub const LINE_STEP: u32 = cycles(1);
    /// Fill set-up (Mednafen).
    pub const FILL_SETUP: u32 = cycles(23);
    /// Fill, per 16 pixels of a row (Mednafen).
    pub const FILL_16_PIXELS: u32 = cycles(1);
    /// Fill, per row (calibrated: FillScreen GP0(2)).
    pub const FILL_ROW: u32 = 1870;
    /// VRAM-to-VRAM copy, per pixel (calibrated: vramToVram).
    pub const COPY_PIXEL: u32 = 347;
    /// CPU-to-VRAM transfer, per data word: two pixels at [`Cost::PIXEL`] each.
    pub const WRITE_WORD: u32 = 2 * Self::PIXEL;
    /// VRAM-to-CPU transfer, per word the GPU fetches for GPUREAD (calibrated: vramToCpu).
    pub const READ_WORD: u32 = 570;
    /// Each CLUT entry loaded into the CLUT cache (Mednafen: half a cycle).
    pub const CLUT_ENTRY: u32 = UNITS_PER_CYCLE / 2;

    /// One triangle: set-up, then per row walked, per pixel drawn, per shaded (Gouraud or
    /// textured) pixel and per pixel pair read back when blending or mask-checking. A
    /// primitive walks at most 1024 rows and draws at most 1024 x 512 pixels, so the sum stays
    /// under 2^28 and the wrapping arithmetic never wraps.
    #[inline(always)]
    pub fn triangle(
        second_of_quad: bool,
        gouraud: bool,
        textured: bool,
        read_back: bool,
        drawn: DrawCount,
    ) -> u32 {
        let setup = if second_of_quad {
            Self::QUAD_SECOND_SETUP
        } else {
            Self::TRIANGLE_SETUP
        };
        let shading = match (gouraud, textured) {
            (true, true) => Self::GOURAUD_TEXTURED_SETUP,
            (true, false) => Self::GOURAUD_SETUP,
            (false, true) => Self::TEXTURED_SETUP,
            (false, false) => 0,
        };
        let shaded = if gouraud || textured { drawn.pixels } else { 0 };
        setup
            .wrapping_add(shading)
            .wrapping_add(Self::span_work(read_back, drawn))
            .wrapping_add(shaded.wrapping_mul(Self::SHADED_PIXEL))
    }

    /// Rows, pixels and read-back pairs (bounded as for [`Cost::triangle`]).
    #[inline(always)]
    fn span_work(read_back: bool, drawn: DrawCount) -> u32 {
        let pairs = if read_back { drawn.pairs } else { 0 };
        drawn
            .rows
            .wrapping_mul(Self::ROW)
            .wrapping_add(drawn.pixels.wrapping_mul(Self::PIXEL))
            .wrapping_add(pairs.wrapping_mul(Self::PAIR))
    }

    /// One rectangle: set-up, per row walked, per pixel drawn, and per pixel pair read back
    /// when blending or mask-checking (bounded as for [`Cost::triangle`]). A textured
    /// rectangle pays nothing per texel beyond its texture cache misses: Mednafen's sprite
    /// path charges a sprite's row its width alone (plus the read-back), where its polygon
    /// path charges a textured or shaded triangle's row twice its width.
    #[inline(always)]
    pub fn rectangle(read_back: bool, drawn: DrawCount) -> u32 {
        Self::RECTANGLE_SETUP.wrapping_add(Self::span_work(read_back, drawn))
    }

    /// One line segment: set-up and each step along the major axis (the points stepped
    /// minus one; at most 2047 steps).
    #[inline(always)]
    pub fn line(drawn: DrawCount) -> u32 {
        Self::LINE_SETUP.wrapping_add(drawn.pixels.saturating_sub(1).wrapping_mul(Self::LINE_STEP))
    }

    /// GP0(02h) over `width` (already rounded to 16) x `height`.
    pub fn fill(width: u32, height: u32) -> u32 {
        let row = (width / 16) * Self::FILL_16_PIXELS + Self::FILL_ROW;
        Self::FILL_SETUP.saturating_add(height.saturating_mul(row))
    }

    /// GP0(80h) over `pixels`.
    pub fn copy(pixels: u32) -> u32 {
        pixels.saturating_mul(Self::COPY_PIXEL)
    }

    /// Loading `entries` CLUT entries into the CLUT cache.
    pub fn clut_load(entries: u32) -> u32 {
        entries.saturating_mul(Self::CLUT_ENTRY)
    }

    /// Per texture cache miss (docs/hardware/gpu.md §10), 8.81 CPU cycles (calibrated:
    /// Polygon quad textured, whose 15-bit page stretched across 320x240 misses on about one
    /// texel in five). Mednafen charges 2 CPU cycles and its comment gives the console as
    /// 12 + 4 GPU cycles for sprites; this figure is 13.8 GPU cycles.
    pub const TEXTURE_MISS: u32 = 2255;

    /// `misses` texture cache misses.
    pub fn texture_misses(misses: u32) -> u32 {
        misses.saturating_mul(Self::TEXTURE_MISS)
    }
}

/// One unit of work waiting in the FIFO: the words it occupies and its time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Queued {
    words: u32,
    cycles: u32,
}

/// Drawing-busy time and FIFO occupancy, in GPU cycles.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Drawing {
    /// GPU cycles left on the unit being executed.
    busy: u32,
    /// Units received while busy, oldest first (ring buffer).
    queue: [Queued; QUEUE_LEN],
    head: usize,
    len: usize,
    /// Words in the FIFO: queued units plus the received part of the next one.
    fifo_words: u32,
    /// Words of the incomplete unit that are waiting in the FIFO.
    partial_words: u32,
    /// GPU cycles the drawing side has already been run past the clock (while a DMA waited
    /// for FIFO room); the next `advance` calls skip them.
    ahead: u32,
    /// The GPU went from busy to idle and `run` has not reported it yet.
    done_pending: bool,
    /// What the conversion of draw units to GPU cycles has carried over: a fraction of a
    /// GPU cycle, in units of 1 / (256 x the clock ratio's denominator).
    #[cfg_attr(feature = "serde", serde(default))]
    carry: u64,
    /// GPU cycles of every unit received so far.
    #[cfg_attr(feature = "serde", serde(default))]
    total: u64,
}

/// [`Drawing`] as save-state version 1 wrote it: without the carried fraction and the work
/// counter, which load as 0 (the state was saved before either was kept).
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
pub(crate) struct DrawingV1 {
    busy: u32,
    queue: [Queued; QUEUE_LEN],
    head: usize,
    len: usize,
    fifo_words: u32,
    partial_words: u32,
    ahead: u32,
    done_pending: bool,
}

#[cfg(feature = "serde")]
impl From<DrawingV1> for Drawing {
    fn from(d: DrawingV1) -> Self {
        Drawing {
            busy: d.busy,
            queue: d.queue,
            head: d.head,
            len: d.len,
            fifo_words: d.fifo_words,
            partial_words: d.partial_words,
            ahead: d.ahead,
            done_pending: d.done_pending,
            carry: 0,
            total: 0,
        }
    }
}

impl Drawing {
    /// Nothing is executing and nothing is queued.
    pub fn idle(&self) -> bool {
        self.busy == 0 && self.len == 0
    }

    /// The queue indices are in range, the FIFO word count is the queued units' words plus
    /// the partial unit's, and an idle GPU holds no words.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        if self.head >= QUEUE_LEN || self.len > QUEUE_LEN {
            return Err("drawing queue index out of range");
        }
        let queued = (0..self.len).try_fold(self.partial_words, |acc, i| {
            let q = self.queue.get((self.head + i) % QUEUE_LEN)?;
            acc.checked_add(q.words)
        });
        if queued != Some(self.fifo_words) {
            return Err("FIFO word count differs from the queued units");
        }
        if self.idle() && self.fifo_words != 0 {
            return Err("idle GPU with words in the FIFO");
        }
        if self.carry >= PAL_RATIO.1.max(NTSC_RATIO.1) * UNITS_PER_CYCLE as u64 {
            return Err("drawing-time carry of a whole GPU cycle or more");
        }
        Ok(())
    }

    /// Words waiting in the FIFO.
    pub fn fifo_words(&self) -> u32 {
        self.fifo_words
    }

    /// A complete unit is waiting behind the executing one.
    pub fn unit_queued(&self) -> bool {
        self.len != 0
    }

    /// A GP0 word arrived; `takes_space` is false for the commands psx-spx lists as not
    /// using FIFO space (GP0(00h), 04h-1Eh, E0h, E3h-E5h, E7h-EFh).
    pub fn receive(&mut self, takes_space: bool) {
        if takes_space && !self.idle() {
            self.partial_words += 1;
            self.fifo_words += 1;
        }
    }

    /// `n` GP0 words of one command arrived and form a unit costing `units` draw units: `n`
    /// calls of [`Drawing::receive`], then [`Drawing::complete`]. Returns the unit's GPU
    /// cycles.
    pub fn receive_unit(
        &mut self,
        takes_space: bool,
        n: u32,
        units: u32,
        standard: VideoStandard,
    ) -> u32 {
        let queued = if takes_space && !self.idle() { n } else { 0 };
        self.fifo_words += queued;
        let words = core::mem::take(&mut self.partial_words) + queued;
        let cycles = self.convert(units, standard);
        self.complete_words(words, cycles);
        cycles
    }

    /// The words received since the previous unit form a unit costing `units` draw units.
    /// Returns the unit's GPU cycles.
    pub fn complete(&mut self, units: u32, standard: VideoStandard) -> u32 {
        let words = core::mem::take(&mut self.partial_words);
        let cycles = self.convert(units, standard);
        self.complete_words(words, cycles);
        cycles
    }

    /// `units` draw units in GPU cycles at the clock ratio of `standard`'s console, the
    /// fraction left over carried to the next call; counted in [`Drawing::total`]. Each
    /// console's ratio is a constant, so the divisions are by constants.
    #[inline(always)]
    fn convert(&mut self, units: u32, standard: VideoStandard) -> u32 {
        const NTSC_PER_CYCLE: u64 = NTSC_RATIO.1 * UNITS_PER_CYCLE as u64;
        const PAL_PER_CYCLE: u64 = PAL_RATIO.1 * UNITS_PER_CYCLE as u64;
        match standard {
            VideoStandard::Ntsc => self.convert_at::<{ NTSC_RATIO.0 }, NTSC_PER_CYCLE>(units),
            VideoStandard::Pal => self.convert_at::<{ PAL_RATIO.0 }, PAL_PER_CYCLE>(units),
        }
    }

    /// [`Drawing::convert`] at `NUM` GPU cycles per `PER_CYCLE` draw units.
    #[inline(always)]
    fn convert_at<const NUM: u64, const PER_CYCLE: u64>(&mut self, units: u32) -> u32 {
        let scaled = units as u64 * NUM + self.carry;
        self.carry = scaled % PER_CYCLE;
        let cycles = u32::try_from(scaled / PER_CYCLE).unwrap_or(u32::MAX);
        self.total = self.total.saturating_add(cycles as u64);
        cycles
    }

    /// The words received since the previous unit form a unit of `cycles` GPU cycles.
    #[cfg(test)]
    fn complete_gpu(&mut self, cycles: u32) {
        let words = core::mem::take(&mut self.partial_words);
        self.complete_words(words, cycles);
    }

    /// GPU cycles of every unit received since power-on (or the last GP1(00h)).
    pub fn total(&self) -> u64 {
        self.total
    }

    /// `words` FIFO words form a unit costing `cycles`.
    #[inline(always)]
    fn complete_words(&mut self, words: u32, cycles: u32) {
        if self.idle() {
            self.fifo_words -= words.min(self.fifo_words);
            self.busy = cycles;
            return;
        }
        if words == 0 && cycles == 0 {
            return;
        }
        let unit = Queued { words, cycles };
        if self.len < QUEUE_LEN {
            let slot = (self.head + self.len) % QUEUE_LEN;
            if let Some(q) = self.queue.get_mut(slot) {
                *q = unit;
            }
            self.len += 1;
        } else {
            let last = (self.head + QUEUE_LEN - 1) % QUEUE_LEN;
            if let Some(q) = self.queue.get_mut(last) {
                q.words += unit.words;
                q.cycles = q.cycles.saturating_add(unit.cycles);
            }
        }
    }

    /// Let `gpu_cycles` GPU cycles pass; returns whether the GPU went from busy to idle.
    pub fn advance(&mut self, gpu_cycles: u32) -> bool {
        let skip = self.ahead.min(gpu_cycles);
        self.ahead -= skip;
        self.run_for(gpu_cycles - skip)
    }

    /// Run the drawing side `gpu_cycles` ahead of the clock (a DMA waiting for room); the
    /// following `advance` calls skip that time.
    pub fn run_ahead(&mut self, gpu_cycles: u32) {
        self.ahead = self.ahead.saturating_add(gpu_cycles);
        if self.run_for(gpu_cycles) {
            self.done_pending = true;
        }
    }

    fn run_for(&mut self, mut t: u32) -> bool {
        let was_busy = !self.idle();
        loop {
            if self.busy > t {
                self.busy -= t;
                break;
            }
            t -= self.busy;
            self.busy = 0;
            if self.len == 0 {
                // The rest of an incomplete unit goes straight to the command buffer.
                self.fifo_words -= self.partial_words.min(self.fifo_words);
                self.partial_words = 0;
                break;
            }
            let unit = self.queue.get(self.head).copied().unwrap_or_default();
            self.head = (self.head + 1) % QUEUE_LEN;
            self.len -= 1;
            self.fifo_words -= unit.words.min(self.fifo_words);
            self.busy = unit.cycles;
        }
        was_busy && self.idle()
    }

    /// GPU cycles until everything received so far has executed.
    pub fn cycles_until_idle(&self) -> u32 {
        self.queued_cycles(self.len)
    }

    /// GPU cycles until the executing unit and the first `n` queued ones are done.
    fn queued_cycles(&self, n: usize) -> u32 {
        (0..n.min(self.len)).fold(self.busy, |acc, i| {
            let q = self.queue.get((self.head + i) % QUEUE_LEN);
            acc.saturating_add(q.map_or(0, |q| q.cycles))
        })
    }

    /// GPU cycles until the FIFO can take one more word (0 when it can now).
    pub fn cycles_until_room(&self) -> u32 {
        if self.fifo_words < FIFO_WORDS || self.idle() {
            return 0;
        }
        // Unit n leaves the FIFO when it starts: after the executing unit and units 0..n.
        let mut words = self.fifo_words;
        for n in 0..self.len {
            let q = self.queue.get((self.head + n) % QUEUE_LEN);
            words -= q.map_or(0, |q| q.words).min(words);
            if words < FIFO_WORDS {
                return self.queued_cycles(n);
            }
        }
        self.cycles_until_idle()
    }

    /// GPU cycles the drawing side has been run ahead of the clock.
    pub fn ahead(&self) -> u32 {
        self.ahead
    }

    /// A busy-to-idle transition awaits delivery; `take` clears it.
    pub fn take_done(&mut self) -> bool {
        core::mem::take(&mut self.done_pending)
    }

    /// Whether a busy-to-idle transition awaits delivery.
    pub fn done_pending(&self) -> bool {
        self.done_pending
    }

    /// Record a busy-to-idle transition for the next report.
    pub fn set_done(&mut self) {
        self.done_pending = true;
    }

    /// GP1(01h): queued and partly received units are dropped; the executing one finishes.
    pub fn clear_fifo(&mut self) {
        *self = Self {
            busy: self.busy,
            ahead: self.ahead,
            done_pending: self.done_pending,
            carry: self.carry,
            total: self.total,
            ..Self::default()
        };
    }
}

impl crate::Gpu {
    /// Advance the drawing side by `gpu_cycles` GPU cycles; returns (GP0(1Fh) raised the IRQ,
    /// the GPU went from busy to idle) since the previous call, each reported once.
    pub(crate) fn advance_drawing(&mut self, gpu_cycles: u32) -> (bool, bool) {
        if self.drawing.advance(gpu_cycles) {
            self.drawing.set_done();
        }
        let irq = core::mem::take(&mut self.irq_event);
        (irq, self.drawing.take_done())
    }

    /// GPU cycles until [`crate::Gpu::advance_drawing`] would report something: 0 while a
    /// report is pending, the time to idle (counted from the clock, so including time a DMA
    /// ran ahead) while drawing, `None` when idle.
    pub(crate) fn drawing_cycles_until_event(&self) -> Option<u32> {
        if self.irq_event || self.drawing.done_pending() {
            Some(0)
        } else if self.drawing.idle() {
            None
        } else {
            Some(
                self.drawing
                    .ahead()
                    .saturating_add(self.drawing.cycles_until_idle()),
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_conversion_matches_the_clock_ratio() {
        assert_eq!(clock_ratio(VideoStandard::Ntsc), (11, 7));
        let ntsc = VideoStandard::Ntsc;
        let mut d = Drawing::default();
        // 7 CPU cycles = 11 GPU cycles exactly, nothing carried.
        assert_eq!(d.convert(cycles(7), ntsc), 11);
        assert_eq!(d.carry, 0);
        // Half a CPU cycle is 11/14 GPU cycle: 0 now, the fraction carried; fourteen of them
        // make 11 cycles in all.
        assert_eq!(d.convert(128, ntsc), 0);
        let sum: u32 = (0..13).map(|_| d.convert(128, ntsc)).sum();
        assert_eq!(sum, 11);
        assert_eq!(d.carry, 0);
        assert_eq!(d.total(), 22);
        // PAL: 451,584 CPU cycles are 709,379 GPU cycles.
        assert_eq!(clock_ratio(VideoStandard::Pal), (709_379, 451_584));
        let mut d = Drawing::default();
        assert_eq!(d.convert(cycles(451_584), VideoStandard::Pal), 709_379);
        assert_eq!(d.carry, 0);
    }

    #[test]
    fn idle_gpu_takes_words_without_filling_the_fifo() {
        let mut d = Drawing::default();
        for _ in 0..3 {
            d.receive(true);
        }
        d.complete(cycles(7000), VideoStandard::Ntsc);
        assert_eq!(d.fifo_words(), 0);
        assert_eq!(d.cycles_until_idle(), 11000);
        assert!(!d.idle());
    }

    #[test]
    fn words_queue_while_busy_and_drain_in_order() {
        let mut d = Drawing::default();
        d.receive(true);
        d.complete_gpu(100);
        // Two 3-word units behind it.
        for cost in [50, 70] {
            for _ in 0..3 {
                d.receive(true);
            }
            d.complete_gpu(cost);
        }
        assert_eq!(d.fifo_words(), 6);
        assert_eq!(d.cycles_until_idle(), 220);
        assert!(!d.advance(99));
        assert_eq!(d.fifo_words(), 6);
        // At 100 the first queued unit leaves the FIFO.
        assert!(!d.advance(1));
        assert_eq!(d.fifo_words(), 3);
        assert!(!d.advance(50));
        assert_eq!(d.fifo_words(), 0);
        assert_eq!(d.cycles_until_idle(), 70);
        assert!(d.advance(1000));
        assert!(d.idle());
    }

    #[test]
    fn words_that_take_no_space_never_count() {
        let mut d = Drawing::default();
        d.receive(true);
        d.complete_gpu(10);
        d.receive(false);
        d.complete_gpu(0);
        assert_eq!(d.fifo_words(), 0);
        assert!(!d.unit_queued());
    }

    #[test]
    fn room_appears_when_enough_units_leave() {
        let mut d = Drawing::default();
        d.complete_gpu(10);
        // Four 4-word units fill the FIFO.
        for cost in [1, 2, 3, 4] {
            for _ in 0..4 {
                d.receive(true);
            }
            d.complete_gpu(cost);
        }
        assert_eq!(d.fifo_words(), 16);
        // The executing unit (10) must finish, then the first queued unit is pulled.
        assert_eq!(d.cycles_until_room(), 10);
        d.run_ahead(10);
        assert_eq!(d.fifo_words(), 12);
        assert_eq!(d.cycles_until_room(), 0);
        // The run-ahead time is skipped by the next advance.
        assert!(!d.advance(10));
        assert_eq!(d.cycles_until_idle(), 1 + 2 + 3 + 4);
    }

    #[test]
    fn fifo_clear_keeps_the_executing_unit() {
        let mut d = Drawing::default();
        d.complete_gpu(10);
        d.receive(true);
        d.complete_gpu(5);
        d.clear_fifo();
        assert_eq!(d.fifo_words(), 0);
        assert_eq!(d.cycles_until_idle(), 10);
    }
}
