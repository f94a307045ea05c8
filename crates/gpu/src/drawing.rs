//! Drawing time and the GP0 command FIFO (docs/emulator.md, "Drawing time, FIFO and DMA").
//!
//! Commands still execute into VRAM the moment their last word arrives; this module keeps the
//! time they would take on the console. Each command (or, for long commands, each unit the
//! GPU consumes: one CPU-to-VRAM data word, one polyline vertex) gets a cost in GPU clock
//! cycles from [`Cost`]. While the GPU is busy, arriving words wait in the 16-word FIFO
//! (psx-spx "GPU I/O Ports": "a 64-byte (16-word) command FIFO buffer"); the queue below
//! replays that: the GPU pulls the next unit once the current one's time is spent.
//!
//! Costs are counted in draw units of half a CPU cycle (the unit of Mednafen's drawing-time
//! accounting, which gains two units per CPU cycle) and converted once per command to GPU
//! cycles at the NTSC clock ratio, rounded up.

use crate::rasterizer::DrawCount;

/// Words the GP0 FIFO holds (psx-spx "GPU I/O Ports").
pub(crate) const FIFO_WORDS: u32 = 16;

/// Queue entries kept; a command needs at least one FIFO word, so 16 are enough unless the
/// FIFO is overfilled, in which case the newest entries merge.
const QUEUE_LEN: usize = FIFO_WORDS as usize;

/// GPU clock over two CPU clocks: 11/14, the NTSC console's 11/7 ratio
/// (docs/hardware/timing.md §1; PAL's clock is within 0.04% of it, inside this model's error).
const UNIT_TO_GPU: (u64, u64) = (11, 14);

/// Draw units (half CPU cycles) to GPU cycles, rounded up, saturating at `u32::MAX`.
pub(crate) fn units_to_gpu(units: u64) -> u32 {
    let (num, den) = UNIT_TO_GPU;
    let cycles = units.saturating_mul(num).div_ceil(den);
    u32::try_from(cycles).unwrap_or(u32::MAX)
}

/// The drawing-cost model, in draw units (half CPU cycles). See docs/emulator.md for the
/// table and its sources; every figure there is approximate.
pub(crate) struct Cost;

impl Cost {
    /// Polygon set-up of a triangle, or of the first triangle of a quad.
    pub const TRIANGLE_SETUP: u32 = 64 + 18;
    /// Set-up of the second triangle of a quad.
    pub const QUAD_SECOND_SETUP: u32 = 28 + 18;
    /// Extra set-up per triangle: Gouraud and textured.
    pub const GOURAUD_TEXTURED_SETUP: u32 = 150 * 3;
    /// Extra set-up per triangle: Gouraud only.
    pub const GOURAUD_SETUP: u32 = 96 * 3;
    /// Extra set-up per triangle: textured only.
    pub const TEXTURED_SETUP: u32 = 60 * 3;
    /// Rectangle set-up.
    pub const RECTANGLE_SETUP: u32 = 16;
    /// Line (and polyline segment) set-up.
    pub const LINE_SETUP: u32 = 16;
    /// Per step along a line's major axis.
    pub const LINE_STEP: u32 = 2;
    /// Fill set-up.
    pub const FILL_SETUP: u32 = 46;
    /// Fill, per row, on top of width / 8.
    pub const FILL_ROW: u32 = 9;
    /// VRAM-to-VRAM copy, per pixel.
    pub const COPY_PIXEL: u32 = 2;
    /// CPU-to-VRAM transfer, per data word (two pixels).
    pub const WRITE_WORD: u32 = 2;

