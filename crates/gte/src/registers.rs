//! The GTE register file: 32 data registers (MTC2/MFC2) and 32 control registers
//! (CTC2/CFC2), with every read/write quirk of docs/hardware/gte.md §2.

use crate::flag::Flag;

/// A 3x3 matrix of signed 1.3.12 entries, row-major (`m[row][column]`).
pub(crate) type Matrix = [[i16; 3]; 3];

/// Register names as MFC2/CFC2 number them: data r0..r31 then control c0..c31 (64 entries).
pub const REGISTER_NAMES: [&str; 64] = [
    "VXY0", "VZ0", "VXY1", "VZ1", "VXY2", "VZ2", "RGBC", "OTZ", "IR0", "IR1", "IR2", "IR3", "SXY0",
    "SXY1", "SXY2", "SXYP", "SZ0", "SZ1", "SZ2", "SZ3", "RGB0", "RGB1", "RGB2", "RES1", "MAC0",
    "MAC1", "MAC2", "MAC3", "IRGB", "ORGB", "LZCS", "LZCR", "RT11RT12", "RT13RT21", "RT22RT23",
    "RT31RT32", "RT33", "TRX", "TRY", "TRZ", "L11L12", "L13L21", "L22L23", "L31L32", "L33", "RBK",
    "GBK", "BBK", "LR1LR2", "LR3LG1", "LG2LG3", "LB1LB2", "LB3", "RFC", "GFC", "BFC", "OFX", "OFY",
    "H", "DQA", "DQB", "ZSF3", "ZSF4", "FLAG",
];

/// The register file as the hardware stores it (16-bit registers keep 16 bits), without the
/// side effects of MTC2/CTC2 (docs/hardware/gte.md §2): setting a field changes that field
/// only. Part of a [`GteState`](crate::GteState).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Registers {
    /// V0, V1, V2 (r0-r5): X, Y, Z.
    pub v: [[i16; 3]; 3],
    /// RGBC (r6): R, G, B, CODE bytes.
    pub rgbc: u32,
    /// OTZ (r7).
    pub otz: u16,
    /// IR0..IR3 (r8-r11).
    pub ir: [i16; 4],
    /// Screen XY FIFO SXY0..SXY2 (r12-r14), packed X | Y << 16.
    pub sxy: [u32; 3],
    /// Screen Z FIFO SZ0..SZ3 (r16-r19).
    pub sz: [u16; 4],
    /// Colour FIFO RGB0..RGB2 (r20-r22).
    pub rgb: [u32; 3],
    /// RES1 (r23), prohibited but read/write.
    pub res1: u32,
    /// MAC0..MAC3 (r24-r27).
    pub mac: [i32; 4],
    /// LZCS (r30).
    pub lzcs: u32,
    /// LZCR (r31); an LZCS write sets it to the count of leading sign bits.
    pub lzcr: u32,
    /// Rotation matrix RT (c0-c4), row-major.
    pub rt: [[i16; 3]; 3],
    /// Translation TR (c5-c7).
    pub tr: [i32; 3],
    /// Light matrix LLM (c8-c12), row-major.
    pub llm: [[i16; 3]; 3],
    /// Background colour BK (c13-c15).
    pub bk: [i32; 3],
    /// Light colour matrix LCM (c16-c20), row-major.
    pub lcm: [[i16; 3]; 3],
    /// Far colour FC (c21-c23).
    pub fc: [i32; 3],
    /// Screen offset OFX (c24), 16.16.
    pub ofx: i32,
    /// Screen offset OFY (c25), 16.16.
    pub ofy: i32,
    /// Projection plane distance H (c26), unsigned in the maths.
    pub h: u16,
    /// Depth-cue coefficient DQA (c27).
    pub dqa: i16,
    /// Depth-cue offset DQB (c28).
    pub dqb: i32,
    /// AVSZ3 scale ZSF3 (c29).
    pub zsf3: i16,
    /// AVSZ4 scale ZSF4 (c30).
    pub zsf4: i16,
    /// FLAG (c31).
    pub flag: Flag,
}

