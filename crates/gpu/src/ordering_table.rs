//! Ordering tables (docs/hardware/gpu.md §2): a main-RAM-like word buffer holding an OT and a primitive
//! buffer, the DMA6 (OTC) clear, packet insertion, and the DMA2 linked-list walk that feeds
//! packets to GP0 from the far end of the table to the near end (the painter's algorithm; the
//! GPU has no z-buffer).
//!
//! Links are 24-bit byte addresses into the buffer, as in main RAM. A node is a header word
//! `N << 24 | next` followed by N GP0 words. The walk ends after the node whose link has
//! bit 23 set (the end marker written by the clear is 00FFFFFFh). The walk is the one DMA2
//! uses over main RAM ([`Gpu::dma_linked_list`]).

use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use crate::Gpu;
use crate::dma::{WalkEnd, WordImage, walk_nodes};

/// The end-of-list marker DMA6 writes into the first entry.
pub const END_MARKER: u32 = 0x00FF_FFFF;
/// Most GP0 words one node can carry (the header's 8-bit count).
pub const MAX_PACKET_WORDS: usize = 255;
/// Most words a table (entries plus primitive buffer) can address: links are 24-bit byte
/// addresses whose bit 23 is the end marker, so a node's byte address `4 * index` must stay
/// below 80_0000h (docs/hardware/gpu.md §2).
pub const MAX_WORDS: usize = 0x80_0000 / 4;
/// Deepest table [`OrderingTable::new`] accepts: every entry must be addressable.
pub const MAX_DEPTH: usize = MAX_WORDS - 1;

/// Why an insertion or walk failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OtError {
    /// The depth index is not below the table's depth.
    IndexOutOfRange {
        /// Index given.
        index: usize,
        /// Table depth.
        depth: usize,
    },
    /// The packet has more than 255 words.
    PacketTooLong(usize),
    /// The primitive buffer has no room for the packet.
    PrimitiveBufferFull,
    /// A link or a node's words point outside the buffer.
    BadLink(u32),
    /// The walk visited more nodes than the buffer can hold: the list has a cycle.
    Cycle,
    /// The requested depth needs entries at byte addresses 80_0000h or above, which a 24-bit
    /// link with bit 23 as the end marker cannot reach.
    TooDeep {
        /// Depth requested.
        depth: usize,
        /// Largest depth accepted ([`MAX_DEPTH`]).
        max: usize,
    },
}

impl fmt::Display for OtError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OtError::IndexOutOfRange { index, depth } => {
                write!(
                    f,
                    "ordering-table index {index} out of range (depth {depth})"
                )
            }
            OtError::PacketTooLong(n) => write!(f, "packet of {n} words exceeds 255"),
            OtError::PrimitiveBufferFull => write!(f, "primitive buffer full"),
            OtError::BadLink(a) => write!(f, "link {a:06X}h points outside the buffer"),
            OtError::Cycle => write!(f, "linked list has a cycle"),
            OtError::TooDeep { depth, max } => write!(
                f,
                "ordering-table depth {depth} exceeds {max}: 24-bit links reach byte addresses \
                 below 800000h only"
            ),
        }
    }
}

impl core::error::Error for OtError {}

/// What a walk delivered.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WalkStats {
    /// Nodes visited (OT entries included).
    pub nodes: usize,
    /// Nodes that carried GP0 words.
    pub packets: usize,
    /// GP0 words delivered.
    pub words: usize,
}

/// Walk a DMA2 linked list in `ram` (a word image of main RAM, byte address = 4 * index)
/// from byte address `start`, giving each node's GP0 words to `sink`. The walk is the DMA
/// channel's ([`Gpu::dma_linked_list`] walks RAM with the same walker) and is bounded: a
/// list with more nodes than the buffer has words revisits a node, and is reported as a
/// cycle.
pub fn walk_ram(
    ram: &[u32],
    start: u32,
    mut sink: impl FnMut(&[u32]),
) -> Result<WalkStats, OtError> {
    let mut stats = WalkStats::default();
    let (end, _) = walk_nodes(
        &WordImage(ram),
        start,
        ram.len().saturating_add(1),
        |addr, count| {
            let index = (addr / 4) as usize + 1;
            let count = count as usize;
            stats.nodes += 1;
            if let Some(words) = ram.get(index..index + count).filter(|w| !w.is_empty()) {
                stats.packets += 1;
                stats.words += count;
                sink(words);
            }
            true
        },
    );
    match end {
        WalkEnd::EndMarker => Ok(stats),
        WalkEnd::Stopped(_) => Err(OtError::Cycle),
        WalkEnd::BadLink(a) => Err(OtError::BadLink(a)),
    }
}

