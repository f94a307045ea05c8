//! Writing a dump: the magic of a dialect, then packets, to any byte sink.

use super::{Dialect, GpuVersion, MAX_PACKET_WORDS, Packet, PacketType, VsyncTime, Words};
use alloc::vec::Vec;
use core::convert::Infallible;
use core::fmt;

/// Where a [`Writer`] puts its bytes: a `Vec<u8>` in memory, or an adapter over a file.
pub trait Sink {
    /// Why a write failed.
    type Error;
    /// Append `bytes`.
    fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), Self::Error>;
}

impl Sink for Vec<u8> {
    type Error = Infallible;
    fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), Infallible> {
        self.extend_from_slice(bytes);
        Ok(())
    }
}

impl<S: Sink + ?Sized> Sink for &mut S {
    type Error = S::Error;
    fn write_bytes(&mut self, bytes: &[u8]) -> Result<(), S::Error> {
        (**self).write_bytes(bytes)
    }
}

/// Why a packet was not written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WriteError<E> {
    /// The sink failed.
    Sink(E),
    /// A payload longer than a header can give ([`MAX_PACKET_WORDS`] words).
    TooLong {
        /// Words asked for.
        words: usize,
    },
    /// A string holding a zero byte (a reader would stop there).
    ZeroInString,
    /// A packet [`Packet::Unknown`] with a type byte revision 1 defines: write it through
    /// its own variant.
    KnownType {
        /// The type byte.
        kind: u8,
    },
}

impl<E: fmt::Display> fmt::Display for WriteError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            WriteError::Sink(e) => write!(f, "{e}"),
            WriteError::TooLong { words } => write!(
                f,
                "a packet of {words} words; a packet holds at most {MAX_PACKET_WORDS}"
            ),
            WriteError::ZeroInString => write!(f, "a string packet's text holds a zero byte"),
            WriteError::KnownType { kind } => write!(
                f,
                "packet type {kind:02X}h is defined by the format; write it as such"
            ),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> core::error::Error for WriteError<E> {}

/// Bytes gathered before they go to the sink, so a long payload is not written four bytes
/// at a time.
const CHUNK: usize = 256;

/// Writes a dump: the magic on creation, then one packet per call; nothing is held back
/// between calls. Payloads go to the sink in pieces of at most 256 bytes.
///
/// ```
/// use gpu::dump::{Dialect, GpuVersion, Writer};
/// let mut w = Writer::new(Vec::new(), Dialect::DuckStation).unwrap();
/// w.gpu_version(GpuVersion::V2).unwrap();
/// let bytes = w.into_inner();
/// assert_eq!(&bytes[..14], b"PSXGPUDUMPv1\0\0");
/// // Length 1, type 06h, then DuckStation's number for a v2 GPU with 1 MB: 1.
/// assert_eq!(&bytes[14..], &[1, 0, 0, 6, 1, 0, 0, 0]);
/// ```
#[derive(Debug)]
pub struct Writer<S> {
    sink: S,
    dialect: Dialect,
}

impl<S: Sink> Writer<S> {
    /// Start a dump of `dialect` in `sink`: writes the magic header.
    pub fn new(mut sink: S, dialect: Dialect) -> Result<Self, WriteError<S::Error>> {
        sink.write_bytes(dialect.magic())
            .map_err(WriteError::Sink)?;
        Ok(Writer { sink, dialect })
    }

    /// The dialect being written.
    pub fn dialect(&self) -> Dialect {
        self.dialect
    }

    /// The sink.
    pub fn get_mut(&mut self) -> &mut S {
        &mut self.sink
    }

    /// Finish: the sink back.
    pub fn into_inner(self) -> S {
        self.sink
    }

    fn header(&mut self, kind: u8, words: usize) -> Result<(), WriteError<S::Error>> {
        if words > MAX_PACKET_WORDS {
            return Err(WriteError::TooLong { words });
        }
        let head = (kind as u32) << 24 | words as u32;
        self.sink
            .write_bytes(&head.to_le_bytes())
            .map_err(WriteError::Sink)
    }

    pub(super) fn words(
        &mut self,
        kind: u8,
        words: impl ExactSizeIterator<Item = u32>,
    ) -> Result<(), WriteError<S::Error>> {
        self.header(kind, words.len())?;
        let mut buf = [0u8; CHUNK];
        let mut n = 0;
        for w in words {
            if let Some(slot) = buf.get_mut(n..n + 4) {
                slot.copy_from_slice(&w.to_le_bytes());
            }
            n += 4;
            if n == CHUNK {
                self.sink.write_bytes(&buf).map_err(WriteError::Sink)?;
                n = 0;
            }
        }
        self.sink
            .write_bytes(buf.get(..n).unwrap_or_default())
            .map_err(WriteError::Sink)
    }

