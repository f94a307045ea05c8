//! Property tests of the register-level engine. Expected values come from the reference
//! model (`gte::reference`, written from docs/hardware/gte.md apart from the engine and held
//! to the console vectors by tests/reference.rs), from the hardware reference's rules
//! written out here, or from hand calculation; never from the engine's own output. The
//! generators aim at the edges: translations near the 44-bit limits, operands scaled to
//! every magnitude, so that each saturation is hit on both sides.

use gte::reference::{self, Trace};
use gte::unr::{exact_divide, unr_divide};
use gte::{Command, MatrixSel, Opcode, TranslationSel, VectorSel};
use gte::{DivideMode, Flag, Gte};
use proptest::prelude::*;

fn any_command() -> impl Strategy<Value = u32> {
    prop_oneof![
        any::<u32>(),
        (prop::sample::select(Opcode::ALL.to_vec()), any::<u32>())
            .prop_map(|(op, bits)| (bits & !0x3F) | op.bits()),
    ]
}

/// A translation component: uniform, or within 2^18 of either end of i32, where
/// TR << 12 plus one 16x16 product can cross +-2^43.
fn translation() -> impl Strategy<Value = i32> {
    prop_oneof![
        any::<i32>(),
        (i32::MAX - 0x4_0000)..=i32::MAX,
        i32::MIN..=(i32::MIN + 0x4_0000),
    ]
}

/// A GTE with the identity rotation, V0 = `v` and the control registers `control` (number,
/// value) written: RTPS (sf = 1) then gives IR1-3 = V + TR and the depth VZ + TRZ.
fn identity(control: &[(u32, u32)], v: [i16; 3]) -> Gte {
    let mut gte = Gte::new();
    for (i, w) in [0x1000u32, 0, 0x1000, 0, 0x1000].into_iter().enumerate() {
        gte.write_control(i as u32, w);
    }
    for &(r, w) in control {
        gte.write_control(r, w);
    }
    gte.write_data(0, packed(v[0], v[1]));
    gte.write_data(1, v[2] as u16 as u32);
    gte
}

/// [`identity`] after RTPS (sf = 1, lm = 0).
fn identity_rtps(control: &[(u32, u32)], v: [i16; 3]) -> Gte {
    let mut gte = identity(control, v);
    gte.execute(cmd(Opcode::Rtps, true, false));
    gte
}

/// Run `word` on `gte` and on the reference model given `gte`'s registers: the two leave
/// the same registers, FLAG included, and FLAG's bit 31 is the OR of its sources. Returns the
/// model's trace.
fn agree(gte: &mut Gte, word: u32) -> Result<Trace, TestCaseError> {
    let mut model = gte.registers();
    let trace = reference::execute(&mut model, word);
    gte.execute(word);
    prop_assert_eq!(gte.registers(), model, "command {:08X}", word);
    prop_assert_eq!(gte.flag(), trace.flag());
    prop_assert!(summary_follows_sources(gte.flag()), "{}", gte.flag());
    Ok(trace)
}

/// FLAG bit 31 is the OR of bits 30-23 and 18-13 (docs/hardware/gte.md §3).
fn summary_follows_sources(flag: Flag) -> bool {
    (flag.bits() >> 31 == 1) == (flag.bits() & 0x7F87_E000 != 0)
}

fn packed(lo: i16, hi: i16) -> u32 {
    (lo as u16 as u32) | ((hi as u16 as u32) << 16)
}

fn cmd(op: Opcode, sf: bool, lm: bool) -> u32 {
    Command::build(
        op,
        sf,
        lm,
        MatrixSel::Rotation,
        VectorSel::V0,
        TranslationSel::None,
    )
    .word()
}

