//! DMA channel 2 (GPU) in block and linked-list mode, and channel 6 (OTC), over the
//! emulator's main RAM (docs/hardware/dma.md; docs/emulator.md, "Drawing time, FIFO and
//! DMA").
//!
//! Main RAM is given as bytes, little-endian words. Addresses are 24-bit MADR values; RAM is
//! the 2 MiB that the first 8 MiB mirror, so an address selects byte `addr & 1FFFFCh`
//! (docs/hardware/dma.md §2).

use core::fmt;

use crate::Gpu;

/// Main RAM size: addresses wrap at 2 MiB.
pub const RAM_SIZE: usize = 2 * 1024 * 1024;
/// The word-aligned address mask of 2 MiB main RAM.
pub const RAM_MASK: u32 = 0x1F_FFFC;
/// Header and data words one [`Gpu::dma_linked_list`] call reads at most before it pauses
/// and reports where to resume: a list that loops forever (which the console keeps walking,
/// docs/hardware/dma.md §6) cannot hang the caller.
pub const LINKED_LIST_WORD_BUDGET: u32 = 0x1_0000;

/// Why a DMA could not run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DmaError {
    /// An address falls outside the RAM slice given (only possible when it is shorter than
    /// 2 MiB).
    AddressOutOfRange(u32),
    /// An OTC word count above 10000h (the 16-bit BCR holds at most FFFFh, and 0 means
    /// 10000h).
    CountTooLarge(u32),
}

impl fmt::Display for DmaError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DmaError::AddressOutOfRange(a) => write!(f, "address {a:06X}h is outside RAM"),
            DmaError::CountTooLarge(n) => write!(f, "OTC count {n} exceeds 65536 words"),
        }
    }
}

impl core::error::Error for DmaError {}

/// How a linked-list walk ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ListEnd {
    /// A node whose link has bit 23 set (the end code; OTC writes 00FFFFFFh).
    EndMarker,
    /// The word budget ran out; the list continues at this node address (a list that loops
    /// forever always ends here). The console would still be transferring.
    Paused {
        /// Address of the next node header.
        next: u32,
    },
    /// A header or data word lies outside the RAM slice given.
    BadAddress(u32),
}

/// What a linked-list DMA delivered and how long it took.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LinkedListReport {
    /// Nodes whose header was read.
    pub nodes: u32,
    /// GP0 words delivered.
    pub words: u32,
    /// CPU cycles the transfer took: a cycle per header and data word plus the time spent
    /// waiting for FIFO room.
    pub cycles: u32,
    /// CPU cycles of `cycles` spent waiting for FIFO room.
    pub wait_cycles: u32,
    /// How the walk ended.
    pub end: ListEnd,
}

/// Memory a linked list is read from, addressed by 24-bit byte address.
pub(crate) trait ListMemory {
    /// The word at `addr`, or `None` outside the memory.
    fn word(&self, addr: u32) -> Option<u32>;
    /// The address of the `i`-th word after `addr` (wrapping as the memory does).
    fn offset(&self, addr: u32, i: u32) -> u32;
    /// Whether the `count` words after the header at `addr` all lie in the memory.
    fn node_present(&self, addr: u32, count: u32) -> bool {
        (1..=count).all(|i| self.word(self.offset(addr, i)).is_some())
    }
}

/// Main RAM as bytes: addresses mirror every 2 MiB.
pub(crate) struct ByteRam<'a>(pub &'a [u8]);

impl ListMemory for ByteRam<'_> {
    fn word(&self, addr: u32) -> Option<u32> {
        let i = (addr & RAM_MASK) as usize;
        let b = self.0.get(i..i + 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    fn offset(&self, addr: u32, i: u32) -> u32 {
        addr.wrapping_add(i.wrapping_mul(4)) & RAM_MASK
    }
}

/// A word image of memory (byte address = 4 * index), no mirroring.
pub(crate) struct WordImage<'a>(pub &'a [u32]);

