//! The GP0/GP1 command-stream text format (docs/formats.md): one command a line,
//! `gp0 XXXXXXXX [XXXXXXXX ...]` (words sent to GP0 in order) or `gp1 XXXXXXXX`; `#` starts a
//! comment; blank lines are ignored. Words are 1 to 8 hex digits, optionally prefixed `0x`;
//! a leading UTF-8 byte-order mark is skipped.
//!
//! Directive lines carry what a GPU dump holds besides port writes ([`Directive`]):
//! `vsync`, `discard N`, `readback N`, `trace-begin`, `gpu-version`, `game-id "..."`,
//! `video-format "..."`, `comment "..."` and `packet TT ...` for packet types the dump
//! format does not define; [`to_dump`] and [`from_dump`] convert between the text and
//! [`crate::dump`] losslessly.

use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt::{self, Write as _};

use crate::dump::{
    DumpError, GpuVersion, MAX_PACKET_WORDS, Packet, PacketType, Reader, Sink, VsyncTime,
    WriteError, Writer,
};
use crate::{Gpu, PendingInput};

/// The port a stream line writes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Port {
    /// GP0: rendering and VRAM transfers.
    Gp0,
    /// GP1: display control.
    Gp1,
}

/// One line of a stream: its 1-based line number, port and words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamCommand {
    /// Line number in the source text (1-based).
    pub line: usize,
    /// Destination port.
    pub port: Port,
    /// Words in order (exactly one for GP1).
    pub words: Vec<u32>,
}

/// A GPU version as a `gpu-version` line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VersionName {
    /// `v1`, `v2` or `v2-2mb`: written with the number the dump's dialect gives it.
    Known(GpuVersion),
    /// `raw N`: a reserved value, written as it is.
    Raw(u32),
}

/// A line that is not a port write: one GPU-dump packet ([`crate::dump::Packet`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Directive {
    /// `vsync` (no timestamp), `vsync N` (a one-word timestamp) or `vsync64 N` (two words):
    /// a frame ends. N is decimal CPU cycles.
    VSync(VsyncTime),
    /// `discard N`: read N words from GPUREAD and throw them away.
    Discard(u32),
    /// `readback N`: read N words from GPUREAD and send them back.
    Readback(u32),
    /// `trace-begin`: the lines before it only restore state.
    TraceBegin,
    /// `gpu-version v1|v2|v2-2mb|raw N`.
    GpuVersion(VersionName),
    /// `game-id "SLUS-00001"`.
    GameId(Vec<u8>),
    /// `video-format "NTSC"`.
    VideoFormat(Vec<u8>),
    /// `comment "..."`: a comment packet (unlike `#` comments, kept in a dump).
    Comment(Vec<u8>),
    /// `packet TT [XXXXXXXX ...]`: a packet of a type (hex) the dump format does not define.
    Packet {
        /// The type byte.
        kind: u8,
        /// The payload.
        words: Vec<u32>,
    },
}

/// One meaningful line of a stream.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Entry {
    /// A port write.
    Command(StreamCommand),
    /// Any other packet.
    Directive {
        /// Line number (1-based).
        line: usize,
        /// The packet.
        directive: Directive,
    },
}

impl Entry {
    /// The entry's line number.
    pub fn line(&self) -> usize {
        match self {
            Entry::Command(c) => c.line,
            Entry::Directive { line, .. } => *line,
        }
    }
}

/// The directives a timed stream (docs/formats.md, "Timed streams") adds to the command-stream
/// format. A plain command stream refuses them by name.
pub(crate) const TIMED_DIRECTIVES: [&str; 10] = [
    "dma",
    "dma-read",
    "dma-block",
    "read",
    "wait",
    "cpu",
    "timer",
    "report",
    "repeat",
    "end",
];

/// A malformed stream line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamError {
    /// Line number (1-based).
    pub line: usize,
    /// What is wrong with it.
    pub message: String,
}

impl fmt::Display for StreamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl core::error::Error for StreamError {}

/// The line without its `#` comment; a `#` inside a quoted string is text.
fn strip_comment(raw: &str) -> &str {
    let mut quoted = false;
    let mut escaped = false;
    for (i, c) in raw.char_indices() {
        match c {
            _ if escaped => escaped = false,
            '\\' if quoted => escaped = true,
            '"' => quoted = !quoted,
            '#' if !quoted => return raw.get(..i).unwrap_or(raw),
            _ => {}
        }
    }
    raw
}

