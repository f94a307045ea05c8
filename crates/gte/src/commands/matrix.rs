//! Matrix-vector commands: MVMVA (with the FC and mx=3 hardware bugs), SQR and OP
//! (docs/hardware/gte.md §8).
//!
//! Why this shape: MVMVA reads its operands at offsets from its selector fields rather than
//! dispatching on each (327 → 319 instructions a call, docs/performance.md, "Where the
//! per-call time went"), decides that they are all stored registers with one bit test (128
//! → 116 in the plain loop, "The plain loop: short paths"), and its step's three rows are written out (`row_sums`): left as a
//! `core::array::from_fn` call, its nine products went through the stack (17.62 → 12.54 ns,
//! "The timed loop"). SQR uses that its squares are never negative: one compare per row
//! ("The plain loop").

use crate::Gte;
use crate::command::{Command, MatrixSel, TranslationSel, VectorSel};
use crate::mac::{bit, mac_ir_each_row, matrix_products, row_sums};

impl Gte {
    /// IR1-3 widened.
    #[inline(always)]
    pub(crate) fn ir_vector(&self) -> [i64; 3] {
        [1, 2, 3].map(|n| self.regs.ir(n) as i64)
    }

    /// MVMVA: MAC/IR = cv + mx * v with the selected operands (docs/hardware/gte.md §8).
    /// Returns the FLAG bits.
    #[inline(always)]
    pub(crate) fn mvmva(&mut self, c: Command, shift: u32, lm: bool) -> u32 {
        with_constant_sf_lm!(shift, lm, self.mvmva_with(c, shift, lm))
    }

    #[inline(always)]
    fn mvmva_with(&mut self, c: Command, shift: u32, lm: bool) -> u32 {
        // A stored matrix, V0-2 and TR, BK or none: operands read at offsets from the
        // selector fields, without a dispatch on each.
        if c.mvmva_stored_operands() {
            let (mx, v, cv) = c.mvmva_fields();
            let m = self.regs.stored_matrix_wide(mx);
            let v = self.regs.v(v).map(i64::from);
            let (t, plain) = self.regs.add_vector(cv);
            return self.multiply_add(&m, v, t, plain, shift, lm);
        }
        let m = match c.mx() {
            MatrixSel::Rotation => self.regs.rt_wide(),
            MatrixSel::Light => self.regs.llm_wide(),
            MatrixSel::LightColor => self.regs.lcm_wide(),
            MatrixSel::Garbage => {
                // Rows [-(R<<4), R<<4, IR0], [RT13]x3, [RT22]x3 (docs/hardware/gte.md §8).
                let r = ((self.regs.rgbc() & 0xFF) as i64) << 4;
                let rt = self.regs.rt_wide();
                let (rt13, rt22) = (rt[0][2], rt[1][1]);
                [[-r, r, self.regs.ir(0) as i64], [rt13; 3], [rt22; 3]]
            }
        };
        let v = match c.v() {
            VectorSel::V0 => self.regs.v(0).map(i64::from),
            VectorSel::V1 => self.regs.v(1).map(i64::from),
            VectorSel::V2 => self.regs.v(2).map(i64::from),
            VectorSel::Ir => self.ir_vector(),
        };
        let (t, plain) = match c.cv() {
            TranslationSel::Translation => (self.regs.tr(), self.regs.tr_plain()),
            TranslationSel::Background => (self.regs.bk(), self.regs.bk_plain()),
            TranslationSel::FarColor => {
                self.flag_bits = 0;
                self.mvmva_far_color_bug(&m, v, shift, lm);
                return self.flag_bits;
            }
            TranslationSel::None => ([0; 3], true),
        };
        self.multiply_add(&m, v, t, plain, shift, lm)
    }