    /// One triangle: set-up, then per drawn pixel 1, plus 1 more when Gouraud-shaded or
    /// textured, else half a unit per pixel pair when blending or mask-checking.
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
        let extra = if gouraud || textured {
            drawn.pixels
        } else if read_back {
            drawn.pairs
        } else {
            0
        };
        setup
            .saturating_add(shading)
            .saturating_add(drawn.pixels)
            .saturating_add(extra)
    }

    /// One rectangle: set-up, per drawn pixel 1, plus half a unit per pixel pair when
    /// blending or mask-checking.
    pub fn rectangle(read_back: bool, drawn: DrawCount) -> u32 {
        let extra = if read_back { drawn.pairs } else { 0 };
        Self::RECTANGLE_SETUP
            .saturating_add(drawn.pixels)
            .saturating_add(extra)
    }

    /// One line segment of `steps` major-axis steps (the drawn points minus one).
    pub fn line(drawn: DrawCount) -> u32 {
        Self::LINE_SETUP.saturating_add(drawn.pixels.saturating_sub(1) * Self::LINE_STEP)
    }

    /// GP0(02h) over `width` (already rounded to 16) x `height`.
    pub fn fill(width: u32, height: u32) -> u32 {
        Self::FILL_SETUP + height * (width / 8 + Self::FILL_ROW)
    }

    /// GP0(80h) over `pixels`.
    pub fn copy(pixels: u32) -> u32 {
        pixels.saturating_mul(Self::COPY_PIXEL)
    }

    /// Loading `entries` CLUT entries into the CLUT cache.
    pub fn clut_load(entries: u32) -> u32 {
        entries
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

    /// `n` GP0 words of one command arrived and form a unit costing `cycles`: `n` calls of
    /// [`Drawing::receive`], then [`Drawing::complete`].
    pub fn receive_unit(&mut self, takes_space: bool, n: u32, cycles: u32) {
        let queued = if takes_space && !self.idle() { n } else { 0 };
        self.fifo_words += queued;
        let words = core::mem::take(&mut self.partial_words) + queued;
        self.complete_words(words, cycles);
    }

    /// The words received since the previous unit form a unit costing `cycles`.
    pub fn complete(&mut self, cycles: u32) {
        let words = core::mem::take(&mut self.partial_words);
        self.complete_words(words, cycles);
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
        let busy = self.busy;
        let ahead = self.ahead;
        let done = self.done_pending;
        *self = Self::default();
        self.busy = busy;
        self.ahead = ahead;
        self.done_pending = done;
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
        // 14 units = 7 CPU cycles = 11 GPU cycles exactly.
        assert_eq!(units_to_gpu(14), 11);
        // One unit is 0.79 GPU cycles: rounds up to 1.
        assert_eq!(units_to_gpu(1), 1);
        assert_eq!(units_to_gpu(0), 0);
        // 100 units = 78.57 GPU cycles, rounded up.
        assert_eq!(units_to_gpu(100), 79);
    }

    #[test]
    fn idle_gpu_takes_words_without_filling_the_fifo() {
        let mut d = Drawing::default();
        for _ in 0..3 {
            d.receive(true);
        }
        d.complete(1000);
        assert_eq!(d.fifo_words(), 0);
        assert_eq!(d.cycles_until_idle(), 1000);
        assert!(!d.idle());
    }

    #[test]
    fn words_queue_while_busy_and_drain_in_order() {
        let mut d = Drawing::default();
        d.receive(true);
        d.complete(100);
        // Two 3-word units behind it.
        for cost in [50, 70] {
            for _ in 0..3 {
                d.receive(true);
            }
            d.complete(cost);
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
        d.complete(10);
        d.receive(false);
        d.complete(0);
        assert_eq!(d.fifo_words(), 0);
        assert!(!d.unit_queued());
    }

    #[test]
    fn room_appears_when_enough_units_leave() {
        let mut d = Drawing::default();
        d.complete(10);
        // Four 4-word units fill the FIFO.
        for cost in [1, 2, 3, 4] {
            for _ in 0..4 {
                d.receive(true);
            }
            d.complete(cost);
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
        d.complete(10);
        d.receive(true);
        d.complete(5);
        d.clear_fifo();
        assert_eq!(d.fifo_words(), 0);
        assert_eq!(d.cycles_until_idle(), 10);
    }
}
