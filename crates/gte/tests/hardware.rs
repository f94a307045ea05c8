//! Replays the 1,150 GTE vectors recorded on a real PlayStation (fixtures/gte, ps1-tests, MIT)
//! and compares all 64 registers, FLAG included, as the fixture's README prescribes.

use gte::{Gte, REGISTER_NAMES};
use serde_json::Value;

mod support;
use support::vectors::{FIXTURE, words};

#[test]
fn all_hardware_vectors_match() {
    let text = std::fs::read_to_string(FIXTURE).expect("fixture readable");
    let mut passed = 0;
    let mut failures = Vec::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: Value = serde_json::from_str(line).expect("valid JSON");
        let name = v["name"].as_str().unwrap_or("?").to_string();
        let input: Vec<u32> = [words(&v, "in_data"), words(&v, "in_ctrl")].concat();
        let expected: Vec<u32> = [words(&v, "out_data"), words(&v, "out_ctrl")].concat();
        assert_eq!(input.len(), 64);
        assert_eq!(expected.len(), 64);
        let mut gte = Gte::new();
        for (reg, &value) in (0..).zip(&input) {
            gte.write(reg, value);
        }
        if let Some(cmd) = v["cmd"].as_u64() {
            gte.execute(u32::try_from(cmd).expect("32-bit command"));
        }
        let mut diffs = Vec::new();
        for ((reg, &want), name) in (0..).zip(&expected).zip(REGISTER_NAMES) {
            let got = gte.read(reg);
            if got != want {
                diffs.push(format!("{name} got {got:08X} expected {want:08X}"));
            }
        }
        if diffs.is_empty() {
            passed += 1;
        } else {
            failures.push(format!("{name} (cmd {:?}): {}", v["cmd"], diffs.join(", ")));
        }
    }
    for f in failures.iter().take(40) {
        eprintln!("{f}");
    }
    assert_eq!(passed, 1150, "{} vectors failed", failures.len());
    assert!(failures.is_empty());
}
