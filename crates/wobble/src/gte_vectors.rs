//! Replay of GTE test vectors in the JSON-lines schema of `fixtures/gte/README.md`
//! (docs/formats.md, "GTE vector files").

use gte::{Gte, REGISTER_NAMES};
use serde_json::Value;
use std::fmt;
use std::fmt::Write as _;

/// What is wrong with one line of a vector file.
#[derive(Debug)]
pub enum VectorError {
    /// The line is not JSON.
    NotJson(serde_json::Error),
    /// The line is JSON but not an object.
    NotObject,
    /// A value that must be a 32-bit unsigned integer is not (`what` names it).
    NotInteger {
        /// The field and index.
        what: String,
    },
    /// A register array without exactly 32 values.
    RegisterCount {
        /// The field.
        field: &'static str,
        /// Values present.
        count: usize,
    },
    /// A register field that is not an array.
    NotArray {
        /// The field.
        field: &'static str,
    },
    /// A `writes` entry that is not a `[reg, value]` pair.
    NotPair {
        /// Index in `writes`.
        index: usize,
    },
    /// A `writes` register index outside 0..=63.
    RegisterIndex {
        /// Index in `writes`.
        index: usize,
    },
    /// A required field is absent.
    Missing {
        /// The field.
        field: &'static str,
    },
}

impl fmt::Display for VectorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            VectorError::NotJson(e) => write!(f, "not JSON: {e}"),
            VectorError::NotObject => write!(f, "not a JSON object"),
            VectorError::NotInteger { what } => {
                write!(f, "{what} is not an integer in 0..=4294967295")
            }
            VectorError::RegisterCount { field, count } => {
                write!(f, "`{field}` has {count} values, expected 32")
            }
            VectorError::NotArray { field } => write!(f, "`{field}` is not an array"),
            VectorError::NotPair { index } => {
                write!(f, "`writes`[{index}] is not a [reg, value] pair")
            }
            VectorError::RegisterIndex { index } => {
                write!(f, "`writes`[{index}]: register index must be 0..=63")
            }
            VectorError::Missing { field } => write!(f, "missing `{field}`"),
        }
    }
}

impl std::error::Error for VectorError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            VectorError::NotJson(e) => Some(e),
            _ => None,
        }
    }
}

/// A malformed line of a vector file, with its 1-based number.
#[derive(Debug)]
pub struct ReplayError {
    /// Line number.
    pub line: usize,
    /// What is wrong.
    pub error: VectorError,
}

impl fmt::Display for ReplayError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.error)
    }
}

impl std::error::Error for ReplayError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// The text is not a vector file: its first line that holds anything is not a JSON object,
/// so replay stops there instead of reporting every line.
#[derive(Debug)]
pub struct NotVectorFile {
    /// The 1-based line.
    pub line: usize,
    /// What is wrong with it ([`VectorError::NotJson`] or [`VectorError::NotObject`]).
    pub error: VectorError,
}

impl fmt::Display for NotVectorFile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "not a GTE vector file: line {} is {}; a vector file holds one JSON object a line \
             (docs/formats.md, \"GTE vector files\")",
            self.line,
            match &self.error {
                VectorError::NotJson(_) => "not JSON".to_string(),
                e => e.to_string(),
            }
        )
    }
}

impl std::error::Error for NotVectorFile {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// Outcome of a replay: counts and the text to print.
#[derive(Debug, Default)]
pub struct ReplayOutcome {
    /// Vectors whose 64 registers all matched (or, when emitting, that ran).
    pub passed: usize,
    /// Vectors that differed or could not be read.
    pub failed: usize,
    /// Report lines (failures; or, when emitting, one JSON object per vector).
    pub output: Vec<String>,
    /// Malformed input lines, each naming its line number.
    pub errors: Vec<ReplayError>,
}

/// A vector as read from one line.
struct Vector {
    name: String,
    cmd: Option<u32>,
    writes: Vec<(usize, u32)>,
    expected: Option<[u32; 64]>,
}

fn u32_field(v: &Value, what: &str) -> Result<u32, VectorError> {
    v.as_u64()
        .and_then(|n| u32::try_from(n).ok())
        .ok_or_else(|| VectorError::NotInteger { what: what.into() })
}

fn registers(v: &Value, field: &'static str) -> Result<Option<Vec<u32>>, VectorError> {
    match v.get(field) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Array(items)) => {
            if items.len() != 32 {
                return Err(VectorError::RegisterCount {
                    field,
                    count: items.len(),
                });
            }
            items
                .iter()
                .enumerate()
                .map(|(i, x)| u32_field(x, &format!("`{field}`[{i}]")))
                .collect::<Result<Vec<_>, _>>()
                .map(Some)
        }
        Some(_) => Err(VectorError::NotArray { field }),
    }
}

