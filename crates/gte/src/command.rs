//! The COP2 command word: opcode and the sf/lm/mx/v/cv fields, and each command's cycle
//! count (docs/hardware/gte.md §1).

/// A decoded 25-bit COP2 command word (docs/hardware/gte.md §1). Bits 20-24 are ignored by the hardware.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Command(u32);

/// The 22 commands, by opcode (bits 0-5) (docs/hardware/gte.md §1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Opcode {
    /// 01h perspective transform, single.
    Rtps,
    /// 06h normal clipping.
    Nclip,
    /// 0Ch outer product.
    Op,
    /// 10h depth cueing, single.
    Dpcs,
    /// 11h interpolation.
    Intpl,
    /// 12h matrix-vector multiply and add.
    Mvmva,
    /// 13h normal colour depth cue, single.
    Ncds,
    /// 14h colour depth cue.
    Cdp,
    /// 16h normal colour depth cue, triple.
    Ncdt,
    /// 1Bh normal colour colour, single.
    Nccs,
    /// 1Ch colour colour.
    Cc,
    /// 1Eh normal colour, single.
    Ncs,
    /// 20h normal colour, triple.
    Nct,
    /// 28h square of vector IR.
    Sqr,
    /// 29h depth cue colour light.
    Dcpl,
    /// 2Ah depth cueing, triple.
    Dpct,
    /// 2Dh average of three Z values.
    Avsz3,
    /// 2Eh average of four Z values.
    Avsz4,
    /// 30h perspective transform, triple.
    Rtpt,
    /// 3Dh general purpose interpolation.
    Gpf,
    /// 3Eh general purpose interpolation with base.
    Gpl,
    /// 3Fh normal colour colour, triple.
    Ncct,
}

impl Opcode {
    /// The opcode for bits 0-5, or `None` for the 42 undefined values.
    #[inline]
    pub const fn from_bits(bits: u32) -> Option<Opcode> {
        Some(match bits & 0x3F {
            0x01 => Opcode::Rtps,
            0x06 => Opcode::Nclip,
            0x0C => Opcode::Op,
            0x10 => Opcode::Dpcs,
            0x11 => Opcode::Intpl,
            0x12 => Opcode::Mvmva,
            0x13 => Opcode::Ncds,
            0x14 => Opcode::Cdp,
            0x16 => Opcode::Ncdt,
            0x1B => Opcode::Nccs,
            0x1C => Opcode::Cc,
            0x1E => Opcode::Ncs,
            0x20 => Opcode::Nct,
            0x28 => Opcode::Sqr,
            0x29 => Opcode::Dcpl,
            0x2A => Opcode::Dpct,
            0x2D => Opcode::Avsz3,
            0x2E => Opcode::Avsz4,
            0x30 => Opcode::Rtpt,
            0x3D => Opcode::Gpf,
            0x3E => Opcode::Gpl,
            0x3F => Opcode::Ncct,
            _ => return None,
        })
    }

    /// Bits 0-5 of the command word.
    #[inline]
    pub const fn bits(self) -> u32 {
        match self {
            Opcode::Rtps => 0x01,
            Opcode::Nclip => 0x06,
            Opcode::Op => 0x0C,
            Opcode::Dpcs => 0x10,
            Opcode::Intpl => 0x11,
            Opcode::Mvmva => 0x12,
            Opcode::Ncds => 0x13,
            Opcode::Cdp => 0x14,
            Opcode::Ncdt => 0x16,
            Opcode::Nccs => 0x1B,
            Opcode::Cc => 0x1C,
            Opcode::Ncs => 0x1E,
            Opcode::Nct => 0x20,
            Opcode::Sqr => 0x28,
            Opcode::Dcpl => 0x29,
            Opcode::Dpct => 0x2A,
            Opcode::Avsz3 => 0x2D,
            Opcode::Avsz4 => 0x2E,
            Opcode::Rtpt => 0x30,
            Opcode::Gpf => 0x3D,
            Opcode::Gpl => 0x3E,
            Opcode::Ncct => 0x3F,
        }
    }

