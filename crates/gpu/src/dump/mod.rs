//! PS1 GPU dumps (`.psxgpu`): a recording of the words a program sent to the GPU's ports,
//! with frame (VSync) marks, GPUREAD reads and information about the recording, in the
//! ps1dev community's `GPUDUMP.md` format (docs/formats.md, "GPU dumps").
//!
//! A dump is a magic header followed by packets. Each packet is one little-endian header
//! word, bits 0-23 the payload length in words and bits 24-31 the [`PacketType`], then the
//! payload. Two dialects exist ([`Dialect`]): the specification's 16-byte magic
//! `PSXGPUDUMPv1r1\0\0` with GPU versions numbered from 1, and DuckStation's 14-byte magic
//! `PSXGPUDUMPv1\0\0` (so its packets start at byte 14, not on a word boundary) with GPU
//! versions numbered from 0.
//!
//! - [`Reader`] walks the packets of a dump held in memory without allocating; every
//!   malformed input gives a [`DumpError`] naming the byte offset.
//! - [`Writer`] writes packets in either dialect to a [`Sink`].
//! - [`Recorder`] records a dump while an emulator drives a [`Gpu`](crate::Gpu): it opens
//!   with packets that restore the GPU's state (VRAM, display and drawing registers) and
//!   then logs port writes, GPUREAD reads and VSyncs.
//!
//! ```
//! use gpu::dump::{Dialect, Packet, Reader, Writer, VsyncTime};
//! let mut w = Writer::new(Vec::new(), Dialect::Spec).unwrap();
//! w.gp0(&[0x0200_00FF, 0, 0x0001_0010]).unwrap(); // GP0(02h): fill 16x1 with red
//! w.vsync(VsyncTime::None).unwrap();
//! let bytes = w.into_inner();
//! assert_eq!(&bytes[..16], b"PSXGPUDUMPv1r1\0\0");
//! let mut r = Reader::new(&bytes).unwrap();
//! let (offset, first) = r.next().unwrap().unwrap();
//! assert_eq!(offset, 16);
//! let Packet::Gp0(words) = first else { panic!() };
//! assert_eq!(words.get(0), Some(0x0200_00FF));
//! assert!(matches!(r.next(), Some(Ok((32, Packet::VSync(VsyncTime::None))))));
//! assert!(r.next().is_none());
//! ```

mod reader;
mod recorder;
mod writer;

pub use reader::{Header, Reader};
pub use recorder::{GP0_PACKET_WORDS, RecordError, RecordInfo, Recorder};
pub use writer::{Sink, WriteError, Writer};

use core::fmt;

/// The first ten bytes of every dump.
pub const MAGIC_PREFIX: &[u8; 10] = b"PSXGPUDUMP";

/// The specification's magic: format version 1, revision 1, 16 bytes.
pub const SPEC_MAGIC: &[u8; 16] = b"PSXGPUDUMPv1r1\0\0";

/// DuckStation's magic: format version 1 without a revision, 14 bytes.
pub const DUCKSTATION_MAGIC: &[u8; 14] = b"PSXGPUDUMPv1\0\0";

/// The longest payload a packet header can give: 24 bits of words.
pub const MAX_PACKET_WORDS: usize = 0xFF_FFFF;

/// Which of the two magic and GPU-version conventions a dump follows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Dialect {
    /// `GPUDUMP.md`: 16-byte magic `PSXGPUDUMPv1r1\0\0`; GPU version 1 = v1 1 MB, 2 = v2
    /// 1 MB, 3 = v2 2 MB.
    #[default]
    Spec,
    /// DuckStation: 14-byte magic `PSXGPUDUMPv1\0\0`; GPU version 0 = v1 1 MB, 1 = v2 1 MB,
    /// 2 = v2 2 MB.
    DuckStation,
}

impl Dialect {
    /// The magic header this dialect writes.
    pub const fn magic(self) -> &'static [u8] {
        match self {
            Dialect::Spec => SPEC_MAGIC,
            Dialect::DuckStation => DUCKSTATION_MAGIC,
        }
    }

    /// A short name: `spec` or `DuckStation`.
    pub const fn name(self) -> &'static str {
        match self {
            Dialect::Spec => "spec",
            Dialect::DuckStation => "DuckStation",
        }
    }
}

