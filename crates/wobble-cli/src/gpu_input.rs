//! Input files of the GPU commands: command streams (`.gpu` text) and GPU dumps (`.psxgpu`,
//! compressed or not), told apart by their contents; and the message for a binary file
//! given where text is expected.

use crate::compress::{self, Compression};
use std::path::Path;
use wobble::gpu_dump::Dump;

/// What an input file held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InputKind {
    /// A command stream's text.
    Text,
    /// A GPU dump.
    Dump,
}

/// A loaded input: its packets as a dump, what it was, how it was compressed.
pub struct Input {
    /// The packets (a command stream converted, one packet per line).
    pub dump: Dump,
    /// What the file held.
    pub kind: InputKind,
    /// How it was compressed.
    pub compression: Compression,
}

/// What a binary file looks like, from its first bytes and size, when it is a format the
/// tool knows of.
pub fn looks_like(bytes: &[u8]) -> Option<&'static str> {
    let starts = |m: &[u8]| bytes.starts_with(m);
    Some(if starts(gpu::dump::MAGIC_PREFIX) {
        "a PS1 GPU dump (.psxgpu)"
    } else if starts(&[0x28, 0xB5, 0x2F, 0xFD]) {
        "zstd-compressed data"
    } else if starts(&[0xFD, b'7', b'z', b'X', b'Z', 0]) {
        "xz-compressed data"
    } else if starts(b"\x89PNG") {
        "a PNG image"
    } else if starts(b"GIF8") {
        "a GIF image"
    } else if starts(b"PS-X EXE") {
        "a PS1 executable (PS-X EXE)"
    } else if bytes.len() == 1024 * 512 * 2 {
        "raw VRAM (1,048,576 bytes)"
    } else {
        return None;
    })
}

/// Whether `bytes` are text: UTF-8 with no NUL byte.
fn is_text(bytes: &[u8]) -> bool {
    !bytes.contains(&0) && std::str::from_utf8(bytes).is_ok()
}

/// The error for binary `bytes` given where `what` (a text format) was expected: what the
/// file looks like, and the first byte that is not text.
pub fn binary_error(path: &Path, bytes: &[u8], what: &str) -> String {
    let at = match std::str::from_utf8(bytes) {
        Err(e) => e.valid_up_to(),
        Ok(_) => bytes.iter().position(|&b| b == 0).unwrap_or(0),
    };
    format!(
        "{}: not {what}: the file is binary ({}byte {at} is not UTF-8 text)",
        path.display(),
        looks_like(bytes)
            .map(|k| format!("{k}; "))
            .unwrap_or_default()
    )
}

/// The formats GPU commands are read from, for messages.
pub const GPU_INPUTS: &str = "a GPU command stream (.gpu text) or a GPU dump (.psxgpu, .psxgpu.zst, .psxgpu.xz; docs/formats.md)";

/// Load a command stream or a GPU dump, compressed with zstd or XZ or not, whatever its
/// name: the contents decide. A name ending `.zst`/`.xz` whose contents are not that
/// format is refused; text under a dump's name that is no command stream either is
/// reported as not a dump.
pub fn load(path: &Path) -> Result<Input, String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let raw = std::fs::read(path).map_err(|e| at(&e))?;
    let compression = Compression::sniff(&raw);
    let named = Compression::from_name(path);
    if named != Compression::None && named != compression {
        return Err(at(&format!(
            "the name says {} but the contents are {}",
            named.name(),
            looks_like(&raw).unwrap_or(if is_text(&raw) { "text" } else { "other data" })
        )));
    }
    let bytes = compress::decompress(&raw, compression).map_err(|e| at(&e))?;
    drop(raw);
    if bytes.starts_with(gpu::dump::MAGIC_PREFIX) {
        let dump = Dump::from_bytes(bytes).map_err(|e| at(&e))?;
        return Ok(Input {
            dump,
            kind: InputKind::Dump,
            compression,
        });
    }
    if !is_text(&bytes) {
        return Err(binary_error(path, &bytes, GPU_INPUTS));
    }
    let text = String::from_utf8(bytes).map_err(|e| at(&e))?;
    let dump = Dump::from_text(&text).map_err(|e| {
        if matches!(output_format(path), Ok(OutputFormat::Dump(_))) {
            at(&format!(
                "not a GPU dump (it does not start with `PSXGPUDUMP`), nor a command stream \
                 (.gpu text): {e}"
            ))
        } else if e.to_string().contains("timing directive") {
            at(&format!(
                "{e}; `wobble replay --timing` reads timed streams"
            ))
        } else {
            at(&e)
        }
    })?;
    Ok(Input {
        dump,
        kind: InputKind::Text,
        compression,
    })
}

/// How an output file of GPU commands is written, from its name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    /// `.gpu`: command-stream text.
    Text,
    /// `.psxgpu`, `.psxgpu.zst`, `.psxgpu.xz`: a dump, compressed as named.
    Dump(Compression),
}

/// The format an output name asks for; an error listing the names accepted otherwise.
pub fn output_format(path: &Path) -> Result<OutputFormat, String> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let format = if name.ends_with(".gpu") {
        OutputFormat::Text
    } else if name.ends_with(".psxgpu") {
        OutputFormat::Dump(Compression::None)
    } else if name.ends_with(".psxgpu.zst") {
        OutputFormat::Dump(Compression::Zstd)
    } else if name.ends_with(".psxgpu.xz") {
        OutputFormat::Dump(Compression::Xz)
    } else {
        return Err(format!(
            "{}: cannot tell the format from the name; use .gpu (command stream text), \
             .psxgpu, .psxgpu.zst or .psxgpu.xz (GPU dump)",
            path.display()
        ));
    };
    Ok(format)
}

/// Write `bytes` (a dump) to `out`, compressed as `path`'s name says, and commit it. Returns
/// the bytes written.
pub fn write_dump(
    path: &Path,
    bytes: &[u8],
    mut out: crate::output::Output,
) -> Result<u64, String> {
    let format = match output_format(path)? {
        OutputFormat::Dump(c) => c,
        OutputFormat::Text => Compression::None,
    };
    let packed =
        compress::compress(bytes, format).map_err(|e| format!("{}: {e}", path.display()))?;
    std::io::Write::write_all(&mut out, &packed).map_err(|e| format!("{}: {e}", out.name()))?;
    out.commit()?;
    Ok(packed.len() as u64)
}
