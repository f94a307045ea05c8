//! The VRAM rows drawing writes under interlace (docs/hardware/gpu.md §8): primitives and
//! VRAM fills both take a [`Rows`].

/// The VRAM lines a primitive may write. In 480i with GP0(E1h) bit 10 clear, drawing
/// skips the lines of the field being displayed (docs/hardware/gpu.md §8; psx-spx "GP1(08h)":
/// the interlace flag affects GP0 drawing). Chosen once per primitive: an unfiltered
/// primitive walks its rows as before, a filtered one walks every second row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) enum Rows {
    /// Every line.
    #[default]
    All,
    /// Lines whose bit 0 differs from this value (0 or 1).
    SkipParity(u8),
}

impl Rows {
    /// The first drawn row at or after `y`.
    #[inline(always)]
    pub(crate) fn first(self, y: i32) -> i32 {
        match self {
            Rows::All => y,
            Rows::SkipParity(p) => Self::first_from(p, y),
        }
    }

    /// The first row at or after `y` that is drawn.
    #[inline(always)]
    fn first_from(parity: u8, y: i32) -> i32 {
        if (y & 1) as u8 == parity & 1 {
            y + 1
        } else {
            y
        }
    }

    /// How many rows of `lo..hi` are drawn.
    #[inline(always)]
    pub(crate) fn count(self, lo: i32, hi: i32) -> u32 {
        let mut n = 0u32;
        if lo < hi {
            match self {
                Rows::All => n = (hi - lo) as u32,
                Rows::SkipParity(p) => {
                    let first = Self::first_from(p, lo);
                    if first < hi {
                        n = ((hi - first + 1) / 2) as u32;
                    }
                }
            }
        }
        n
    }

    /// Call `f` for each drawn row of `lo..hi`, ascending.
    #[inline(always)]
    pub(crate) fn each(self, lo: i32, hi: i32, mut f: impl FnMut(i32)) {
        // One loop, so that `f` is inlined once rather than called from two.
        let (mut y, step) = match self {
            Rows::All => (lo, 1),
            Rows::SkipParity(p) => (Self::first_from(p, lo), 2),
        };
        while y < hi {
            f(y);
            y += step;
        }
    }

    /// Whether row `y` is drawn.
    #[inline(always)]
    pub fn keeps(self, y: i32) -> bool {
        match self {
            Rows::All => true,
            Rows::SkipParity(p) => (y & 1) as u8 != p & 1,
        }
    }
}
