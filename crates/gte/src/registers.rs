//! The GTE register file: 32 data registers (MTC2/MFC2) and 32 control registers
//! (CTC2/CFC2), with every read/write quirk of docs/hardware/gte.md §2.
//!
//! Why this shape: an emulator writes a command's inputs with MTC2 just before the command
//! reads them, and a load narrower than the store it reads from waits about seven cycles
//! instead of two (docs/performance.md, "Store forwarding"). So each register is a 4-byte
//! word, the registers commands read right after such writes (VZ for RTPS/RTPT, IR, SZ, RGBC)
//! are loaded whole through `Words::whole` (AVSZ3 7.42 → 6.45 ns), and MTC2/MFC2 of the
//! registers with side effects are out of line, so that a plain write falls through to its
//! store ("Straight paths and tests folded into others").

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

/// The register file field by field, as the hardware stores it (16-bit registers keep 16
/// bits), without the side effects of MTC2/CTC2 (docs/hardware/gte.md §2): setting a field
/// changes that field only. Read with [`Gte::registers`](crate::Gte::registers); part of a
/// [`GteState`](crate::GteState).
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

/// How a register holds a written word and gives it back (docs/hardware/gte.md §2): all 32
/// bits, or the low 16 bits read back sign- or zero-extended.
#[derive(Clone, Copy)]
enum Width {
    Word,
    Signed16,
    Unsigned16,
}

use Width::{Signed16 as S16, Unsigned16 as U16, Word as W32};

/// Data registers r0-r31. r15 (SXYP), r28 (IRGB), r29 (ORGB), r30 (LZCS) and r31 (LZCR) have
/// side effects or computed reads and are handled apart; their entries here are unused.
const DATA_WIDTH: [Width; 32] = [
    W32, S16, W32, S16, W32, S16, // VXY0, VZ0, VXY1, VZ1, VXY2, VZ2
    W32, U16, // RGBC, OTZ
    S16, S16, S16, S16, // IR0-IR3
    W32, W32, W32, W32, // SXY0-SXY2, SXYP
    U16, U16, U16, U16, // SZ0-SZ3
    W32, W32, W32, W32, // RGB0-RGB2, RES1
    W32, W32, W32, W32, // MAC0-MAC3
    W32, W32, W32, W32, // IRGB, ORGB, LZCS, LZCR
];

/// Control registers c0-c31: the odd halves of the matrices (RT33, L33, LB3), H, DQA, ZSF3
/// and ZSF4 are 16-bit and read sign-extended (H too, although the maths uses it unsigned).
/// c31 (FLAG) is handled apart.
const CONTROL_WIDTH: [Width; 32] = [
    W32, W32, W32, W32, S16, // RT
    W32, W32, W32, // TRX, TRY, TRZ
    W32, W32, W32, W32, S16, // LLM
    W32, W32, W32, // RBK, GBK, BBK
    W32, W32, W32, W32, S16, // LCM
    W32, W32, W32, // RFC, GFC, BFC
    W32, W32, S16, S16, W32, S16, S16, // OFX, OFY, H, DQA, DQB, ZSF3, ZSF4
    W32, // FLAG
];

/// Per register, the mask and sign bit that turn a written word into the stored value:
/// `((value & mask) ^ sign) - sign` sign-extends from bit 15 when `sign` is 8000h.
const fn extension(widths: [Width; 32]) -> ([u32; 32], [u32; 32]) {
    let (mut mask, mut sign) = ([u32::MAX; 32], [0; 32]);
    let mut r = 0;
    while r < 32 {
        match widths[r] {
            Width::Word => {}
            Width::Signed16 => (mask[r], sign[r]) = (0xFFFF, 0x8000),
            Width::Unsigned16 => mask[r] = 0xFFFF,
        }
        r += 1;
    }
    (mask, sign)
}

/// The data registers of one width, as a bit set by register number.
const fn data_of_width(width: Width) -> u32 {
    let mut set = 0;
    let mut r = 0;
    while r < 32 {
        if DATA_WIDTH[r] as u8 == width as u8 {
            set |= 1 << r;
        }
        r += 1;
    }
    set
}
const CONTROL_EXTENSION: ([u32; 32], [u32; 32]) = extension(CONTROL_WIDTH);

