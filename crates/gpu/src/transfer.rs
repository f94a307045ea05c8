//! VRAM transfer commands: fill (02h), VRAM-to-VRAM copy (80h), CPU-to-VRAM (A0h) and
//! VRAM-to-CPU (C0h) (docs/hardware/gpu.md §8).

use crate::rows::Rows;
use crate::state::MaskSettings;
use crate::{VRAM_LEN, VRAM_WIDTH, Vram};

/// A transfer rectangle as the copy commands mask it (docs/hardware/gpu.md §8): x & 3FFh, y & 1FFh,
/// w = ((w-1) & 3FFh) + 1, h = ((h-1) & 1FFh) + 1, so a size of 0 means the maximum.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TransferRect {
    /// Left edge.
    pub x: u16,
    /// Top line.
    pub y: u16,
    /// Width, 1..=1024.
    pub w: u16,
    /// Height, 1..=512.
    pub h: u16,
}

impl TransferRect {
    /// Decode a position word and a size word.
    pub fn decode(pos: u32, size: u32) -> Self {
        Self {
            x: (pos & 0x3FF) as u16,
            y: ((pos >> 16) & 0x1FF) as u16,
            w: (((size & 0xFFFF).wrapping_sub(1) & 0x3FF) + 1) as u16,
            h: ((((size >> 16) & 0xFFFF).wrapping_sub(1) & 0x1FF) + 1) as u16,
        }
    }

    /// A rectangle the copy commands can produce: x < 1024, y < 512, w in 1..=1024, h in
    /// 1..=512 (docs/hardware/gpu.md §8).
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        if self.x < 1024
            && self.y < 512
            && (1..=1024).contains(&self.w)
            && (1..=512).contains(&self.h)
        {
            Ok(())
        } else {
            Err("transfer rectangle outside the masked ranges")
        }
    }

    /// Pixels in the rectangle.
    pub fn pixels(&self) -> u32 {
        self.w as u32 * self.h as u32
    }

    /// VRAM (x, y) of pixel `i` in row-major order, wrapped at the VRAM edges.
    fn position(&self, i: u32) -> (usize, usize) {
        let w = self.w as u32;
        (
            ((self.x as u32 + i % w) & 1023) as usize,
            ((self.y as u32 + i / w) & 511) as usize,
        )
    }
}

/// Write one transferred pixel obeying E6 (docs/hardware/gpu.md §6, §8).
fn write_masked(vram: &mut Vram, x: usize, y: usize, value: u16, mask: MaskSettings) {
    if mask.check && vram.pixel(x, y) & 0x8000 != 0 {
        return;
    }
    let set = if mask.set { 0x8000 } else { 0 };
    vram.set_pixel(x, y, value | set);
}

/// The rectangle of a GP0(02h) fill (docs/hardware/gpu.md §8): x & 3F0h, y & 1FFh, the
/// width & 3FFh rounded up to a multiple of 16, the height & 1FFh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FillRect {
    /// Left edge, a multiple of 16.
    pub x: u16,
    /// Top line.
    pub y: u16,
    /// Width, a multiple of 16 up to 1024.
    pub w: u16,
    /// Height, up to 511.
    pub h: u16,
}

impl FillRect {
    /// Decode a fill's position and size words.
    pub fn decode(pos: u32, size: u32) -> Self {
        Self {
            x: (pos & 0x3F0) as u16,
            y: ((pos >> 16) & 0x1FF) as u16,
            w: (((size & 0x3FF) + 0xF) & !0xF) as u16,
            h: ((size >> 16) & 0x1FF) as u16,
        }
    }
}

/// GP0(02h) fill of `rect` (docs/hardware/gpu.md §8): colour channels >> 3 with bit 15
/// clear; wraps; ignores drawing area, offset and E6. Lines `rows` drops are skipped (480i,
/// docs/hardware/gpu.md §8). Returns the filled width and height.
pub fn fill(vram: &mut Vram, color: u32, rect: FillRect, rows: Rows) -> (u32, u32) {
    let (x, y) = (usize::from(rect.x), usize::from(rect.y));
    let (w, h) = (usize::from(rect.w), usize::from(rect.h));
    let c = ((color & 0xFF) >> 3)
        | (((color >> 8) & 0xFF) >> 3) << 5
        | (((color >> 16) & 0xFF) >> 3) << 10;
    let pixels = vram.as_array_mut();
    for row in 0..h {
        if !rows.keeps(((y + row) & 511) as i32) {
            continue;
        }
        let base = ((y + row) & 511) * VRAM_WIDTH;
        for col in 0..w {
            pixels[(base + ((x + col) & 1023)) & (VRAM_LEN - 1)] = c as u16;
        }
    }
    (w as u32, h as u32)
}

/// GP0(80h) VRAM-to-VRAM copy (docs/hardware/gpu.md §8). Rows are copied top to bottom, each row read
/// whole before it is written (docs/gpu.md, "Overlapping copies"); E6 applies. Returns the
/// pixels copied.
pub fn copy(vram: &mut Vram, src: u32, dst: u32, size: u32, mask: MaskSettings) -> u32 {
    let s = TransferRect::decode(src, size);
    let d = TransferRect::decode(dst, size);
    let mut row = [0u16; VRAM_WIDTH];
    for r in 0..s.h as usize {
        let sy = (s.y as usize + r) & 511;
        let dy = (d.y as usize + r) & 511;
        for (c, slot) in row.iter_mut().take(s.w as usize).enumerate() {
            *slot = vram.pixel(s.x as usize + c, sy);
        }
        for (c, &value) in row.iter().take(s.w as usize).enumerate() {
            write_masked(vram, d.x as usize + c, dy, value, mask);
        }
    }
    s.pixels()
}

