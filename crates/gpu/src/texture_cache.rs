//! The texture cache (docs/hardware/gpu.md §10): 2 KB holding 256 entries of four VRAM
//! halfwords (16 texels at 4-bit, 8 at 8-bit, 4 at 15-bit). A texture page is tiled into
//! cache blocks of 64x64 (4-bit), 64x32 (8-bit) or 32x32 (15-bit) texels, 256 entries each;
//! an entry holds the copy of one block's entry at a time, named by its tag. Texels are read
//! from the copy, so VRAM written under a resident entry (by drawing or a fill) is not seen
//! until the entry is reloaded: after a miss on another block's entry of the same number, or
//! after an invalidation (GP0(01h), a texture page change, a VRAM transfer, GP1(00h)).
//!
//! The cache can be switched off ([`crate::Gpu::set_texture_cache`]): texels are then read
//! straight from VRAM and no miss is counted (docs/gpu.md, "Texture cache").

use crate::VRAM_LEN;
use crate::state::{DrawMode, TextureDepth};

/// Entries in the cache (docs/hardware/gpu.md §10).
pub(crate) const ENTRIES: usize = 256;

/// Halfwords per entry: eight bytes.
const ENTRY_HALFWORDS: usize = 4;

/// The tag of an entry that holds nothing: no VRAM address gives it.
const INVALID: u32 = u32::MAX;

/// The highest tag an address gives: the last four halfwords of VRAM.
#[cfg(feature = "serde")]
const MAX_TAG: u32 = (VRAM_LEN / ENTRY_HALFWORDS) as u32 - 1;

/// The entry of the cache that holds the VRAM halfword at `address` (`y * 1024 + x`) for a
/// texture of kind `tex` (1 = 4-bit, 2 = 8-bit, 3 = 15-bit) (docs/hardware/gpu.md §10): a
/// 4-bit block is 16 halfwords (4 entries) wide and 64 lines high, an 8-bit or 15-bit block
/// 32 halfwords (8 entries) wide and 32 lines high; entries are numbered along the block's
/// lines, so blocks tile VRAM and an entry's number repeats from block to block.
#[inline(always)]
pub(crate) const fn entry_index<const TEX: u8>(address: usize) -> usize {
    if TEX == 1 {
        ((address >> 2) & 0x3) | ((address >> 8) & 0xFC)
    } else {
        ((address >> 2) & 0x7) | ((address >> 7) & 0xF8)
    }
}

/// [`entry_index`] of eight addresses at once.
#[inline(always)]
pub(crate) fn entry_index_lanes<const TEX: u8>(address: wide::u32x8) -> wide::u32x8 {
    use wide::u32x8;
    if TEX == 1 {
        ((address >> 2) & u32x8::splat(0x3)) | ((address >> 8) & u32x8::splat(0xFC))
    } else {
        ((address >> 2) & u32x8::splat(0x7)) | ((address >> 7) & u32x8::splat(0xF8))
    }
}

/// The tag an entry holding the halfword at `address` carries: the VRAM address of its
/// first halfword, divided by four.
#[inline(always)]
pub(crate) const fn tag_of(address: usize) -> u32 {
    (address >> 2) as u32
}

/// Reads worked out eight at a time ([`TextureCache::track_lanes`]).
const LANES: usize = 8;

/// The lanes of eight whose bit is clear in a mask of eight bits, by mask: the misses of a
/// group of eight reads whose hits are the mask's set bits.
const MISSED_LANES: [u8; 1 << LANES] = {
    let mut t = [0; 1 << LANES];
    let mut m = 0;
    while m < t.len() {
        t[m] = (LANES as u32 - (m as u32).count_ones()) as u8;
        m += 1;
    }
    t
};

/// Whether the reads of a span of a texture of kind `TEX` (1 = 4-bit, 2 = 8-bit, 3 =
/// 15-bit), whose texel coordinates step by `(du, dv)` per pixel (8.24, two's complement),
/// step slowly: a pixel moves by at most a quarter of an entry's width in U plus lines in V.
/// An entry holds 16, 8 or 4 texels of one line (docs/hardware/gpu.md §10), so on average at
/// most one read in four leaves the entry of the read before it, as on textures drawn at or
/// near their size; such spans are tracked with [`TextureCache::track_slow_lanes`].
#[inline(always)]
pub(crate) fn steps_slowly<const TEX: u8>((du, dv): (u32, u32)) -> bool {
    let width_log2 = match TEX {
        1 => 4,
        2 => 3,
        _ => 2,
    };
    let (du, dv) = ((du as i32).unsigned_abs(), (dv as i32).unsigned_abs());
    (du >> width_log2) + dv <= 1 << 22
}

