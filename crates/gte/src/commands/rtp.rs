//! RTPS/RTPT: rotate, translate and perspective-project vertices (docs/hardware/gte.md §5).
//!
//! Why this shape: RTPS's time is the chain from VZ0 through SZ3 and the divide to SXY2, IR0
//! and FLAG (docs/performance.md, "Rows under 2x on Zen 4"). VZ is loaded as a whole word (a
//! narrower load of a word just written waits about five cycles longer, "Store forwarding"),
//! one copy per sf and lm makes IR's range a constant (7 fewer instructions a call, "The timed
//! loop"), and the tests that seldom fire (IR1-3 with SZ3, SX2 with SY2, the screen values'
//! MAC0 only when SX2/SY2 saturate) stay off the straight path ("Straight paths and tests
//! folded into others").

#[cfg(feature = "divide-modes")]
use crate::DivideMode;
use crate::mac::{all_within, all_within_32, bit, clamp, ir_range, row_sums};
use crate::{Gte, unr};

/// Divide selectors for the const parameter of the projection. RTPT chooses the mode once
/// per command, so the hardware path carries no per-vertex branch for the knob; RTPS, with
/// one vertex, reads it at the divide ([`BY_MODE`]), which keeps one copy of the vertex's code.
const UNR: u8 = 0;
#[cfg(feature = "divide-modes")]
const EXACT: u8 = 1;
#[cfg(feature = "divide-modes")]
const F32: u8 = 2;
#[cfg(feature = "divide-modes")]
const BY_MODE: u8 = 3;

/// The quotient of a non-hardware divide mode, out of the hardware path's way.
#[cfg(feature = "divide-modes")]
#[cold]
#[inline(never)]
fn knob_quotient(mode: DivideMode, h: u16, sz3: u16) -> u32 {
    match mode {
        DivideMode::F32 => unr::f32_quotient(h, sz3),
        _ => unr::exact_quotient(h, sz3),
    }
}

impl Gte {
    /// RTPS: project V0; depth cue from it.
    #[inline(always)]
    pub(crate) fn rtps(&mut self, shift: u32, lm: bool) {
        #[cfg(feature = "divide-modes")]
        const MODE: u8 = BY_MODE;
        #[cfg(not(feature = "divide-modes"))]
        const MODE: u8 = UNR;
        // One copy per sf and lm: the MAC shifts and IR's range are then constants.
        with_constant_sf_lm!(shift, lm, self.project_vertex::<MODE>(0, shift, lm, true));
    }

    /// RTPT: project V0, V1, V2 in order; depth cue from the last only.
    pub(crate) fn rtpt(&mut self, shift: u32, lm: bool) {
        #[cfg(feature = "divide-modes")]
        match self.divide_mode {
            DivideMode::Exact => self.rtpt_with::<EXACT>(shift, lm),
            DivideMode::F32 => self.rtpt_with::<F32>(shift, lm),
            DivideMode::Unr => with_constant_sf_lm!(shift, lm, self.rtpt_with::<UNR>(shift, lm)),
        }
        #[cfg(not(feature = "divide-modes"))]
        with_constant_sf_lm!(shift, lm, self.rtpt_with::<UNR>(shift, lm));
    }

    #[inline(always)]
    fn rtpt_with<const MODE: u8>(&mut self, shift: u32, lm: bool) {
        self.project_vertex::<MODE>(0, shift, lm, false);
        self.project_vertex::<MODE>(1, shift, lm, false);
        self.project_vertex::<MODE>(2, shift, lm, true);
    }

