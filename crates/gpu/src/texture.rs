//! Texture sampling: texture window, 4/8/15-bit texel fetch, CLUT lookup and the CLUT cache
//! (docs/hardware/gpu.md §7).

use crate::color::{DitheredCells, dithered_clut4};
use crate::primitive::Texture;
use crate::state::{TextureDepth, TextureWindow};
use crate::texture_cache::TextureCache;
use crate::{VRAM_LEN, VRAM_WIDTH};

/// The latched CLUT (docs/hardware/gpu.md §7, "CLUT cache"): entries are loaded from VRAM when a 4/8-bit
/// primitive is drawn with a CLUT position other than the cached one, or needs 8-bit entries
/// when only 4-bit ones are cached; GP0(01h) invalidates it. Overwriting the CLUT in VRAM does
/// not refresh it.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ClutCache {
    #[cfg_attr(feature = "serde", serde(with = "crate::serde_array"))]
    entries: [u16; 256],
    key: Option<(u16, u16)>,
    loaded_8bit: bool,
    /// The first 16 entries shaded for one colour in every dither cell: derived from the
    /// entries, forgotten whenever they are reloaded, never saved.
    #[cfg_attr(feature = "serde", serde(skip))]
    dithered: DitheredClut4,
}

/// The cached [`DitheredCells`] and the colour they were shaded with. Colours are kept as
/// [`color_key`] words, [`NO_COLOR`] for none.
#[derive(Clone)]
struct DitheredClut4 {
    /// The colour `cells` were shaded for, or [`NO_COLOR`] (not valid).
    color: u32,
    /// The colour the previous request asked for, and how many requests in a row asked for
    /// it: the third primitive in a row with one colour has the table shaded, whatever its
    /// size (the two triangles of one quad alone do not).
    requested: u32,
    run: u8,
    cells: DitheredCells,
}

impl Default for DitheredClut4 {
    fn default() -> Self {
        Self {
            color: NO_COLOR,
            requested: NO_COLOR,
            run: 0,
            cells: [[[0; 16]; 4]; 4],
        }
    }
}

/// A colour key no 8-bit RGB colour has.
const NO_COLOR: u32 = u32::MAX;

/// An 8-bit RGB colour as one word, R in bits 0-7, G 8-15, B 16-23.
#[inline(always)]
fn color_key([r, g, b]: [u8; 3]) -> u32 {
    u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16
}

impl core::fmt::Debug for DitheredClut4 {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DitheredClut4")
            .field("color", &(self.color != NO_COLOR).then_some(self.color))
            .finish_non_exhaustive()
    }
}

/// Two caches are equal when they hold the same entries for the same CLUT; the derived
/// dithered table is not part of the chip state.
impl PartialEq for ClutCache {
    fn eq(&self, other: &Self) -> bool {
        self.entries == other.entries
            && self.key == other.key
            && self.loaded_8bit == other.loaded_8bit
    }
}

impl Eq for ClutCache {}

impl Default for ClutCache {
    fn default() -> Self {
        Self {
            entries: [0; 256],
            key: None,
            loaded_8bit: false,
            dithered: DitheredClut4::default(),
        }
    }
}

impl ClutCache {
    /// GP0(01h): forget the latched CLUT so the next 4/8-bit primitive reloads it.
    pub fn invalidate(&mut self) {
        self.key = None;
        self.loaded_8bit = false;
        self.dithered.color = NO_COLOR;
    }