/// The packet types of format revision 1 (`GPUDUMP.md`, "Packet Types").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PacketType {
    /// 00h: words written to GP0.
    Gp0,
    /// 01h: words written to GP1.
    Gp1,
    /// 02h: a vertical sync, with 0, 1 or 2 words of CPU-cycle timestamp.
    VSync,
    /// 03h: read this many GPUREAD words and throw them away.
    Discard,
    /// 04h: read this many GPUREAD words and send them back.
    Readback,
    /// 05h: the recording proper starts here; earlier GP0/GP1 packets restore state.
    TraceBegin,
    /// 06h: GPU version and VRAM size (numbering depends on the [`Dialect`]).
    GpuVersion,
    /// 10h: the game's ID, e.g. `SLUS-00001`.
    GameId,
    /// 11h: `PAL` or `NTSC`, for information.
    VideoFormat,
    /// 12h: a comment, e.g. the tool that wrote the dump.
    Comment,
}

impl PacketType {
    /// Every type, in type-byte order.
    pub const ALL: [PacketType; 10] = [
        PacketType::Gp0,
        PacketType::Gp1,
        PacketType::VSync,
        PacketType::Discard,
        PacketType::Readback,
        PacketType::TraceBegin,
        PacketType::GpuVersion,
        PacketType::GameId,
        PacketType::VideoFormat,
        PacketType::Comment,
    ];

    /// The type byte (header bits 24-31).
    pub const fn byte(self) -> u8 {
        match self {
            PacketType::Gp0 => 0x00,
            PacketType::Gp1 => 0x01,
            PacketType::VSync => 0x02,
            PacketType::Discard => 0x03,
            PacketType::Readback => 0x04,
            PacketType::TraceBegin => 0x05,
            PacketType::GpuVersion => 0x06,
            PacketType::GameId => 0x10,
            PacketType::VideoFormat => 0x11,
            PacketType::Comment => 0x12,
        }
    }

    /// The type of a type byte; `None` for types revision 1 does not define.
    pub const fn from_byte(byte: u8) -> Option<PacketType> {
        Some(match byte {
            0x00 => PacketType::Gp0,
            0x01 => PacketType::Gp1,
            0x02 => PacketType::VSync,
            0x03 => PacketType::Discard,
            0x04 => PacketType::Readback,
            0x05 => PacketType::TraceBegin,
            0x06 => PacketType::GpuVersion,
            0x10 => PacketType::GameId,
            0x11 => PacketType::VideoFormat,
            0x12 => PacketType::Comment,
            _ => return None,
        })
    }

    /// The specification's name for the type.
    pub const fn name(self) -> &'static str {
        match self {
            PacketType::Gp0 => "GPU port 0 data",
            PacketType::Gp1 => "GPU port 1 data",
            PacketType::VSync => "VSync event",
            PacketType::Discard => "throw away port 0 data",
            PacketType::Readback => "readback port 0 data",
            PacketType::TraceBegin => "trace begin",
            PacketType::GpuVersion => "GPU version",
            PacketType::GameId => "game ID",
            PacketType::VideoFormat => "textual video format",
            PacketType::Comment => "comment",
        }
    }
}

/// The GPU a dump was recorded on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GpuVersion {
    /// The v1 ("old", 160-pin) GPU with 1 MB of VRAM.
    V1,
    /// The v2 ("new", 208-pin) GPU with 1 MB of VRAM: the one the `gpu` crate models.
    V2,
    /// The v2 GPU with 2 MB of VRAM (development and arcade boards).
    V2Vram2Mb,
}

impl GpuVersion {
    /// The version a GPU-version packet's word names in `dialect`; `None` for the values
    /// the specification reserves.
    pub const fn from_word(word: u32, dialect: Dialect) -> Option<GpuVersion> {
        let index = match dialect {
            Dialect::Spec => word.wrapping_sub(1),
            Dialect::DuckStation => word,
        };
        match index {
            0 => Some(GpuVersion::V1),
            1 => Some(GpuVersion::V2),
            2 => Some(GpuVersion::V2Vram2Mb),
            _ => None,
        }
    }

    /// The word naming this version in `dialect`.
    pub const fn word(self, dialect: Dialect) -> u32 {
        let index = match self {
            GpuVersion::V1 => 0,
            GpuVersion::V2 => 1,
            GpuVersion::V2Vram2Mb => 2,
        };
        match dialect {
            Dialect::Spec => index + 1,
            Dialect::DuckStation => index,
        }
    }

    /// A short description: `v2, 1 MB VRAM`.
    pub const fn describe(self) -> &'static str {
        match self {
            GpuVersion::V1 => "v1, 1 MB VRAM",
            GpuVersion::V2 => "v2, 1 MB VRAM",
            GpuVersion::V2Vram2Mb => "v2, 2 MB VRAM",
        }
    }
}

