//! The reference model (`gte::reference`) against the 1,150 vectors recorded on a real
//! PlayStation, replayed through the model's own register rules (docs/hardware/gte.md §9).

#![cfg(feature = "reference")]

use gte::{REGISTER_NAMES, Registers, reference};
use serde_json::Value;

mod support;
use support::vectors::{FIXTURE, words};

#[test]
fn reference_matches_every_hardware_vector() {
    let text = std::fs::read_to_string(FIXTURE).expect("fixture readable");
    let mut passed = 0;
    let mut failures = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Value = serde_json::from_str(line).expect("valid JSON");
        let input: Vec<u32> = [words(&v, "in_data"), words(&v, "in_ctrl")].concat();
        let expected: Vec<u32> = [words(&v, "out_data"), words(&v, "out_ctrl")].concat();
        let mut regs = Registers::default();
        for (index, &value) in (0..).zip(&input) {
            reference::write(&mut regs, index, value);
        }
        if let Some(cmd) = v["cmd"].as_u64() {
            let trace = reference::execute(&mut regs, u32::try_from(cmd).expect("32-bit"));
            assert_eq!(trace.flag(), regs.flag);
        }
        let diffs: Vec<String> = (0..64u32)
            .zip(REGISTER_NAMES)
            .filter(|&(i, _)| reference::read(&regs, i) != expected[i as usize])
            .map(|(i, name)| {
                format!(
                    "{name} got {:08X} expected {:08X}",
                    reference::read(&regs, i),
                    expected[i as usize]
                )
            })
            .collect();
        if diffs.is_empty() {
            passed += 1;
        } else {
            failures.push(format!(
                "{} (cmd {:?}): {}",
                v["name"],
                v["cmd"],
                diffs.join(", ")
            ));
        }
    }
    for f in failures.iter().take(40) {
        eprintln!("{f}");
    }
    assert_eq!(passed, 1150, "{} vectors failed", failures.len());
}

use gte::reference::Trace;
use gte::{DivideMode, Gte, GteState, Opcode, strategy};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// The divide modes this build's engine runs.
fn supported_modes() -> Vec<DivideMode> {
    [DivideMode::Unr, DivideMode::Exact, DivideMode::F32]
        .into_iter()
        .filter(|m| m.is_supported())
        .collect()
}

/// An engine holding `regs` exactly, dividing by `mode`.
fn engine(regs: &Registers, mode: DivideMode) -> Gte {
    let mut gte = Gte::new();
    let state = GteState {
        version: GteState::VERSION,
        registers: regs.clone(),
        divide_mode: mode,
    };
    gte.load_state(&state)
        .expect("a state of this version and a supported mode");
    gte
}

/// The engine and the model run `word` on the same registers: every register, FLAG
/// included, ends equal, and the trace's FLAG is FLAG.
fn agree(regs: &Registers, word: u32, mode: DivideMode) -> Result<Trace, TestCaseError> {
    let mut gte = engine(regs, mode);
    let mut model = regs.clone();
    let trace = reference::execute_with(&mut model, word, mode);
    let cycles = gte.execute(word);
    prop_assert_eq!(cycles.is_some(), trace != Trace::Undefined);
    prop_assert_eq!(gte.registers(), model.clone(), "command {:08X}", word);
    prop_assert_eq!(gte.flag(), trace.flag());
    for i in 0..64 {
        prop_assert_eq!(gte.read(i), reference::read(&model, i), "register {}", i);
    }
    Ok(trace)
}