/// The reads of one span whose texels step slowly ([`steps_slowly`]), tracked eight at a
/// time ([`TextureCache::track_slow_lanes`]): made at the start of each span, so that nothing
/// but the span's own reads touches the cache while it is in use.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlowReads {
    /// No read of the span has been tracked yet.
    first: bool,
}

impl SlowReads {
    /// A span before its first read.
    #[inline(always)]
    pub(crate) const fn new() -> Self {
        Self { first: true }
    }
}

/// One texture cache entry as a debugger sees it (docs/hardware/gpu.md §10): the four VRAM
/// halfwords it was loaded from and their values then, which differ from VRAM's when VRAM
/// under the entry has been drawn or filled since.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureCacheEntry {
    /// VRAM column of the first halfword, a multiple of 4.
    pub x: u16,
    /// VRAM line.
    pub y: u16,
    /// The halfwords as loaded.
    pub halfwords: [u16; 4],
}

/// How a primitive's texel reads use the cache: a const parameter of the span routines,
/// chosen once per primitive by [`TextureCache::mode`].
///
/// The cache's copy of an entry differs from VRAM only once VRAM under the entry has been
/// written since it was loaded. Until a write may do that, the copies are not kept: reads
/// track the tags (and count the misses) and take the texel from VRAM, which holds the same
/// halfwords. Before a primitive or fill writes where resident entries may lie, the copies
/// are taken from VRAM ([`TextureCache::prepare`]) and reads use them from then on, until
/// the cache is emptied.
pub(crate) mod mode {
    /// The cache is off: texels are read from VRAM and nothing is tracked.
    pub(crate) const OFF: u8 = 0;
    /// Tags tracked, texels read from VRAM (every resident entry still equals VRAM).
    pub(crate) const TAGS: u8 = 1;
    /// [`TAGS`] for reads that step through VRAM in order (a rectangle's rows): the tags
    /// are consulted only when a read leaves the entry of the read before it.
    pub(crate) const RUNS: u8 = 2;
    /// Texels read from the entries' copies, loaded on a miss.
    pub(crate) const COPIES: u8 = 3;
}

/// What a primitive or fill may write: columns `[x, x + width)` wrapping at 1024 and lines
/// `[y, y + height)` wrapping at 512.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct WriteRegion {
    pub(crate) x: u32,
    pub(crate) width: u32,
    pub(crate) y: u32,
    pub(crate) height: u32,
}

impl WriteRegion {
    /// What a GP0(02h) fill of `rect` writes (docs/hardware/gpu.md §8).
    pub(crate) fn fill(rect: &crate::transfer::FillRect) -> Self {
        Self {
            x: u32::from(rect.x),
            width: u32::from(rect.w),
            y: u32::from(rect.y),
            height: u32::from(rect.h),
        }
    }

    /// The drawing area of GP0(E3h)/(E4h): every primitive's pixels lie inside it
    /// (docs/hardware/gpu.md §3.5); empty when a corner is past the other.
    pub(crate) fn area(area: &crate::state::DrawingArea) -> Self {
        let width = (u32::from(area.right) + 1).saturating_sub(u32::from(area.left));
        let height = (u32::from(area.bottom) + 1).saturating_sub(u32::from(area.top));
        Self {
            x: u32::from(area.left),
            width,
            y: u32::from(area.top),
            height,
        }
    }
}

/// Whether the arcs `[a, a + a_len)` and `[b, b + b_len)` of a circle of `m` positions meet.
fn arcs_meet(a: u32, a_len: u32, b: u32, b_len: u32, m: u32) -> bool {
    if a_len == 0 || b_len == 0 {
        return false;
    }
    if a_len >= m || b_len >= m {
        return true;
    }
    (b % m + m - a % m) % m < a_len || (a % m + m - b % m) % m < b_len
}

/// Where resident entries may lie: nowhere, in one texture page's 256 columns (the widest
/// page, 15-bit) and 256 lines, or anywhere.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Resident {
    #[default]
    Nowhere,
    Page {
        x: u16,
        y: u16,
    },
    Anywhere,
}

impl Resident {
    /// Whether entries that may lie here could be written by `w`.
    fn meets(self, w: &WriteRegion) -> bool {
        match self {
            Resident::Nowhere => false,
            Resident::Anywhere => true,
            Resident::Page { x, y } => {
                arcs_meet(u32::from(x), 256, w.x, w.width, 1024)
                    && arcs_meet(u32::from(y), 256, w.y, w.height, 512)
            }
        }
    }
}

