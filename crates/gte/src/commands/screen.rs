//! Screen-space commands: NCLIP (winding of SXY0-2) and AVSZ3/AVSZ4 (ordering-table depth)
//! (docs/hardware/gte.md §7).
//!
//! Why this shape: NCLIP and AVSZ3 cost little more than their register traffic (docs/
//! performance.md, "The floor"): NCLIP reads SXY0-2 as whole words (12 → 5.4 ns, "Store
//! forwarding") and takes the area in 32-bit arithmetic, falling back to 64 bits only when a
//! step overflows ("The plain loop: short paths"), and AVSZ3/AVSZ4 test OTZ's saturation on
//! a cold branch and MAC0 only when OTZ saturates ("Saturation tests", "Straight paths and
//! tests folded into others").

use crate::Gte;
use crate::mac::{bit, mac0_flags};

impl Gte {
    /// NCLIP: MAC0 = the signed doubled area of triangle SXY0, SXY1, SXY2 (docs/hardware/gte.md
    /// §7). Returns the FLAG bits.
    #[inline(always)]
    pub(crate) fn nclip(&mut self) -> u32 {
        let (x0, y0) = self.regs.sxy(0);
        let (x1, y1) = self.regs.sxy(1);
        let (x2, y2) = self.regs.sxy(2);
        // x0*y1 + x1*y2 + x2*y0 - x0*y2 - x1*y0 - x2*y1 as the cross product of the edges
        // from vertex 0: the same integer, in two products. The edges fit 17 bits; for
        // screen coordinates (SX2/SY2 saturate to -400h..3FFh) the products and their
        // difference fit 32 bits, where MAC0 needs no FLAG test. A step that overflows 32
        // bits sends the command to the 64-bit form, which tests MAC0 (docs/hardware/gte.md
        // §4).
        let (dx1, dy1, dx2, dy2) = (x1 - x0, y1 - y0, x2 - x0, y2 - y0);
        let area = dx1
            .checked_mul(dy2)
            .and_then(|p| dx2.checked_mul(dy1).and_then(|q| p.checked_sub(q)));
        if let Some(area) = area {
            self.regs.set_mac(0, area);
            return 0;
        }
        core::hint::cold_path();
        self.nclip_wide()
    }

    /// NCLIP in 64-bit arithmetic with MAC0's FLAG test, for the areas that leave 32 bits.
    #[cold]
    #[inline(never)]
    fn nclip_wide(&mut self) -> u32 {
        let [(x0, y0), (x1, y1), (x2, y2)] = [0, 1, 2]
            .map(|n| self.regs.sxy(n))
            .map(|(x, y)| (x as i64, y as i64));
        let area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
        let mut flags = 0;
        mac0_flags(&mut flags, area);
        self.regs.set_mac(0, area as i32);
        flags
    }

    /// AVSZ3: OTZ = ZSF3 * (SZ1 + SZ2 + SZ3) SAR 12 (docs/hardware/gte.md §7). Returns the
    /// FLAG bits.
    #[inline(always)]
    pub(crate) fn avsz3(&mut self) -> u32 {
        let sz = |n| self.regs.sz(n) as i64;
        let sum = sz(1) + sz(2) + sz(3);
        self.average_z(self.regs.zsf().0 as i64 * sum)
    }

    /// AVSZ4: OTZ = ZSF4 * (SZ0 + SZ1 + SZ2 + SZ3) SAR 12 (docs/hardware/gte.md §7). Returns
    /// the FLAG bits.
    #[inline(always)]
    pub(crate) fn avsz4(&mut self) -> u32 {
        let sz = |n| self.regs.sz(n) as i64;
        let sum = sz(0) + sz(1) + sz(2) + sz(3);
        self.average_z(self.regs.zsf().1 as i64 * sum)
    }

    /// MAC0 = `s` and OTZ = `s` SAR 12 saturated to 0..=FFFFh; returns their FLAG bits.
    #[inline(always)]
    fn average_z(&mut self, s: i64) -> u32 {
        let otz = s >> 12;
        // OTZ inside 0..=FFFFh is one unsigned compare, and it puts `s` inside 0..2^28, so
        // MAC0 needs no test of its own. Outside takes a sum of Z values past 3 or 4 times
        // FFFFh scaled by ZSF3/ZSF4 (past 1000h / 3 or / 4) or a negative scale: rare enough
        // for a branch marked cold.
        if otz as u64 <= 0xFFFF {
            self.regs.set_mac(0, s as i32);
            self.regs.set_otz(otz as u16);
            0
        } else {
            core::hint::cold_path();
            let mut flags = bit::SZ3_OTZ;
            mac0_flags(&mut flags, s);
            self.regs.set_mac(0, s as i32);
            self.regs.set_otz(if otz < 0 { 0 } else { 0xFFFF });
            flags
        }
    }
}
