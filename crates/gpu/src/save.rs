//! Versioned save states (feature `serde`): a header naming the format and its version, then
//! the whole chip state. Loading checks the header before the body and every field against
//! what the hardware can reach, so a state from an unknown version, a truncated or a garbled
//! one is an error, never a GPU in an impossible state (docs/emulator.md, "Save states").
//!
//! Version 2 writes VRAM as one block of bytes (each halfword little-endian, row-major), which
//! binary formats copy whole; version 1 wrote it as a sequence of halfwords and still loads.

use core::fmt;

use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use alloc::boxed::Box;
use alloc::vec::Vec;

use crate::state::DrawState;
use crate::texture::ClutCache;
use crate::texture_cache::TextureCache;
use crate::{DisplayState, Gpu, VRAM_LEN, Vram, drawing, gp0, serde_array, timing, transfer};

/// First field of every GPU save state: "WGPU" read as a little-endian `u32`.
pub const SAVE_STATE_MAGIC: u32 = u32::from_le_bytes(*b"WGPU");

/// The save-state layout this build writes. It changes whenever a field of the chip state is
/// added, removed, reordered or given another meaning. This build also reads every version
/// from [`SAVE_STATE_OLDEST_VERSION`] up.
pub const SAVE_STATE_VERSION: u32 = 2;

/// The oldest save-state layout this build reads: version 1, whose VRAM is a sequence of
/// halfwords.
pub const SAVE_STATE_OLDEST_VERSION: u32 = 1;

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
    /// Written in a layout this build does not read: a [`SAVE_STATE_VERSION`] newer than its
    /// own or older than [`SAVE_STATE_OLDEST_VERSION`].
    Version {
        /// The version in the state.
        found: u32,
        /// The newest version this build reads (the one it writes).
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
                "GPU save state version {found}, this build reads versions \
                 {SAVE_STATE_OLDEST_VERSION} to {expected}"
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
    /// display registers, a packet, transfer or polyline in progress, the CLUT and texture
    /// caches (with the texture cache's switch and miss count), the
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

fn check_version<E: de::Error>(found: u32) -> Result<u32, E> {
    if (SAVE_STATE_OLDEST_VERSION..=SAVE_STATE_VERSION).contains(&found) {
        Ok(found)
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
        let gpu = match check_version(version)? {
            1 => seq.next_element::<GpuV1>()?.map(|g| g.0),
            _ => seq.next_element()?,
        };
        let gpu = gpu.ok_or_else(|| de::Error::invalid_length(2, &self))?;
        Ok(SaveState { gpu })
    }

    /// Self-describing formats: each header field is checked where it is read, and a map
    /// without both is refused. The body may come before the version (a map read back with
    /// its keys sorted), so its VRAM is read in either layout and must then be the one of the
    /// version.
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let (mut magic, mut version, mut gpu) = (false, None, None);
        while let Some(key) = map.next_key()? {
            match key {
                Field::Magic if !magic => {
                    check_magic(map.next_value()?)?;
                    magic = true;
                }
                Field::Version if version.is_none() => {
                    version = Some(check_version(map.next_value()?)?);
                }
                Field::Gpu if gpu.is_none() => gpu = Some(map.next_value::<GpuAnyLayout>()?),
                Field::Magic => return Err(de::Error::duplicate_field("magic")),
                Field::Version => return Err(de::Error::duplicate_field("version")),
                Field::Gpu => return Err(de::Error::duplicate_field("gpu")),
            }
        }
        match (version, gpu) {
            _ if !magic => Err(de::Error::missing_field("magic")),
            (None, _) => Err(de::Error::missing_field("version")),
            (_, None) => Err(de::Error::missing_field("gpu")),
            (Some(v), Some(GpuAnyLayout { gpu, layout })) if v == layout => Ok(SaveState { gpu }),
            (Some(_), Some(GpuAnyLayout { layout, .. })) => {
                Err(de::Error::custom(StateError::Invalid(if layout == 1 {
                    "VRAM as halfwords (version 1) in a later version's state"
                } else {
                    "VRAM as bytes (version 2 on) in a version-1 state"
                })))
            }
        }
    }
}

impl<'de> Deserialize<'de> for SaveState<Gpu> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_struct("GpuSaveState", FIELDS, SaveStateVisitor)
    }
}