fn decimal<T: core::str::FromStr>(field: Option<&str>, what: &str) -> Result<T, String> {
    match field {
        Some(f) if !f.is_empty() && f.bytes().all(|b| b.is_ascii_digit()) => f
            .parse()
            .map_err(|_| alloc::format!("{what} `{f}` is too large")),
        Some(f) => Err(alloc::format!("{what}: `{f}` is not a decimal number")),
        None => Err(alloc::format!("{what} missing")),
    }
}

/// A quoted string: `\"`, `\\` and `\xHH` escapes; the bytes as written otherwise.
fn quoted(rest: &str) -> Result<Vec<u8>, String> {
    let rest = rest.trim();
    let body = rest
        .strip_prefix('"')
        .and_then(|r| r.strip_suffix('"'))
        .filter(|_| rest.len() >= 2)
        .ok_or_else(|| alloc::format!("expected a string in double quotes, got `{rest}`"))?;
    let mut out = Vec::new();
    let mut bytes = body.bytes();
    while let Some(b) = bytes.next() {
        match b {
            b'\\' => match bytes.next() {
                Some(b'"') => out.push(b'"'),
                Some(b'\\') => out.push(b'\\'),
                Some(b'x') => {
                    let hi = bytes.next().and_then(|c| (c as char).to_digit(16));
                    let lo = bytes.next().and_then(|c| (c as char).to_digit(16));
                    match (hi, lo) {
                        (Some(0), Some(0)) => return Err("a string cannot hold \\x00".into()),
                        (Some(h), Some(l)) => out.push((h * 16 + l) as u8),
                        _ => return Err("\\x takes two hex digits".into()),
                    }
                }
                _ => return Err("unknown escape (use \\\", \\\\ or \\xHH)".into()),
            },
            b'"' => return Err("a quote inside the string must be written \\\"".into()),
            _ => out.push(b),
        }
    }
    Ok(out)
}

/// A directive line: `keyword` already lower-cased, `rest` the text after it.
fn directive(keyword: &str, rest: &str) -> Result<Option<Directive>, String> {
    let mut fields = rest.split_whitespace();
    let no_more = |mut f: core::str::SplitWhitespace<'_>| match f.next() {
        None => Ok(()),
        Some(x) => Err(alloc::format!("unexpected `{x}` after `{keyword}`")),
    };
    let d = match keyword {
        "vsync" => match fields.next() {
            None => Directive::VSync(VsyncTime::None),
            Some(t) => {
                let t = decimal(Some(t), "vsync timestamp")?;
                no_more(fields)?;
                Directive::VSync(VsyncTime::Cycles32(t))
            }
        },
        "vsync64" => {
            let t = decimal(fields.next(), "vsync64 timestamp")?;
            no_more(fields)?;
            Directive::VSync(VsyncTime::Cycles64(t))
        }
        "discard" | "readback" => {
            let n = decimal(fields.next(), "word count")?;
            no_more(fields)?;
            if keyword == "discard" {
                Directive::Discard(n)
            } else {
                Directive::Readback(n)
            }
        }
        "trace-begin" => {
            no_more(fields)?;
            Directive::TraceBegin
        }
        "gpu-version" => {
            let name = fields.next().map(str::to_ascii_lowercase);
            let v = match name.as_deref() {
                Some("v1") => VersionName::Known(GpuVersion::V1),
                Some("v2") => VersionName::Known(GpuVersion::V2),
                Some("v2-2mb") => VersionName::Known(GpuVersion::V2Vram2Mb),
                Some("raw") => VersionName::Raw(decimal(fields.next(), "raw version")?),
                _ => return Err("gpu-version takes v1, v2, v2-2mb or raw N".into()),
            };
            no_more(fields)?;
            Directive::GpuVersion(v)
        }
        "game-id" => Directive::GameId(quoted(rest)?),
        "video-format" => Directive::VideoFormat(quoted(rest)?),
        "comment" => Directive::Comment(quoted(rest)?),
        "packet" => {
            let t = fields.next().ok_or("packet type missing")?;
            let kind = match u8::from_str_radix(t, 16) {
                Ok(k) if t.len() <= 2 => k,
                _ => return Err(alloc::format!("`{t}` is not a packet type (2 hex digits)")),
            };
            if let Some(known) = PacketType::from_byte(kind) {
                return Err(alloc::format!(
                    "packet type {kind:02X}h is the format's {}: use its own line",
                    known.name()
                ));
            }
            let words = fields.map(parse_word).collect::<Result<Vec<_>, _>>()?;
            Directive::Packet { kind, words }
        }
        _ => return Ok(None),
    };
    Ok(Some(d))
}

