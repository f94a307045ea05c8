//! Versioned save states (feature `serde`): a header naming the format and its version, then
//! the whole chip state. Loading checks the header before the body and every field against
//! what the hardware can reach, so a state from another version, a truncated or a garbled one
//! is an error, never a GPU in an impossible state (docs/emulator.md, "Save states").

use core::fmt;

use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::state::DrawState;
use crate::texture::ClutCache;
use crate::{DisplayState, Gpu, Vram, drawing, gp0, timing, transfer};

/// First field of every GPU save state: "WGPU" read as a little-endian `u32`.
pub const SAVE_STATE_MAGIC: u32 = u32::from_le_bytes(*b"WGPU");

/// The save-state layout this build writes and reads. It changes whenever a field of the
/// chip state is added, removed, reordered or given another meaning.
pub const SAVE_STATE_VERSION: u32 = 2;

/// Why a save state was refused. Serde formats carry it as their custom error, whose message
/// is this type's `Display` text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum StateError {
    /// The first field is not [`SAVE_STATE_MAGIC`]: not a GPU save state.
    NotAGpuState {
        /// The value found.
        found: u32,
    },
    /// Written by a build with another [`SAVE_STATE_VERSION`].
    Version {
        /// The version in the state.
        found: u32,
        /// The version this build reads.
        expected: u32,
    },
    /// A field holds a value the GPU can never reach; the text names it.
    Invalid(&'static str),
}

impl fmt::Display for StateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotAGpuState { found } => {
                write!(f, "not a GPU save state (magic {found:#010x})")
            }
            Self::Version { found, expected } => write!(
                f,
                "GPU save state version {found}, this build reads version {expected}"
            ),
            Self::Invalid(what) => write!(f, "invalid GPU save state: {what}"),
        }
    }
}

impl core::error::Error for StateError {}

/// A GPU save state: magic, version, then the chip state. `SaveState<&Gpu>` (from
/// [`Gpu::save_state`]) serializes; `SaveState<Gpu>` deserializes, checking the header and
/// every field.
#[derive(Clone, Debug)]
pub struct SaveState<G = Gpu> {
    gpu: G,
}

impl SaveState<Gpu> {
    /// The GPU the state holds, ready to continue where it was saved.
    pub fn into_gpu(self) -> Gpu {
        self.gpu
    }
}

impl Gpu {
    /// The whole chip state with the format header, for serializing: VRAM, drawing and
    /// display registers, a packet, transfer or polyline in progress, the CLUT cache, the
    /// FIFO and drawing time, video timing and the events not yet reported by [`Gpu::run`],
    /// the GPUREAD latch.
    pub fn save_state(&self) -> SaveState<&Gpu> {
        SaveState { gpu: self }
    }
}

const FIELDS: &[&str] = &["magic", "version", "gpu"];

impl Serialize for SaveState<&Gpu> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut s = serializer.serialize_struct("GpuSaveState", FIELDS.len())?;
        s.serialize_field("magic", &SAVE_STATE_MAGIC)?;
        s.serialize_field("version", &SAVE_STATE_VERSION)?;
        s.serialize_field("gpu", self.gpu)?;
        s.end()
    }
}

fn check_magic<E: de::Error>(found: u32) -> Result<(), E> {
    if found == SAVE_STATE_MAGIC {
        Ok(())
    } else {
        Err(E::custom(StateError::NotAGpuState { found }))
    }
}

fn check_version<E: de::Error>(found: u32) -> Result<(), E> {
    if found == SAVE_STATE_VERSION {
        Ok(())
    } else {
        Err(E::custom(StateError::Version {
            found,
            expected: SAVE_STATE_VERSION,
        }))
    }
}

#[derive(Deserialize)]
#[serde(field_identifier, rename_all = "lowercase")]
enum Field {
    Magic,
    Version,
    Gpu,
}

struct SaveStateVisitor;

impl<'de> Visitor<'de> for SaveStateVisitor {
    type Value = SaveState<Gpu>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a GPU save state")
    }

    /// Positional formats: the header is checked before the body is read.
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let magic: u32 = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(0, &self))?;
        check_magic(magic)?;
        let version: u32 = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(1, &self))?;
        check_version(version)?;
        let gpu = seq
            .next_element()?
            .ok_or_else(|| de::Error::invalid_length(2, &self))?;
        Ok(SaveState { gpu })
    }

    /// Self-describing formats: each header field is checked where it is read (the header
    /// is written first); a map without both is refused.
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let (mut magic, mut version, mut gpu) = (false, false, None);
        while let Some(key) = map.next_key()? {
            match key {
                Field::Magic if !magic => {
                    check_magic(map.next_value()?)?;
                    magic = true;
                }
                Field::Version if !version => {
                    check_version(map.next_value()?)?;
                    version = true;
                }
                Field::Gpu if gpu.is_none() => gpu = Some(map.next_value()?),
                Field::Magic => return Err(de::Error::duplicate_field("magic")),
                Field::Version => return Err(de::Error::duplicate_field("version")),
                Field::Gpu => return Err(de::Error::duplicate_field("gpu")),
            }
        }
        match gpu {
            _ if !magic => Err(de::Error::missing_field("magic")),
            _ if !version => Err(de::Error::missing_field("version")),
            Some(gpu) => Ok(SaveState { gpu }),
            None => Err(de::Error::missing_field("gpu")),
        }
    }
}

impl<'de> Deserialize<'de> for SaveState<Gpu> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_struct("GpuSaveState", FIELDS, SaveStateVisitor)
    }
}

/// The serialized fields of [`Gpu`], in its declaration order, before their invariants are
/// checked.
#[derive(Deserialize)]
pub(crate) struct GpuFields {
    draw: DrawState,
    clut: ClutCache,
    gp0: gp0::Gp0State,
    read: transfer::ReadTransfer,
    display: DisplayState,
    gpuread_latch: u32,
    irq: bool,
    irq_event: bool,
    texture_disable_allowed: bool,
    drawing: drawing::Drawing,
    timing: timing::Timing,
    vram: Vram,
}

impl TryFrom<GpuFields> for Gpu {
    type Error = StateError;

    fn try_from(f: GpuFields) -> Result<Self, StateError> {
        f.draw.check().map_err(StateError::Invalid)?;
        f.clut.check().map_err(StateError::Invalid)?;
        f.gp0.check().map_err(StateError::Invalid)?;
        f.read.check().map_err(StateError::Invalid)?;
        f.display.check().map_err(StateError::Invalid)?;
        f.drawing.check().map_err(StateError::Invalid)?;
        f.timing.check().map_err(StateError::Invalid)?;
        Ok(Gpu {
            draw: f.draw,
            clut: f.clut,
            gp0: f.gp0,
            read: f.read,
            display: f.display,
            gpuread_latch: f.gpuread_latch,
            irq: f.irq,
            irq_event: f.irq_event,
            texture_disable_allowed: f.texture_disable_allowed,
            drawing: f.drawing,
            timing: f.timing,
            vram: f.vram,
        })
    }
}