    fn text(&mut self, kind: PacketType, text: &[u8]) -> Result<(), WriteError<S::Error>> {
        if text.contains(&0) {
            return Err(WriteError::ZeroInString);
        }
        // The text, its zero, and zeros to the next word.
        let words = text.len() / 4 + 1;
        self.header(kind.byte(), words)?;
        self.sink.write_bytes(text).map_err(WriteError::Sink)?;
        let pad = [0u8; 4];
        self.sink
            .write_bytes(pad.get(..words * 4 - text.len()).unwrap_or_default())
            .map_err(WriteError::Sink)
    }

    /// One GP0 packet holding `words`.
    pub fn gp0(&mut self, words: &[u32]) -> Result<(), WriteError<S::Error>> {
        self.words(PacketType::Gp0.byte(), words.iter().copied())
    }

    /// One GP1 packet holding `words`.
    pub fn gp1(&mut self, words: &[u32]) -> Result<(), WriteError<S::Error>> {
        self.words(PacketType::Gp1.byte(), words.iter().copied())
    }

    /// A VSync packet.
    pub fn vsync(&mut self, time: VsyncTime) -> Result<(), WriteError<S::Error>> {
        let (words, n) = time.words();
        self.words(PacketType::VSync.byte(), words.iter().copied().take(n))
    }

    /// Discard `words` GPUREAD words.
    pub fn discard(&mut self, words: u32) -> Result<(), WriteError<S::Error>> {
        self.words(PacketType::Discard.byte(), [words].into_iter())
    }

    /// Read back `words` GPUREAD words.
    pub fn readback(&mut self, words: u32) -> Result<(), WriteError<S::Error>> {
        self.words(PacketType::Readback.byte(), [words].into_iter())
    }

    /// The trace-begin mark.
    pub fn trace_begin(&mut self) -> Result<(), WriteError<S::Error>> {
        self.header(PacketType::TraceBegin.byte(), 0)
    }

    /// The GPU version, numbered as the dialect numbers it.
    pub fn gpu_version(&mut self, version: GpuVersion) -> Result<(), WriteError<S::Error>> {
        self.gpu_version_word(version.word(self.dialect))
    }

    /// A GPU-version packet holding `word` as it is (a reserved value, or one copied from
    /// another dump of the same dialect).
    pub fn gpu_version_word(&mut self, word: u32) -> Result<(), WriteError<S::Error>> {
        self.words(PacketType::GpuVersion.byte(), [word].into_iter())
    }

    /// The game ID (e.g. `SLUS-00001`).
    pub fn game_id(&mut self, text: &[u8]) -> Result<(), WriteError<S::Error>> {
        self.text(PacketType::GameId, text)
    }

    /// The video format (`PAL` or `NTSC`).
    pub fn video_format(&mut self, text: &[u8]) -> Result<(), WriteError<S::Error>> {
        self.text(PacketType::VideoFormat, text)
    }

    /// A comment.
    pub fn comment(&mut self, text: &[u8]) -> Result<(), WriteError<S::Error>> {
        self.text(PacketType::Comment, text)
    }

    /// A packet of a type revision 1 does not define, with its payload.
    pub fn unknown(&mut self, kind: u8, payload: &[u32]) -> Result<(), WriteError<S::Error>> {
        if PacketType::from_byte(kind).is_some() {
            return Err(WriteError::KnownType { kind });
        }
        self.words(kind, payload.iter().copied())
    }

    /// Any packet, as a [`Reader`](super::Reader) returned it. A GPU-version packet naming a
    /// known version is numbered as this writer's dialect numbers it (so copying packets
    /// between dialects keeps their meaning); a reserved word is kept as it is.
    pub fn packet(&mut self, packet: &Packet<'_>) -> Result<(), WriteError<S::Error>> {
        let raw =
            |w: &mut Self, kind: PacketType, words: &Words<'_>| w.words(kind.byte(), words.iter());
        match packet {
            Packet::Gp0(words) => raw(self, PacketType::Gp0, words),
            Packet::Gp1(words) => raw(self, PacketType::Gp1, words),
            Packet::VSync(t) => self.vsync(*t),
            Packet::Discard(n) => self.discard(*n),
            Packet::Readback(n) => self.readback(*n),
            Packet::TraceBegin => self.trace_begin(),
            Packet::GpuVersion {
                version: Some(v), ..
            } => self.gpu_version(*v),
            Packet::GpuVersion {
                word,
                version: None,
            } => self.gpu_version_word(*word),
            Packet::GameId(t) => self.game_id(t.as_bytes()),
            Packet::VideoFormat(t) => self.video_format(t.as_bytes()),
            Packet::Comment(t) => self.comment(t.as_bytes()),
            Packet::Unknown { kind, payload } => {
                if PacketType::from_byte(*kind).is_some() {
                    return Err(WriteError::KnownType { kind: *kind });
                }
                self.words(*kind, payload.iter())
            }
        }
    }
}