impl ListMemory for WordImage<'_> {
    fn word(&self, addr: u32) -> Option<u32> {
        self.0.get((addr / 4) as usize).copied()
    }
    fn offset(&self, addr: u32, i: u32) -> u32 {
        addr.wrapping_add(i.wrapping_mul(4)) & 0xFF_FFFF
    }
    /// A header inside an image of at most 2 Mi words (8 MiB) is followed by at most 255
    /// words that stay below address 1000000h and so do not wrap: they are present when the
    /// last one is.
    fn node_present(&self, addr: u32, count: u32) -> bool {
        if self.0.len() <= 1 << 21 && (addr / 4) < 1 << 21 {
            (addr / 4) as usize + (count as usize) < self.0.len()
        } else {
            (1..=count).all(|i| self.word(self.offset(addr, i)).is_some())
        }
    }
}

/// How [`walk_nodes`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum WalkEnd {
    /// The end code.
    EndMarker,
    /// `node_limit` nodes were read, or the visitor asked to stop; the next node is here.
    Stopped(u32),
    /// A header, or a node's data, lies outside memory (the node's header address).
    BadLink(u32),
}

/// Walk a DMA2 linked list (docs/hardware/dma.md §5, §6; docs/emulator.md):
/// from `start`, read a header `N << 24 | next`, hand the node (its header address and N) to
/// `visit`, and follow `next` until a link with bit 23 set. At most `node_limit` headers are
/// read; `visit` returns false to stop after its node. Returns how it ended and the nodes
/// read.
pub(crate) fn walk_nodes<M: ListMemory>(
    mem: &M,
    start: u32,
    node_limit: usize,
    mut visit: impl FnMut(u32, u32) -> bool,
) -> (WalkEnd, usize) {
    let mut addr = start & 0xFF_FFFC;
    let mut nodes = 0usize;
    loop {
        if nodes >= node_limit {
            return (WalkEnd::Stopped(addr), nodes);
        }
        let Some(header) = mem.word(addr) else {
            return (WalkEnd::BadLink(addr), nodes);
        };
        let count = header >> 24;
        if !mem.node_present(addr, count) {
            return (WalkEnd::BadLink(addr), nodes);
        }
        nodes += 1;
        let go_on = visit(addr, count);
        let next = header & 0xFF_FFFF;
        if next & 0x80_0000 != 0 {
            return (WalkEnd::EndMarker, nodes);
        }
        if !go_on {
            return (WalkEnd::Stopped(next & 0xFF_FFFC), nodes);
        }
        addr = next & 0xFF_FFFC;
    }
}

/// The walk [`Gpu::dma_linked_list`] makes (docs/hardware/dma.md §5, §6): each node's data
/// words (at most 255, the header's count field) to `send` as one slice, in order, at most
/// [`LINKED_LIST_WORD_BUDGET`] header and data words read. Returns how it ended, the nodes,
/// the data words sent and the words read.
pub(crate) fn linked_list_walk(
    ram: &[u8],
    start: u32,
    mut send: impl FnMut(&[u32]),
) -> (WalkEnd, usize, u32, u32) {
    let mem = ByteRam(ram);
    let mut words = 0u32;
    let mut read = 0u32;
    let mut node = [0u32; 255];
    let (end, nodes) = walk_nodes(&mem, start, usize::MAX, |addr, count| {
        for (i, slot) in (1..=count).zip(node.iter_mut()) {
            *slot = mem.word(mem.offset(addr, i)).unwrap_or(0);
        }
        send(node.get(..count as usize).unwrap_or_default());
        words += count;
        read += 1 + count;
        read < LINKED_LIST_WORD_BUDGET
    });
    (end, nodes, words, read)
}

/// CPU cycles a DMA moving `words` words takes: one per word plus one per 16 for DRAM row
/// changes (110h clocks per 100h words, docs/hardware/dma.md §10).
fn transfer_cycles(words: u32) -> u32 {
    words.saturating_add(words / 16)
}

/// The time of one DMA as it goes: CPU cycles since it began, and the GPU cycles the drawing
/// side has been run ahead along with them, so that the GPU drains the FIFO while the DMA
/// fills it.
#[derive(Clone, Copy, Debug, Default)]
struct DmaClock {
    /// Words moved so far.
    words: u32,
    /// CPU cycles since the DMA began: the words' transfer time and the waits.
    cpu: u32,
    /// CPU cycles of `cpu` spent waiting on the GPU.
    waited: u32,
    /// GPU cycles the drawing side has been run ahead.
    gpu: u32,
}