    /// A latched CLUT position is one a CLUT attribute can give: X a multiple of 16 up to
    /// 1008, Y below 512 (docs/hardware/gpu.md §7); 8-bit entries are only loaded with a position.
    #[cfg(feature = "serde")]
    pub(crate) fn check(&self) -> Result<(), &'static str> {
        match self.key {
            Some((x, y)) if !x.is_multiple_of(16) || x > 1008 || y > 511 => {
                Err("CLUT cache position outside VRAM or not a multiple of 16")
            }
            None if self.loaded_8bit => Err("CLUT cache with 8-bit entries but no position"),
            _ => Ok(()),
        }
    }

    /// The latched entries.
    pub fn entries(&self) -> &[u16; 256] {
        &self.entries
    }

    /// How many entries [`ClutCache::latch`] would load from VRAM for `texture`: 0 when the
    /// cache already holds them or the texture is 15-bit, else 16 or 256.
    pub fn load_size(&self, texture: &Texture) -> u32 {
        let needs_8bit = match texture.depth {
            TextureDepth::Clut4 => false,
            TextureDepth::Clut8 => true,
            TextureDepth::Direct15 => return 0,
        };
        let key = (texture.clut_x, texture.clut_y);
        if self.key != Some(key) || (needs_8bit && !self.loaded_8bit) {
            if needs_8bit { 256 } else { 16 }
        } else {
            0
        }
    }

    /// Make sure the entries a primitive with `texture` needs are latched; returns them.
    pub fn latch(&mut self, vram: &[u16; crate::VRAM_LEN], texture: &Texture) -> &[u16; 256] {
        let needs_8bit = match texture.depth {
            TextureDepth::Clut4 => false,
            TextureDepth::Clut8 => true,
            TextureDepth::Direct15 => return &self.entries,
        };
        let key = (texture.clut_x, texture.clut_y);
        if self.key != Some(key) || (needs_8bit && !self.loaded_8bit) {
            let count = if needs_8bit { 256 } else { 16 };
            let row = (texture.clut_y as usize & 511) * VRAM_WIDTH;
            for (i, entry) in self.entries.iter_mut().take(count).enumerate() {
                *entry = vram[row + ((texture.clut_x as usize + i) & 1023)];
            }
            self.key = Some(key);
            self.loaded_8bit = needs_8bit;
            self.dithered.color = NO_COLOR;
        }
        &self.entries
    }

    /// [`ClutCache::latch`] for a 4-bit texture modulated by the one colour `rgb` and
    /// dithered, and the latched entries shaded for every dither cell: kept from an earlier
    /// primitive with the same colour and entries, else shaded now when the two requests
    /// before were for the same colour or `build` says so, else `None`.
    pub(crate) fn latch_dithered(
        &mut self,
        vram: &[u16; crate::VRAM_LEN],
        texture: &Texture,
        rgb: [u8; 3],
        build: impl FnOnce() -> bool,
    ) -> (&[u16; 256], Option<&DitheredCells>) {
        self.latch(vram, texture);
        let d = &mut self.dithered;
        let key = color_key(rgb);
        d.run = if d.requested == key {
            d.run.saturating_add(1)
        } else {
            1
        };
        d.requested = key;
        if d.color != key && (d.run >= 3 || build()) {
            dithered_clut4(&self.entries, rgb, &mut d.cells);
            d.color = key;
        }
        let cells = (d.color == key).then_some(&d.cells);
        (&self.entries, cells)
    }
}

impl TextureWindow {
    /// Apply the window to an 8-bit U: (u & !(maskX*8)) | ((offX & maskX) * 8) (docs/hardware/gpu.md §7).
    #[inline(always)]
    pub fn apply_u(&self, u: u8) -> u8 {
        (u & !(self.mask_x << 3)) | ((self.offset_x & self.mask_x) << 3)
    }

    /// Apply the window to an 8-bit V.
    #[inline(always)]
    pub fn apply_v(&self, v: u8) -> u8 {
        (v & !(self.mask_y << 3)) | ((self.offset_y & self.mask_y) << 3)
    }
}

/// Everything a textured span needs to fetch texels, fixed per primitive.
#[derive(Clone, Copy)]
pub struct Sampler<'a> {
    /// Latched CLUT.
    pub clut: &'a [u16; 256],
    /// Page left edge.
    pub page_x: usize,
    /// Page top line.
    pub page_y: usize,
    /// The texture window as AND/OR masks on U: `u' = (u & u_and) | u_or` (docs/hardware/gpu.md §7).
    pub u_and: u8,
    /// OR mask on U.
    pub u_or: u8,
    /// AND mask on V.
    pub v_and: u8,
    /// OR mask on V.
    pub v_or: u8,
}

/// The VRAM halfword at `address` (masked to VRAM) as a texture of kind `TEX` (1 = 4-bit,
/// 2 = 8-bit, 3 = 15-bit) reads it, through `cache` in the cache mode `CACHE`
/// (docs/hardware/gpu.md §10).
#[inline(always)]
pub(crate) fn texture_halfword<const TEX: u8, const CACHE: u8>(
    vram: &[u16; VRAM_LEN],
    cache: &mut TextureCache,
    address: usize,
) -> u16 {
    cache.halfword::<TEX, CACHE>(vram, address)
}

