//! Placement of textures and CLUTs in VRAM beside two display buffers (docs/hardware/gpu.md §7).
//!
//! Layout: display buffers at (0, 0) and (0, height) (`width` x `height` each, height at
//! most 256); texture pages (64-halfword columns, rows at y = 0 and 256) to the right of the
//! buffers; CLUTs in the lines below the second buffer (x multiple of 16). When the buffers
//! leave no line below them (height 256), the last columns of page row 1 (y 256..511) hold the
//! CLUTs instead and take no texture: one 64-halfword column (x 960..1023, four 4-bit CLUTs to a
//! line) when every CLUT has 16 entries, four columns (x 768..1023, one 8-bit CLUT to a line)
//! when a scene has an 8-bit texture.

use crate::scene::texture::Texture;
use gpu::{BlendMode, ClutAttr, Texpage, TextureDepth};
use std::fmt;

/// Where a texture and its CLUT went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    /// Texture page left edge (multiple of 64).
    pub page_x: u16,
    /// Texture page top (0 or 256).
    pub page_y: u16,
    /// CLUT position (x multiple of 16), when the texture has one.
    pub clut: Option<(u16, u16)>,
}

impl Placement {
    /// The texpage attribute (GP0 polygon vertex 1 UV word, high half) of this placement
    /// (docs/hardware/gpu.md §2).
    pub fn texpage(&self, depth: TextureDepth, blend: BlendMode) -> Texpage {
        Texpage {
            page_x: self.page_x,
            page_y: self.page_y,
            blend,
            depth,
            ..Texpage::default()
        }
    }

    /// The CLUT attribute (vertex 0 UV word, high half; docs/hardware/gpu.md §7); zero
    /// without a CLUT.
    pub fn clut_attr(&self) -> ClutAttr {
        self.clut
            .map_or(ClutAttr::default(), |(x, y)| ClutAttr { x, y })
    }
}

/// VRAM has no room left for a texture or its CLUT.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum VramAllocError {
    /// No texture-page slot for the texture.
    Texture {
        /// The texture's name.
        name: String,
        /// The screen size the display buffers were laid out for.
        screen: (u16, u16),
    },
    /// No CLUT slot for the texture's CLUT.
    Clut {
        /// The texture's name.
        name: String,
        /// The screen size the display buffers were laid out for.
        screen: (u16, u16),
    },
}

impl fmt::Display for VramAllocError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (what, name, (w, h)) = match self {
            VramAllocError::Texture { name, screen } => ("texture", name, *screen),
            VramAllocError::Clut { name, screen } => ("the CLUT of texture", name, *screen),
        };
        write!(
            f,
            "VRAM full: no room for {what} `{name}` beside two {w}x{h} display buffers \
             (textures take the 64-halfword columns right of x = {w}); a narrower --size, or \
             fewer or smaller textures, leaves more room"
        )
    }
}

impl std::error::Error for VramAllocError {}

/// Hands out texture pages and CLUT slots.
#[derive(Clone, Debug)]
pub struct VramAllocator {
    first_column: u16,
    next: u16,
    clut_x: u16,
    clut_y: u16,
    clut_left: u16,
    clut_right: u16,
    clut_bottom: u16,
    /// Page columns at the right of page row 1 that hold CLUTs and take no texture (0 when
    /// the CLUTs go below the display buffers).
    clut_columns: u16,
    screen: (u16, u16),
}

impl VramAllocator {
    /// An allocator for display buffers of `width` x `height` (two, stacked), for textures
    /// whose widest CLUT has `widest_clut` entries (0 when no texture has a CLUT).
    pub fn new(width: u16, height: u16, widest_clut: usize) -> Self {
        let first_column = width.div_ceil(64).min(16);
        let below = height.saturating_mul(2).min(512);
        let screen = (width, height);
        if below < 512 || widest_clut == 0 {
            Self {
                first_column,
                next: 0,
                clut_x: 0,
                clut_y: below,
                clut_left: 0,
                clut_right: width.min(1024),
                clut_bottom: 512,
                clut_columns: 0,
                screen,
            }
        } else {
            // CLUTs need a strip as wide as the widest one, in whole page columns.
            let clut_columns = u16::try_from(widest_clut.div_ceil(64))
                .unwrap_or(u16::MAX)
                .min(16 - first_column);
            let clut_left = 1024 - 64 * clut_columns;
            Self {
                first_column,
                next: 0,
                clut_x: clut_left,
                clut_y: 256,
                clut_left,
                clut_right: 1024,
                clut_bottom: 512,
                clut_columns,
                screen,
            }
        }
    }