/// Parse a whole stream, port writes and directives; the first malformed line is reported
/// with its number.
pub fn parse_entries(text: &str) -> Result<Vec<Entry>, StreamError> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    let mut entries = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = strip_comment(raw).trim();
        let err = |message: String| StreamError { line, message };
        let (first, rest) = content
            .split_once(char::is_whitespace)
            .unwrap_or((content, ""));
        if first.is_empty() {
            continue;
        }
        let keyword = first.to_ascii_lowercase();
        let port = match keyword.as_str() {
            "gp0" => Port::Gp0,
            "gp1" => Port::Gp1,
            other if TIMED_DIRECTIVES.contains(&other) => {
                return Err(err(alloc::format!(
                    "`{other}` is a timing directive, read by gpu::bus::parse \
                     (docs/formats.md, \"Timed streams\")"
                )));
            }
            _ => match directive(&keyword, rest).map_err(err)? {
                Some(directive) => {
                    entries.push(Entry::Directive { line, directive });
                    continue;
                }
                None => {
                    return Err(err(alloc::format!(
                        "unknown port `{keyword}` (expected gp0 or gp1, or a directive: vsync, \
                         discard, readback, trace-begin, gpu-version, game-id, video-format, \
                         comment, packet)"
                    )));
                }
            },
        };
        let words = rest
            .split_whitespace()
            .map(parse_word)
            .collect::<Result<Vec<u32>, String>>()
            .map_err(err)?;
        match (port, words.len()) {
            (_, 0) => return Err(err("missing word after the port".to_string())),
            (Port::Gp1, n) if n > 1 => {
                return Err(err(alloc::format!("gp1 takes exactly one word, got {n}")));
            }
            _ => {}
        }
        entries.push(Entry::Command(StreamCommand { line, port, words }));
    }
    Ok(entries)
}

/// Parse a whole stream's port writes; directive lines are checked and left out. The first
/// malformed line is reported with its number.
pub fn parse(text: &str) -> Result<Vec<StreamCommand>, StreamError> {
    Ok(parse_entries(text)?
        .into_iter()
        .filter_map(|e| match e {
            Entry::Command(c) => Some(c),
            Entry::Directive { .. } => None,
        })
        .collect())
}

/// A string as a directive writes it, in double quotes: text as it is, `\"` and `\\`, and
/// `\xHH` for control characters and bytes that are not UTF-8.
fn write_quoted(out: &mut impl fmt::Write, bytes: &[u8]) -> fmt::Result {
    out.write_char('"')?;
    for chunk in bytes.utf8_chunks() {
        for c in chunk.valid().chars() {
            match c {
                '"' => out.write_str("\\\"")?,
                '\\' => out.write_str("\\\\")?,
                c if c.is_control() => {
                    let mut buf = [0u8; 4];
                    for b in c.encode_utf8(&mut buf).bytes() {
                        write!(out, "\\x{b:02x}")?;
                    }
                }
                c => out.write_char(c)?,
            }
        }
        for b in chunk.invalid() {
            write!(out, "\\x{b:02x}")?;
        }
    }
    out.write_char('"')
}

/// The directive's line, as [`parse_entries`] reads it back.
impl fmt::Display for Directive {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Directive::VSync(VsyncTime::None) => f.write_str("vsync"),
            Directive::VSync(VsyncTime::Cycles32(t)) => write!(f, "vsync {t}"),
            Directive::VSync(VsyncTime::Cycles64(t)) => write!(f, "vsync64 {t}"),
            Directive::Discard(n) => write!(f, "discard {n}"),
            Directive::Readback(n) => write!(f, "readback {n}"),
            Directive::TraceBegin => f.write_str("trace-begin"),
            Directive::GpuVersion(VersionName::Known(v)) => f.write_str(match v {
                GpuVersion::V1 => "gpu-version v1",
                GpuVersion::V2 => "gpu-version v2",
                GpuVersion::V2Vram2Mb => "gpu-version v2-2mb",
            }),
            Directive::GpuVersion(VersionName::Raw(n)) => write!(f, "gpu-version raw {n}"),
            Directive::GameId(t) => {
                f.write_str("game-id ")?;
                write_quoted(f, t)
            }
            Directive::VideoFormat(t) => {
                f.write_str("video-format ")?;
                write_quoted(f, t)
            }
            Directive::Comment(t) => {
                f.write_str("comment ")?;
                write_quoted(f, t)
            }
            Directive::Packet { kind, words } => {
                write!(f, "packet {kind:02x}")?;
                words.iter().try_for_each(|w| write!(f, " {w:08x}"))
            }
        }
    }
}