/// Data registers whose MTC2 does more than store: SXYP, IRGB, ORGB, LZCS, LZCR.
const DATA_WRITE_SPECIAL: u32 = 1 << 15 | 1 << 28 | 1 << 29 | 1 << 30 | 1 << 31;
/// Data registers whose MFC2 is not the stored word: SXYP, IRGB, ORGB.
const DATA_READ_SPECIAL: u32 = 1 << 15 | 1 << 28 | 1 << 29;
/// Data registers whose MFC2 is the stored word as it is.
const DATA_READ_WORD: u32 = data_of_width(Width::Word) & !DATA_READ_SPECIAL;
/// Data registers read back as their low half, zero-extended (OTZ, SZ0-3).
const DATA_UNSIGNED16: u32 = data_of_width(Width::Unsigned16);
/// Control register FLAG, whose CTC2 keeps bits 12-30 and recomputes bit 31.
const FLAG: usize = 31;

#[inline(always)]
fn extend(value: u32, (mask, sign): (&[u32; 32], &[u32; 32]), r: usize) -> u32 {
    ((value & mask[r]) ^ sign[r]).wrapping_sub(sign[r])
}

/// The register file as the engine keeps it, one word per register, so that an MTC2/CTC2 is
/// one store and an MFC2/CFC2 one load, extended for a 16-bit data register, whatever the
/// register number, with no dispatch on it (docs/hardware/gte.md §2): which kind a register
/// is comes from bit masks indexed by its number. The exceptions are the registers with side
/// effects (SXYP, IRGB, ORGB, LZCS, LZCR, FLAG). Control registers hold the word CFC2 reads.
/// A 16-bit data register (VZ0-2, OTZ, IR0-3, SZ0-3) holds the word last written to it, of
/// which the hardware keeps the low half: MFC2 extends that half as the register reads, and
/// commands use only that half. Equality compares what the
/// registers hold. Commands read and write the fields through the typed accessors below.
///
/// It also keeps, for each add vector (TR, BK, FC), whether a sum starting from it can leave
/// the 44-bit range ([`RegisterFile::tr_plain`] and the others), recomputed by every CTC2 of
/// its words: a command then reads one bit instead of testing three words.
#[derive(Clone, Default)]
pub(crate) struct RegisterFile {
    /// r0-r31; r15, r28 and r29 are never stored (their reads are computed).
    data: Words,
    /// c0-c31.
    control: Words,
    /// [`EDGE_TR`], [`EDGE_BK`], [`EDGE_FC`]: the add vectors whose sums are not plain
    /// addition, as [`edge_bits`] computes them from `control`.
    edge: u8,
}

/// 32 registers of 32 bits, each kept as its four bytes, low first: a word is one load or
/// store, and each 16-bit half can be loaded on its own (the high half from its two bytes),
/// so that reading both halves of a matrix word takes two narrow loads and no shifts. The
/// data registers an emulator has usually just written with MTC2 are read as whole words
/// instead (a vertex's X and Y and SXY split after one load, IR and SZ through
/// [`Words::whole`]): a load narrower than the store it reads from is not forwarded from the
/// store on every core (AMD Zen 4 waits; docs/performance.md, "Store forwarding"), where a
/// load of the whole word is.
#[derive(Clone, Copy, Default)]
#[repr(C, align(4))]
struct Words([[u8; 4]; 32]);

impl Words {
    /// Register `r`'s word.
    #[inline(always)]
    fn word(&self, r: usize) -> u32 {
        u32::from_le_bytes(self.0[r])
    }

    /// Set register `r`'s word.
    #[inline(always)]
    fn set(&mut self, r: usize, value: u32) {
        self.0[r] = value.to_le_bytes();
    }

    /// Register `r`'s low half, signed.
    #[inline(always)]
    fn lo(&self, r: usize) -> i16 {
        self.word(r) as i16
    }

