//! A save state: the whole engine as the hardware holds it, read and restored without the
//! side effects register writes have (docs/hardware/gte.md §2: IRGB sets IR1-3, SXYP pushes
//! the FIFO, LZCS sets LZCR, FLAG drops bits).

use crate::registers::Registers;
use crate::unr::{DivideMode, UnsupportedDivideMode};

/// Everything a [`Gte`](crate::Gte) holds between commands: the register file, FLAG included,
/// and the divide mode. Produced by [`Gte::state`](crate::Gte::state), restored by
/// [`Gte::load_state`](crate::Gte::load_state). With the `serde` feature it serializes as a
/// struct whose first field is `version`; human-readable formats (JSON) write the registers
/// field by field, binary ones (postcard, bincode) as one block of 64 little-endian words
/// (docs/gte.md, "Save states").
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GteState {
    /// Layout version; [`GteState::VERSION`] for states this build produces, down to
    /// [`GteState::OLDEST_VERSION`] for states it reads.
    pub version: u32,
    /// The 64 registers as stored.
    pub registers: Registers,
    /// The divide RTPS/RTPT use.
    pub divide_mode: DivideMode,
}

impl GteState {
    /// The layout version this build writes. Version 2 writes the registers of a binary format
    /// as one block of words; version 1 wrote them field by field in every format.
    pub const VERSION: u32 = 2;
    /// The oldest layout version this build reads.
    pub const OLDEST_VERSION: u32 = 1;
}

/// Why a [`GteState`] cannot be loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StateError {
    /// The state has a layout version newer than [`GteState::VERSION`] or older than
    /// [`GteState::OLDEST_VERSION`].
    Version {
        /// The state's version.
        found: u32,
        /// The newest version this build reads (the one it writes).
        expected: u32,
    },
    /// The state selects a divide mode this build cannot run.
    DivideMode(UnsupportedDivideMode),
}

impl core::fmt::Display for StateError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            StateError::Version { found, expected } => write!(
                f,
                "GTE save state version {found}; this build reads versions {} to {expected}",
                GteState::OLDEST_VERSION
            ),
            StateError::DivideMode(e) => write!(f, "GTE save state: {e}"),
        }
    }
}

impl core::error::Error for StateError {}

#[cfg(feature = "serde")]
mod serde_impl {
    //! `version` is written first and checked as soon as it is read, so a state of another
    //! version fails with [`StateError::Version`]'s message rather than a field mismatch. The
    //! registers are a [`Registers`] struct in human-readable formats and in version 1, and one
    //! block of 256 bytes (the 64 words of [`Registers::to_words`], little-endian) in the
    //! binary formats of version 2: one copy instead of a hundred varints.

    use super::{GteState, StateError};
    use crate::registers::Registers;
    use core::fmt;
    use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
    use serde::ser::{SerializeStruct, Serializer};

    const FIELDS: &[&str] = &["version", "registers", "divide_mode"];

    /// Bytes in the binary registers block.
    const BLOCK: usize = 64 * 4;