    /// MAC1-3 and IR1-3 = (t << 12 + m * v) SAR sf, IR by lm (docs/hardware/gte.md §4);
    /// `plain` as for [`crate::mac::accumulate`]. Returns the FLAG bits.
    #[inline(always)]
    fn multiply_add(
        &mut self,
        m: &[[i64; 3]; 3],
        v: [i64; 3],
        t: [i32; 3],
        plain: bool,
        shift: u32,
        lm: bool,
    ) -> u32 {
        let start = t.map(|t| (t as i64) << 12);
        let mut flags = 0;
        // The three sums first, then their MAC/IR: fewer values live at once. Each IR is
        // tested on its own, its saturation off the straight path (`ir_test::EACH_RARE`).
        let sums = row_sums(&mut flags, start, &matrix_products(m, v), plain);
        let last = mac_ir_each_row::<true>(&mut flags, sums, shift, lm);
        self.store_step(last);
        flags
    }

    /// cv=2: per row, FC<<12 + M_n1*V1 is formed and flagged (44-bit and an IR check with the
    /// lm=0 range) and discarded; the result is (M_n2*V2 + M_n3*V3) SAR sf (docs/hardware/gte.md §8).
    fn mvmva_far_color_bug(&mut self, m: &[[i64; 3]; 3], v: [i64; 3], shift: u32, lm: bool) {
        let fc = self.regs.fc();
        for row in 0..3 {
            let r = m[row];
            let discarded = self.accumulate(row + 1, (fc[row] as i64) << 12, &[r[0] * v[0]]);
            self.saturate_ir(row + 1, (discarded >> shift) as i32, false);
            let sum = self.accumulate(row + 1, 0, &[r[1] * v[1], r[2] * v[2]]);
            self.set_mac_ir(row + 1, sum, shift, lm);
        }
    }

    /// SQR: MACn = IRn^2 SAR sf, IRn = MACn saturated (docs/hardware/gte.md §8). Returns the
    /// FLAG bits.
    ///
    /// A square is at most 2^30 and never negative, so each sum is plain addition and MACn
    /// lies in 0..=2^30: IRn saturates only at 7FFFh, whatever lm, and one compare per row
    /// decides it. The saturation is kept off the straight path: with sf = 1 it takes |IRn|
    /// past 2D41h, and a predicted branch lets IRn's store wait on the square alone where a
    /// select adds to the chain a loop of SQR runs through IR (docs/performance.md, "The
    /// plain loop").
    #[inline(always)]
    pub(crate) fn sqr(&mut self, shift: u32) -> u32 {
        // One copy per sf, so that the shift is by a constant.
        if shift == 0 {
            self.squares::<0>()
        } else {
            self.squares::<12>()
        }
    }

    /// [`Gte::sqr`] with sf's shift `SHIFT`.
    #[inline(always)]
    fn squares<const SHIFT: u32>(&mut self) -> u32 {
        let ir = self.ir_vector();
        let mut flags = 0;
        for (n, v) in ir.into_iter().enumerate() {
            let mac = ((v * v) as u64 >> SHIFT) as u32;
            self.regs.set_mac(n + 1, mac as i32);
            let ir = if mac > 0x7FFF {
                core::hint::cold_path();
                flags |= bit::ir(n + 1);
                0x7FFF
            } else {
                mac as i16
            };
            self.regs.set_ir(n + 1, ir);
        }
        flags
    }

    /// OP: outer product of (RT11, RT22, RT33) and IR1-3 (docs/hardware/gte.md §8).
    #[inline]
    pub(crate) fn op(&mut self, shift: u32, lm: bool) {
        let rt = self.regs.rt();
        let d = [rt[0][0] as i64, rt[1][1] as i64, rt[2][2] as i64];
        let ir = self.ir_vector();
        let terms = [
            (ir[2] * d[1], ir[1] * d[2]),
            (ir[0] * d[2], ir[2] * d[0]),
            (ir[1] * d[0], ir[0] * d[1]),
        ];
        for (n, (a, b)) in terms.into_iter().enumerate() {
            let sum = self.accumulate(n + 1, 0, &[a, -b]);
            self.set_mac_ir(n + 1, sum, shift, lm);
        }
    }
}