const fn lo(value: u32) -> i16 {
    value as u16 as i16
}

const fn hi(value: u32) -> i16 {
    (value >> 16) as u16 as i16
}

const fn pack(low: i16, high: i16) -> u32 {
    (low as u16 as u32) | ((high as u16 as u32) << 16)
}

const fn sext(value: i16) -> u32 {
    value as i32 as u32
}

/// Leading bits equal to bit 31, 1..=32 (docs/hardware/gte.md §2, LZCR).
pub(crate) const fn leading_sign_bits(value: u32) -> u32 {
    if value & 0x8000_0000 != 0 {
        value.leading_ones()
    } else {
        value.leading_zeros()
    }
}

/// Pack IR1-3 as IRGB/ORGB read them: each clamp(IRn SAR 7, 0, 1Fh), 5:5:5 (docs/hardware/gte.md §2).
pub(crate) const fn irgb(ir: [i16; 4]) -> u32 {
    const fn c(v: i16) -> u32 {
        let v = v >> 7;
        if v < 0 {
            0
        } else if v > 0x1F {
            0x1F
        } else {
            v as u32
        }
    }
    c(ir[1]) | (c(ir[2]) << 5) | (c(ir[3]) << 10)
}

#[inline]
fn read_matrix(m: &Matrix, index: u32) -> u32 {
    match index {
        0 => pack(m[0][0], m[0][1]),
        1 => pack(m[0][2], m[1][0]),
        2 => pack(m[1][1], m[1][2]),
        3 => pack(m[2][0], m[2][1]),
        _ => sext(m[2][2]),
    }
}

#[inline]
fn write_matrix(m: &mut Matrix, index: u32, value: u32) {
    match index {
        0 => (m[0][0], m[0][1]) = (lo(value), hi(value)),
        1 => (m[0][2], m[1][0]) = (lo(value), hi(value)),
        2 => (m[1][1], m[1][2]) = (lo(value), hi(value)),
        3 => (m[2][0], m[2][1]) = (lo(value), hi(value)),
        _ => m[2][2] = lo(value),
    }
}

