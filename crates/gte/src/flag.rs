//! The FLAG register (control register 31): saturation and overflow bits set by the last
//! command (docs/hardware/gte.md §3).

/// A set of FLAG bits. Bits 0-11 are always zero; bit 31 is the OR of bits 30-23 and 18-13.
///
/// `Debug` and `Display` name the bits set, from bit 31 down:
///
/// ```
/// use gte::Flag;
/// let flag = Flag::from_bits(0x8100_1000);
/// assert_eq!(format!("{flag}"), "ERROR | IR1_SATURATED | IR0_SATURATED");
/// assert_eq!(format!("{flag:?}"), "Flag(0x81001000: ERROR | IR1_SATURATED | IR0_SATURATED)");
/// assert_eq!(format!("{}", Flag::EMPTY), "EMPTY");
/// ```
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(from = "u32", into = "u32")
)]
pub struct Flag(u32);

impl From<u32> for Flag {
    /// As [`Flag::from_bits`]: the value a CTC2 write of `bits` leaves in FLAG.
    fn from(bits: u32) -> Flag {
        Flag::from_bits(bits)
    }
}

impl From<Flag> for u32 {
    /// The raw register value, as CFC2 reads it.
    fn from(flag: Flag) -> u32 {
        flag.bits()
    }
}

impl Flag {
    /// No bit set.
    pub const EMPTY: Flag = Flag(0);
    /// Bit 31: error summary, OR of bits 30-23 and 18-13.
    pub const ERROR: Flag = Flag(1 << 31);
    /// Bit 30: MAC1 above 2^43 - 1.
    pub const MAC1_POSITIVE_OVERFLOW: Flag = Flag(1 << 30);
    /// Bit 29: MAC2 above 2^43 - 1.
    pub const MAC2_POSITIVE_OVERFLOW: Flag = Flag(1 << 29);
    /// Bit 28: MAC3 above 2^43 - 1.
    pub const MAC3_POSITIVE_OVERFLOW: Flag = Flag(1 << 28);
    /// Bit 27: MAC1 below -2^43.
    pub const MAC1_NEGATIVE_OVERFLOW: Flag = Flag(1 << 27);
    /// Bit 26: MAC2 below -2^43.
    pub const MAC2_NEGATIVE_OVERFLOW: Flag = Flag(1 << 26);
    /// Bit 25: MAC3 below -2^43.
    pub const MAC3_NEGATIVE_OVERFLOW: Flag = Flag(1 << 25);
    /// Bit 24: IR1 saturated.
    pub const IR1_SATURATED: Flag = Flag(1 << 24);
    /// Bit 23: IR2 saturated.
    pub const IR2_SATURATED: Flag = Flag(1 << 23);
    /// Bit 22: IR3 saturated.
    pub const IR3_SATURATED: Flag = Flag(1 << 22);
    /// Bit 21: colour FIFO R saturated to 0..FFh.
    pub const COLOR_R_SATURATED: Flag = Flag(1 << 21);
    /// Bit 20: colour FIFO G saturated.
    pub const COLOR_G_SATURATED: Flag = Flag(1 << 20);
    /// Bit 19: colour FIFO B saturated.
    pub const COLOR_B_SATURATED: Flag = Flag(1 << 19);
    /// Bit 18: SZ3 or OTZ saturated to 0..FFFFh.
    pub const SZ3_OTZ_SATURATED: Flag = Flag(1 << 18);
    /// Bit 17: UNR divide overflow (H >= 2*SZ3).
    pub const DIVIDE_OVERFLOW: Flag = Flag(1 << 17);
    /// Bit 16: MAC0 above 2^31 - 1.
    pub const MAC0_POSITIVE_OVERFLOW: Flag = Flag(1 << 16);
    /// Bit 15: MAC0 below -2^31.
    pub const MAC0_NEGATIVE_OVERFLOW: Flag = Flag(1 << 15);
    /// Bit 14: SX2 saturated to -400h..3FFh.
    pub const SX2_SATURATED: Flag = Flag(1 << 14);
    /// Bit 13: SY2 saturated to -400h..3FFh.
    pub const SY2_SATURATED: Flag = Flag(1 << 13);
    /// Bit 12: IR0 saturated to 0..1000h.
    pub const IR0_SATURATED: Flag = Flag(1 << 12);