/// The texture cache: tags and copies of 256 entries, and the misses counted.
#[derive(Clone)]
pub struct TextureCache {
    /// Texel reads go through the cache; when false they read VRAM and every tag is
    /// [`INVALID`].
    enabled: bool,
    /// Each entry's tag ([`tag_of`]), or [`INVALID`].
    tags: [u32; ENTRIES],
    /// Each entry's four halfwords, kept when `copies` is set.
    data: [[u16; ENTRY_HALFWORDS]; ENTRIES],
    /// `data` holds the resident entries (else they equal VRAM and are read from there).
    copies: bool,
    /// Where the resident entries may lie: the page of the textured primitives since the
    /// cache was last emptied.
    resident: Resident,
    /// A write region found clear of `resident`, so that primitives drawn one after the
    /// other into the same drawing area are tested once.
    clear: Option<WriteRegion>,
    /// The tag of the previous read of a [`mode::RUNS`] primitive.
    last: u32,
    /// Misses since the last [`TextureCache::take_misses`].
    misses: u32,
    /// Misses since power-on.
    total: u64,
}

/// Caches are equal when the chip's state is: the switch, the tags, the copies of resident
/// entries while they are kept, where resident entries may lie and the misses since power-on (what a save state
/// holds); the region last found clear, the last tag read and the misses not yet taken are
/// bookkeeping the next command recomputes.
impl PartialEq for TextureCache {
    fn eq(&self, other: &Self) -> bool {
        self.enabled == other.enabled
            && self.tags == other.tags
            && self.copies == other.copies
            && (!self.copies
                || self
                    .tags
                    .iter()
                    .zip(self.data.iter().zip(&other.data))
                    .all(|(&tag, (a, b))| tag == INVALID || a == b))
            && self.resident == other.resident
            && self.total == other.total
    }
}

impl Eq for TextureCache {}

impl Default for TextureCache {
    /// On, every entry invalid (power-on).
    fn default() -> Self {
        Self {
            enabled: true,
            tags: [INVALID; ENTRIES],
            data: [[0; ENTRY_HALFWORDS]; ENTRIES],
            copies: false,
            resident: Resident::Nowhere,
            clear: None,
            last: INVALID,
            misses: 0,
            total: 0,
        }
    }
}

impl core::fmt::Debug for TextureCache {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let resident = self.tags.iter().filter(|&&t| t != INVALID).count();
        f.debug_struct("TextureCache")
            .field("enabled", &self.enabled)
            .field("resident", &resident)
            .field("total_misses", &self.total)
            .finish_non_exhaustive()
    }
}

impl TextureCache {
    /// Whether texel reads go through the cache.
    pub(crate) fn enabled(&self) -> bool {
        self.enabled
    }

    /// Switch the cache on or off; either way it starts empty.
    pub(crate) fn set_enabled(&mut self, on: bool) {
        self.enabled = on;
        self.invalidate();
    }

    /// Forget every entry (docs/hardware/gpu.md §10): the next read of each reloads it.
    pub(crate) fn invalidate(&mut self) {
        self.tags = [INVALID; ENTRIES];
        self.copies = false;
        self.resident = Resident::Nowhere;
        self.clear = None;
    }

    /// The draw mode changes from `old` to `new` (GP0(E1h), a textured polygon's texpage
    /// attribute, docs/hardware/gpu.md §10): a different page, a change between 4-bit and
    /// the other depths, or a change of the texture disable bit empties the cache.
    pub(crate) fn texpage_change(&mut self, old: &DrawMode, new: &DrawMode) {
        let four_bit = |m: &DrawMode| m.depth == TextureDepth::Clut4;
        if old.page_x != new.page_x
            || old.page_y != new.page_y
            || four_bit(old) != four_bit(new)
            || old.texture_disable != new.texture_disable
        {
            self.invalidate();
        }
    }

    /// The [`mode`] a primitive's reads use now.
    pub(crate) fn mode(&self) -> u8 {
        match (self.enabled, self.copies) {
            (false, _) => mode::OFF,
            (true, false) => mode::TAGS,
            (true, true) => mode::COPIES,
        }
    }