impl Registers {
    /// MFC2: read data register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn read_data(&self, reg: u32) -> u32 {
        match reg & 31 {
            r @ (0 | 2 | 4) => pack(self.v[r as usize / 2][0], self.v[r as usize / 2][1]),
            r @ (1 | 3 | 5) => sext(self.v[r as usize / 2][2]),
            6 => self.rgbc,
            7 => self.otz as u32,
            r @ 8..=11 => sext(self.ir[(r - 8) as usize]),
            r @ 12..=14 => self.sxy[(r - 12) as usize],
            15 => self.sxy[2],
            r @ 16..=19 => self.sz[(r - 16) as usize] as u32,
            r @ 20..=22 => self.rgb[(r - 20) as usize],
            23 => self.res1,
            r @ 24..=27 => self.mac[(r - 24) as usize] as u32,
            28 | 29 => irgb(self.ir),
            30 => self.lzcs,
            _ => self.lzcr,
        }
    }

    /// MTC2: write data register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn write_data(&mut self, reg: u32, value: u32) {
        match reg & 31 {
            r @ (0 | 2 | 4) => {
                self.v[r as usize / 2][0] = lo(value);
                self.v[r as usize / 2][1] = hi(value);
            }
            r @ (1 | 3 | 5) => self.v[r as usize / 2][2] = lo(value),
            6 => self.rgbc = value,
            7 => self.otz = value as u16,
            r @ 8..=11 => self.ir[(r - 8) as usize] = lo(value),
            r @ 12..=14 => self.sxy[(r - 12) as usize] = value,
            15 => self.push_sxy(value),
            r @ 16..=19 => self.sz[(r - 16) as usize] = value as u16,
            r @ 20..=22 => self.rgb[(r - 20) as usize] = value,
            23 => self.res1 = value,
            r @ 24..=27 => self.mac[(r - 24) as usize] = value as i32,
            28 => {
                self.ir[1] = ((value & 0x1F) << 7) as i16;
                self.ir[2] = (((value >> 5) & 0x1F) << 7) as i16;
                self.ir[3] = (((value >> 10) & 0x1F) << 7) as i16;
            }
            30 => {
                self.lzcs = value;
                self.lzcr = leading_sign_bits(value);
            }
            // ORGB (r29) and LZCR (r31) ignore writes.
            _ => {}
        }
    }

    /// CFC2: read control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn read_control(&self, reg: u32) -> u32 {
        match reg & 31 {
            r @ 0..=4 => read_matrix(&self.rt, r),
            r @ 5..=7 => self.tr[(r - 5) as usize] as u32,
            r @ 8..=12 => read_matrix(&self.llm, r - 8),
            r @ 13..=15 => self.bk[(r - 13) as usize] as u32,
            r @ 16..=20 => read_matrix(&self.lcm, r - 16),
            r @ 21..=23 => self.fc[(r - 21) as usize] as u32,
            24 => self.ofx as u32,
            25 => self.ofy as u32,
            26 => sext(self.h as i16),
            27 => sext(self.dqa),
            28 => self.dqb as u32,
            29 => sext(self.zsf3),
            30 => sext(self.zsf4),
            _ => self.flag.bits(),
        }
    }

    /// CTC2: write control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn write_control(&mut self, reg: u32, value: u32) {
        match reg & 31 {
            r @ 0..=4 => write_matrix(&mut self.rt, r, value),
            r @ 5..=7 => self.tr[(r - 5) as usize] = value as i32,
            r @ 8..=12 => write_matrix(&mut self.llm, r - 8, value),
            r @ 13..=15 => self.bk[(r - 13) as usize] = value as i32,
            r @ 16..=20 => write_matrix(&mut self.lcm, r - 16, value),
            r @ 21..=23 => self.fc[(r - 21) as usize] = value as i32,
            24 => self.ofx = value as i32,
            25 => self.ofy = value as i32,
            26 => self.h = value as u16,
            27 => self.dqa = lo(value),
            28 => self.dqb = value as i32,
            29 => self.zsf3 = lo(value),
            30 => self.zsf4 = lo(value),
            _ => self.flag = Flag::from_bits(value),
        }
    }

    /// Push a value onto the screen XY FIFO (SXY0 <- SXY1 <- SXY2 <- value).
    #[inline]
    pub(crate) fn push_sxy(&mut self, value: u32) {
        self.sxy = [self.sxy[1], self.sxy[2], value];
    }

    /// Push a value onto the screen Z FIFO (SZ0 <- SZ1 <- SZ2 <- SZ3 <- value).
    pub(crate) fn push_sz(&mut self, value: u16) {
        self.sz = [self.sz[1], self.sz[2], self.sz[3], value];
    }

    /// Push a colour onto the colour FIFO (RGB0 <- RGB1 <- RGB2 <- value).
    pub(crate) fn push_rgb(&mut self, value: u32) {
        self.rgb = [self.rgb[1], self.rgb[2], value];
    }

    /// Screen X and Y of SXYn as signed halves.
    pub(crate) fn sxy_at(&self, n: usize) -> (i16, i16) {
        let v = self.sxy[n % 3];
        (lo(v), hi(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leading_sign_bits_examples() {
        assert_eq!(leading_sign_bits(0), 32);
        assert_eq!(leading_sign_bits(0xFFFF_FFFF), 32);
        assert_eq!(leading_sign_bits(1), 31);
        assert_eq!(leading_sign_bits(0x8000_0000), 1);
        assert_eq!(leading_sign_bits(0x7FFF_FFFF), 1);
        assert_eq!(leading_sign_bits(0xFFFF_0000), 16);
    }
}