fn parse_vector(v: &Value, line: usize, emit: bool) -> Result<Vector, VectorError> {
    if !v.is_object() {
        return Err(VectorError::NotObject);
    }
    let name = match v.get("name") {
        Some(Value::String(s)) => s.clone(),
        _ => format!("line {line}"),
    };
    let cmd = match v.get("cmd") {
        None | Some(Value::Null) => None,
        Some(c) => Some(u32_field(c, "`cmd`")?),
    };
    let writes = match v.get("writes") {
        Some(Value::Array(items)) => {
            let mut writes = Vec::with_capacity(items.len());
            for (i, w) in items.iter().enumerate() {
                let pair = w
                    .as_array()
                    .filter(|p| p.len() == 2)
                    .ok_or(VectorError::NotPair { index: i })?;
                let reg = pair[0]
                    .as_u64()
                    .filter(|r| *r < 64)
                    .ok_or(VectorError::RegisterIndex { index: i })?;
                let value = u32_field(&pair[1], &format!("`writes`[{i}] value"))?;
                writes.push((reg as usize, value));
            }
            writes
        }
        Some(_) => return Err(VectorError::NotArray { field: "writes" }),
        None => {
            let data = registers(v, "in_data")?.ok_or(VectorError::Missing { field: "in_data" })?;
            let ctrl = registers(v, "in_ctrl")?.ok_or(VectorError::Missing { field: "in_ctrl" })?;
            data.into_iter().chain(ctrl).enumerate().collect()
        }
    };
    let expected = if emit {
        None
    } else {
        let data = registers(v, "out_data")?.ok_or(VectorError::Missing { field: "out_data" })?;
        let ctrl = registers(v, "out_ctrl")?.ok_or(VectorError::Missing { field: "out_ctrl" })?;
        let mut all = [0u32; 64];
        for (slot, value) in all.iter_mut().zip(data.into_iter().chain(ctrl)) {
            *slot = value;
        }
        Some(all)
    };
    Ok(Vector {
        name,
        cmd,
        writes,
        expected,
    })
}

/// Run one vector on a fresh GTE and read all 64 registers back.
fn run(vector: &Vector) -> [u32; 64] {
    let mut gte = Gte::new();
    for &(reg, value) in &vector.writes {
        // Register indices are below 64 (checked on parse).
        gte.write(reg as u32, value);
    }
    if let Some(cmd) = vector.cmd {
        gte.execute(cmd);
    }
    let mut out = [0u32; 64];
    for (reg, slot) in (0..).zip(out.iter_mut()) {
        *slot = gte.read(reg);
    }
    out
}