/// DMA6 (OTC): clear an ordering table of `count` words ending at `start` (docs/hardware/
/// dma.md §7): the word at `start` links to the word before it, and so on down; the lowest
/// word gets the end code 00FFFFFFh. Links are 24-bit addresses. A count of 0 means 10000h
/// words. Addresses that wrap below 0 (to FFFFFCh and down, past RAM) are not written
/// (docs/hardware/dma.md §2; psx-spx "D#_MADR"). Returns the CPU cycles taken (one per word, 110h per
/// 100h). Nothing is written when an address lies outside `ram`.
///
/// ```
/// let mut ram = vec![0u8; 2 << 20];
/// gpu::dma_clear_ordering_table(&mut ram, 0x100C, 4).unwrap(); // entries 1000h..100Ch
/// let word = |a: usize| u32::from_le_bytes(ram[a..a + 4].try_into().unwrap());
/// assert_eq!(word(0x100C), 0x1008); // each entry links to the one below
/// assert_eq!(word(0x1000), 0x00FF_FFFF); // the last holds the end code
/// ```
pub fn dma_clear_ordering_table(ram: &mut [u8], start: u32, count: u32) -> Result<u32, DmaError> {
    let n = match count {
        0 => 0x1_0000,
        1..=0x1_0000 => count,
        _ => return Err(DmaError::CountTooLarge(count)),
    };
    let start = start & 0xFF_FFFC;
    let at = |i: u32| start.wrapping_sub(i * 4) & 0xFF_FFFF;
    let written = |a: u32| a < 0x80_0000;
    for i in 0..n {
        let a = at(i);
        if written(a) && (a & RAM_MASK) as usize + 4 > ram.len() {
            return Err(DmaError::AddressOutOfRange(a));
        }
    }
    for i in 0..n {
        let a = at(i);
        if !written(a) {
            continue;
        }
        let value = if i + 1 == n {
            0x00FF_FFFF
        } else {
            a.wrapping_sub(4) & 0xFF_FFFF
        };
        let j = (a & RAM_MASK) as usize;
        if let Some(b) = ram.get_mut(j..j + 4) {
            b.copy_from_slice(&value.to_le_bytes());
        }
    }
    Ok(transfer_cycles(n))
}

impl Gpu {
    /// The GPU clock over the CPU clock of this console (docs/hardware/timing.md §1).
    fn ratio(&self) -> (u64, u64) {
        crate::drawing::clock_ratio(self.timing.standard())
    }

    /// One more word moved by the DMA of `clock`: its transfer time passes on the drawing
    /// side too.
    fn dma_tick(&mut self, clock: &mut DmaClock) {
        let (num, den) = self.ratio();
        clock.words = clock.words.saturating_add(1);
        clock.cpu = transfer_cycles(clock.words).saturating_add(clock.waited);
        let target = u32::try_from(clock.cpu as u64 * num / den).unwrap_or(u32::MAX);
        if target > clock.gpu {
            self.drawing.run_ahead(target - clock.gpu);
            clock.gpu = target;
        }
    }

    /// The DMA of `clock` waited `wait` GPU cycles on the GPU (already run ahead).
    fn dma_waited(&mut self, clock: &mut DmaClock, wait: u32) {
        if wait == 0 {
            return;
        }
        let (num, den) = self.ratio();
        clock.gpu = clock.gpu.saturating_add(wait);
        // The CPU-side time of the DMA now reaches the drawing side's.
        let cpu = u32::try_from((clock.gpu as u64 * den).div_ceil(num)).unwrap_or(u32::MAX);
        if cpu > clock.cpu {
            clock.waited = clock.waited.saturating_add(cpu - clock.cpu);
            clock.cpu = cpu;
        }
    }

    /// One GP0 word from DMA: it takes its transfer time, then waits while the FIFO is full.
    fn dma_word(&mut self, clock: &mut DmaClock, word: u32) {
        self.dma_tick(clock);
        let wait = self.wait_for_room(word);
        self.dma_waited(clock, wait);
        self.gp0_word(word);
    }