/// A CPU-to-VRAM transfer in progress (GP0 A0h): pixels arrive two per word; an odd count
/// leaves the last word's upper half unused (docs/hardware/gpu.md §8).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WriteTransfer {
    rect: TransferRect,
    next: u32,
}

impl WriteTransfer {
    /// Start a transfer to `rect`.
    pub fn new(rect: TransferRect) -> Self {
        Self { rect, next: 0 }
    }

    /// An unfinished transfer: a valid rectangle, an even pixel count (two a word) below its
    /// size.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        self.rect.check()?;
        if self.next < self.rect.pixels() && self.next.is_multiple_of(2) {
            Ok(())
        } else {
            Err("CPU-to-VRAM transfer position past its rectangle or odd")
        }
    }

    /// Pixels still to be written.
    pub fn remaining_pixels(&self) -> u32 {
        self.rect.pixels().saturating_sub(self.next)
    }

    /// Take one data word; returns false when the transfer is complete.
    pub fn push(&mut self, vram: &mut Vram, word: u32, mask: MaskSettings) -> bool {
        for half in [word as u16, (word >> 16) as u16] {
            if self.next < self.rect.pixels() {
                let (x, y) = self.rect.position(self.next);
                write_masked(vram, x, y, half, mask);
                self.next += 1;
            }
        }
        self.next < self.rect.pixels()
    }
}

/// A VRAM-to-CPU transfer in progress (GP0 C0h), read through GPUREAD.
///
/// The GPU fetches the rectangle from VRAM at a fixed rate once it reaches the command
/// (docs/emulator.md, "Drawing time"): the fetch is a drawing unit of `fetch` GPU cycles, and
/// word `k` of `n` is ready `fetch * (k + 1) / n` cycles after it starts. `tail` counts the
/// GPU cycles of units queued after the fetch, which the time to the drawing side's idle
/// includes and the fetch does not.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ReadTransfer {
    rect: TransferRect,
    next: u32,
    active: bool,
    #[cfg_attr(feature = "serde", serde(default))]
    fetch: u32,
    #[cfg_attr(feature = "serde", serde(default))]
    tail: u32,
}

/// [`ReadTransfer`] as save-state version 1 wrote it: without the fetch timing, which loads
/// as 0 (every word ready, as version 1's GPUREAD was).
#[cfg(feature = "serde")]
#[derive(serde::Deserialize)]
pub(crate) struct ReadTransferV1 {
    rect: TransferRect,
    next: u32,
    active: bool,
}

#[cfg(feature = "serde")]
impl From<ReadTransferV1> for ReadTransfer {
    fn from(r: ReadTransferV1) -> Self {
        ReadTransfer {
            rect: r.rect,
            next: r.next,
            active: r.active,
            fetch: 0,
            tail: 0,
        }
    }
}

impl ReadTransfer {
    /// Start reading `rect`.
    pub fn new(rect: TransferRect) -> Self {
        Self {
            rect,
            next: 0,
            active: true,
            fetch: 0,
            tail: 0,
        }
    }

    /// A drawing unit of `cycles` GPU cycles was queued: the transfer's own fetch when
    /// `fetch` (its GP0(C0h) packet), else a unit behind it.
    #[inline(always)]
    pub fn unit_queued(&mut self, fetch: bool, cycles: u32) {
        if fetch {
            self.fetch = cycles;
            self.tail = 0;
        } else if self.active {
            self.tail = self.tail.saturating_add(cycles);
        }
    }

    /// GPU cycles until the next word is fetched, given the GPU cycles until the drawing
    /// side has finished every unit queued so far (0 when it is ready or no transfer is
    /// active).
    pub fn cycles_until_ready(&self, until_idle: u32) -> u32 {
        if !self.active {
            return 0;
        }
        let words = self.rect.pixels().div_ceil(2) as u64;
        let left = self.rect.pixels().saturating_sub(self.next).div_ceil(2) as u64;
        // Fetching the words after the next one takes this long.
        let after = (self.fetch as u64 * left.saturating_sub(1))
            .checked_div(words)
            .unwrap_or(0);
        let end_of_fetch = until_idle.saturating_sub(self.tail) as u64;
        end_of_fetch.saturating_sub(after) as u32
    }

    /// An active transfer has a valid rectangle and an even pixel count below its size; an
    /// inactive one is never read.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        if !self.active {
            return Ok(());
        }
        self.rect.check()?;
        if self.next < self.rect.pixels() && self.next.is_multiple_of(2) {
            Ok(())
        } else {
            Err("VRAM-to-CPU transfer position past its rectangle or odd")
        }
    }

    /// Whether words remain to be read.
    pub fn active(&self) -> bool {
        self.active
    }

    /// The GPUREAD words left to read (0 once the transfer is done).
    pub fn remaining_words(&self) -> u32 {
        if self.active {
            self.rect.pixels().saturating_sub(self.next).div_ceil(2)
        } else {
            0
        }
    }

    /// The next two pixels (first in the low half); the transfer ends after the last.
    pub fn next_word(&mut self, vram: &Vram) -> u32 {
        let mut word = 0u32;
        for half in 0..2 {
            if self.next < self.rect.pixels() {
                let (x, y) = self.rect.position(self.next);
                word |= (vram.pixel(x, y) as u32) << (16 * half);
                self.next += 1;
            }
        }
        if self.next >= self.rect.pixels() {
            self.active = false;
        }
        word
    }
}