/// Every command with every sf, lm and MVMVA selector, on edge-biased register files
/// (`gte::strategy::registers`), 3,000 cases a command, in every divide mode of the build:
/// the engine leaves exactly the registers the reference model leaves.
#[test]
fn engine_equals_reference_on_every_command() {
    for op in Opcode::ALL {
        let mut runner = TestRunner::new(Config {
            cases: 3000,
            failure_persistence: None,
            ..Config::default()
        });
        let strategy = (
            strategy::registers(),
            strategy::command_for(op),
            prop::sample::select(supported_modes()),
        );
        runner
            .run(&strategy, |(regs, word, mode)| {
                agree(&regs, word, mode).map(|_| ())
            })
            .unwrap_or_else(|e| panic!("{op:?}: {e}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// Any 32-bit word, undefined opcodes and ignored bits included.
    #[test]
    fn engine_equals_reference_on_any_word(regs in strategy::registers(), word in strategy::command()) {
        agree(&regs, word, DivideMode::Unr)?;
    }

    /// Register writes and reads: any sequence of MTC2/CTC2 (side effects of SXYP, IRGB,
    /// LZCS and FLAG included) leaves the engine and the model reading the same 64 words.
    #[test]
    fn register_rules_agree(
        regs in strategy::registers(),
        writes in prop::collection::vec((0u32..64, any::<u32>()), 1..40),
    ) {
        let mut gte = engine(&regs, DivideMode::Unr);
        let mut model = regs;
        for (index, value) in writes {
            gte.write(index, value);
            reference::write(&mut model, index, value);
            for i in 0..64 {
                prop_assert_eq!(gte.read(i), reference::read(&model, i), "register {} after writing {}", i, index);
            }
        }
        prop_assert_eq!(gte.registers(), model);
    }

    /// The divides: the model's (written from docs/hardware/gte.md §6 step by step) and the
    /// engine's public ones agree for every mode.
    #[test]
    fn divides_agree(h in strategy::unsigned_half(), sz3 in strategy::unsigned_half()) {
        for mode in [DivideMode::Unr, DivideMode::Exact, DivideMode::F32] {
            let q = reference::divide(mode, h, sz3);
            prop_assert_eq!((q.value, q.overflow), gte::unr::divide(mode, h, sz3), "{:?}", mode);
        }
    }

    /// The model's exact values are what they say: each row's `exact` is the plain sum of
    /// its terms, its accumulator that sum wrapped to 44 bits (the wrap after each addition
    /// adds up to one wrap of the total), MACn the low 32 bits of the accumulator SAR sf, IRn
    /// MACn saturated; the FLAG of a step holds a row's overflow bit only if some partial
    /// sum left the 44-bit range, which the total alone cannot show, so only the converse is
    /// checked: a total outside the range always flags.
    #[test]
    fn mvmva_trace_is_consistent(regs in strategy::registers(), word in strategy::command_for(Opcode::Mvmva)) {
        let mut model = regs.clone();
        let Trace::Mvmva(t) = reference::execute(&mut model, word) else { unreachable!() };
        let c = gte::Command::new(word);
        let wrapped = |x: i64| (x << 20) >> 20;
        for (n, row) in t.step.rows.iter().enumerate() {
            prop_assert_eq!(row.acc, wrapped(row.exact));
            prop_assert_eq!(row.mac, (row.acc >> c.shift()) as i32);
            let min = if c.lm() { 0 } else { -0x8000 };
            prop_assert_eq!(row.ir as i64, (row.mac as i64).clamp(min, 0x7FFF));
            let over = gte::Flag::from_bits(1 << (30 - n) | 1 << (27 - n));
            if !(-(1i64 << 43)..(1i64 << 43)).contains(&row.exact) {
                prop_assert!(t.flag.intersects(over), "row {} exact {:X}", n + 1, row.exact);
            }
        }
    }
}

/// A hand-computed RTPS (docs/hardware/gte.md §5): RT = identity, TR = (0, 0, 1000), V0 =
/// (100, -50, 0), H = 500, OFX = 160.0, OFY = 120.0, DQA = -100h (-1.0 in 8.8), DQB =
/// 1.0 in 8.24 (100_0000h): depth 1000, quotient 500 / 1000 = 8000h (exact in UNR), screen
/// X = 8000h × 100 + A0_0000h = C0_0000h + 20_0000h → 192 - 32 = 160 + 50 = 210,
/// Y = 120 - 25 = 95; D = 8000h × -100h + 100_0000h = 80_0000h, IR0 = 800h.
#[test]
fn rtps_by_hand() {
    let mut regs = Registers {
        rt: [[0x1000, 0, 0], [0, 0x1000, 0], [0, 0, 0x1000]],
        tr: [0, 0, 1000],
        h: 500,
        ofx: 160 << 16,
        ofy: 120 << 16,
        dqa: -0x100,
        dqb: 0x100_0000,
        ..Registers::default()
    };
    regs.v[0] = [100, -50, 0];
    let t = reference::rtps(&mut regs, true, false, DivideMode::Unr);
    assert_eq!(t.vertex.camera.mac(), [100, -50, 1000]);
    assert_eq!(t.vertex.depth, 1000);
    assert_eq!(t.vertex.quotient, 0x8000);
    assert_eq!(
        t.vertex.screen,
        [(160 << 16) + 50 * 65536, (120 << 16) - 25 * 65536]
    );
    assert_eq!(t.vertex.sxy, [210, 95]);
    assert_eq!(t.depth_cue.exact, 0x80_0000);
    assert_eq!(t.depth_cue.ir0, 0x800);
    assert!(t.flag.is_empty());
    assert_eq!(regs.sxy[2], 95 << 16 | 210);
    assert_eq!(regs.sz[3], 1000);
}