    /// Register `r`'s word as one 32-bit load that the compiler keeps whole. The compiler
    /// turns the load of a word whose low half alone is used into a 16-bit load; after the
    /// 32-bit store of an MTC2 such a load waits on some cores (AMD Zen 4), where a 32-bit
    /// load takes the stored word straight from the store (docs/performance.md, "Store
    /// forwarding"). A volatile load is neither narrowed nor merged with its neighbours.
    #[inline(always)]
    #[allow(unsafe_code)]
    fn whole(&self, r: usize) -> u32 {
        let bytes: &[u8; 4] = &self.0[r];
        // SAFETY: `bytes` comes from a shared reference, so it is valid for reads of its 4
        // initialized bytes and nothing writes them while `&self` lives; `Words` is
        // `repr(C, align(4))` around an array of `[u8; 4]`, so register `r` starts at byte
        // 4r of a 4-aligned base and is aligned for `u32`; every 4 bytes are a valid `u32`.
        let word = unsafe { core::ptr::read_volatile((bytes as *const [u8; 4]).cast::<u32>()) };
        u32::from_le(word)
    }

    /// Register `r`'s low half, unsigned.
    #[inline(always)]
    fn lo_unsigned(&self, r: usize) -> u16 {
        self.lo(r) as u16
    }

    /// Register `r`'s high half, signed.
    #[inline(always)]
    fn hi(&self, r: usize) -> i16 {
        let [_, _, a, b] = self.0[r];
        i16::from_le_bytes([a, b])
    }

    /// Copy register `from` into register `to`.
    #[inline(always)]
    fn copy(&mut self, to: usize, from: usize) {
        self.0[to] = self.0[from];
    }
}

/// TR << 12 leaves no room for three products in some row (docs/hardware/gte.md §4).
const EDGE_TR: u8 = 1;
/// BK << 12 leaves no room for three products in some row.
const EDGE_BK: u8 = 2;
/// FC << 12 leaves no room for one product in some row.
const EDGE_FC: u8 = 4;
/// Control registers whose CTC2 can change [`RegisterFile::edge`]: TR, BK, FC.
const EDGE_SOURCES: u32 = 0b111 << 5 | 0b111 << 13 | 0b111 << 21;

/// Which add vectors of `control` start sums that are not plain addition
/// ([`crate::mac::is_plain_start`]): TR and BK with three products (RTPS/RTPT, MVMVA, the
/// lighting commands' second step), FC with one (the depth cue's first step, MVMVA's cv = 2).
fn edge_bits(control: &Words) -> u8 {
    let near = |base: usize, terms: usize, bit: u8| {
        let plain = (base..base + 3)
            .all(|r| crate::mac::is_plain_start((control.word(r) as i32 as i64) << 12, terms));
        if plain { 0 } else { bit }
    };
    near(5, 3, EDGE_TR) | near(13, 3, EDGE_BK) | near(21, 1, EDGE_FC)
}

impl PartialEq for RegisterFile {
    fn eq(&self, other: &Self) -> bool {
        self.snapshot() == other.snapshot()
    }
}

impl Eq for RegisterFile {}

impl core::fmt::Debug for RegisterFile {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        self.snapshot().fmt(f)
    }
}

impl RegisterFile {
    /// MFC2: read data register `reg & 31` (docs/hardware/gte.md §2): a 32-bit register's
    /// word, a 16-bit register's low half sign- or zero-extended. The 32-bit registers, which
    /// most reads name, are tested first.
    #[inline]
    pub(crate) fn read_data(&self, reg: u32) -> u32 {
        let r = (reg & 31) as usize;
        let word = self.data.word(r);
        if DATA_READ_WORD >> r & 1 != 0 {
            word
        } else if DATA_UNSIGNED16 >> r & 1 != 0 {
            word & 0xFFFF
        } else if DATA_READ_SPECIAL >> r & 1 == 0 {
            word as i16 as i32 as u32
        } else {
            self.read_data_special(r)
        }
    }

    /// MFC2 of SXYP, IRGB or ORGB: out of line, so that the reads an emulator makes of
    /// stored registers run straight through.
    #[cold]
    #[inline(never)]
    fn read_data_special(&self, r: usize) -> u32 {
        match r {
            // SXYP reads as SXY2.
            15 => self.data.word(14),
            // IRGB and ORGB read IR1-3 packed.
            _ => irgb([0, self.ir(1), self.ir(2), self.ir(3)]),
        }
    }