/// Replay every vector of a JSON-lines text. Without `emit`, each vector's registers are
/// compared with `out_data`/`out_ctrl`; with it, the computed registers are emitted as JSON.
/// A malformed line is reported with its number, counted as failed, and the rest still runs;
/// but when the first line that holds anything is not a JSON object, the text is not a vector
/// file and replay stops with [`NotVectorFile`].
pub fn replay(text: &str, emit: bool) -> Result<ReplayOutcome, NotVectorFile> {
    let mut outcome = ReplayOutcome::default();
    let mut seen_object = false;
    for (index, line) in text.lines().enumerate() {
        let number = index + 1;
        if line.trim().is_empty() {
            continue;
        }
        let value = match serde_json::from_str::<Value>(line) {
            Ok(v) if v.is_object() => Ok(v),
            Ok(_) => Err(VectorError::NotObject),
            Err(e) => Err(VectorError::NotJson(e)),
        };
        let value = match value {
            Err(error) if !seen_object => {
                return Err(NotVectorFile {
                    line: number,
                    error,
                });
            }
            v => v,
        };
        seen_object = true;
        let vector = value.and_then(|v| parse_vector(&v, number, emit));
        let vector = match vector {
            Ok(v) => v,
            Err(e) => {
                outcome.errors.push(ReplayError {
                    line: number,
                    error: e,
                });
                outcome.failed += 1;
                continue;
            }
        };
        let got = run(&vector);
        match vector.expected {
            None => {
                let json = serde_json::json!({
                    "name": vector.name,
                    "out_data": &got[..32],
                    "out_ctrl": &got[32..],
                });
                outcome.output.push(json.to_string());
                outcome.passed += 1;
            }
            Some(expected) => {
                let mut report = String::new();
                for (reg, (g, e)) in got.iter().zip(expected.iter()).enumerate() {
                    if g != e {
                        let _ = write!(
                            report,
                            "\n  {:<9} got {g:08X} expected {e:08X}",
                            REGISTER_NAMES[reg]
                        );
                    }
                }
                if report.is_empty() {
                    outcome.passed += 1;
                } else {
                    outcome.failed += 1;
                    outcome
                        .output
                        .push(format!("FAIL {} (line {number}):{report}", vector.name));
                }
            }
        }
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zeros() -> String {
        format!("[{}]", vec!["0"; 32].join(","))
    }

    #[test]
    fn register_only_vector_passes_and_mismatch_is_reported() {
        let z = zeros();
        let good = format!(
            r#"{{"name":"zero","cmd":null,"in_data":{z},"in_ctrl":{z},"out_data":{z},"out_ctrl":{z}}}"#
        );
        // LZCR (r31) of LZCS = 0 reads 32, so an all-zero expectation fails on LZCR only.
        let out = replay(&good, false).unwrap();
        assert_eq!((out.passed, out.failed), (0, 1));
        assert!(out.output[0].contains("LZCR"));
        assert!(out.output[0].contains("got 00000020 expected 00000000"));
    }

    #[test]
    fn writes_field_replaces_index_order() {
        // Write LZCS = 1 through the writes list: LZCR reads 31.
        let line = r#"{"name":"w","cmd":null,"writes":[[30,1]]}"#;
        let out = replay(line, true).unwrap();
        assert_eq!(out.passed, 1);
        let v: Value = serde_json::from_str(&out.output[0]).unwrap();
        assert_eq!(v["out_data"][31], 31);
        assert_eq!(v["out_data"][30], 1);
    }

    #[test]
    fn bad_lines_are_numbered_and_the_rest_runs() {
        let text = "{\"name\":\"x\",\"writes\":[[64,1]]}\nnot json\n\n{\"writes\":[]}";
        let out = replay(text, true).unwrap();
        assert_eq!(out.failed, 2);
        assert!(out.errors[0].to_string().starts_with("line 1: `writes`[0]"));
        assert!(out.errors[1].to_string().starts_with("line 2: not JSON"));
        assert_eq!(out.passed, 1);
    }

    /// A text whose first line with anything on it is not a JSON object is not a vector file:
    /// one error for that line, whatever follows (a command stream has a hundred such lines).
    #[test]
    fn a_file_of_another_format_stops_at_its_first_line() {
        let stream = "\n# a GPU command stream\ngp0 e1000000\ngp0 e2000000\n";
        let e = replay(stream, false).unwrap_err();
        assert_eq!(e.line, 2);
        assert!(matches!(e.error, VectorError::NotJson(_)));
        let text = e.to_string();
        assert!(
            text.starts_with("not a GTE vector file: line 2 is not JSON;")
                && text.contains("one JSON object a line"),
            "{text}"
        );
        let e = replay("[1, 2]\n{\"writes\":[]}\n", false).unwrap_err();
        assert_eq!(e.line, 1);
        assert!(matches!(e.error, VectorError::NotObject));
    }
}