/// An ordering table of `depth` entries followed by a primitive buffer, in one word buffer.
/// Higher indices are farther away and are drawn first.
#[derive(Clone, Debug)]
pub struct OrderingTable {
    ram: Vec<u32>,
    depth: usize,
    next_free: usize,
}

impl OrderingTable {
    /// A cleared table of `depth` entries (at least 1) with room for `primitive_words` words of
    /// packets and headers. Words that would lie at byte addresses 80_0000h or above are not
    /// allocated (no link can reach them). A depth above [`MAX_DEPTH`] is refused with
    /// [`OtError::TooDeep`].
    pub fn new(depth: usize, primitive_words: usize) -> Result<Self, OtError> {
        if depth > MAX_DEPTH {
            return Err(OtError::TooDeep {
                depth,
                max: MAX_DEPTH,
            });
        }
        let depth = depth.max(1);
        let primitive_words = primitive_words.min(MAX_WORDS - depth);
        let mut ot = Self {
            ram: vec![0; depth + primitive_words],
            depth,
            next_free: depth,
        };
        ot.clear();
        Ok(ot)
    }

    /// Number of entries.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// DMA6 (OTC): entry i links to entry i-1, entry 0 holds the end marker; the primitive
    /// buffer is emptied.
    pub fn clear(&mut self) {
        for (i, entry) in self.ram.iter_mut().take(self.depth).enumerate() {
            *entry = if i == 0 {
                END_MARKER
            } else {
                ((i - 1) * 4) as u32
            };
        }
        self.next_free = self.depth;
    }

    /// Link a GP0 packet at entry `index`: its words are copied into the primitive buffer and
    /// its node becomes the entry's first, so packets at one index come out
    /// most-recent-first (docs/hardware/gpu.md §2).
    #[inline]
    pub fn insert(&mut self, index: usize, packet: &[u32]) -> Result<(), OtError> {
        if index >= self.depth {
            return Err(OtError::IndexOutOfRange {
                index,
                depth: self.depth,
            });
        }
        if packet.len() > MAX_PACKET_WORDS {
            return Err(OtError::PacketTooLong(packet.len()));
        }
        let node = self.next_free;
        let end = node + 1 + packet.len();
        if end > self.ram.len() || node * 4 >= 0x80_0000 {
            return Err(OtError::PrimitiveBufferFull);
        }
        let entry = self.ram[index];
        self.ram[node] = (packet.len() as u32) << 24 | (entry & 0xFF_FFFF);
        self.ram[node + 1..end].copy_from_slice(packet);
        self.ram[index] = (entry & 0xFF00_0000) | (node * 4) as u32;
        self.next_free = end;
        Ok(())
    }

    /// Words of the primitive buffer in use.
    pub fn used_words(&self) -> usize {
        self.next_free - self.depth
    }

    /// The buffer as a main-RAM word image.
    pub fn ram(&self) -> &[u32] {
        &self.ram
    }

    /// DMA2 linked-list walk from the far end (the last entry) to the terminator.
    pub fn walk(&self, sink: impl FnMut(&[u32])) -> Result<WalkStats, OtError> {
        walk_ram(&self.ram, ((self.depth - 1) * 4) as u32, sink)
    }

    /// Walk into a GPU's GP0 port.
    pub fn walk_into(&self, gpu: &mut Gpu) -> Result<WalkStats, OtError> {
        self.walk(|words| gpu.gp0_words(words))
    }
}