/// Write a stream as GPU-dump packets: each `gp0` line one GP0 packet (split every
/// [`MAX_PACKET_WORDS`] words), each `gp1` line one GP1 packet, each directive its packet.
pub fn to_dump<S: Sink>(
    entries: &[Entry],
    writer: &mut Writer<S>,
) -> Result<(), WriteError<S::Error>> {
    for e in entries {
        match e {
            Entry::Command(c) => {
                for chunk in c.words.chunks(MAX_PACKET_WORDS) {
                    match c.port {
                        Port::Gp0 => writer.gp0(chunk)?,
                        Port::Gp1 => writer.gp1(chunk)?,
                    }
                }
            }
            Entry::Directive { directive, .. } => match directive {
                Directive::VSync(t) => writer.vsync(*t)?,
                Directive::Discard(n) => writer.discard(*n)?,
                Directive::Readback(n) => writer.readback(*n)?,
                Directive::TraceBegin => writer.trace_begin()?,
                Directive::GpuVersion(VersionName::Known(v)) => writer.gpu_version(*v)?,
                Directive::GpuVersion(VersionName::Raw(n)) => writer.gpu_version_word(*n)?,
                Directive::GameId(t) => writer.game_id(t)?,
                Directive::VideoFormat(t) => writer.video_format(t)?,
                Directive::Comment(t) => writer.comment(t)?,
                Directive::Packet { kind, words } => writer.unknown(*kind, words)?,
            },
        }
    }
    Ok(())
}

/// The directive a dump packet becomes; `None` for port writes.
pub fn directive_of(packet: &Packet<'_>) -> Option<Directive> {
    Some(match packet {
        Packet::Gp0(_) | Packet::Gp1(_) => return None,
        Packet::VSync(t) => Directive::VSync(*t),
        Packet::Discard(n) => Directive::Discard(*n),
        Packet::Readback(n) => Directive::Readback(*n),
        Packet::TraceBegin => Directive::TraceBegin,
        Packet::GpuVersion {
            version: Some(v), ..
        } => Directive::GpuVersion(VersionName::Known(*v)),
        Packet::GpuVersion {
            word,
            version: None,
        } => Directive::GpuVersion(VersionName::Raw(*word)),
        Packet::GameId(t) => Directive::GameId(t.as_bytes().to_vec()),
        Packet::VideoFormat(t) => Directive::VideoFormat(t.as_bytes().to_vec()),
        Packet::Comment(t) => Directive::Comment(t.as_bytes().to_vec()),
        Packet::Unknown { kind, payload } => Directive::Packet {
            kind: *kind,
            words: payload.iter().collect(),
        },
    })
}

/// Append the text of a dump to `out`: a `#` line naming the dialect, then one line per
/// packet (a GP1 packet of several words gives one `gp1` line per word). Empty GP0 and GP1
/// packets hold nothing and are left out. Returns the packets read.
pub fn from_dump(reader: Reader<'_>, out: &mut String) -> Result<usize, DumpError> {
    let h = reader.header();
    let _ = writeln!(
        out,
        "# PS1 GPU dump, {} dialect (format v{}{})",
        h.dialect.name(),
        h.major,
        h.minor.map(|m| alloc::format!("r{m}")).unwrap_or_default()
    );
    let mut packets = 0;
    for item in reader {
        let (_, packet) = item?;
        packets += 1;
        match packet {
            Packet::Gp0(words) if !words.is_empty() => {
                out.push_str("gp0");
                for w in words.iter() {
                    let _ = write!(out, " {w:08x}");
                }
                out.push('\n');
            }
            Packet::Gp1(words) => {
                for w in words.iter() {
                    let _ = writeln!(out, "gp1 {w:08x}");
                }
            }
            other => {
                if let Some(d) = directive_of(&other) {
                    let _ = writeln!(out, "{d}");
                }
            }
        }
    }
    Ok(packets)
}

/// What a stream left unfinished when it ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unfinished {
    /// The input in progress ([`Gpu::pending_input`]).
    pub pending: PendingInput,
    /// Line (1-based) of the word that started it.
    pub line: usize,
}

/// The outcome of [`run`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunSummary {
    /// `Some` when the stream ended mid-packet, mid CPU-to-VRAM transfer or inside an
    /// unterminated polyline.
    pub unfinished: Option<Unfinished>,
}