    /// Every bit FLAG can hold with its name, from bit 31 down to bit 12.
    pub const NAMED: [(Flag, &'static str); 20] = [
        (Flag::ERROR, "ERROR"),
        (Flag::MAC1_POSITIVE_OVERFLOW, "MAC1_POSITIVE_OVERFLOW"),
        (Flag::MAC2_POSITIVE_OVERFLOW, "MAC2_POSITIVE_OVERFLOW"),
        (Flag::MAC3_POSITIVE_OVERFLOW, "MAC3_POSITIVE_OVERFLOW"),
        (Flag::MAC1_NEGATIVE_OVERFLOW, "MAC1_NEGATIVE_OVERFLOW"),
        (Flag::MAC2_NEGATIVE_OVERFLOW, "MAC2_NEGATIVE_OVERFLOW"),
        (Flag::MAC3_NEGATIVE_OVERFLOW, "MAC3_NEGATIVE_OVERFLOW"),
        (Flag::IR1_SATURATED, "IR1_SATURATED"),
        (Flag::IR2_SATURATED, "IR2_SATURATED"),
        (Flag::IR3_SATURATED, "IR3_SATURATED"),
        (Flag::COLOR_R_SATURATED, "COLOR_R_SATURATED"),
        (Flag::COLOR_G_SATURATED, "COLOR_G_SATURATED"),
        (Flag::COLOR_B_SATURATED, "COLOR_B_SATURATED"),
        (Flag::SZ3_OTZ_SATURATED, "SZ3_OTZ_SATURATED"),
        (Flag::DIVIDE_OVERFLOW, "DIVIDE_OVERFLOW"),
        (Flag::MAC0_POSITIVE_OVERFLOW, "MAC0_POSITIVE_OVERFLOW"),
        (Flag::MAC0_NEGATIVE_OVERFLOW, "MAC0_NEGATIVE_OVERFLOW"),
        (Flag::SX2_SATURATED, "SX2_SATURATED"),
        (Flag::SY2_SATURATED, "SY2_SATURATED"),
        (Flag::IR0_SATURATED, "IR0_SATURATED"),
    ];

    /// Bits that feed the error summary, bit 31 (docs/hardware/gte.md §3).
    pub const ERROR_SOURCES: u32 = 0x7F87_E000;
    /// Bits a CTC2 write to FLAG keeps (docs/hardware/gte.md §2).
    pub const WRITABLE: u32 = 0x7FFF_F000;

    /// The flag set as FLAG reads it, from raw bits; bits 0-11 are dropped and bit 31
    /// recomputed from the error sources, as a CTC2 write does.
    pub const fn from_bits(bits: u32) -> Flag {
        let kept = bits & Self::WRITABLE;
        Flag(kept | ((kept & Self::ERROR_SOURCES != 0) as u32) << 31)
    }

    /// FLAG as the register holds it: a CTC2 and a command each leave bits 0-11 clear and
    /// bit 31 the OR of the error sources (docs/hardware/gte.md §3); a command's bits are
    /// that value, each error source having brought bit 31 with it.
    #[inline(always)]
    pub(crate) const fn from_register(bits: u32) -> Flag {
        debug_assert!(bits & !Self::WRITABLE & !(1 << 31) == 0);
        debug_assert!((bits >> 31 != 0) == (bits & Self::ERROR_SOURCES != 0));
        Flag(bits)
    }

    /// The raw register value.
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// Whether every bit of `other` is set in `self`.
    pub const fn contains(self, other: Flag) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether any bit of `other` is set in `self`.
    pub const fn intersects(self, other: Flag) -> bool {
        self.0 & other.0 != 0
    }

    /// The union of two sets (bit by bit; bit 31 is not recomputed).
    pub const fn union(self, other: Flag) -> Flag {
        Flag(self.0 | other.0)
    }

    /// Whether the error summary (bit 31) is set.
    pub const fn is_error(self) -> bool {
        self.0 & Self::ERROR.0 != 0
    }

    /// Whether no bit is set.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }
}

impl core::fmt::Display for Flag {
    /// The names of the bits set ([`Flag::NAMED`]) joined by `" | "`, from bit 31 down, or
    /// `EMPTY`.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.is_empty() {
            return f.write_str("EMPTY");
        }
        let mut first = true;
        for (bit, name) in Flag::NAMED {
            if self.contains(bit) {
                if !first {
                    f.write_str(" | ")?;
                }
                f.write_str(name)?;
                first = false;
            }
        }
        Ok(())
    }
}

impl core::fmt::Debug for Flag {
    /// `Flag(0x…: …)`: the register value in hexadecimal and the names of its bits, as
    /// `Display` gives them.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "Flag({:#010X}: {})", self.0, self)
    }
}

impl core::ops::BitOr for Flag {
    type Output = Flag;
    fn bitor(self, rhs: Flag) -> Flag {
        self.union(rhs)
    }
}