    /// Cycles the command takes (docs/hardware/gte.md §1), for an emulator to charge time.
    #[inline]
    pub const fn cycles(self) -> u32 {
        match self {
            Opcode::Rtps => 15,
            Opcode::Nclip => 8,
            Opcode::Op => 6,
            Opcode::Dpcs => 8,
            Opcode::Intpl => 8,
            Opcode::Mvmva => 8,
            Opcode::Ncds => 19,
            Opcode::Cdp => 13,
            Opcode::Ncdt => 44,
            Opcode::Nccs => 17,
            Opcode::Cc => 11,
            Opcode::Ncs => 14,
            Opcode::Nct => 30,
            Opcode::Sqr => 5,
            Opcode::Dcpl => 8,
            Opcode::Dpct => 17,
            Opcode::Avsz3 => 5,
            Opcode::Avsz4 => 6,
            Opcode::Rtpt => 23,
            Opcode::Gpf => 5,
            Opcode::Gpl => 5,
            Opcode::Ncct => 39,
        }
    }

    /// All 22 opcodes in opcode order.
    pub const ALL: [Opcode; 22] = [
        Opcode::Rtps,
        Opcode::Nclip,
        Opcode::Op,
        Opcode::Dpcs,
        Opcode::Intpl,
        Opcode::Mvmva,
        Opcode::Ncds,
        Opcode::Cdp,
        Opcode::Ncdt,
        Opcode::Nccs,
        Opcode::Cc,
        Opcode::Ncs,
        Opcode::Nct,
        Opcode::Sqr,
        Opcode::Dcpl,
        Opcode::Dpct,
        Opcode::Avsz3,
        Opcode::Avsz4,
        Opcode::Rtpt,
        Opcode::Gpf,
        Opcode::Gpl,
        Opcode::Ncct,
    ];
}

/// MVMVA matrix selector, bits 17-18 (docs/hardware/gte.md §1, §8).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MatrixSel {
    /// 0: rotation RT.
    Rotation,
    /// 1: light LLM.
    Light,
    /// 2: light colour LCM.
    LightColor,
    /// 3: the hardware's garbage matrix (docs/hardware/gte.md §8).
    Garbage,
}

/// MVMVA vector selector, bits 15-16.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum VectorSel {
    /// V0, V1, V2, or IR1-3.
    V0,
    /// V1.
    V1,
    /// V2.
    V2,
    /// IR1, IR2, IR3.
    Ir,
}

/// MVMVA add-vector selector, bits 13-14.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TranslationSel {
    /// TR.
    Translation,
    /// BK.
    Background,
    /// FC, with the hardware bug (docs/hardware/gte.md §8).
    FarColor,
    /// No add vector.
    None,
}

impl Command {
    /// Wrap a COP2 command word; bits above 24 are dropped.
    #[inline]
    pub const fn new(word: u32) -> Command {
        Command(word & 0x01FF_FFFF)
    }

    /// Build a command word from its fields (the MVMVA selectors are ignored by other opcodes).
    #[inline]
    pub const fn build(
        opcode: Opcode,
        sf: bool,
        lm: bool,
        mx: MatrixSel,
        v: VectorSel,
        cv: TranslationSel,
    ) -> Command {
        Command(
            opcode.bits()
                | (lm as u32) << 10
                | (cv as u32) << 13
                | (v as u32) << 15
                | (mx as u32) << 17
                | (sf as u32) << 19,
        )
    }

    /// The raw 25-bit word.
    #[inline]
    pub const fn word(self) -> u32 {
        self.0
    }

    /// The opcode, or `None` when bits 0-5 name no command.
    #[inline]
    pub const fn opcode(self) -> Option<Opcode> {
        Opcode::from_bits(self.0)
    }

    /// sf (bit 19): results are shifted right by 12 when set.
    #[inline]
    pub const fn shift(self) -> u32 {
        ((self.0 >> 19) & 1) * 12
    }

    /// lm (bit 10): IR1-3 saturate to 0..7FFFh instead of -8000h..7FFFh.
    #[inline]
    pub const fn lm(self) -> bool {
        self.0 & (1 << 10) != 0
    }

