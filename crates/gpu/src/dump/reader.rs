//! Reading a dump held in memory: the magic header, then one packet at a time, in place.

use super::{
    Dialect, DumpError, DumpErrorKind, GpuVersion, MAGIC_PREFIX, Packet, PacketType, Text,
    VsyncTime, Words,
};

/// What a dump's magic header says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// Which dialect the magic belongs to.
    pub dialect: Dialect,
    /// The format version (`v1`: always 1 for a dump [`Reader::new`] accepts).
    pub major: u32,
    /// The revision (`r1`), absent in DuckStation's magic.
    pub minor: Option<u32>,
    /// Length of the magic in bytes: where the first packet starts (16 or 14).
    pub len: usize,
}

/// Decimal digits at the start of `bytes`: their value (`None` past `u32`) and count.
fn number(bytes: &[u8]) -> (Option<u32>, usize) {
    let digits = bytes.iter().take_while(|b| b.is_ascii_digit()).count();
    let mut value: Option<u32> = Some(0);
    for &b in bytes.iter().take(digits) {
        value = value
            .and_then(|v| v.checked_mul(10))
            .and_then(|v| v.checked_add(u32::from(b - b'0')));
    }
    (value, digits)
}

impl Header {
    /// Parse the magic at the start of `data` (`GPUDUMP.md`, "Magic Header"): `PSXGPUDUMP`,
    /// `v` and the major version, then either `r`, the revision and zeros up to byte 16
    /// (the specification), or two zero bytes (DuckStation, 14 bytes).
    pub fn parse(data: &[u8]) -> Result<Header, DumpError> {
        let err = |kind| DumpError { offset: 0, kind };
        let truncated = err(DumpErrorKind::TruncatedMagic { len: data.len() });
        let shared = data.len().min(MAGIC_PREFIX.len());
        if data.get(..shared) != MAGIC_PREFIX.get(..shared) {
            return Err(err(DumpErrorKind::BadMagic));
        }
        let rest = data.get(MAGIC_PREFIX.len()..).unwrap_or_default();
        match rest.first() {
            None => return Err(truncated),
            Some(b'v') => {}
            Some(_) => return Err(err(DumpErrorKind::BadMagic)),
        }
        let after_v = rest.get(1..).unwrap_or_default();
        let (major, major_digits) = number(after_v);
        if major_digits == after_v.len() {
            return Err(truncated);
        }
        let Some(major) = major.filter(|_| major_digits > 0) else {
            return Err(err(DumpErrorKind::BadMagic));
        };
        let mut at = MAGIC_PREFIX.len() + 1 + major_digits;
        let (minor, len) = if data.get(at) == Some(&b'r') {
            let after_r = data.get(at + 1..).unwrap_or_default();
            let (minor, minor_digits) = number(after_r);
            at += 1 + minor_digits;
            let Some(minor) = minor.filter(|_| minor_digits > 0) else {
                return Err(if minor_digits == after_r.len() {
                    truncated
                } else {
                    err(DumpErrorKind::BadMagic)
                });
            };
            // Zeros pad the text to 16 bytes; at least one zero ends it.
            if at >= 16 {
                return Err(err(DumpErrorKind::BadMagic));
            }
            (Some(minor), 16)
        } else {
            (None, at + 2)
        };
        let padding = data.get(at..len.min(data.len())).unwrap_or_default();
        if padding.iter().any(|&b| b != 0) {
            return Err(err(DumpErrorKind::BadMagic));
        }
        if data.len() < len {
            return Err(truncated);
        }
        if major != 1 {
            return Err(err(DumpErrorKind::UnsupportedVersion { major }));
        }
        let dialect = if minor.is_some() {
            Dialect::Spec
        } else {
            Dialect::DuckStation
        };
        Ok(Header {
            dialect,
            major,
            minor,
            len,
        })
    }
}

/// The packets of a dump held in memory, in order, read in place: iterating yields each
/// packet with the byte offset of its header, and stops after the first error.
///
/// Packets of types revision 1 does not define are returned as [`Packet::Unknown`] and
/// skipped by their length. Fixed-size packets of another size (VSync of more than 2 words,
/// discard/readback/GPU version not 1 word, trace begin not 0) and strings without their
/// zero are errors.
#[derive(Clone, Debug)]
pub struct Reader<'a> {
    data: &'a [u8],
    header: Header,
    pos: usize,
    failed: bool,
}