    /// DMA2 block (sync) mode, RAM to GP0 (docs/hardware/dma.md §4): the words go to GP0 in
    /// order. Returns the CPU cycles taken: one per word (110h per 100h words) plus the time
    /// spent waiting while the FIFO is full. The GPU drains the FIFO while the words arrive:
    /// the drawing side runs along with the transfer, and through the waits, so it has
    /// already been run for the returned cycles: the caller runs them through [`Gpu::run`]
    /// as usual and they are not counted twice.
    pub fn dma_block_write(&mut self, words: &[u32]) -> u32 {
        let mut clock = DmaClock::default();
        for &w in words {
            self.dma_word(&mut clock, w);
        }
        clock.cpu
    }

    /// DMA2 block (sync) mode, GPUREAD to RAM: each word is a [`Gpu::gpuread`] (VRAM data
    /// of a GP0(C0h) transfer, or the latched value once it is done). Returns the CPU cycles
    /// taken: 110h per 100h words, plus the waits for words the GPU has not yet fetched from
    /// VRAM (see [`Gpu::gpuread_timed`]); the drawing side runs along as for
    /// [`Gpu::dma_block_write`].
    pub fn dma_block_read(&mut self, out: &mut [u32]) -> u32 {
        let mut clock = DmaClock::default();
        for w in out.iter_mut() {
            self.dma_tick(&mut clock);
            let wait = self.wait_for_read();
            self.dma_waited(&mut clock, wait);
            *w = self.gpuread();
        }
        clock.cpu
    }

    /// DMA2 linked-list mode (docs/hardware/dma.md §5, §6): walk the list in
    /// `ram` (bytes, little-endian words, addresses masked to 2 MiB) from node address
    /// `start`, giving each node's words to GP0, until a link with bit 23 set. Waits while
    /// the FIFO is full as [`Gpu::dma_block_write`] does. At most
    /// [`LINKED_LIST_WORD_BUDGET`] header and data words are read per call; a longer (or
    /// looping) list pauses with [`ListEnd::Paused`] and can be resumed from `next`. A
    /// header or data word beyond a `ram` shorter than 2 MiB ends the walk with
    /// [`ListEnd::BadAddress`] before that node's words are sent.
    ///
    /// ```
    /// // One node at 2000h holding a 3-word fill, then the end code.
    /// let mut ram = vec![0u8; 2 << 20];
    /// for (i, w) in [0x03FF_FFFFu32, 0x0200_00FF, 0, 0x0001_0010].iter().enumerate() {
    ///     ram[0x2000 + 4 * i..0x2004 + 4 * i].copy_from_slice(&w.to_le_bytes());
    /// }
    /// let mut gpu = gpu::Gpu::new();
    /// let report = gpu.dma_linked_list(&ram, 0x2000);
    /// assert_eq!((report.nodes, report.words), (1, 3));
    /// assert_eq!(report.end, gpu::ListEnd::EndMarker);
    /// assert_eq!(gpu.vram().pixel(0, 0), 0x001F);
    /// ```
    pub fn dma_linked_list(&mut self, ram: &[u8], start: u32) -> LinkedListReport {
        let mem = ByteRam(ram);
        let mut words = 0u32;
        let mut read = 0u32;
        let mut clock = DmaClock::default();
        let (end, nodes) = walk_nodes(&mem, start, usize::MAX, |addr, count| {
            self.dma_tick(&mut clock);
            for i in 1..=count {
                let w = mem.word(mem.offset(addr, i)).unwrap_or(0);
                self.dma_word(&mut clock, w);
            }
            words += count;
            read += 1 + count;
            read < LINKED_LIST_WORD_BUDGET
        });
        let end = match end {
            WalkEnd::EndMarker => ListEnd::EndMarker,
            WalkEnd::Stopped(next) => ListEnd::Paused { next },
            WalkEnd::BadLink(a) => ListEnd::BadAddress(a),
        };
        LinkedListReport {
            nodes: u32::try_from(nodes).unwrap_or(u32::MAX),
            words,
            cycles: clock.cpu,
            wait_cycles: clock.waited,
            end,
        }
    }
}