/// The CLUT index held by texel `u` of a texture halfword `word` of kind `TEX` (1 = 4-bit,
/// 2 = 8-bit): 4 bits from bit `(u & 3) * 4`, or 8 bits from bit `(u & 1) * 8`; a halfword
/// holds four or two texels, the lowest U first (docs/hardware/gpu.md §7).
#[inline(always)]
pub(crate) fn clut_index<const TEX: u8>(word: u16, u: usize) -> usize {
    if TEX == 1 {
        ((word >> ((u & 3) * 4)) & 0xF) as usize
    } else {
        ((word >> ((u & 1) * 8)) & 0xFF) as usize
    }
}

impl<'a> Sampler<'a> {
    /// A sampler for the page at (`page_x`, `page_y`) through `window`.
    pub fn new(clut: &'a [u16; 256], page_x: usize, page_y: usize, window: TextureWindow) -> Self {
        Self {
            clut,
            page_x,
            page_y,
            u_and: !(window.mask_x << 3),
            u_or: (window.offset_x & window.mask_x) << 3,
            v_and: !(window.mask_y << 3),
            v_or: (window.offset_y & window.mask_y) << 3,
        }
    }

    /// Whether the texture window leaves U and V as they are (mask 0).
    #[inline(always)]
    pub fn window_is_identity(&self) -> bool {
        // The four masks compared as one word.
        u32::from_le_bytes([self.u_and, self.u_or, self.v_and, self.v_or]) == 0x00FF_00FF
    }

    /// The VRAM address of the halfword holding texel (u, v) of a page of kind `TEX` (1 =
    /// 4-bit, 2 = 8-bit, 3 = 15-bit), after the texture window; X wraps at 1024, Y at 512
    /// (docs/hardware/gpu.md §7). Returns it with the window-applied U.
    #[inline(always)]
    fn address<const TEX: u8>(&self, u: u8, v: u8) -> (usize, usize) {
        let u = ((u & self.u_and) | self.u_or) as usize;
        let v = ((v & self.v_and) | self.v_or) as usize;
        let shift = match TEX {
            1 => 2,
            2 => 1,
            _ => 0,
        };
        let row = ((self.page_y + v) & 511) * VRAM_WIDTH;
        (row + ((self.page_x + (u >> shift)) & 1023), u)
    }

    /// The 4-bit texel index (a CLUT entry number) at (u, v), after the texture window; X
    /// wraps at 1024 (docs/hardware/gpu.md §7). Read through `cache` in mode `CACHE` (§10).
    #[inline(always)]
    pub fn index4<const CACHE: u8>(
        &self,
        vram: &[u16; VRAM_LEN],
        cache: &mut TextureCache,
        u: u8,
        v: u8,
    ) -> usize {
        let (address, u) = self.address::<1>(u, v);
        clut_index::<1>(texture_halfword::<1, CACHE>(vram, cache, address), u)
    }

    /// The texel at (u, v) for a page of kind `TEX` (1 = 4-bit, 2 = 8-bit, 3 = 15-bit),
    /// after the texture window; X wraps at 1024 (docs/hardware/gpu.md §7). Read through
    /// `cache` in mode `CACHE` (§10).
    #[inline(always)]
    pub fn fetch<const TEX: u8, const CACHE: u8>(
        &self,
        vram: &[u16; VRAM_LEN],
        cache: &mut TextureCache,
        u: u8,
        v: u8,
    ) -> u16 {
        let (address, u) = self.address::<TEX>(u, v);
        let word = texture_halfword::<TEX, CACHE>(vram, cache, address);
        match TEX {
            1 | 2 => self.clut[clut_index::<TEX>(word, u)],
            _ => word,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The AND/OR form equals the hardware-reference formula for every window and coordinate.
    #[test]
    fn window_masks_match_formula() {
        for mask in 0..32u8 {
            for offset in 0..32u8 {
                let w = TextureWindow {
                    mask_x: mask,
                    mask_y: offset,
                    offset_x: offset,
                    offset_y: mask,
                };
                let s = Sampler::new(&[0; 256], 0, 0, w);
                for c in 0..=255u8 {
                    assert_eq!((c & s.u_and) | s.u_or, w.apply_u(c));
                    assert_eq!((c & s.v_and) | s.v_or, w.apply_v(c));
                    let by_formula = (c as u32 & !(mask as u32 * 8)) | ((offset & mask) as u32 * 8);
                    assert_eq!(w.apply_u(c) as u32, by_formula);
                }
            }
        }
    }
}
