//! A save state: the whole engine as the hardware holds it, read and restored without the
//! side effects register writes have (gte.md §2: IRGB sets IR1-3, SXYP pushes the FIFO, LZCS
//! sets LZCR, FLAG drops bits).

use crate::registers::Registers;
use crate::unr::{DivideMode, UnsupportedDivideMode};

/// Everything a [`Gte`](crate::Gte) holds between commands: the register file, FLAG included,
/// and the divide mode. Produced by [`Gte::state`](crate::Gte::state), restored by
/// [`Gte::load_state`](crate::Gte::load_state). With the `serde` feature it serializes as a
/// map whose first entry is `version`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GteState {
    /// Layout version; [`GteState::VERSION`] for states this build produces.
    pub version: u32,
    /// The 64 registers as stored.
    pub registers: Registers,
    /// The divide RTPS/RTPT use.
    pub divide_mode: DivideMode,
}

impl GteState {
    /// The layout version this build writes and accepts.
    pub const VERSION: u32 = 1;
}

/// Why a [`GteState`] cannot be loaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum StateError {
    /// The state has another layout version than [`GteState::VERSION`].
    Version {
        /// The state's version.
        found: u32,
        /// The version this build reads.
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
                "GTE save state version {found}; this build reads version {expected}"
            ),
            StateError::DivideMode(e) => write!(f, "GTE save state: {e}"),
        }
    }
}

impl core::error::Error for StateError {}

#[cfg(feature = "serde")]
mod serde_impl {
    //! `version` is written first and checked as soon as it is read, so a state of another
    //! version fails with [`StateError::Version`]'s message rather than a field mismatch.

    use super::{GteState, StateError};
    use core::fmt;
    use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};
    use serde::ser::{SerializeStruct, Serializer};

    const FIELDS: &[&str] = &["version", "registers", "divide_mode"];

    impl serde::Serialize for GteState {
        fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
            let mut s = serializer.serialize_struct("GteState", 3)?;
            s.serialize_field("version", &self.version)?;
            s.serialize_field("registers", &self.registers)?;
            s.serialize_field("divide_mode", &self.divide_mode)?;
            s.end()
        }
    }

    fn check<E: de::Error>(found: u32) -> Result<u32, E> {
        if found == GteState::VERSION {
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
            let registers = seq.next_element()?.ok_or_else(|| missing(1))?;
            let divide_mode = seq.next_element()?.ok_or_else(|| missing(2))?;
            Ok(GteState {
                version,
                registers,
                divide_mode,
            })
        }

        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<GteState, A::Error> {
            let (mut version, mut registers, mut divide_mode) = (None, None, None);
            while let Some(key) = map.next_key()? {
                match key {
                    Field::Version if version.is_none() => {
                        version = Some(check(map.next_value()?)?);
                    }
                    Field::Registers if registers.is_none() => {
                        registers = Some(map.next_value()?);
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