    /// MTC2: write data register `reg & 31` (docs/hardware/gte.md §2). The whole word is
    /// stored; a 16-bit register's upper half is never read.
    #[inline]
    pub(crate) fn write_data(&mut self, reg: u32, value: u32) {
        let r = (reg & 31) as usize;
        if DATA_WRITE_SPECIAL >> r & 1 != 0 {
            return self.write_data_special(r, value);
        }
        self.data.set(r, value);
    }

    /// MTC2 of SXYP, IRGB, ORGB, LZCS or LZCR: out of line, so that the writes an
    /// emulator makes of every other register run straight through to their store.
    #[cold]
    #[inline(never)]
    fn write_data_special(&mut self, r: usize, value: u32) {
        match r {
            15 => self.push_sxy(value),
            // IRGB sets IR1-3 to each 5-bit field << 7.
            28 => {
                for n in 1..=3 {
                    self.data.set(8 + n, ((value >> (5 * (n - 1))) & 0x1F) << 7);
                }
            }
            30 => {
                self.data.set(30, value);
                self.data.set(31, leading_sign_bits(value));
            }
            // ORGB (r29) and LZCR (r31) ignore writes.
            _ => {}
        }
    }

    /// CFC2: read control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn read_control(&self, reg: u32) -> u32 {
        self.control.word((reg & 31) as usize)
    }

    /// CTC2: write control register `reg & 31` (docs/hardware/gte.md §2).
    #[inline]
    pub(crate) fn write_control(&mut self, reg: u32, value: u32) {
        let r = (reg & 31) as usize;
        let (mask, sign) = &CONTROL_EXTENSION;
        let stored = if r == FLAG {
            Flag::from_bits(value).bits()
        } else {
            extend(value, (mask, sign), r)
        };
        self.control.set(r, stored);
        if EDGE_SOURCES >> r & 1 != 0 {
            self.edge = edge_bits(&self.control);
        }
    }

    /// Whether every row's sum from TR << 12 with three products is plain addition.
    #[inline(always)]
    pub(crate) fn tr_plain(&self) -> bool {
        self.edge & EDGE_TR == 0
    }

    /// Whether every row's sum from BK << 12 with three products is plain addition.
    #[inline(always)]
    pub(crate) fn bk_plain(&self) -> bool {
        self.edge & EDGE_BK == 0
    }

    /// Whether every row's sum from FC << 12 with one product is plain addition.
    #[inline(always)]
    pub(crate) fn fc_plain(&self) -> bool {
        self.edge & EDGE_FC == 0
    }

    /// Vertex Vn (n = 0..2): X, Y, Z.
    #[inline(always)]
    pub(crate) fn v(&self, n: usize) -> [i16; 3] {
        let xy = self.data.word(2 * n);
        [xy as i16, (xy >> 16) as i16, self.data.lo(2 * n + 1)]
    }

    /// Vertex Vn as [`RegisterFile::v`], with VZn's word loaded whole ([`Words::whole`]), for
    /// RTPS/RTPT: the depth is the start of the projection's longest chain (SZ3, the divide,
    /// the screen position), and an emulator has usually just written it with MTC2. The
    /// other commands keep the narrow load, whose place the compiler is free to choose.
    #[inline(always)]
    pub(crate) fn v_whole(&self, n: usize) -> [i16; 3] {
        let xy = self.data.word(2 * n);
        [
            xy as i16,
            (xy >> 16) as i16,
            self.data.whole(2 * n + 1) as i16,
        ]
    }

    /// RGBC (r6).
    #[inline(always)]
    pub(crate) fn rgbc(&self) -> u32 {
        self.data.whole(6)
    }

    /// OTZ (r7).
    #[inline(always)]
    pub(crate) fn set_otz(&mut self, value: u16) {
        self.data.set(7, value as u32);
    }

    /// IRn (n = 0..3), from the whole word ([`Words::whole`]): commands read IR as an input
    /// an emulator has just written.
    #[inline(always)]
    pub(crate) fn ir(&self, n: usize) -> i16 {
        self.data.whole(8 + n) as i16
    }

    /// Set IRn (n = 0..3).
    #[inline(always)]
    pub(crate) fn set_ir(&mut self, n: usize, value: i16) {
        self.data.set(8 + n, sext(value));
    }

    /// Screen X and Y of SXYn (n = 0..2), widened to 32 bits, from one load of the word: Y
    /// is the word shifted down 16, X its low half (one instruction each).
    #[inline(always)]
    pub(crate) fn sxy(&self, n: usize) -> (i32, i32) {
        let w = self.data.word(12 + n) as i32;
        (w as i16 as i32, w >> 16)
    }

    /// Push a value onto the screen XY FIFO (SXY0 <- SXY1 <- SXY2 <- value).
    #[inline(always)]
    pub(crate) fn push_sxy(&mut self, value: u32) {
        self.data.copy(12, 13);
        self.data.copy(13, 14);
        self.data.set(14, value);
    }

    /// SZn (n = 0..3), from the whole word ([`Words::whole`]).
    #[inline(always)]
    pub(crate) fn sz(&self, n: usize) -> u16 {
        self.data.whole(16 + n) as u16
    }

    /// Push a value onto the screen Z FIFO (SZ0 <- SZ1 <- SZ2 <- SZ3 <- value).
    #[inline(always)]
    pub(crate) fn push_sz(&mut self, value: u16) {
        self.data.copy(16, 17);
        self.data.copy(17, 18);
        self.data.copy(18, 19);
        self.data.set(19, value as u32);
    }

    /// RGBn (n = 0..2).
    #[inline(always)]
    pub(crate) fn rgb(&self, n: usize) -> u32 {
        self.data.word(20 + n)
    }

    /// Push a colour onto the colour FIFO (RGB0 <- RGB1 <- RGB2 <- value).
    #[inline(always)]
    pub(crate) fn push_rgb(&mut self, value: u32) {
        self.data.copy(20, 21);
        self.data.copy(21, 22);
        self.data.set(22, value);
    }

    /// MACn (n = 0..3).
    #[inline(always)]
    pub(crate) fn mac(&self, n: usize) -> i32 {
        self.data.word(24 + n) as i32
    }

    /// Set MACn (n = 0..3).
    #[inline(always)]
    pub(crate) fn set_mac(&mut self, n: usize, value: i32) {
        self.data.set(24 + n, value as u32);
    }

    /// The matrix stored in the five control registers from `base` (RT c0, LLM c8, LCM c16),
    /// row-major: 11 | 12 << 16, 13 | 21 << 16, 22 | 23 << 16, 31 | 32 << 16, 33.
    #[inline(always)]
    fn matrix(&self, base: usize) -> Matrix {
        let lo = |k: usize| self.control.lo(base + k);
        let hi = |k: usize| self.control.hi(base + k);
        [
            [lo(0), hi(0), lo(1)],
            [hi(1), lo(2), hi(2)],
            [lo(3), hi(3), lo(4)],
        ]
    }

    /// The matrix from control register `base` as [`RegisterFile::matrix`], each entry
    /// sign-extended to 64 bits straight from its word (no 16-bit array in between).
    #[inline(always)]
    fn matrix_wide(&self, base: usize) -> [[i64; 3]; 3] {
        let lo = |k: usize| self.control.lo(base + k) as i64;
        let hi = |k: usize| self.control.hi(base + k) as i64;
        [
            [lo(0), hi(0), lo(1)],
            [hi(1), lo(2), hi(2)],
            [lo(3), hi(3), lo(4)],
        ]
    }

    /// The three 32-bit words from control register `base`.
    #[inline(always)]
    fn vector(&self, base: usize) -> [i32; 3] {
        [
            self.control.word(base) as i32,
            self.control.word(base + 1) as i32,
            self.control.word(base + 2) as i32,
        ]
    }

    /// Stored matrix `n` (0 RT, 1 LLM, 2 LCM), widened.
    #[inline(always)]
    pub(crate) fn stored_matrix_wide(&self, n: usize) -> [[i64; 3]; 3] {
        self.matrix_wide(8 * n)
    }

    /// Add vector `n` of MVMVA's cv (0 TR, 1 BK, 3 none; not 2, FC) and whether sums from it
    /// are plain addition (as [`RegisterFile::tr_plain`]).
    #[inline(always)]
    pub(crate) fn add_vector(&self, n: usize) -> ([i32; 3], bool) {
        let keep = if n == 3 { 0 } else { -1 };
        let words = self.vector(5 + 8 * (n & 1)).map(|w| w & keep);
        // EDGE_TR is bit 0 and EDGE_BK bit 1; no range bit is at 3 (none).
        (words, self.edge >> n & 1 == 0)
    }

    /// Rotation matrix RT (c0-c4).
    #[inline(always)]
    pub(crate) fn rt(&self) -> Matrix {
        self.matrix(0)
    }

    /// Rotation matrix RT (c0-c4), widened.
    #[inline(always)]
    pub(crate) fn rt_wide(&self) -> [[i64; 3]; 3] {
        self.matrix_wide(0)
    }

    /// Translation TR (c5-c7).
    #[inline(always)]
    pub(crate) fn tr(&self) -> [i32; 3] {
        self.vector(5)
    }

    /// Light matrix LLM (c8-c12), widened.
    #[inline(always)]
    pub(crate) fn llm_wide(&self) -> [[i64; 3]; 3] {
        self.matrix_wide(8)
    }

    /// Background colour BK (c13-c15).
    #[inline(always)]
    pub(crate) fn bk(&self) -> [i32; 3] {
        self.vector(13)
    }

    /// Light colour matrix LCM (c16-c20), widened.
    #[inline(always)]
    pub(crate) fn lcm_wide(&self) -> [[i64; 3]; 3] {
        self.matrix_wide(16)
    }

    /// Far colour FC (c21-c23).
    #[inline(always)]
    pub(crate) fn fc(&self) -> [i32; 3] {
        self.vector(21)
    }

    /// Screen offsets OFX, OFY (c24, c25), 16.16.
    #[inline(always)]
    pub(crate) fn offset(&self) -> (i32, i32) {
        (self.control.word(24) as i32, self.control.word(25) as i32)
    }

    /// Projection plane distance H (c26), unsigned in the maths.
    #[inline(always)]
    pub(crate) fn h(&self) -> u16 {
        self.control.lo_unsigned(26)
    }

    /// Depth-cue coefficient DQA (c27) and offset DQB (c28).
    #[inline(always)]
    pub(crate) fn depth_cue(&self) -> (i16, i32) {
        (self.control.lo(27), self.control.word(28) as i32)
    }

    /// AVSZ3 and AVSZ4 scales ZSF3, ZSF4 (c29, c30).
    #[inline(always)]
    pub(crate) fn zsf(&self) -> (i16, i16) {
        (self.control.lo(29), self.control.lo(30))
    }

    /// FLAG (c31).
    #[inline(always)]
    pub(crate) fn flag(&self) -> Flag {
        Flag::from_register(self.control.word(FLAG))
    }

    /// Set FLAG (c31).
    #[inline(always)]
    pub(crate) fn set_flag(&mut self, flag: Flag) {
        self.control.set(FLAG, flag.bits());
    }

    /// The registers as stored, field by field.
    pub(crate) fn snapshot(&self) -> Registers {
        let d = |r| self.data.word(r);
        let matrix = |base| self.matrix(base);
        Registers {
            v: [self.v(0), self.v(1), self.v(2)],
            rgbc: d(6),
            otz: d(7) as u16,
            ir: [self.ir(0), self.ir(1), self.ir(2), self.ir(3)],
            sxy: [d(12), d(13), d(14)],
            sz: [self.sz(0), self.sz(1), self.sz(2), self.sz(3)],
            rgb: [d(20), d(21), d(22)],
            res1: d(23),
            mac: [self.mac(0), self.mac(1), self.mac(2), self.mac(3)],
            lzcs: d(30),
            lzcr: d(31),
            rt: matrix(0),
            tr: self.tr(),
            llm: matrix(8),
            bk: self.bk(),
            lcm: matrix(16),
            fc: self.fc(),
            ofx: self.offset().0,
            ofy: self.offset().1,
            h: self.h(),
            dqa: self.depth_cue().0,
            dqb: self.depth_cue().1,
            zsf3: self.zsf().0,
            zsf4: self.zsf().1,
            flag: self.flag(),
        }
    }

    /// A register file holding `r` exactly, without the side effects of MTC2/CTC2; FLAG keeps
    /// what the hardware can hold (as [`Flag::from_bits`]).
    pub(crate) fn from_snapshot(r: &Registers) -> RegisterFile {
        let mut f = RegisterFile::default();
        let d = &mut f.data;
        for n in 0..3 {
            d.set(2 * n, pack(r.v[n][0], r.v[n][1]));
            d.set(2 * n + 1, sext(r.v[n][2]));
            d.set(12 + n, r.sxy[n]);
            d.set(20 + n, r.rgb[n]);
        }
        d.set(6, r.rgbc);
        d.set(7, r.otz as u32);
        for n in 0..4 {
            d.set(8 + n, sext(r.ir[n]));
            d.set(16 + n, r.sz[n] as u32);
            d.set(24 + n, r.mac[n] as u32);
        }
        d.set(23, r.res1);
        d.set(30, r.lzcs);
        d.set(31, r.lzcr);
        let c = &mut f.control;
        for (base, m) in [(0, &r.rt), (8, &r.llm), (16, &r.lcm)] {
            c.set(base, pack(m[0][0], m[0][1]));
            c.set(base + 1, pack(m[0][2], m[1][0]));
            c.set(base + 2, pack(m[1][1], m[1][2]));
            c.set(base + 3, pack(m[2][0], m[2][1]));
            c.set(base + 4, sext(m[2][2]));
        }
        for (base, v) in [(5, &r.tr), (13, &r.bk), (21, &r.fc)] {
            for (n, &value) in v.iter().enumerate() {
                c.set(base + n, value as u32);
            }
        }
        c.set(24, r.ofx as u32);
        c.set(25, r.ofy as u32);
        c.set(26, sext(r.h as i16));
        c.set(27, sext(r.dqa));
        c.set(28, r.dqb as u32);
        c.set(29, sext(r.zsf3));
        c.set(30, sext(r.zsf4));
        c.set(FLAG, Flag::from_bits(r.flag.bits()).bits());
        f.edge = edge_bits(&f.control);
        f
    }
}

