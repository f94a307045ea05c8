//! Serde support for the large fixed-size halfword arrays of the chip state (the CLUT cache
//! and VRAM): a sequence of `u16`, read back with its exact length checked.

use core::fmt;

use serde::de::{self, SeqAccess, Visitor};
use serde::{Deserializer, Serializer};

/// Serialize `[u16; N]` as a sequence.
pub(crate) fn serialize<S: Serializer, const N: usize>(
    array: &[u16; N],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_seq(array.iter())
}

/// Deserialize `[u16; N]` from a sequence of exactly N halfwords.
pub(crate) fn deserialize<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<[u16; N], D::Error> {
    let mut array = [0u16; N];
    deserializer.deserialize_seq(Fill(&mut array[..]))?;
    Ok(array)
}

/// Fills a halfword slice from a sequence of exactly its length.
pub(crate) struct Fill<'a>(pub(crate) &'a mut [u16]);

impl<'de> Visitor<'de> for Fill<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a sequence of {} halfwords", self.0.len())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let len = self.0.len();
        let expected = Expected(len);
        for (i, slot) in self.0.iter_mut().enumerate() {
            *slot = seq
                .next_element()?
                .ok_or_else(|| de::Error::invalid_length(i, &expected))?;
        }
        if seq.next_element::<u16>()?.is_some() {
            return Err(de::Error::invalid_length(len + 1, &expected));
        }
        Ok(())
    }
}

/// "a sequence of N halfwords", for length errors.
struct Expected(usize);

impl de::Expected for Expected {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "a sequence of {} halfwords", self.0)
    }
}