/// VRAM is serialized as one block of `2 * VRAM_LEN` bytes: each halfword little-endian,
/// row-major.
impl Serialize for Vram {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[cfg(target_endian = "little")]
        {
            serializer.serialize_bytes(bytemuck::cast_slice(self.as_slice()))
        }
        #[cfg(not(target_endian = "little"))]
        {
            let pairs: Vec<[u8; 2]> = self.as_slice().iter().map(|p| p.to_le_bytes()).collect();
            serializer.serialize_bytes(pairs.as_flattened())
        }
    }
}

/// VRAM is read back from a block of exactly `2 * VRAM_LEN` bytes (or, in formats that write
/// bytes as a sequence, a sequence of that many bytes); any other length is an error.
impl<'de> Deserialize<'de> for Vram {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_bytes(VramBytes)
    }
}

/// Builds VRAM from its byte block.
struct VramBytes;

impl VramBytes {
    fn from_bytes<E: de::Error>(bytes: &[u8]) -> Result<Vram, E> {
        if bytes.len() != 2 * VRAM_LEN {
            return Err(E::invalid_length(bytes.len(), &VramBytes));
        }
        let (pairs, _) = bytes.as_chunks::<2>();
        let pixels: Vec<u16> = pairs.iter().map(|&b| u16::from_le_bytes(b)).collect();
        let pixels: Box<[u16; VRAM_LEN]> = pixels
            .into_boxed_slice()
            .try_into()
            .map_err(|_| E::invalid_length(bytes.len(), &VramBytes))?;
        Ok(Vram { pixels })
    }
}

impl<'de> Visitor<'de> for VramBytes {
    type Value = Vram;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "VRAM as {} bytes", 2 * VRAM_LEN)
    }

    fn visit_bytes<E: de::Error>(self, v: &[u8]) -> Result<Vram, E> {
        Self::from_bytes(v)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vram, A::Error> {
        let mut vram = Vram::new();
        for (i, p) in vram.as_mut_slice().iter_mut().enumerate() {
            let mut byte = |k: usize| {
                seq.next_element::<u8>()?
                    .ok_or_else(|| de::Error::invalid_length(2 * i + k, &self))
            };
            let lo = byte(0)?;
            let hi = byte(1)?;
            *p = u16::from_le_bytes([lo, hi]);
        }
        if seq.next_element::<u8>()?.is_some() {
            return Err(de::Error::invalid_length(2 * VRAM_LEN + 1, &self));
        }
        Ok(vram)
    }
}

/// VRAM as version 1 wrote it: a sequence of exactly `VRAM_LEN` halfwords.
struct VramV1(Vram);

impl<'de> Deserialize<'de> for VramV1 {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut vram = Vram::new();
        deserializer.deserialize_seq(serde_array::Fill(vram.as_mut_slice()))?;
        Ok(VramV1(vram))
    }
}

/// A version-1 body: the fields of [`GpuFields`] with VRAM as a sequence of halfwords, the
/// VRAM-to-CPU transfer without its fetch timing, the drawing time without its carried
/// fraction and work counter (both added in version 2, loaded as 0) and no texture cache
/// (added in version 2: loaded on and empty, as after GP0(01h)).
struct GpuV1(Gpu);

/// The texture cache of a version-1 state, which had none: nothing in binary formats, an
/// absent field in self-describing ones.
#[derive(Default, Deserialize)]
struct NoTextureCache;

impl From<NoTextureCache> for TextureCache {
    fn from(_: NoTextureCache) -> Self {
        TextureCache::default()
    }
}

impl<'de> Deserialize<'de> for GpuV1 {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let f = GpuFields::<VramV1, transfer::ReadTransferV1, drawing::DrawingV1, NoTextureCache>::deserialize(
            deserializer,
        )?;
        Ok(GpuV1(f.into_gpu(|v| v.0)?))
    }
}

/// VRAM in the layout of any version, told apart by what the format holds: a byte block, or
/// a sequence of `2 * VRAM_LEN` bytes, is version 2's; a sequence of `VRAM_LEN` halfwords is
/// version 1's. Only for self-describing formats, which can say what they hold.
struct AnyVram {
    vram: Vram,
    /// The version whose layout it was.
    layout: u32,
}