    /// Place a texture: its own page slot (one to four 64-halfword columns, one page row),
    /// and a CLUT slot when it has a CLUT.
    pub fn place(&mut self, name: &str, texture: &Texture) -> Result<Placement, VramAllocError> {
        let columns = texture.row_halfwords().div_ceil(64).max(1) as u16;
        let per_row = 16 - self.first_column;
        let full = || VramAllocError::Texture {
            name: name.into(),
            screen: self.screen,
        };
        if columns > per_row {
            return Err(full());
        }
        // Slots run along page row 0, then page row 1; a texture never straddles rows.
        let row_len = |row: u16| {
            if row == 1 {
                per_row - self.clut_columns
            } else {
                per_row
            }
        };
        let mut row = self.next / per_row;
        let mut col = self.next % per_row;
        if col + columns > row_len(row) {
            row += 1;
            col = 0;
        }
        if row > 1 || columns > row_len(row) {
            return Err(full());
        }
        self.next = row * per_row + col + columns;
        let page_x = (self.first_column + col) * 64;
        let page_y = row * 256;
        let clut = if texture.clut.is_empty() {
            None
        } else {
            let len = u16::try_from(texture.clut.len()).unwrap_or(u16::MAX);
            if self.clut_x.saturating_add(len) > self.clut_right {
                self.clut_x = self.clut_left;
                self.clut_y += 1;
            }
            if self.clut_y >= self.clut_bottom
                || len > self.clut_right.saturating_sub(self.clut_left)
            {
                return Err(VramAllocError::Clut {
                    name: name.into(),
                    screen: self.screen,
                });
            }
            let at = (self.clut_x, self.clut_y);
            self.clut_x += len;
            Some(at)
        };
        Ok(Placement {
            page_x,
            page_y,
            clut,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tex(depth: TextureDepth, width: u16) -> Texture {
        Texture {
            width,
            height: 64,
            depth,
            texels: vec![0; width as usize * 64],
            clut: vec![0; depth.clut_len()],
        }
    }

    #[test]
    fn pages_right_of_display_and_cluts_below() {
        let mut a = VramAllocator::new(320, 240, 16);
        // A 256-wide 15-bit texture (the third) needs four columns, and no CLUT.
        for (name, depth, width, page_x, clut) in [
            ("a", TextureDepth::Clut4, 64, 320, Some((0, 480))),
            ("b", TextureDepth::Clut4, 64, 384, Some((16, 480))),
            ("c", TextureDepth::Direct15, 256, 448, None),
        ] {
            let p = a.place(name, &tex(depth, width)).unwrap();
            assert_eq!((p.page_x, p.page_y, p.clut), (page_x, 0, clut), "{name}");
        }
    }

    /// At height 256 the buffers fill VRAM's height: 4-bit CLUTs go to x 960..1023 of
    /// lines 256..511, four to a line, and no texture overlaps them.
    #[test]
    fn cluts_beside_full_height_buffers() {
        let mut a = VramAllocator::new(640, 256, 16);
        let p = a.place("a", &tex(TextureDepth::Clut4, 64)).unwrap();
        assert_eq!((p.page_x, p.page_y, p.clut), (640, 0, Some((960, 256))));
        let mut pages = vec![(p.page_x, p.page_y)];
        let mut cluts = Vec::new();
        for _ in 0..5 {
            let q = a.place("b", &tex(TextureDepth::Clut4, 64)).unwrap();
            pages.push((q.page_x, q.page_y));
            cluts.push(q.clut);
        }
        assert_eq!(
            cluts,
            [(976, 256), (992, 256), (1008, 256), (960, 257), (976, 257)].map(Some)
        );
        // Columns 10..15 of row 0 and 10..14 of row 1: eleven one-column textures in all.
        while let Ok(q) = a.place("c", &tex(TextureDepth::Clut4, 64)) {
            pages.push((q.page_x, q.page_y));
        }
        assert_eq!(pages.len(), 11);
        assert!(
            pages.iter().all(|&(x, y)| y == 0 || x + 64 <= 960),
            "{pages:?}"
        );
    }

    /// With an 8-bit texture in the scene, the CLUT strip beside full-height buffers is four
    /// columns wide (x 768..1023: 256 entries, one CLUT to a line) and textures keep out of it.
    #[test]
    fn eight_bit_cluts_beside_full_height_buffers() {
        let mut a = VramAllocator::new(640, 256, 256);
        let p = a.place("a", &tex(TextureDepth::Clut8, 128)).unwrap();
        assert_eq!((p.page_x, p.page_y, p.clut), (640, 0, Some((768, 256))));
        let q = a.place("b", &tex(TextureDepth::Clut4, 64)).unwrap();
        assert_eq!(q.clut, Some((768, 257)));
        let mut pages = vec![(p.page_x, p.page_y, 1), (q.page_x, q.page_y, 1)];
        while let Ok(r) = a.place("c", &tex(TextureDepth::Clut4, 64)) {
            pages.push((r.page_x, r.page_y, 1));
        }
        // Row 0: columns 10..15 (six); row 1: columns 10..11 (two) left of the strip.
        assert_eq!(pages.iter().map(|p| p.2).sum::<u16>(), 8);
        assert!(
            pages.iter().all(|&(x, y, _)| y == 0 || x + 64 <= 768),
            "{pages:?}"
        );
    }

    /// A texture that cannot fit names the screen size that left no room.
    #[test]
    fn full_names_the_screen_size() {
        let mut a = VramAllocator::new(640, 256, 256);
        let e = a.place("wide", &tex(TextureDepth::Direct15, 256)).unwrap();
        assert_eq!((e.page_x, e.page_y), (640, 0));
        let e = a
            .place("wide2", &tex(TextureDepth::Direct15, 256))
            .unwrap_err();
        assert_eq!(
            e,
            VramAllocError::Texture {
                name: "wide2".into(),
                screen: (640, 256)
            }
        );
        let text = e.to_string();
        assert!(
            text.contains("640x256") && text.contains("--size"),
            "{text}"
        );
    }

    #[test]
    fn reports_full() {
        let mut a = VramAllocator::new(320, 240, 16);
        let mut placed = 0;
        while a.place("t", &tex(TextureDepth::Direct15, 256)).is_ok() {
            placed += 1;
        }
        // 11 free columns per row: two 4-column textures per row, two rows; 3 columns of
        // the second row are left for three 1-column textures.
        assert_eq!(placed, 4);
        for _ in 0..3 {
            a.place("s", &tex(TextureDepth::Clut4, 8)).unwrap();
        }
        assert_eq!(
            a.place("x", &tex(TextureDepth::Clut4, 8)).unwrap_err(),
            VramAllocError::Texture {
                name: "x".into(),
                screen: (320, 240)
            }
        );
    }
}