    /// Before a primitive that reads the texture page at (`page_x`, `page_y`) (`None` for
    /// an untextured one) and may write `write`: the page joins where resident entries may
    /// lie, and when the write may reach resident entries their copies are taken from
    /// `vram` (VRAM still holds what they loaded) and kept from then on.
    #[inline]
    pub(crate) fn prepare(
        &mut self,
        vram: &[u16; VRAM_LEN],
        page: Option<(u16, u16)>,
        write: WriteRegion,
    ) {
        if !self.enabled || self.copies {
            return;
        }
        if let Some((x, y)) = page {
            let here = Resident::Page { x, y };
            if self.resident != here {
                self.resident = match self.resident {
                    Resident::Nowhere => here,
                    _ => Resident::Anywhere,
                };
                self.clear = None;
            }
        }
        if self.clear == Some(write) {
            return;
        }
        if self.resident.meets(&write) {
            self.keep_copies(vram);
        } else {
            self.clear = Some(write);
        }
    }

    /// Take the resident entries' copies from `vram` and read them from then on.
    #[cold]
    pub(crate) fn keep_copies(&mut self, vram: &[u16; VRAM_LEN]) {
        if !self.enabled || self.copies || self.resident == Resident::Nowhere {
            return;
        }
        for (&tag, data) in self.tags.iter().zip(&mut self.data) {
            if tag != INVALID {
                *data = Self::loaded(vram, tag);
            }
        }
        self.copies = true;
    }

    /// The four halfwords of VRAM an entry with `tag` holds.
    #[inline(always)]
    fn loaded(vram: &[u16; VRAM_LEN], tag: u32) -> [u16; ENTRY_HALFWORDS] {
        let first = (tag as usize * ENTRY_HALFWORDS) & (VRAM_LEN - ENTRY_HALFWORDS);
        vram.get(first..)
            .and_then(|s| s.first_chunk())
            .copied()
            .unwrap_or_default()
    }

    /// Start a primitive whose reads use [`mode::RUNS`].
    #[inline(always)]
    pub(crate) fn begin_runs(&mut self) {
        self.last = INVALID;
    }

    /// The VRAM halfword at `address` (below `VRAM_LEN`) as a texture of kind `TEX` (1 =
    /// 4-bit, 2 = 8-bit, 3 = 15-bit) reads it in [`mode`] `MODE`: a read whose entry does not
    /// hold the halfword's four is a miss, which loads them (docs/hardware/gpu.md §10).
    #[inline(always)]
    pub(crate) fn halfword<const TEX: u8, const MODE: u8>(
        &mut self,
        vram: &[u16; VRAM_LEN],
        address: usize,
    ) -> u16 {
        let address = address & (VRAM_LEN - 1);
        match MODE {
            mode::OFF => {}
            mode::TAGS => self.track::<TEX>(address),
            mode::RUNS => {
                let tag = tag_of(address);
                if tag != self.last {
                    self.track::<TEX>(address);
                    self.last = tag;
                }
            }
            _ => {
                let i = entry_index::<TEX>(address);
                let tag = tag_of(address);
                if self.tags[i] != tag {
                    self.data[i] = Self::loaded(vram, tag);
                    self.tags[i] = tag;
                    self.misses = self.misses.wrapping_add(1);
                }
                return self.data[i][address & 3];
            }
        }
        vram[address]
    }

    /// The four VRAM halfwords from `address` (a multiple of four, below `VRAM_LEN`) read
    /// one after the other, the lowest first, as a texture of kind `TEX` reads them in
    /// [`mode`] `MODE`: they share one entry and one tag (docs/hardware/gpu.md §10), so the
    /// first read may miss and the other three hit, and the misses and tags left are those of
    /// four [`TextureCache::halfword`] reads. The halfwords are those reads' when nothing
    /// is written under them between the reads.
    #[inline(always)]
    pub(crate) fn entry_halfwords<const TEX: u8, const MODE: u8>(
        &mut self,
        vram: &[u16; VRAM_LEN],
        address: usize,
    ) -> [u16; ENTRY_HALFWORDS] {
        let address = address & (VRAM_LEN - ENTRY_HALFWORDS);
        let tag = tag_of(address);
        match MODE {
            mode::OFF => {}
            mode::TAGS => self.track::<TEX>(address),
            mode::RUNS => {
                if tag != self.last {
                    self.track::<TEX>(address);
                    self.last = tag;
                }
            }
            _ => {
                let i = entry_index::<TEX>(address);
                if self.tags[i] != tag {
                    self.data[i] = Self::loaded(vram, tag);
                    self.tags[i] = tag;
                    self.misses = self.misses.wrapping_add(1);
                }
                return self.data[i];
            }
        }
        Self::loaded(vram, tag)
    }