    /// The MVMVA selector fields as numbers: mx (bits 17-18), v (bits 15-16), cv (bits 13-14).
    #[inline(always)]
    pub(crate) const fn mvmva_fields(self) -> (usize, usize, usize) {
        let w = self.0 as usize;
        ((w >> 17) & 3, (w >> 15) & 3, (w >> 13) & 3)
    }

    /// Whether MVMVA's operands are all stored registers: a stored matrix (mx 0-2), V0-2
    /// (v 0-2) and TR, BK or none (cv 0, 1, 3), none of the selections with a hardware bug
    /// or a computed operand (docs/hardware/gte.md §8). One bit test on bits 13-18 of the
    /// word.
    #[inline(always)]
    pub(crate) const fn mvmva_stored_operands(self) -> bool {
        /// Bit cv + 4v + 16mx is set when mx < 3, v < 3 and cv != 2.
        const STORED: u64 = {
            let mut set = 0u64;
            let mut f = 0;
            while f < 64 {
                if f >> 4 != 3 && (f >> 2) & 3 != 3 && f & 3 != 2 {
                    set |= 1 << f;
                }
                f += 1;
            }
            set
        };
        STORED >> ((self.0 >> 13) & 0x3F) & 1 != 0
    }

    /// MVMVA matrix.
    #[inline]
    pub const fn mx(self) -> MatrixSel {
        match (self.0 >> 17) & 3 {
            0 => MatrixSel::Rotation,
            1 => MatrixSel::Light,
            2 => MatrixSel::LightColor,
            _ => MatrixSel::Garbage,
        }
    }

    /// MVMVA vector.
    #[inline]
    pub const fn v(self) -> VectorSel {
        match (self.0 >> 15) & 3 {
            0 => VectorSel::V0,
            1 => VectorSel::V1,
            2 => VectorSel::V2,
            _ => VectorSel::Ir,
        }
    }

    /// MVMVA add vector.
    #[inline]
    pub const fn cv(self) -> TranslationSel {
        match (self.0 >> 13) & 3 {
            0 => TranslationSel::Translation,
            1 => TranslationSel::Background,
            2 => TranslationSel::FarColor,
            _ => TranslationSel::None,
        }
    }

    /// Cycle count (docs/hardware/gte.md §1); `None` for undefined opcodes, which have no hardware timing data.
    #[inline]
    pub const fn cycles(self) -> Option<u32> {
        match self.opcode() {
            Some(op) => Some(op.cycles()),
            None => None,
        }
    }
}

/// Cycle count of a command word (docs/hardware/gte.md §1); `None` for undefined opcodes.
#[inline]
pub const fn cycles(command: u32) -> Option<u32> {
    Command::new(command).cycles()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn opcode_round_trip() {
        for op in Opcode::ALL {
            assert_eq!(Opcode::from_bits(op.bits()), Some(op));
        }
        let defined = (0..64).filter(|b| Opcode::from_bits(*b).is_some()).count();
        assert_eq!(defined, 22);
    }

    #[test]
    fn fields_decode() {
        // RTPT with sf=1, lm=0: the 0x0280030 word SDKs emit (opcode 30h, sf bit 19, bit 23 fake).
        let c = Command::new(0x0280030);
        assert_eq!(c.opcode(), Some(Opcode::Rtpt));
        assert_eq!(c.shift(), 12);
        assert!(!c.lm());
        assert_eq!(cycles(0x0280030), Some(23));
        let m = Command::build(
            Opcode::Mvmva,
            false,
            true,
            MatrixSel::Garbage,
            VectorSel::Ir,
            TranslationSel::FarColor,
        );
        assert_eq!(m.word(), 0x12 | 1 << 10 | 2 << 13 | 3 << 15 | 3 << 17);
        assert_eq!(m.mx(), MatrixSel::Garbage);
        assert_eq!(m.v(), VectorSel::Ir);
        assert_eq!(m.cv(), TranslationSel::FarColor);
    }
}
