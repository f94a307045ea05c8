//! Compressed GPU dumps: zstd (`.zst`) and XZ (`.xz`), recognised by their magic bytes when
//! read and chosen by the file name when written (docs/formats.md, "Compression").

use std::io::{Read, Write};
use std::path::Path;

/// Most bytes a compressed input may expand to: a guard against a small file that would
/// fill memory.
pub const MAX_DECOMPRESSED: u64 = 4 << 30;

/// A compression format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    /// Stored as it is.
    None,
    /// Zstandard (magic 28 B5 2F FD).
    Zstd,
    /// XZ (magic FD 37 7A 58 5A 00).
    Xz,
}

const ZSTD_MAGIC: [u8; 4] = [0x28, 0xB5, 0x2F, 0xFD];
const XZ_MAGIC: [u8; 6] = [0xFD, b'7', b'z', b'X', b'Z', 0x00];

impl Compression {
    /// The format whose magic `bytes` start with.
    pub fn sniff(bytes: &[u8]) -> Compression {
        if bytes.starts_with(&ZSTD_MAGIC) {
            Compression::Zstd
        } else if bytes.starts_with(&XZ_MAGIC) {
            Compression::Xz
        } else {
            Compression::None
        }
    }

    /// The format a file name's last extension names: `.zst`/`.zstd`, `.xz`.
    pub fn from_name(path: &Path) -> Compression {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("zst" | "zstd") => Compression::Zstd,
            Some("xz") => Compression::Xz,
            _ => Compression::None,
        }
    }

    /// The format's name.
    pub fn name(self) -> &'static str {
        match self {
            Compression::None => "uncompressed",
            Compression::Zstd => "zstd",
            Compression::Xz => "xz",
        }
    }
}

/// Read all of `reader`, refusing more than [`MAX_DECOMPRESSED`] bytes.
fn read_limited(reader: impl Read, out: &mut Vec<u8>) -> Result<(), String> {
    let room = MAX_DECOMPRESSED.saturating_sub(out.len() as u64);
    reader
        .take(room + 1)
        .read_to_end(out)
        .map_err(|e| e.to_string())?;
    if out.len() as u64 > MAX_DECOMPRESSED {
        return Err(format!(
            "decompresses to more than {} GiB",
            MAX_DECOMPRESSED >> 30
        ));
    }
    Ok(())
}

/// The contents of `bytes` in `format`, decompressed (every zstd frame or XZ stream in
/// turn).
pub fn decompress(bytes: &[u8], format: Compression) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    match format {
        Compression::None => out.extend_from_slice(bytes),
        Compression::Zstd => {
            let mut input = bytes;
            while !input.is_empty() {
                let decoder = ruzstd::decoding::StreamingDecoder::new(&mut input)
                    .map_err(|e| format!("zstd: {e}"))?;
                read_limited(decoder, &mut out).map_err(|e| format!("zstd: {e}"))?;
            }
        }
        Compression::Xz => {
            let decoder = lzma_rust2::XzReader::new(bytes, true);
            read_limited(decoder, &mut out).map_err(|e| format!("xz: {e}"))?;
        }
    }
    Ok(out)
}

/// `bytes` compressed in `format`: zstd at ruzstd's fastest level (about zstd's level 1),
/// XZ at preset 6 (xz's default).
pub fn compress(bytes: &[u8], format: Compression) -> Result<Vec<u8>, String> {
    match format {
        Compression::None => Ok(bytes.to_vec()),
        Compression::Zstd => Ok(ruzstd::encoding::compress_to_vec(
            bytes,
            ruzstd::encoding::CompressionLevel::Fastest,
        )),
        Compression::Xz => {
            let mut w =
                lzma_rust2::XzWriter::new(Vec::new(), lzma_rust2::XzOptions::with_preset(6))
                    .map_err(|e| format!("xz: {e}"))?;
            w.write_all(bytes).map_err(|e| format!("xz: {e}"))?;
            w.finish().map_err(|e| format!("xz: {e}"))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each format round-trips, and is recognised by its magic.
    #[test]
    fn round_trip() {
        let data: Vec<u8> = (0..200_000u32)
            .flat_map(|i| (i / 7).to_le_bytes())
            .collect();
        for format in [Compression::None, Compression::Zstd, Compression::Xz] {
            let packed = compress(&data, format).unwrap();
            assert_eq!(Compression::sniff(&packed), format);
            if format != Compression::None {
                assert!(
                    packed.len() < data.len() / 2,
                    "{format:?}: {}",
                    packed.len()
                );
            }
            assert_eq!(decompress(&packed, format).unwrap(), data);
        }
    }

    /// Damaged data is an error, not a panic.
    #[test]
    fn damaged_input_is_an_error() {
        let data = vec![7u8; 10_000];
        for format in [Compression::Zstd, Compression::Xz] {
            let mut packed = compress(&data, format).unwrap();
            let n = packed.len();
            packed.truncate(n / 2);
            assert!(decompress(&packed, format).is_err(), "{format:?} truncated");
        }
        assert!(decompress(&ZSTD_MAGIC, Compression::Zstd).is_err());
    }
}