#[cfg(feature = "serde")]
impl Registers {
    /// The 64 registers as words, data r0-r31 then control c0-c31, as the engine stores them:
    /// a 16-bit register's value sign- or zero-extended as MFC2/CFC2 reads it, FLAG as
    /// [`Flag::from_bits`] keeps it, and 0 for r15 (SXYP), r28 (IRGB) and r29 (ORGB), which
    /// are not stored but read from SXY2 and IR1-3 (docs/hardware/gte.md §2). The binary save
    /// state holds them as one block.
    pub(crate) fn to_words(&self) -> [u32; 64] {
        let f = RegisterFile::from_snapshot(self);
        core::array::from_fn(|i| {
            if i < 32 {
                f.data.word(i)
            } else {
                f.control.word(i - 32)
            }
        })
    }

    /// The registers of a block from [`Registers::to_words`], or `None` when a word is not as
    /// the engine stores it (bits above a 16-bit register's extension, a non-zero r15, r28 or
    /// r29, FLAG bits it cannot hold).
    pub(crate) fn from_words(words: &[u32; 64]) -> Option<Registers> {
        // FLAG is checked before the register file reads it: the file holds only values a
        // CTC2 or a command can leave there.
        let flag = words[32 + FLAG];
        if Flag::from_bits(flag).bits() != flag {
            return None;
        }
        let mut f = RegisterFile::default();
        for (i, &w) in words.iter().enumerate() {
            if i < 32 {
                f.data.set(i, w);
            } else {
                f.control.set(i - 32, w);
            }
        }
        let r = f.snapshot();
        (r.to_words() == *words).then_some(r)
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
