//! The reference model (`gte::reference`) against the 1,150 vectors recorded on a real
//! PlayStation, replayed through the model's own register rules (docs/hardware/gte.md §9).

#![cfg(feature = "reference")]

use gte::{DivideMode, REGISTER_NAMES, Registers, reference};
use serde_json::Value;

const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../fixtures/gte/ps1-tests-hw.jsonl"
);

fn words(v: &Value, field: &str) -> Vec<u32> {
    v[field]
        .as_array()
        .unwrap_or_else(|| panic!("field {field} missing"))
        .iter()
        .map(|w| u32::try_from(w.as_u64().expect("register value")).expect("32-bit value"))
        .collect()
}

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