impl<'de> Deserialize<'de> for AnyVram {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(AnyVramVisitor)
    }
}

struct AnyVramVisitor;

impl<'de> Visitor<'de> for AnyVramVisitor {
    type Value = AnyVram;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "VRAM as {} bytes or {VRAM_LEN} halfwords", 2 * VRAM_LEN)
    }

    fn visit_bytes<E: de::Error>(self, v: &[u8]) -> Result<AnyVram, E> {
        let vram = VramBytes::from_bytes(v)?;
        Ok(AnyVram { vram, layout: 2 })
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<AnyVram, A::Error> {
        let mut items: Vec<u16> =
            Vec::with_capacity(seq.size_hint().unwrap_or(0).min(2 * VRAM_LEN));
        while let Some(v) = seq.next_element::<u16>()? {
            if items.len() == 2 * VRAM_LEN {
                return Err(de::Error::invalid_length(items.len() + 1, &self));
            }
            items.push(v);
        }
        let mut vram = Vram::new();
        let layout = if items.len() == VRAM_LEN {
            vram.as_mut_slice().copy_from_slice(&items);
            1
        } else if items.len() == 2 * VRAM_LEN {
            for (p, b) in vram.as_mut_slice().iter_mut().zip(items.chunks_exact(2)) {
                let byte = |v: u16| {
                    u8::try_from(v).map_err(|_| {
                        de::Error::invalid_value(de::Unexpected::Unsigned(v.into()), &"a byte")
                    })
                };
                *p = u16::from_le_bytes([byte(b[0])?, byte(b[1])?]);
            }
            2
        } else {
            return Err(de::Error::invalid_length(items.len(), &self));
        };
        Ok(AnyVram { vram, layout })
    }
}

/// A body whose VRAM may be in either layout, and which one it was.
struct GpuAnyLayout {
    gpu: Gpu,
    layout: u32,
}

impl<'de> Deserialize<'de> for GpuAnyLayout {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let f = GpuFields::<AnyVram>::deserialize(deserializer)?;
        let layout = f.vram.layout;
        let gpu = f.into_gpu(|v| v.vram)?;
        Ok(GpuAnyLayout { gpu, layout })
    }
}

/// The serialized fields of [`Gpu`], in its declaration order, before their invariants are
/// checked; `V` is VRAM, `R` the VRAM-to-CPU transfer and `D` the drawing time in the layout
/// of the version read.
#[derive(Deserialize)]
pub(crate) struct GpuFields<
    V = Vram,
    R = transfer::ReadTransfer,
    D = drawing::Drawing,
    C = TextureCache,
> {
    draw: DrawState,
    clut: ClutCache,
    /// Absent from version-1 states in self-describing formats (see [`NoTextureCache`]).
    #[serde(default)]
    texture_cache: C,
    gp0: gp0::Gp0State,
    read: R,
    display: DisplayState,
    gpuread_latch: u32,
    irq: bool,
    irq_event: bool,
    texture_disable_allowed: bool,
    drawing: D,
    timing: timing::Timing,
    vram: V,
}

impl<V, R: Into<transfer::ReadTransfer>, D: Into<drawing::Drawing>, C: Into<TextureCache>>
    GpuFields<V, R, D, C>
{
    /// The checked GPU of these fields, their VRAM converted by `vram`, the transfer and
    /// drawing time by their version's conversion.
    fn into_gpu<E: de::Error>(self, vram: impl FnOnce(V) -> Vram) -> Result<Gpu, E> {
        Gpu::try_from(GpuFields {
            draw: self.draw,
            clut: self.clut,
            texture_cache: self.texture_cache.into(),
            gp0: self.gp0,
            read: self.read.into(),
            display: self.display,
            gpuread_latch: self.gpuread_latch,
            irq: self.irq,
            irq_event: self.irq_event,
            texture_disable_allowed: self.texture_disable_allowed,
            drawing: self.drawing.into(),
            timing: self.timing,
            vram: vram(self.vram),
        })
        .map_err(E::custom)
    }
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
            texture_cache: f.texture_cache,
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
            host: crate::host_cpu::HostCpu::detect(),
        })
    }
}