    /// A read of the halfword at `address` with the copies not kept: a miss replaces the
    /// entry's tag.
    #[inline(always)]
    fn track<const TEX: u8>(&mut self, address: usize) {
        self.track_entry(entry_index::<TEX>(address), tag_of(address));
    }

    /// A read, with the copies not kept ([`mode::TAGS`]), of a halfword whose entry is `i`
    /// and tag `tag` (from [`entry_index`] and [`tag_of`]): the tag is stored and a miss
    /// counted without a branch, since texels that jump from entry to entry make a miss as
    /// likely as a hit.
    #[inline(always)]
    pub(crate) fn track_entry(&mut self, i: usize, tag: u32) {
        let t = &mut self.tags[i & (ENTRIES - 1)];
        self.misses = self.misses.wrapping_add(u32::from(*t != tag));
        *t = tag;
    }

    /// Reads, with the copies not kept ([`mode::TAGS`]), of the halfwords at the first `n`
    /// (at most 8) of the eight `address`es (below `VRAM_LEN`), in lane order: the misses
    /// and the tags left are those of reading the `n` halfwords one by one
    /// (docs/hardware/gpu.md §10). No read branches on whether it hits: texels that jump
    /// from entry to entry make a miss as likely as a hit.
    #[inline(always)]
    pub(crate) fn track_lanes<const TEX: u8>(&mut self, address: wide::u32x8, n: usize) {
        if n >= LANES {
            self.track_group::<TEX>(address);
        } else {
            self.track_some_lanes::<TEX>(address, n);
        }
    }

    /// [`TextureCache::track_lanes`] of the first `n` lanes, fewer than eight: each read
    /// stores its tag and counts a miss.
    #[inline(always)]
    pub(crate) fn track_some_lanes<const TEX: u8>(&mut self, address: wide::u32x8, n: usize) {
        let tag = (address >> 2u32).to_array();
        let entry = entry_index_lanes::<TEX>(address).to_array();
        let mut misses = 0;
        for (&i, &tag) in entry.iter().zip(&tag).take(n) {
            let t = &mut self.tags[i as usize & (ENTRIES - 1)];
            misses += u32::from(*t != tag);
            *t = tag;
        }
        self.misses = self.misses.wrapping_add(misses);
    }

    /// [`TextureCache::track_lanes`] of all eight lanes. The tags the reads find are gathered
    /// as they are replaced, lane by lane (a lane whose entry an earlier lane of the group
    /// used finds that lane's tag, docs/hardware/gpu.md §10), and compared with the reads'
    /// tags eight at a time.
    #[inline(always)]
    pub(crate) fn track_group<const TEX: u8>(&mut self, address: wide::u32x8) {
        let tags = address >> 2u32;
        let tag = tags.to_array();
        let entry = entry_index_lanes::<TEX>(address).to_array();
        let mut found = [0; LANES];
        for ((f, &i), &tag) in found.iter_mut().zip(&entry).zip(&tag) {
            let t = &mut self.tags[i as usize & (ENTRIES - 1)];
            *f = *t;
            *t = tag;
        }
        let hits = wide::u32x8::new(found).simd_eq(tags).to_bitmask();
        let misses = MISSED_LANES[hits as usize & (MISSED_LANES.len() - 1)];
        self.misses = self.misses.wrapping_add(u32::from(misses));
    }

    /// [`TextureCache::track_lanes`] for the next reads of `span`, a span whose texels step
    /// slowly ([`steps_slowly`]); `before` holds the address of the read just before each
    /// lane's in the span (the lane before it, or for lane 0 the previous group's last
    /// read). A read with the tag of the read just before it is a hit that changes nothing:
    /// the entry of that tag holds it since that read (docs/hardware/gpu.md §10), and nothing
    /// but the span's reads touches the cache in between. Only the lanes whose tag differs
    /// from their `before`'s, and the span's first read, are looked up.
    ///
    /// `before` comes from the span's texel coordinates one pixel back, not from the reads
    /// tracked before, so which lanes are looked up is known without waiting on the previous
    /// group. The two lowest such lanes are looked up with no test of how many there are: a
    /// group with fewer looks its one such lane up twice, or its lane 0, whose tag has been
    /// in its entry since the read before it (hits that change nothing); the rest, where a
    /// group has more than two, one by one.
    #[inline(always)]
    pub(crate) fn track_slow_lanes<const TEX: u8>(
        &mut self,
        address: wide::u32x8,
        before: wide::u32x8,
        n: usize,
        span: &mut SlowReads,
    ) {
        let tags = address >> 2u32;
        let valid = (1u32 << n.min(LANES)) - 1;
        let mut changed =
            (!tags.simd_eq(before >> 2u32).to_bitmask() | u32::from(span.first)) & valid;
        span.first = false;
        let t = tags.to_array();
        let entry = entry_index_lanes::<TEX>(address).to_array();
        let mut misses = 0;
        let mut look_up = |k: usize| {
            let k = k & (LANES - 1);
            let slot = &mut self.tags[entry[k] as usize & (ENTRIES - 1)];
            misses += u32::from(*slot != t[k]);
            *slot = t[k];
        };
        let lowest = |m: u32, or: u32| if m != 0 { m.trailing_zeros() } else { or };
        let k1 = lowest(changed, 0);
        changed &= changed.wrapping_sub(1);
        let k2 = lowest(changed, k1);
        changed &= changed.wrapping_sub(1);
        look_up(k1 as usize);
        look_up(k2 as usize);
        while changed != 0 {
            look_up(changed.trailing_zeros() as usize);
            changed &= changed - 1;
        }
        self.misses = self.misses.wrapping_add(misses);
    }