/// RTPS with sf = 0 where MAC1 and MAC2 lie inside IR's range, MAC3 beyond 7FFFh and
/// acc_3 SAR 12 inside both IR3's flag range and SZ3's (docs/hardware/gte.md §5.1-5.4):
/// RT = 1.0 on the diagonal, V0 = (0, 0, 100h), TR = 0, so acc_3 = 1000h × 100h = 100000h.
/// MAC3 = 100000h (sf = 0) and IR3 = 7FFFh, yet FLAG bit 22 stays clear, because its test
/// is on acc_3 SAR 12 = 100h (§5.3); SZ3 = 100h. H = 0 gives q = 0, so SXY2 = 0, and DQB = 0
/// gives IR0 = 0: FLAG is 0.
#[test]
fn rtps_sf0_ir3_saturates_while_depth_in_range() {
    for lm in [false, true] {
        let mut gte = Gte::new();
        gte.write_control(0, packed(0x1000, 0));
        gte.write_control(2, packed(0x1000, 0));
        gte.write_control(4, 0x1000);
        gte.write_data(0, 0);
        gte.write_data(1, 0x100);
        gte.execute(cmd(Opcode::Rtps, false, lm));
        assert_eq!(gte.read_data(25), 0, "MAC1");
        assert_eq!(gte.read_data(26), 0, "MAC2");
        assert_eq!(gte.read_data(27), 0x10_0000, "MAC3");
        assert_eq!(gte.read_data(9), 0, "IR1");
        assert_eq!(gte.read_data(10), 0, "IR2");
        assert_eq!(gte.read_data(11), 0x7FFF, "IR3");
        assert_eq!(gte.read_data(19), 0x100, "SZ3");
        assert_eq!(gte.read_data(14), 0, "SXY2");
        assert_eq!(gte.read_data(8), 0, "IR0");
        assert_eq!(gte.read_control(31), 0, "FLAG");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// The engine keeps, per add vector (TR, BK, FC), whether sums from it can leave the
    /// 44-bit range; any sequence of CTC2 writes (values drawn near the edges too) leaves it
    /// as an engine loaded from scratch with the same registers computes it: every command
    /// that starts a sum from TR, BK or FC gives both engines the same 64 registers.
    #[test]
    fn add_vector_range_follows_every_write(
        steps in prop::collection::vec(
            (prop::sample::select(vec![5u32, 6, 7, 13, 14, 15, 21, 22, 23]), translation(), any::<u32>()),
            1..24,
        ),
        regs in prop::collection::vec(any::<u32>(), 64),
    ) {
        let mut a = Gte::new();
        for (i, v) in regs.iter().enumerate() {
            if !matches!(i, 15 | 28 | 30) {
                a.write(i as u32, *v);
            }
        }
        let commands = [
            Opcode::Rtps, Opcode::Rtpt, Opcode::Mvmva, Opcode::Dpcs, Opcode::Dpct, Opcode::Intpl,
            Opcode::Dcpl, Opcode::Ncds, Opcode::Ncdt, Opcode::Nccs, Opcode::Ncs, Opcode::Cc,
            Opcode::Cdp,
        ];
        for (reg, value, pick) in steps {
            a.write_control(reg, value as u32);
            let op = commands[pick as usize % commands.len()];
            let cv = [TranslationSel::Translation, TranslationSel::Background,
                TranslationSel::FarColor, TranslationSel::None][(pick >> 8) as usize % 4];
            let word = Command::build(op, pick & 1 << 16 != 0, pick & 1 << 17 != 0,
                MatrixSel::Rotation, VectorSel::V0, cv).word();
            let mut b = Gte::new();
            prop_assert!(b.load_state(&a.state()).is_ok());
            a.execute(word);
            b.execute(word);
            for r in 0..64 {
                prop_assert_eq!(a.read(r), b.read(r), "register {} after {:?}", r, op);
            }
        }
    }

    /// RTPT on three equal vertices leaves the registers RTPS run three times on that vertex
    /// leaves (each vertex is steps 1-6 of docs/hardware/gte.md §5 and the last also step 7;
    /// RTPT's FLAG is the OR of three equal vertices' bits), in every divide mode of the build.
    #[test]
    fn rtpt_of_equal_vertices_is_rtps_three_times(
        regs in prop::collection::vec(any::<u32>(), 64),
        sf in any::<bool>(),
        lm in any::<bool>(),
    ) {
        let modes = [DivideMode::Unr, DivideMode::Exact, DivideMode::F32];
        for mode in modes.into_iter().filter(|m| m.is_supported()) {
            let mut a = Gte::new();
            prop_assert_eq!(a.set_divide_mode(mode), Ok(()));
            for (i, v) in regs.iter().enumerate() {
                // Skip the writes with side effects on other registers (SXYP, IRGB, LZCS).
                if !matches!(i, 15 | 28 | 30) {
                    a.write(i as u32, *v);
                }
            }
            a.write(2, regs[0]);
            a.write(3, regs[1]);
            a.write(4, regs[0]);
            a.write(5, regs[1]);
            let mut b = a.clone();
            for _ in 0..3 {
                a.execute(cmd(Opcode::Rtps, sf, lm));
            }
            b.execute(cmd(Opcode::Rtpt, sf, lm));
            for r in 0..64 {
                prop_assert_eq!(a.read(r), b.read(r), "register {} in {:?}", r, mode);
            }
        }
    }

    /// The 16-bit data registers (VZ0-2, OTZ, IR0-3, SZ0-3) keep the low half of an MTC2
    /// (docs/hardware/gte.md §2): writing them with any upper half, or with the low half
    /// already extended as MFC2 reads it, gives the same engine, and after any command the
    /// same 64 registers.
    #[test]
    fn upper_half_of_16_bit_registers_is_never_read(
        regs in prop::collection::vec(any::<u32>(), 64),
        word in any_command(),
    ) {
        const SIGNED: [usize; 7] = [1, 3, 5, 8, 9, 10, 11];
        const UNSIGNED: [usize; 5] = [7, 16, 17, 18, 19];
        let mut raw = Gte::new();
        let mut extended = Gte::new();
        // The 16-bit registers last, so that no IRGB write replaces IR1-3 after them.
        let narrow = |i: &usize| SIGNED.contains(i) || UNSIGNED.contains(i);
        let order = (0..64).filter(|i| !narrow(i)).chain((0..64).filter(narrow));
        for i in order {
            let v = regs[i];
            let e = if SIGNED.contains(&i) {
                v as u16 as i16 as i32 as u32
            } else if UNSIGNED.contains(&i) {
                v & 0xFFFF
            } else {
                v
            };
            raw.write(i as u32, v);
            extended.write(i as u32, e);
        }
        prop_assert_eq!(&raw, &extended);
        prop_assert_eq!(raw.state(), extended.state());
        let cycles = raw.execute(word);
        prop_assert_eq!(cycles, extended.execute(word));
        for i in 0..64 {
            prop_assert_eq!(raw.read(i), extended.read(i), "register {}", i);
        }
        prop_assert_eq!(raw.state(), extended.state());
    }

    /// Any register state and any 32-bit command word: no panic (overflow checks are on in
    /// tests), every register readable, FLAG bits 0-11 zero and bit 31 the OR of its sources.
    #[test]
    fn no_panic_any_state_any_command(regs in prop::collection::vec(any::<u32>(), 64), word in any_command()) {
        let mut gte = Gte::new();
        for (i, v) in regs.iter().enumerate() {
            gte.write((i) as u32, *v);
        }
        gte.execute(word);
        for i in 0..64 {
            let _ = gte.read(i);
        }
        let flag = gte.read(63);
        prop_assert_eq!(flag & 0xFFF, 0);
        prop_assert_eq!(flag >> 31 == 1, flag & 0x7F87_E000 != 0);
    }

    /// UNR against exact rounded division: never more than 3 units apart (docs/gte.md states
    /// the bound and the exhaustive sweep that establishes it).
    #[test]
    fn unr_within_bound_of_exact(sz3 in 1u16.., h_frac in 0.0f64..1.0) {
        let h = ((2 * sz3 as u32 - 1) as f64 * h_frac) as u32;
        let h = h.min(0xFFFF) as u16;
        prop_assume!((h as u32) < 2 * sz3 as u32);
        let (q, overflow) = unr_divide(h, sz3);
        prop_assert!(!overflow);
        let exact = ((h as u128) << 16) as f64 / sz3 as f64;
        let exact = (exact + 0.5).floor().min(0x1FFFF as f64) as i64;
        prop_assert!((q as i64 - exact).abs() <= 3, "H={} SZ3={} unr={} exact={}", h, sz3, q, exact);
        prop_assert_eq!(exact_divide(h, sz3).0 as i64, exact);
    }

    /// Overflow rule: H >= 2*SZ3 gives 1FFFFh with FLAG.17, otherwise no flag.
    #[test]
    fn unr_overflow_rule(h in any::<u16>(), sz3 in any::<u16>()) {
        let (q, overflow) = unr_divide(h, sz3);
        prop_assert_eq!(overflow, h as u32 >= 2 * sz3 as u32);
        if overflow {
            prop_assert_eq!(q, 0x1FFFF);
        }
        prop_assert!(q <= 0x1FFFF);
    }

    /// MAC1-3 44-bit flags and wrap: MVMVA (RT, V0, TR) with only the first matrix column
    /// non-zero and translations near the ends of i32, so each row's running sum after its
    /// first product, TRn << 12 + RTn1 × VX, lands on either side of ±2^43.
    #[test]
    fn mac_overflow_flags(tr in prop::array::uniform3(translation()), col in prop::array::uniform3(any::<i16>()), vx in any::<i16>(), sf in any::<bool>()) {
        let mut gte = Gte::new();
        // RT11 (c0 low), RT21 (c1 high), RT31 (c3 low).
        gte.write_control(0, col[0] as u16 as u32);
        gte.write_control(1, (col[1] as u16 as u32) << 16);
        gte.write_control(3, col[2] as u16 as u32);
        for (n, t) in tr.iter().enumerate() {
            gte.write_control((5 + n) as u32, *t as u32);
        }
        gte.write_data(0, packed(vx, 0));
        let word = Command::build(Opcode::Mvmva, sf, false, MatrixSel::Rotation, VectorSel::V0, TranslationSel::Translation).word();
        let Trace::Mvmva(t) = agree(&mut gte, word)? else { unreachable!() };
        for (n, row) in t.step.rows.iter().enumerate() {
            prop_assert_eq!(row.exact, ((tr[n] as i64) << 12) + col[n] as i64 * vx as i64);
        }
    }

    /// IR1-3 saturation with both lm settings: MVMVA (RT, V0, no add) with sf=0, where the
    /// products are small enough that MACn is the exact dot product.
    #[test]
    fn ir_saturation_flags(m in prop::array::uniform9(-2000i16..2000), v in prop::array::uniform3(any::<i16>()), lm in any::<bool>()) {
        let mut gte = Gte::new();
        let words = [packed(m[0], m[1]), packed(m[2], m[3]), packed(m[4], m[5]), packed(m[6], m[7]), m[8] as u32];
        for (i, w) in words.into_iter().enumerate() {
            gte.write_control((i) as u32, w);
        }
        gte.write_data(0, packed(v[0], v[1]));
        gte.write_data(1, v[2] as u16 as u32);
        let word = Command::build(Opcode::Mvmva, false, lm, MatrixSel::Rotation, VectorSel::V0, TranslationSel::None).word();
        let Trace::Mvmva(t) = agree(&mut gte, word)? else { unreachable!() };
        prop_assert_eq!(t.step.mac().map(i64::from), t.step.exact());
    }

    /// RTPS's saturations (docs/hardware/gte.md §5 steps 3-6) at every magnitude: rotation,
    /// vertex and translation scaled down by random shifts, so that IR1-3, SZ3, SX2 and SY2
    /// fall inside their ranges, on their edges and outside, alone or together. H = 0 makes
    /// the quotient 0 (or 1FFFFh with the divide overflow when SZ3 = 0, §6), so SX2 and SY2
    /// come from OFX and OFY. TR stays within 2^30, where no sum leaves 44 bits.
    #[test]
    fn rtps_saturation_at_every_magnitude(
        m in prop::array::uniform9(any::<i16>()),
        v in prop::array::uniform3(any::<i16>()),
        tr in prop::array::uniform3(-(1i32 << 30)..(1 << 30)),
        shifts in prop::array::uniform3(0u32..16),
        tr_shift in 0u32..31,
        ofs in prop::array::uniform2(any::<i32>()),
        ofs_shift in 0u32..16,
        sf in any::<bool>(),
        lm in any::<bool>(),
    ) {
        let m = m.map(|e| e >> shifts[0]);
        let v = v.map(|e| e >> shifts[1]);
        let tr = tr.map(|t| t >> tr_shift);
        let ofs = ofs.map(|o| o >> ofs_shift);
        let mut gte = Gte::new();
        let words = [packed(m[0], m[1]), packed(m[2], m[3]), packed(m[4], m[5]), packed(m[6], m[7]), m[8] as u32];
        for (i, w) in words.into_iter().enumerate() {
            gte.write_control(i as u32, w);
        }
        for (i, t) in tr.into_iter().enumerate() {
            gte.write_control(5 + i as u32, t as u32);
        }
        gte.write_control(24, ofs[0] as u32);
        gte.write_control(25, ofs[1] as u32);
        gte.write_data(0, packed(v[0], v[1]));
        gte.write_data(1, v[2] as u16 as u32);
        let Trace::Rtps(t) = agree(&mut gte, cmd(Opcode::Rtps, sf, lm))? else { unreachable!() };
        // H = 0: the quotient is 0, or 1FFFFh when SZ3 = 0.
        prop_assert_eq!(t.vertex.quotient, if t.vertex.sz3 == 0 { 0x1FFFF } else { 0 });
    }

    /// NCS's two steps (docs/hardware/gte.md §8: IR = LLM * V, then IR = BK + LCM * IR, the
    /// colour from the last MACs) at every magnitude: both matrices, the normal and BK scaled
    /// down by random shifts, so that each step's IR1-3 fall inside their range, on its
    /// edges and outside, alone or together.
    #[test]
    fn ncs_saturation_at_every_magnitude(
        llm in prop::array::uniform9(any::<i16>()),
        lcm in prop::array::uniform9(any::<i16>()),
        v in prop::array::uniform3(any::<i16>()),
        bk in prop::array::uniform3(-(1i32 << 30)..(1 << 30)),
        shifts in prop::array::uniform4(0u32..16),
        bk_shift in 0u32..31,
        sf in any::<bool>(),
        lm in any::<bool>(),
    ) {
        let llm = llm.map(|e| e >> shifts[0]);
        let lcm = lcm.map(|e| e >> shifts[1]);
        let v = v.map(|e| e >> shifts[2]);
        let bk = bk.map(|b| b >> bk_shift);
        let mut gte = Gte::new();
        for (base, m) in [(8u32, llm), (16, lcm)] {
            let words = [packed(m[0], m[1]), packed(m[2], m[3]), packed(m[4], m[5]), packed(m[6], m[7]), m[8] as u32];
            for (i, w) in words.into_iter().enumerate() {
                gte.write_control(base + i as u32, w);
            }
        }
        for (i, b) in bk.into_iter().enumerate() {
            gte.write_control(13 + i as u32, b as u32);
        }
        gte.write_data(0, packed(v[0], v[1]));
        gte.write_data(1, v[2] as u16 as u32);
        gte.write_data(6, 0x2A00_0000);
        let Trace::Lit(t) = agree(&mut gte, cmd(Opcode::Ncs, sf, lm))? else { unreachable!() };
        prop_assert_eq!(t.push.code, 0x2A);
    }

    /// MAC0 flags and value: NCLIP of arbitrary screen XY values.
    #[test]
    fn nclip_mac0_flags(p in prop::array::uniform6(any::<i16>())) {
        let mut gte = Gte::new();
        for i in 0..3 {
            gte.write_data((12 + i) as u32, packed(p[2 * i], p[2 * i + 1]));
        }
        agree(&mut gte, Opcode::Nclip.bits())?;
    }

    /// SZ3/OTZ saturation: AVSZ3 and AVSZ4 with arbitrary ZSF and SZ values.
    #[test]
    fn otz_saturation(zsf in any::<i16>(), sz in prop::array::uniform4(any::<u16>()), four in any::<bool>()) {
        let mut gte = Gte::new();
        for (i, z) in sz.iter().enumerate() {
            gte.write_data((16 + i) as u32, *z as u32);
        }
        gte.write_control(if four { 30 } else { 29 }, zsf as u16 as u32);
        agree(&mut gte, if four { Opcode::Avsz4 } else { Opcode::Avsz3 }.bits())?;
    }

    /// Colour FIFO saturation: GPF, Cn = (IRn * IR0 >> shift) >> 4 clamped to 0..FFh.
    #[test]
    fn color_saturation(ir in prop::array::uniform3(any::<i16>()), ir0 in any::<i16>(), sf in any::<bool>()) {
        let mut gte = Gte::new();
        gte.write_data(8, ir0 as u16 as u32);
        for (i, v) in ir.iter().enumerate() {
            gte.write_data((9 + i) as u32, *v as u16 as u32);
        }
        agree(&mut gte, cmd(Opcode::Gpf, sf, false))?;
    }

    /// SX2/SY2 and IR0 saturation in RTPS: identity rotation, so IR = V and the depth VZ +
    /// TRZ; any H, offsets, DQA and DQB.
    #[test]
    fn screen_and_ir0_saturation(
        v in prop::array::uniform3(-4000i16..4000), trz in -5000i32..100_000, h in any::<u16>(),
        ofx in any::<i32>(), ofy in any::<i32>(), dqa in any::<i16>(), dqb in any::<i32>()
    ) {
        let mut gte = identity(&[(7, trz as u32), (24, ofx as u32), (25, ofy as u32), (26, h as u32), (27, dqa as u16 as u32), (28, dqb as u32)], v);
        let Trace::Rtps(t) = agree(&mut gte, cmd(Opcode::Rtps, true, false))? else { unreachable!() };
        prop_assert_eq!(t.vertex.depth, v[2] as i64 + trz as i64);
    }

    /// IR0 saturation is not an error source: an RTPS whose screen position, depth and
    /// depth-cue sum all stay in range leaves FLAG at the IR0 bit alone, without bit 31
    /// (docs/hardware/gte.md §3).
    #[test]
    fn ir0_saturation_alone_leaves_bit_31_clear(
        v in prop::array::uniform3(-500i16..500), trz in 1000i32..5000, h in 0u16..1000,
        dqa in -8000i16..8000, dqb in -(1i32 << 29)..(1 << 29)
    ) {
        let mut gte = identity(&[(7, trz as u32), (26, h as u32), (27, dqa as u16 as u32), (28, dqb as u32)], v);
        let Trace::Rtps(t) = agree(&mut gte, cmd(Opcode::Rtps, true, false))? else { unreachable!() };
        // SZ3 = VZ + TRZ is at least 500 and H below 1000, so the quotient is below 2.0.
        let saturated = !(0..=0x1000).contains(&(t.depth_cue.exact >> 12));
        // CFC2 FLAG.
        prop_assert_eq!(gte.read_control(31), if saturated { Flag::IR0_SATURATED.bits() } else { 0 });
    }
    /// Register read/write rules (docs/hardware/gte.md §2).
    #[test]
    fn register_quirks(value in any::<u32>()) {
        let mut gte = Gte::new();
        let sext = value as u16 as i16 as i32 as u32;
        let zext = value & 0xFFFF;
        // 32-bit registers keep every bit.
        for r in [0, 2, 4, 6, 12, 13, 14, 20, 21, 22, 23, 24, 25, 26, 27, 30] {
            gte.write_data(r, value);
            prop_assert_eq!(gte.read_data(r), value, "r{}", r);
        }
        for r in (0..=28).filter(|r| ![4, 12, 20, 26, 27].contains(r)) {
            gte.write_control(r, value);
            prop_assert_eq!(gte.read_control(r), value, "c{}", r);
        }
        for r in [1, 3, 5, 8, 9, 10, 11] {
            gte.write_data(r, value);
            prop_assert_eq!(gte.read_data(r), sext, "r{}", r);
        }
        for r in [7, 16, 17, 18, 19] {
            gte.write_data(r, value);
            prop_assert_eq!(gte.read_data(r), zext, "r{}", r);
        }
        for r in [4, 12, 20, 26, 27, 29, 30] {
            gte.write_control(r, value);
            prop_assert_eq!(gte.read_control(r), sext, "c{}", r);
        }
        // FLAG: keep 7FFFF000h, bit 31 = any of 7F87E000h.
        gte.write_control(31, value);
        let kept = value & 0x7FFF_F000;
        prop_assert_eq!(gte.read_control(31), kept | if kept & 0x7F87_E000 != 0 { 1 << 31 } else { 0 });
        // LZCS/LZCR: count leading bits equal to bit 31 one by one.
        gte.write_data(30, value);
        let top = value >> 31;
        let count = (0..32).rev().take_while(|b| (value >> b) & 1 == top).count() as u32;
        prop_assert_eq!(gte.read_data(31), count);
        gte.write_data(31, 0);
        prop_assert_eq!(gte.read_data(31), count);
        // IRGB write expands into IR1-3; IRGB/ORGB read back live from IR1-3.
        gte.write_data(28, value);
        for n in 0..3 {
            prop_assert_eq!(gte.read_data(9 + n), ((value >> (5 * n)) & 0x1F) << 7);
        }
        prop_assert_eq!(gte.read_data(28), value & 0x7FFF);
        prop_assert_eq!(gte.read_data(29), value & 0x7FFF);
        gte.write_data(29, !value);
        prop_assert_eq!(gte.read_data(29), value & 0x7FFF);
    }

    /// IRGB/ORGB read of arbitrary IR values: clamp(IRn >> 7, 0, 1Fh) each.
    #[test]
    fn orgb_clamps(ir in prop::array::uniform3(any::<i16>())) {
        let mut gte = Gte::new();
        for (i, v) in ir.iter().enumerate() {
            gte.write_data((9 + i) as u32, *v as u16 as u32);
        }
        let expect: u32 = (0..3).map(|n| (((ir[n] as i32) >> 7).clamp(0, 31) as u32) << (5 * n)).sum();
        prop_assert_eq!(gte.read_data(29), expect);
    }

    /// SXYP: a write pushes the FIFO, a read returns SXY2.
    #[test]
    fn sxyp_fifo(a in any::<u32>(), b in any::<u32>(), c in any::<u32>(), d in any::<u32>()) {
        let mut gte = Gte::new();
        gte.write_data(12, a);
        gte.write_data(13, b);
        gte.write_data(14, c);
        gte.write_data(15, d);
        prop_assert_eq!([gte.read_data(12), gte.read_data(13), gte.read_data(14), gte.read_data(15)], [b, c, d, d]);
    }
}

/// Undefined opcodes (docs/gte.md): FLAG cleared, every other register unchanged.
#[test]
fn undefined_opcodes_only_clear_flag() {
    for op in 0..64u32 {
        if Opcode::from_bits(op).is_some() {
            continue;
        }
        let mut gte = Gte::new();
        for r in 0..63 {
            gte.write(r, 0x1234_5678u32.rotate_left(r));
        }
        gte.write_control(31, 0xFFFF_FFFF);
        let before: Vec<u32> = (0..63).map(|r| gte.read(r)).collect();
        assert_eq!(gte.execute(op), None);
        let after: Vec<u32> = (0..63).map(|r| gte.read(r)).collect();
        assert_eq!(before, after, "opcode {op:02X}");
        assert_eq!(gte.read_control(31), 0);
    }
}

/// The H = 2*SZ3 boundary overflows (H < 2*SZ3 is required), and the largest non-overflow
/// quotients are clamped to 1FFFFh without a flag (docs/gte.md).
#[test]
fn divide_boundaries() {
    assert_eq!(unr_divide(0x1000, 0x800), (0x1FFFF, true));
    let (q, of) = unr_divide(0x1001, 0x801);
    assert!(!of);
    // 0x1001 * 65536 / 0x801 = 131040.02: UNR within 3 units.
    assert!((q as i64 - 131_040).abs() <= 3);
    // docs/hardware/gte.md §6: FE3Fh/7F20h reaches 20000h and is clamped, with no flag.
    assert_eq!(unr_divide(0xFE3F, 0x7F20), (0x1FFFF, false));
}

/// The edges of the depth ranges, value by value: RTPS's SZ3 (0..FFFFh, FLAG.18) and IR3
/// flag (-8000h..7FFFh from the unshifted sum, FLAG.22) with identity rotation, sf = 1, so
/// that the depth is VZ + TRZ; AVSZ3's OTZ (0..FFFFh, FLAG.18) with ZSF3 = 1.0 or -1.0, so
/// that it is the sum of SZ1-3 or its negation (docs/hardware/gte.md §5, §7).
#[test]
fn depth_range_edges() {
    let edges = [
        -0x8001i32, -0x8000, -0x7FFF, -1, 0, 1, 0x7FFE, 0x7FFF, 0x8000, 0xFFFE, 0xFFFF, 0x1_0000,
        0x1_0001,
    ];
    for &z in &edges {
        let gte = identity_rtps(&[(7, (z - 100) as u32)], [0, 0, 100]); // TRZ, VZ0
        let flag = gte.flag();
        assert_eq!(
            gte.read_data(19) as i32,
            z.clamp(0, 0xFFFF),
            "SZ3 for depth {z}"
        );
        assert_eq!(
            flag.contains(Flag::SZ3_OTZ_SATURATED),
            !(0..=0xFFFF).contains(&z),
            "FLAG.18 for depth {z}"
        );
        assert_eq!(
            gte.read_data(11) as i32,
            z.clamp(-0x8000, 0x7FFF),
            "IR3 for depth {z}"
        );
        assert_eq!(
            flag.contains(Flag::IR3_SATURATED),
            !(-0x8000..=0x7FFF).contains(&z),
            "FLAG.22 for depth {z}"
        );

        for zsf in [0x1000i32, -0x1000] {
            let sum = z.max(0);
            let mut gte = Gte::new();
            gte.write_data(17, sum.min(0xFFFF) as u32); // SZ1
            gte.write_data(18, (sum - sum.min(0xFFFF)) as u32); // SZ2
            gte.write_control(29, zsf as u16 as u32); // ZSF3
            gte.execute(Opcode::Avsz3.bits());
            let otz = sum * zsf.signum();
            assert_eq!(
                gte.read_data(7) as i32,
                otz.clamp(0, 0xFFFF),
                "OTZ for {otz}"
            );
            assert_eq!(
                gte.flag().contains(Flag::SZ3_OTZ_SATURATED),
                !(0..=0xFFFF).contains(&otz),
                "FLAG.18 for OTZ {otz}"
            );
        }
    }
}

/// Cycle counts (docs/hardware/gte.md §1).
#[test]
fn cycle_counts() {
    let expected = [
        (0x01, 15),
        (0x06, 8),
        (0x0C, 6),
        (0x10, 8),
        (0x11, 8),
        (0x12, 8),
        (0x13, 19),
        (0x14, 13),
        (0x16, 44),
        (0x1B, 17),
        (0x1C, 11),
        (0x1E, 14),
        (0x20, 30),
        (0x28, 5),
        (0x29, 8),
        (0x2A, 17),
        (0x2D, 5),
        (0x2E, 6),
        (0x30, 23),
        (0x3D, 5),
        (0x3E, 5),
        (0x3F, 39),
    ];
    for (op, cycles) in expected {
        assert_eq!(gte::cycles(op), Some(cycles), "opcode {op:02X}");
        assert_eq!(Gte::new().execute(op | 0x1F0_0000), Some(cycles));
    }
    assert_eq!(gte::cycles(0), None);
    // `execute` dispatches on bits 0-5 itself: it must define exactly the opcodes above.
    for bits in 0..64u32 {
        let listed = expected.iter().find(|(op, _)| *op == bits).map(|e| e.1);
        assert_eq!(Gte::new().execute(bits), listed, "opcode {bits:02X}");
        assert_eq!(Opcode::from_bits(bits).map(Opcode::cycles), listed);
    }
}

/// The non-hardware divides run only in a build with `divide-modes`; without it they are
/// refused and the hardware divide stays selected (docs/gte.md, "Features").
#[test]
fn divide_mode_support_follows_the_feature() {
    let with = cfg!(feature = "divide-modes");
    for mode in [DivideMode::Exact, DivideMode::F32] {
        let mut gte = Gte::new();
        assert_eq!(mode.is_supported(), with);
        let result = gte.set_divide_mode(mode);
        if with {
            assert_eq!(result, Ok(()));
            assert_eq!(gte.divide_mode(), mode);
        } else {
            assert_eq!(result, Err(gte::UnsupportedDivideMode(mode)));
            assert_eq!(gte.divide_mode(), DivideMode::Unr);
        }
    }
    assert!(DivideMode::Unr.is_supported());
    assert_eq!(Gte::new().set_divide_mode(DivideMode::Unr), Ok(()));
}