impl<'a> Reader<'a> {
    /// Check the magic header of `data` and stand before the first packet.
    pub fn new(data: &'a [u8]) -> Result<Reader<'a>, DumpError> {
        let header = Header::parse(data)?;
        Ok(Reader {
            data,
            header,
            pos: header.len,
            failed: false,
        })
    }

    /// Stand before the first packet of `data`, whose magic `header` is (from
    /// [`Header::parse`] of the same data). Another header reads whatever words lie at its
    /// length.
    pub fn with_header(data: &'a [u8], header: Header) -> Reader<'a> {
        Reader {
            data,
            header,
            pos: header.len.min(data.len()),
            failed: false,
        }
    }

    /// The magic header.
    pub fn header(&self) -> Header {
        self.header
    }

    /// The dump's dialect.
    pub fn dialect(&self) -> Dialect {
        self.header.dialect
    }

    /// Byte offset of the next packet (the data's length at the end).
    pub fn offset(&self) -> usize {
        self.pos
    }

    /// The whole dump.
    pub fn data(&self) -> &'a [u8] {
        self.data
    }

    /// Continue from byte `offset`, an [`offset`](Reader::offset) this reader (or another
    /// over the same data) returned; other offsets read whatever words lie there.
    pub fn seek(&mut self, offset: usize) {
        self.pos = offset.min(self.data.len());
        self.failed = false;
    }

    fn read(&mut self) -> Result<Option<(usize, Packet<'a>)>, DumpError> {
        let at = self.pos;
        let rest = self.data.get(at..).unwrap_or_default();
        if rest.is_empty() {
            return Ok(None);
        }
        let err = |kind| DumpError { offset: at, kind };
        let Some(head) = rest.first_chunk::<4>() else {
            return Err(err(DumpErrorKind::TruncatedPacketHeader {
                bytes: rest.len(),
            }));
        };
        let head = u32::from_le_bytes(*head);
        let words = head & 0xFF_FFFF;
        let kind = (head >> 24) as u8;
        let body = rest.get(4..).unwrap_or_default();
        let Some(payload) = body.get(..words as usize * 4) else {
            return Err(err(DumpErrorKind::PastEnd {
                kind,
                words,
                available: body.len() / 4,
            }));
        };
        let payload = Words::new(payload);
        let packet = match PacketType::from_byte(kind) {
            None => Packet::Unknown { kind, payload },
            Some(t) => typed(t, payload, self.header.dialect).map_err(err)?,
        };
        self.pos = at + 4 + payload.as_bytes().len();
        Ok(Some((at, packet)))
    }
}

/// A known packet from its payload.
fn typed(t: PacketType, payload: Words<'_>, dialect: Dialect) -> Result<Packet<'_>, DumpErrorKind> {
    let size = || DumpErrorKind::PayloadSize {
        kind: t,
        words: payload.len() as u32,
    };
    let single = || match payload.len() {
        1 => payload.get(0).ok_or_else(size),
        _ => Err(size()),
    };
    let text = || {
        let bytes = payload.as_bytes();
        match bytes.iter().position(|&b| b == 0) {
            Some(end) => Ok(Text {
                bytes: bytes.get(..end).unwrap_or_default(),
            }),
            None => Err(DumpErrorKind::UnterminatedString { kind: t }),
        }
    };
    Ok(match t {
        PacketType::Gp0 => Packet::Gp0(payload),
        PacketType::Gp1 => Packet::Gp1(payload),
        PacketType::VSync => Packet::VSync(match (payload.len(), payload.get(0), payload.get(1)) {
            (0, _, _) => VsyncTime::None,
            (1, Some(lo), _) => VsyncTime::Cycles32(lo),
            (2, Some(lo), Some(hi)) => VsyncTime::Cycles64(u64::from(hi) << 32 | u64::from(lo)),
            _ => return Err(size()),
        }),
        PacketType::Discard => Packet::Discard(single()?),
        PacketType::Readback => Packet::Readback(single()?),
        PacketType::TraceBegin if payload.is_empty() => Packet::TraceBegin,
        PacketType::TraceBegin => return Err(size()),
        PacketType::GpuVersion => {
            let word = single()?;
            Packet::GpuVersion {
                word,
                version: GpuVersion::from_word(word, dialect),
            }
        }
        PacketType::GameId => Packet::GameId(text()?),
        PacketType::VideoFormat => Packet::VideoFormat(text()?),
        PacketType::Comment => Packet::Comment(text()?),
    })
}

impl<'a> Iterator for Reader<'a> {
    type Item = Result<(usize, Packet<'a>), DumpError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        match self.read() {
            Ok(p) => p.map(Ok),
            Err(e) => {
                self.failed = true;
                Some(Err(e))
            }
        }
    }
}

impl core::iter::FusedIterator for Reader<'_> {}
