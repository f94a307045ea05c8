//! Pixel history: every change every command made to VRAM, stored per 64x64 tile of VRAM
//! so that the page answers "which commands wrote this pixel, and what did it hold before
//! and after each" by loading one file (docs/inspect.md, "Pixel history").
//!
//! A tile's file is `data/hist/tile-TTT.js`, calling
//! `INSPECT.hist([T, "initial", [[command, y, x, "values"], ...]])`: the tile's 4,096
//! halfwords before the first command (row-major), then one record per run of adjacent
//! changed pixels in a row, in command order, with the run's new values. Values are 4 hex
//! digits each, `hhhh:N;` standing for `N` copies of `hhhh`.

use gpu::VRAM_WIDTH;
use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Side of a tile in pixels.
pub const TILE: usize = 64;

/// Tiles across VRAM.
pub const TILES_X: usize = VRAM_WIDTH / TILE;

/// Tiles in VRAM.
pub const TILES: usize = TILES_X * (gpu::VRAM_HEIGHT / TILE);

/// Append `values` to `out`, a run of equal values as `hhhh:N;`.
pub fn encode_values(values: &[u16], out: &mut String) {
    let mut i = 0;
    while let Some(&v) = values.get(i) {
        let n = values[i..].iter().take_while(|&&w| w == v).count();
        let _ = write!(out, "{v:04x}");
        if n > 1 {
            let _ = write!(out, ":{n};");
        }
        i += n;
    }
}

/// The history files being written.
pub struct History {
    dir: PathBuf,
    files: Vec<Option<BufWriter<File>>>,
    record: String,
}

fn io_err(path: &Path, e: std::io::Error) -> String {
    format!("{}: {e}", path.display())
}

impl History {
    /// Start the history in `out/data/hist`.
    pub fn new(out: &Path) -> Result<Self, String> {
        let dir = out.join("data/hist");
        std::fs::create_dir_all(&dir).map_err(|e| io_err(&dir, e))?;
        Ok(Self {
            dir,
            files: (0..TILES).map(|_| None).collect(),
            record: String::new(),
        })
    }

    fn path(&self, tile: usize) -> PathBuf {
        self.dir.join(format!("tile-{tile:03}.js"))
    }

    /// Record that command `index` changed the pixels of row `y` from column `x` on to
    /// `values` (all in one tile); `initial` is VRAM before the first command.
    pub fn run(
        &mut self,
        index: usize,
        y: usize,
        x: usize,
        values: &[u16],
        initial: &[u16],
    ) -> Result<(), String> {
        let tile = (y / TILE) * TILES_X + x / TILE;
        let path = self.path(tile);
        let Some(slot) = self.files.get_mut(tile) else {
            return Ok(());
        };
        self.record.clear();
        if slot.is_none() {
            let f = File::create(&path).map_err(|e| io_err(&path, e))?;
            let mut init = Vec::with_capacity(TILE * TILE);
            let (tx, ty) = (x / TILE * TILE, y / TILE * TILE);
            for row in ty..ty + TILE {
                let at = row * VRAM_WIDTH + tx;
                init.extend_from_slice(initial.get(at..at + TILE).unwrap_or(&[0; TILE]));
            }
            let _ = write!(self.record, "INSPECT.hist([{tile},\"");
            encode_values(&init, &mut self.record);
            self.record.push_str("\",[");
            *slot = Some(BufWriter::new(f));
        } else {
            self.record.push(',');
        }
        let _ = write!(self.record, "[{index},{y},{x},\"");
        encode_values(values, &mut self.record);
        self.record.push_str("\"]");
        if let Some(w) = slot {
            w.write_all(self.record.as_bytes())
                .map_err(|e| io_err(&path, e))?;
        }
        Ok(())
    }

    /// Close every file; returns the tiles that have one, in order.
    pub fn finish(self) -> Result<Vec<usize>, String> {
        let mut tiles = Vec::new();
        for (tile, slot) in self.files.into_iter().enumerate() {
            if let Some(mut w) = slot {
                let path = self.dir.join(format!("tile-{tile:03}.js"));
                w.write_all(b"]]);\n").map_err(|e| io_err(&path, e))?;
                w.flush().map_err(|e| io_err(&path, e))?;
                tiles.push(tile);
            }
        }
        Ok(tiles)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_equal_values_are_counted() {
        let mut s = String::new();
        encode_values(&[1, 1, 1, 0x7fff, 2, 2], &mut s);
        assert_eq!(s, "0001:3;7fff0002:2;");
    }
}