    /// Entry `index`: where its halfwords came from and their values (from `vram` while the
    /// copies are not kept, when they are the same); `None` when it holds nothing.
    pub(crate) fn entry(&self, index: u8, vram: &[u16; VRAM_LEN]) -> Option<TextureCacheEntry> {
        let i = usize::from(index);
        let tag = self.tags[i];
        (tag != INVALID).then(|| {
            let address = tag as usize * ENTRY_HALFWORDS;
            TextureCacheEntry {
                x: (address % crate::VRAM_WIDTH) as u16,
                y: (address / crate::VRAM_WIDTH) as u16,
                halfwords: if self.copies {
                    self.data[i]
                } else {
                    Self::loaded(vram, tag)
                },
            }
        })
    }

    /// The misses counted since the previous call, added to the running total.
    pub(crate) fn take_misses(&mut self) -> u32 {
        let n = core::mem::take(&mut self.misses);
        self.total = self.total.wrapping_add(u64::from(n));
        n
    }

    /// Misses since power-on.
    pub(crate) fn total_misses(&self) -> u64 {
        self.total
    }
}

impl crate::Gpu {
    /// Before a primitive, which writes inside the drawing area and reads `texture`'s page
    /// when textured: [`TextureCache::prepare`].
    #[inline]
    pub(crate) fn prepare_texture_cache(&mut self, texture: Option<&crate::primitive::Texture>) {
        let page = texture.map(|t| (t.page_x, t.page_y));
        let write = WriteRegion::area(&self.draw.area);
        self.texture_cache
            .prepare(self.vram.as_array(), page, write);
    }
}

/// The serialized form of [`TextureCache`] (feature `serde`): the switch, the tags, whether
/// the copies are kept and, when they are, the copies (else zeros: the resident entries
/// equal VRAM), where resident entries may lie, and the misses since power-on.
#[cfg(feature = "serde")]
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(rename = "TextureCache")]
struct Fields {
    enabled: bool,
    tags: alloc::vec::Vec<u32>,
    copies: bool,
    data: alloc::vec::Vec<u16>,
    resident: Resident,
    total: u64,
}

#[cfg(feature = "serde")]
impl serde::Serialize for TextureCache {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        // The copies of resident entries only: an invalid entry's halfwords are left over
        // from before and never read.
        let data = if self.copies {
            self.tags
                .iter()
                .zip(&self.data)
                .flat_map(|(&tag, d)| {
                    if tag == INVALID {
                        [0; ENTRY_HALFWORDS]
                    } else {
                        *d
                    }
                })
                .collect()
        } else {
            alloc::vec![0; ENTRIES * ENTRY_HALFWORDS]
        };
        Fields {
            enabled: self.enabled,
            tags: self.tags.to_vec(),
            copies: self.copies,
            data,
            resident: self.resident,
            total: self.total,
        }
        .serialize(serializer)
    }
}