/// One 32-bit word: 1 to 8 hex digits, optionally prefixed `0x`.
pub(crate) fn parse_word(field: &str) -> Result<u32, String> {
    let digits = field
        .strip_prefix("0x")
        .or_else(|| field.strip_prefix("0X"))
        .unwrap_or(field);
    if digits.is_empty() || digits.len() > 8 || !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(alloc::format!(
            "`{field}` is not a 32-bit hex word (1 to 8 hex digits)"
        ));
    }
    u32::from_str_radix(digits, 16).map_err(|_| alloc::format!("`{field}` is not a hex word"))
}

/// Send parsed commands to a GPU in order; report input the stream left unfinished, with the
/// line where it started.
pub fn run(gpu: &mut Gpu, commands: &[StreamCommand]) -> RunSummary {
    let mut start_line = 0;
    for c in commands {
        match c.port {
            Port::Gp0 => {
                for &w in &c.words {
                    if gpu.pending_input().is_none() {
                        start_line = c.line;
                    }
                    gpu.gp0(w);
                }
            }
            Port::Gp1 => {
                for &w in &c.words {
                    gpu.gp1(w);
                }
            }
        }
    }
    RunSummary {
        unfinished: gpu.pending_input().map(|pending| Unfinished {
            pending,
            line: start_line,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_ports_words_comments() {
        let cmds = parse("# header\n\ngp1 00000000\ngp0 e1000400 0x02ffffff # trailing\n").unwrap();
        assert_eq!(cmds.len(), 2);
        assert_eq!(cmds[0].line, 3);
        assert_eq!(cmds[0].port, Port::Gp1);
        assert_eq!(cmds[1].words, [0xE100_0400, 0x02FF_FFFF]);
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(parse("gp0 1\ngp2 0").unwrap_err().line, 2);
        assert_eq!(parse("gp0 xyz").unwrap_err().line, 1);
        assert_eq!(parse("gp0").unwrap_err().line, 1);
        assert_eq!(parse("gp0 1\n\ngp1 1 2").unwrap_err().line, 3);
        assert_eq!(parse("gp0 123456789").unwrap_err().line, 1);
        // A timed stream's directive is named as such.
        let e = parse("gp0 1\nwait 28\n").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("timing directive"), "{}", e.message);
    }

    #[test]
    fn leading_bom_accepted() {
        let cmds = parse("\u{FEFF}gp0 1\n").unwrap();
        assert_eq!(cmds[0].words, [1]);
        assert_eq!(cmds[0].port, Port::Gp0);
    }

    #[test]
    fn only_hex_digits() {
        for bad in ["+1", "-1", "0x+1", "1_0", "0x", "g", " 1\u{663}"] {
            assert!(parse(&alloc::format!("gp0 {bad}")).is_err(), "{bad:?}");
        }
        assert_eq!(parse("gp0 0XaBcD").unwrap()[0].words, [0xABCD]);
    }

    fn run_text(text: &str) -> RunSummary {
        let mut gpu = Gpu::new();
        run(&mut gpu, &parse(text).unwrap())
    }

    #[test]
    fn reports_unfinished_input_with_its_line() {
        assert_eq!(
            run_text("gp0 e3000000\ngp0 02000000 0 00010010\n").unfinished,
            None
        );
        // A flat triangle (4 words) cut after 3, started on line 2.
        let u = run_text("gp0 e3000000\ngp0 20ff0000 0\n# more\ngp0 00100000\n")
            .unfinished
            .unwrap();
        assert_eq!(u.line, 2);
        assert_eq!(
            u.pending,
            PendingInput::Packet {
                command: 0x20FF_0000,
                received: 3,
                expected: 4
            }
        );
        // CPU-to-VRAM 3x3 = 9 pixels = 5 words; 2 sent.
        let u = run_text("gp1 0\ngp0 a0000000 0 00030003\ngp0 1 2\n")
            .unfinished
            .unwrap();
        assert_eq!(
            (u.line, u.pending),
            (2, PendingInput::Transfer { remaining_words: 3 })
        );
        // A polyline without its terminator.
        let u = run_text("gp0 0\ngp0 48ffffff 0 00100010\ngp0 00200020\n")
            .unfinished
            .unwrap();
        assert_eq!((u.line, u.pending), (2, PendingInput::Polyline));
        // GP1(01h) drops the partial packet.
        assert_eq!(run_text("gp0 20ff0000\ngp1 01000000\n").unfinished, None);
    }
}