/// A VSync packet's timestamp in CPU cycles: none, one word (wraps every 2^32 cycles) or
/// two words (low word first).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum VsyncTime {
    /// No timestamp (a payload of 0 words).
    #[default]
    None,
    /// A one-word timestamp.
    Cycles32(u32),
    /// A two-word timestamp.
    Cycles64(u64),
}

impl VsyncTime {
    /// The timestamp's payload words.
    pub fn words(self) -> ([u32; 2], usize) {
        match self {
            VsyncTime::None => ([0, 0], 0),
            VsyncTime::Cycles32(t) => ([t, 0], 1),
            VsyncTime::Cycles64(t) => ([t as u32, (t >> 32) as u32], 2),
        }
    }

    /// The cycle count, if any.
    pub fn cycles(self) -> Option<u64> {
        match self {
            VsyncTime::None => None,
            VsyncTime::Cycles32(t) => Some(t as u64),
            VsyncTime::Cycles64(t) => Some(t),
        }
    }
}

/// A packet's payload words, read in place from the dump's bytes (which need not be
/// word-aligned: DuckStation's packets start at byte 14).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Words<'a> {
    bytes: &'a [u8],
}

impl<'a> Words<'a> {
    /// The words of `bytes`, little-endian; a trailing partial word is left out.
    pub fn new(bytes: &'a [u8]) -> Self {
        let whole = bytes.len() / 4 * 4;
        Words {
            bytes: bytes.get(..whole).unwrap_or_default(),
        }
    }

    /// Number of words.
    pub fn len(&self) -> usize {
        self.bytes.len() / 4
    }

    /// No words.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// Word `index`, if there.
    pub fn get(&self, index: usize) -> Option<u32> {
        let at = index.checked_mul(4)?;
        let b = self.bytes.get(at..at.checked_add(4)?)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The words in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = u32> + DoubleEndedIterator + 'a {
        self.bytes
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The payload's bytes (4 per word, little-endian).
    pub fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// Copy words from `start` into `out`; returns how many were copied (fewer than
    /// `out.len()` at the end of the payload).
    pub fn copy_to(&self, start: usize, out: &mut [u32]) -> usize {
        let from = start.saturating_mul(4).min(self.bytes.len());
        let mut n = 0;
        let rest = self.bytes.get(from..).unwrap_or_default();
        for (slot, b) in out.iter_mut().zip(rest.chunks_exact(4)) {
            *slot = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            n += 1;
        }
        n
    }
}

impl fmt::Debug for Words<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// A zero-terminated string packet's text: the bytes before the first zero. Usually ASCII;
/// other bytes are kept as they are.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Text<'a> {
    bytes: &'a [u8],
}

impl<'a> Text<'a> {
    /// The text's bytes, without the terminating zero.
    pub fn as_bytes(&self) -> &'a [u8] {
        self.bytes
    }

    /// The text when it is valid UTF-8.
    pub fn to_str(&self) -> Option<&'a str> {
        core::str::from_utf8(self.bytes).ok()
    }
}

/// Shows the text with each invalid UTF-8 sequence replaced by U+FFFD.
impl fmt::Display for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for chunk in self.bytes.utf8_chunks() {
            f.write_str(chunk.valid())?;
            if !chunk.invalid().is_empty() {
                f.write_str("\u{FFFD}")?;
            }
        }
        Ok(())
    }
}

impl fmt::Debug for Text<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\"", self.bytes.escape_ascii())
    }
}