/// A cache is read back only when it is one the GPU can reach: 256 tags and 1,024
/// halfwords; each tag invalid or naming four halfwords of VRAM that its entry can hold
/// (under the 4-bit or the 8/15-bit tiling) and, while the copies are not kept, inside the
/// page resident entries may lie in (a page's corner: X a multiple of 64, Y 0 or 256);
/// everything empty when the cache is off.
#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for TextureCache {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let f = Fields::deserialize(deserializer)?;
        let invalid = |what| D::Error::custom(crate::StateError::Invalid(what));
        if f.tags.len() != ENTRIES || f.data.len() != ENTRIES * ENTRY_HALFWORDS {
            return Err(invalid(
                "texture cache without 256 entries of four halfwords",
            ));
        }
        if !f.enabled && (f.copies || f.resident != Resident::Nowhere) {
            return Err(invalid("texture cache off but not empty"));
        }
        if let Resident::Page { x, y } = f.resident
            && (x % 64 != 0 || x > 960 || (y != 0 && y != 256))
        {
            return Err(invalid("texture cache page not at a texture page's corner"));
        }
        let mut cache = TextureCache {
            enabled: f.enabled,
            copies: f.copies,
            resident: f.resident,
            total: f.total,
            ..TextureCache::default()
        };
        for (i, (&tag, slot)) in f.tags.iter().zip(&mut cache.tags).enumerate() {
            if tag != INVALID {
                let address = tag as usize * ENTRY_HALFWORDS;
                let fits = entry_index::<1>(address) == i || entry_index::<3>(address) == i;
                let one = WriteRegion {
                    x: (address % crate::VRAM_WIDTH) as u32,
                    width: 1,
                    y: (address / crate::VRAM_WIDTH) as u32,
                    height: 1,
                };
                if !f.enabled || tag > MAX_TAG || !fits {
                    return Err(invalid("texture cache tag its entry cannot hold"));
                }
                if !f.copies && !f.resident.meets(&one) {
                    return Err(invalid("texture cache tag outside the page it reads"));
                }
            }
            *slot = tag;
        }
        if f.copies {
            cache.data.as_flattened_mut().copy_from_slice(&f.data);
        }
        Ok(cache)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tiling of docs/hardware/gpu.md §10, counted in halfwords: each 4-bit block is 16
    /// halfwords by 64 lines and each 8/15-bit block 32 by 32, every entry number appears
    /// exactly once in a block, and the blocks repeat the same numbering.
    #[test]
    fn blocks_number_their_entries_once() {
        fn check<const TEX: u8>(width: usize, height: usize) {
            for (bx, by) in [(0, 0), (width, 0), (0, height), (960, 448)] {
                let mut seen = [false; ENTRIES];
                for y in 0..height {
                    for x in (0..width).step_by(4) {
                        let a = (by + y) * 1024 + bx + x;
                        let i = entry_index::<TEX>(a);
                        assert!(!seen[i], "entry {i} twice in block ({bx}, {by})");
                        seen[i] = true;
                        // The block at the origin gives the same number at the same place.
                        assert_eq!(i, entry_index::<TEX>(y * 1024 + x));
                        // The four halfwords of an entry share it.
                        for k in 1..4 {
                            assert_eq!(entry_index::<TEX>(a + k), i);
                        }
                    }
                }
                assert!(seen.iter().all(|&s| s));
            }
        }
        check::<1>(16, 64);
        check::<2>(32, 32);
        check::<3>(32, 32);
    }

    #[test]
    fn lanes_number_entries_as_addresses_do() {
        let addresses: [u32; 8] = [0, 3, 4, 1023, 1024, 0x3_FFFF, 0x4_0405, 0x7_FFFF];
        let a = wide::u32x8::new(addresses);
        let (four, other) = (
            entry_index_lanes::<1>(a).to_array(),
            entry_index_lanes::<3>(a).to_array(),
        );
        for (k, &address) in addresses.iter().enumerate() {
            assert_eq!(four[k] as usize, entry_index::<1>(address as usize));
            assert_eq!(other[k] as usize, entry_index::<3>(address as usize));
        }
    }

    /// Eight reads at a time leave the misses and tags of the same reads made one by one,
    /// whether the span is taken as stepping slowly or not: runs of reads in one entry,
    /// jumps between entries, the same entry number in another block, partial groups, and
    /// spans after spans on a cache left as the one before left it.
    #[test]
    fn lanes_track_as_reads_one_by_one() {
        fn check<const TEX: u8>(reads: &[u32]) {
            for slow in [false, true] {
                let (mut lanes, mut one) = (TextureCache::default(), TextureCache::default());
                // The reads as two spans, the second starting where the first left the cache.
                let (first, second) = reads.split_at(reads.len() / 2);
                for span in [first, second] {
                    let mut reads = SlowReads::new();
                    for (g, group) in span.chunks(8).enumerate() {
                        let mut a = [0u32; 8];
                        a[..group.len()].copy_from_slice(group);
                        // Each read's previous one. The span's first has none: it is given
                        // its own address, so only the span's start has it looked up.
                        let b = core::array::from_fn(|k| {
                            let i = (g * 8 + k).saturating_sub(1);
                            span.get(i).copied().unwrap_or(0)
                        });
                        let (a, b) = (wide::u32x8::new(a), wide::u32x8::new(b));
                        if slow {
                            lanes.track_slow_lanes::<TEX>(a, b, group.len(), &mut reads);
                        } else {
                            lanes.track_lanes::<TEX>(a, group.len());
                        }
                        for &address in group {
                            one.track::<TEX>(address as usize);
                        }
                    }
                }
                assert_eq!(lanes.tags, one.tags, "slow {slow}");
                assert_eq!(lanes.take_misses(), one.take_misses(), "slow {slow}");
            }
        }
        // A 15-bit row stepping one halfword a pixel, then back over the same entries.
        let row: alloc::vec::Vec<u32> =
            (0..21).chain((0..21).rev()).map(|x| 5 * 1024 + x).collect();
        // A 4-bit column: each read a line down, and the same entry numbers 64 lines below.
        let column: alloc::vec::Vec<u32> = (0..140).map(|y| y * 1024 + 70).collect();
        // Scattered reads, entries shared by reads far apart.
        let mut x = 12345u32;
        let scattered: alloc::vec::Vec<u32> = (0..203)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                (x >> 8) & if x & 1 == 0 { 0x7_C0FF } else { 0x7_FFFF }
            })
            .collect();
        // A 4-bit row at a quarter texel a pixel: many reads of each halfword, then the
        // same entries again from the block to the right.
        let slow: alloc::vec::Vec<u32> = (0..300).map(|k| 9 * 1024 + 60 + k / 16).collect();
        for reads in [&row, &column, &scattered, &slow] {
            check::<1>(reads);
            check::<2>(reads);
            check::<3>(reads);
            // Partial groups: every length from 1 to 8.
            for n in 1..=8 {
                check::<1>(&reads[..n]);
                check::<3>(&reads[..n]);
            }
        }
    }

    /// A span steps slowly when a pixel moves at most a quarter of an entry: 4, 2 or 1
    /// texels in U (4-bit, 8-bit, 15-bit) or a quarter of a line in V, or a mix of the two;
    /// either direction.
    #[test]
    fn spans_step_slowly_up_to_a_quarter_entry() {
        let texel = 1u32 << 24;
        let slow = |tex: u8, du: u32, dv: u32| match tex {
            1 => steps_slowly::<1>((du, dv)),
            2 => steps_slowly::<2>((du, dv)),
            _ => steps_slowly::<3>((du, dv)),
        };
        for (tex, quarter) in [(1, 4), (2, 2), (3, 1)] {
            assert!(slow(tex, quarter * texel, 0));
            assert!(slow(tex, (quarter * texel).wrapping_neg(), 0));
            assert!(!slow(tex, quarter * texel + (1 << 4), 0));
            assert!(slow(tex, quarter * texel / 2, texel / 8));
            assert!(!slow(tex, quarter * texel / 2, texel / 8 + 1));
        }
        assert!(slow(3, 0, texel / 4));
        assert!(!slow(3, 0, (texel / 4 + 1).wrapping_neg()));
        assert!(!slow(1, u32::MAX / 2, 0));
    }

    #[test]
    fn a_miss_loads_four_halfwords_and_a_hit_keeps_them() {
        // Reads from the copies (the mode after a write under resident entries).
        let mut vram = alloc::boxed::Box::new([0u16; VRAM_LEN]);
        for (i, p) in vram.iter_mut().enumerate().take(4096) {
            *p = i as u16;
        }
        let mut cache = TextureCache::default();
        const COPIES: u8 = mode::COPIES;
        // Halfword 1030 is (6, 1): entry 1 of the 15-bit tiling, halfwords 1028-1031.
        assert_eq!(cache.halfword::<3, COPIES>(&vram, 1030), 1030);
        assert_eq!(cache.take_misses(), 1);
        vram[1028..1032].fill(0xAAAA);
        for a in 1028..1032 {
            assert_eq!(cache.halfword::<3, COPIES>(&vram, a), a as u16);
        }
        assert_eq!(cache.take_misses(), 0);
        // (6, 33) is the same entry number in the block below: it replaces the entry.
        assert_eq!(cache.halfword::<3, COPIES>(&vram, 33 * 1024 + 6), 0);
        assert_eq!(cache.halfword::<3, COPIES>(&vram, 1030), 0xAAAA);
        assert_eq!(cache.take_misses(), 2);
        assert_eq!(cache.total_misses(), 3);
    }
}