    /// One vertex of RTPS/RTPT (docs/hardware/gte.md §5 steps 1-7), with divide `MODE`.
    #[inline(always)]
    fn project_vertex<const MODE: u8>(
        &mut self,
        index: usize,
        shift: u32,
        lm: bool,
        depth_cue: bool,
    ) {
        let v = self.regs.v_whole(index);
        let rt = self.regs.rt();
        let tr = self.regs.tr();
        let plain = self.regs.tr_plain();
        let start = tr.map(|t| (t as i64) << 12);
        let products = rt.map(|m| {
            [
                m[0] as i64 * v[0] as i64,
                m[1] as i64 * v[1] as i64,
                m[2] as i64 * v[2] as i64,
            ]
        });
        let acc = row_sums(&mut self.flag_bits, start, &products, plain);
        let mac1 = self.set_mac(1, acc[0], shift);
        let mac2 = self.set_mac(2, acc[1], shift);
        let mac3 = self.set_mac(3, acc[2], shift);
        let z = acc[2] >> 12;
        // IR1-3 inside their range and z inside 0..=7FFFh (inside the IR3 flag's lm=0 range
        // and SZ3's range both) is one test; otherwise the steps saturate one by one. With
        // sf = 1, MAC3 is z, so z's test is MAC3's too.
        let (ir_min, ir_span) = ir_range(lm);
        let in_range = if shift == 12 {
            all_within_32([mac1, mac2], ir_min, ir_span)
        } else {
            all_within_32([mac1, mac2, mac3], ir_min, ir_span)
        };
        let (ir1, ir2, sz3) = if in_range & (z as u64 <= 0x7FFF) {
            self.regs.set_ir(1, mac1 as i16);
            self.regs.set_ir(2, mac2 as i16);
            self.regs.set_ir(3, mac3 as i16);
            (mac1 as i16, mac2 as i16, z)
        } else {
            self.saturate_projection(mac1, mac2, mac3, z, lm)
        };
        self.regs.push_sz(sz3 as u16);
        // Divide (step 5).
        let (h, sz3) = (self.regs.h(), sz3 as u16);
        let q = if unr::divide_overflows(h, sz3) {
            self.flag_bits |= bit::DIVIDE;
            unr::QUOTIENT_MAX
        } else {
            match MODE {
                #[cfg(feature = "divide-modes")]
                EXACT => unr::exact_quotient(h, sz3),
                #[cfg(feature = "divide-modes")]
                F32 => unr::f32_quotient(h, sz3),
                #[cfg(feature = "divide-modes")]
                BY_MODE => match self.divide_mode {
                    DivideMode::Unr => unr::unr_quotient(h, sz3),
                    mode => knob_quotient(mode, h, sz3),
                },
                // UNR: the hardware's divide.
                _ => unr::unr_quotient(h, sz3),
            }
        };
        let q = q as i64;
        // Screen position from the untruncated 64-bit value (step 6).
        let (ofx, ofy) = self.regs.offset();
        let x = q * ir1 as i64 + ofx as i64;
        let y = q * ir2 as i64 + ofy as i64;
        // SX2 and SY2 inside -400h..=3FFh is one test. It also clears the MAC0 flags: X
        // and Y are then inside -2^26..2^26, well within 32 bits.
        let (sx, sy) = (x >> 16, y >> 16);
        let (sx, sy) = if all_within([sx, sy], -0x400, 0x7FF) {
            (sx, sy)
        } else {
            self.saturate_screen(x, y)
        };
        self.regs
            .push_sxy((sx as i16 as u16 as u32) | ((sy as i16 as u16 as u32) << 16));
        if depth_cue {
            // Depth cue (step 7).
            let (dqa, dqb) = self.regs.depth_cue();
            let d = q * dqa as i64 + dqb as i64;
            self.set_mac0(d);
            // A select, not a branch: whether IR0 saturates depends on the depth.
            let v = d >> 12;
            let ir0 = v.clamp(0, 0x1000);
            // Outside 0..=1000h is one unsigned compare.
            self.flag_bits |= (v as u64 > 0x1000) as u32 * bit::IR0;
            self.regs.set_ir(0, ir0 as i16);
        }
    }

    /// IR1-3 and SZ3 of a projection one of whose values leaves its range (docs/hardware/gte.md
    /// §5 steps 3-4): IR1-3 saturated by lm with their flags, the IR3 flag from z against
    /// the lm=0 range, SZ3 = z saturated to 0..=FFFFh.
    #[cold]
    #[inline(never)]
    fn saturate_projection(
        &mut self,
        mac1: i32,
        mac2: i32,
        mac3: i32,
        z: i64,
        lm: bool,
    ) -> (i16, i16, i64) {
        let ir1 = self.set_ir(1, mac1, lm);
        let ir2 = self.set_ir(2, mac2, lm);
        // IR3: value from MAC3 by lm, flag from acc3 SAR 12 against the lm=0 range (step 3).
        let ir3_min = ir_range(lm).0 as i64;
        self.regs
            .set_ir(3, clamp(mac3 as i64, ir3_min, 0x7FFF).0 as i16);
        if (z + 0x8000) as u64 > 0xFFFF {
            self.flag_bits |= bit::ir(3);
        }
        // SZ3 from the 44-bit accumulator, independent of sf (step 4).
        let mut sz3 = z;
        if sz3 as u64 > 0xFFFF {
            sz3 = if sz3 < 0 { 0 } else { 0xFFFF };
            self.flag_bits |= bit::SZ3_OTZ;
        }
        (ir1, ir2, sz3)
    }

    /// SX2 and SY2 from the screen values `x` and `y` (16.16) when one of them leaves
    /// -400h..=3FFh: the MAC0 flags of each value, then each saturated with its flag
    /// (docs/hardware/gte.md §5 step 6).
    #[cold]
    #[inline(never)]
    fn saturate_screen(&mut self, x: i64, y: i64) -> (i64, i64) {
        self.flag_mac0(x);
        self.flag_mac0(y);
        let (sx, sx_sat) = clamp(x >> 16, -0x400, 0x3FF);
        let (sy, sy_sat) = clamp(y >> 16, -0x400, 0x3FF);
        if sx_sat {
            self.flag_bits |= bit::SX2;
        }
        if sy_sat {
            self.flag_bits |= bit::SY2;
        }
        (sx, sy)
    }
}
