//! The 1,150 GTE vectors recorded on a console (fixtures/gte/ps1-tests-hw.jsonl): one JSON
//! object per line with the registers before (`in_data`, `in_ctrl`) and after the command.

use serde_json::Value;

/// Path of the console-recorded vectors.
pub const FIXTURE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../fixtures/gte/ps1-tests-hw.jsonl"
);

/// The 32-bit register words of a vector's field.
pub fn words(v: &Value, field: &str) -> Vec<u32> {
    v[field]
        .as_array()
        .unwrap_or_else(|| panic!("field {field} missing"))
        .iter()
        .map(|w| u32::try_from(w.as_u64().expect("register value")).expect("32-bit value"))
        .collect()
}