/// One packet of a dump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Packet<'a> {
    /// Words written to GP0, in order.
    Gp0(Words<'a>),
    /// Words written to GP1, in order.
    Gp1(Words<'a>),
    /// A vertical sync: a frame ends here.
    VSync(VsyncTime),
    /// Read this many words from GPUREAD and throw them away.
    Discard(u32),
    /// Read this many words from GPUREAD and send them back.
    Readback(u32),
    /// The recording proper starts: earlier GP0/GP1 packets were made to restore state.
    TraceBegin,
    /// The GPU version word and the version it names in the dump's dialect (`None` when
    /// reserved).
    GpuVersion {
        /// The payload word as written.
        word: u32,
        /// What it means in the dump's dialect.
        version: Option<GpuVersion>,
    },
    /// The game's ID.
    GameId(Text<'a>),
    /// The video format, `PAL` or `NTSC`.
    VideoFormat(Text<'a>),
    /// A comment.
    Comment(Text<'a>),
    /// A packet of a type revision 1 does not define, kept with its payload.
    Unknown {
        /// The type byte.
        kind: u8,
        /// The payload.
        payload: Words<'a>,
    },
}

impl Packet<'_> {
    /// The type byte this packet is written with.
    pub fn type_byte(&self) -> u8 {
        match self {
            Packet::Gp0(_) => PacketType::Gp0.byte(),
            Packet::Gp1(_) => PacketType::Gp1.byte(),
            Packet::VSync(_) => PacketType::VSync.byte(),
            Packet::Discard(_) => PacketType::Discard.byte(),
            Packet::Readback(_) => PacketType::Readback.byte(),
            Packet::TraceBegin => PacketType::TraceBegin.byte(),
            Packet::GpuVersion { .. } => PacketType::GpuVersion.byte(),
            Packet::GameId(_) => PacketType::GameId.byte(),
            Packet::VideoFormat(_) => PacketType::VideoFormat.byte(),
            Packet::Comment(_) => PacketType::Comment.byte(),
            Packet::Unknown { kind, .. } => *kind,
        }
    }
}

/// What is wrong with a dump.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DumpErrorKind {
    /// The data ends inside the magic header.
    TruncatedMagic {
        /// Bytes present.
        len: usize,
    },
    /// The data does not start with `PSXGPUDUMPv<major>` followed by `r<minor>` and zeros
    /// to byte 16, or by two zero bytes.
    BadMagic,
    /// A format version other than 1 (a breaking change this reader does not know).
    UnsupportedVersion {
        /// The major version in the magic.
        major: u32,
    },
    /// The data ends inside a packet header.
    TruncatedPacketHeader {
        /// Bytes left for the header (1 to 3).
        bytes: usize,
    },
    /// A packet's payload runs past the end of the data.
    PastEnd {
        /// The packet's type byte.
        kind: u8,
        /// The payload length the header gives, in words.
        words: u32,
        /// Whole words left after the header.
        available: usize,
    },
    /// A packet of a fixed size has another length.
    PayloadSize {
        /// The packet's type.
        kind: PacketType,
        /// The payload length the header gives, in words.
        words: u32,
    },
    /// A string packet holds no zero byte.
    UnterminatedString {
        /// The packet's type.
        kind: PacketType,
    },
}

/// A malformed dump: what is wrong and the byte offset of the packet (or header) at fault.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DumpError {
    /// Byte offset of the magic (0) or of the packet header at fault.
    pub offset: usize,
    /// What is wrong.
    pub kind: DumpErrorKind,
}

/// The type byte and, when known, the type's name.
struct TypeName(u8);

impl fmt::Display for TypeName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match PacketType::from_byte(self.0) {
            Some(t) => write!(f, "{:02X}h ({})", self.0, t.name()),
            None => write!(f, "{:02X}h", self.0),
        }
    }
}

impl fmt::Display for DumpError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let at = self.offset;
        match self.kind {
            DumpErrorKind::TruncatedMagic { len } => write!(
                f,
                "truncated GPU dump: {len} bytes, fewer than its magic header needs"
            ),
            DumpErrorKind::BadMagic => write!(
                f,
                "not a PS1 GPU dump: it does not start with the magic PSXGPUDUMPv1r1 \
                 (16 bytes) or PSXGPUDUMPv1 (14 bytes)"
            ),
            DumpErrorKind::UnsupportedVersion { major } => write!(
                f,
                "GPU dump format version {major}; only version 1 is known"
            ),
            DumpErrorKind::TruncatedPacketHeader { bytes } => write!(
                f,
                "byte {at}: the dump ends inside a packet header ({bytes} of its 4 bytes)"
            ),
            DumpErrorKind::PastEnd {
                kind,
                words,
                available,
            } => write!(
                f,
                "byte {at}: packet type {} says {words} words but only {available} follow",
                TypeName(kind)
            ),
            DumpErrorKind::PayloadSize { kind, words } => {
                let expected = match kind {
                    PacketType::VSync => "0, 1 or 2",
                    PacketType::TraceBegin => "0",
                    _ => "1",
                };
                write!(
                    f,
                    "byte {at}: packet type {} has {words} words; it holds {expected}",
                    TypeName(kind.byte())
                )
            }
            DumpErrorKind::UnterminatedString { kind } => write!(
                f,
                "byte {at}: packet type {} holds a string without its terminating zero",
                TypeName(kind.byte())
            ),
        }
    }
}

impl core::error::Error for DumpError {}