    impl serde::Serialize for GteState {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            let human = serializer.is_human_readable();
            let mut s = serializer.serialize_struct("GteState", 3)?;
            s.serialize_field("version", &self.version)?;
            if human {
                s.serialize_field("registers", &self.registers)?;
            } else {
                s.serialize_field("registers", &RegisterBlock(&self.registers))?;
            }
            s.serialize_field("divide_mode", &self.divide_mode)?;
            s.end()
        }
    }

    /// The registers as one block of bytes.
    struct RegisterBlock<'a>(&'a Registers);

    impl serde::Serialize for RegisterBlock<'_> {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            let mut bytes = [0u8; BLOCK];
            for (b, w) in bytes.chunks_exact_mut(4).zip(self.0.to_words()) {
                b.copy_from_slice(&w.to_le_bytes());
            }
            serializer.serialize_bytes(&bytes)
        }
    }

    /// The registers in version 2's layout: the struct in human-readable formats, the block
    /// in binary ones.
    struct Registers2(Registers);

    impl<'de> serde::Deserialize<'de> for Registers2 {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            if deserializer.is_human_readable() {
                Registers::deserialize(deserializer).map(Registers2)
            } else {
                deserializer.deserialize_bytes(BlockVisitor).map(Registers2)
            }
        }
    }

    /// Reads the block: exactly [`BLOCK`] bytes whose words are as the engine stores them.
    struct BlockVisitor;

    impl BlockVisitor {
        fn registers<E: de::Error>(bytes: &[u8]) -> Result<Registers, E> {
            let (words, rest) = bytes.as_chunks::<4>();
            if words.len() != 64 || !rest.is_empty() {
                return Err(E::invalid_length(bytes.len(), &BlockVisitor));
            }
            let words: [u32; 64] = core::array::from_fn(|i| u32::from_le_bytes(words[i]));
            Registers::from_words(&words).ok_or_else(|| {
                E::custom("GTE save state: register words not as the engine stores them")
            })
        }
    }

    impl<'de> Visitor<'de> for BlockVisitor {
        type Value = Registers;

        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            write!(f, "the GTE registers as {BLOCK} bytes")
        }

        fn visit_bytes<E: de::Error>(self, v: &[u8]) -> Result<Registers, E> {
            Self::registers(v)
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Registers, A::Error> {
            let mut bytes = [0u8; BLOCK];
            for (i, b) in bytes.iter_mut().enumerate() {
                *b = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::invalid_length(i, &self))?;
            }
            if seq.next_element::<u8>()?.is_some() {
                return Err(de::Error::invalid_length(BLOCK + 1, &self));
            }
            Self::registers(&bytes)
        }
    }

    fn check<E: de::Error>(found: u32) -> Result<u32, E> {
        if (GteState::OLDEST_VERSION..=GteState::VERSION).contains(&found) {
            Ok(found)
        } else {
            Err(E::custom(StateError::Version {
                found,
                expected: GteState::VERSION,
            }))
        }
    }

    enum Field {
        Version,
        Registers,
        DivideMode,
    }

    impl<'de> serde::Deserialize<'de> for Field {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Field, D::Error> {
            struct FieldVisitor;
            impl Visitor<'_> for FieldVisitor {
                type Value = Field;
                fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                    f.write_str("`version`, `registers` or `divide_mode`")
                }
                fn visit_str<E: de::Error>(self, v: &str) -> Result<Field, E> {
                    match v {
                        "version" => Ok(Field::Version),
                        "registers" => Ok(Field::Registers),
                        "divide_mode" => Ok(Field::DivideMode),
                        _ => Err(E::unknown_field(v, FIELDS)),
                    }
                }
            }
            deserializer.deserialize_identifier(FieldVisitor)
        }
    }

    struct StateVisitor;

    impl<'de> Visitor<'de> for StateVisitor {
        type Value = GteState;

        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("a GTE save state")
        }

        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<GteState, A::Error> {
            let missing = |i| de::Error::invalid_length(i, &self);
            let version = check(seq.next_element()?.ok_or_else(|| missing(0))?)?;
            let registers = if version == 1 {
                seq.next_element::<Registers>()?
            } else {
                seq.next_element::<Registers2>()?.map(|r| r.0)
            };
            let registers = registers.ok_or_else(|| missing(1))?;
            let divide_mode = seq.next_element()?.ok_or_else(|| missing(2))?;
            Ok(GteState {
                version,
                registers,
                divide_mode,
            })
        }

        /// Maps: the registers are read in the layout of the version read before them, or of
        /// this version when they come first (a map read back with sorted keys; in
        /// human-readable formats both versions write the same struct).
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<GteState, A::Error> {
            let (mut version, mut registers, mut divide_mode) = (None, None, None);
            while let Some(key) = map.next_key()? {
                match key {
                    Field::Version if version.is_none() => {
                        version = Some(check(map.next_value()?)?);
                    }
                    Field::Registers if registers.is_none() => {
                        registers = Some(if version == Some(1) {
                            map.next_value::<Registers>()?
                        } else {
                            map.next_value::<Registers2>()?.0
                        });
                    }
                    Field::DivideMode if divide_mode.is_none() => {
                        divide_mode = Some(map.next_value()?);
                    }
                    Field::Version => return Err(de::Error::duplicate_field("version")),
                    Field::Registers => return Err(de::Error::duplicate_field("registers")),
                    Field::DivideMode => return Err(de::Error::duplicate_field("divide_mode")),
                }
            }
            Ok(GteState {
                version: version.ok_or_else(|| de::Error::missing_field("version"))?,
                registers: registers.ok_or_else(|| de::Error::missing_field("registers"))?,
                divide_mode: divide_mode.ok_or_else(|| de::Error::missing_field("divide_mode"))?,
            })
        }
    }

    impl<'de> serde::Deserialize<'de> for GteState {
        fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<GteState, D::Error> {
            deserializer.deserialize_struct("GteState", FIELDS, StateVisitor)
        }
    }
}
