//! The GP0/GP1 command-stream text format (docs/formats.md): one command a line,
//! `gp0 XXXXXXXX [XXXXXXXX ...]` (words sent to GP0 in order) or `gp1 XXXXXXXX`; `#` starts a
//! comment; blank lines are ignored. Words are 1 to 8 hex digits, optionally prefixed `0x`;
//! a leading UTF-8 byte-order mark is skipped.

use alloc::string::{String, ToString};
use alloc::vec::Vec;
use core::fmt;

use crate::{Gpu, PendingInput};

/// The port a stream line writes to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Port {
    /// GP0: rendering and VRAM transfers.
    Gp0,
    /// GP1: display control.
    Gp1,
}

/// One line of a stream: its 1-based line number, port and words.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamCommand {
    /// Line number in the source text (1-based).
    pub line: usize,
    /// Destination port.
    pub port: Port,
    /// Words in order (exactly one for GP1).
    pub words: Vec<u32>,
}

/// A malformed stream line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamError {
    /// Line number (1-based).
    pub line: usize,
    /// What is wrong with it.
    pub message: String,
}

impl fmt::Display for StreamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

impl core::error::Error for StreamError {}

/// Parse a whole stream; the first malformed line is reported with its number.
pub fn parse(text: &str) -> Result<Vec<StreamCommand>, StreamError> {
    let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
    let mut commands = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("");
        let mut fields = content.split_whitespace();
        let Some(port) = fields.next() else {
            continue;
        };
        let err = |message: String| StreamError { line, message };
        let port = match port.to_ascii_lowercase().as_str() {
            "gp0" => Port::Gp0,
            "gp1" => Port::Gp1,
            other if crate::bus::is_directive(other) => {
                return Err(err(alloc::format!(
                    "`{other}` is a timing directive, read by gpu::bus::parse \
                     (docs/formats.md, \"Timed streams\")"
                )));
            }
            other => {
                return Err(err(alloc::format!(
                    "unknown port `{other}` (expected gp0 or gp1)"
                )));
            }
        };
        let mut words = Vec::new();
        for field in fields {
            words.push(parse_word(field).map_err(err)?);
        }
        match (port, words.len()) {
            (_, 0) => return Err(err("missing word after the port".to_string())),
            (Port::Gp1, n) if n > 1 => {
                return Err(err(alloc::format!("gp1 takes exactly one word, got {n}")));
            }
            _ => {}
        }
        commands.push(StreamCommand { line, port, words });
    }
    Ok(commands)
}

/// What a stream left unfinished when it ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Unfinished {
    /// The input in progress ([`Gpu::pending_input`]).
    pub pending: PendingInput,
    /// Line (1-based) of the word that started it.
    pub line: usize,
}

/// The outcome of [`run`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunSummary {
    /// `Some` when the stream ended mid-packet, mid CPU-to-VRAM transfer or inside an
    /// unterminated polyline.
    pub unfinished: Option<Unfinished>,
}

/// One 32-bit word: 1 to 8 hex digits, optionally prefixed `0x`.
pub(crate) fn parse_word(field: &str) -> Result<u32, String> {
    let digits = field
        .strip_prefix("0x")
        .or_else(|| field.strip_prefix("0X"))
        .unwrap_or(field);
    if digits.is_empty() || digits.len() > 8 || !digits.bytes().all(|b| b.is_ascii_hexdigit()) {
        return Err(alloc::format!(
            "`{field}` is not a 32-bit hex word (1 to 8 hex digits)"
        ));
    }
    u32::from_str_radix(digits, 16).map_err(|_| alloc::format!("`{field}` is not a hex word"))
}

/// Send parsed commands to a GPU in order; report input the stream left unfinished, with the
/// line where it started.
pub fn run(gpu: &mut Gpu, commands: &[StreamCommand]) -> RunSummary {
    let mut start_line = 0;
    for c in commands {
        match c.port {
            Port::Gp0 => {
                for &w in &c.words {
                    if gpu.pending_input().is_none() {
                        start_line = c.line;
                    }
                    gpu.gp0(w);
                }
            }
            Port::Gp1 => {
                for &w in &c.words {
                    gpu.gp1(w);
                }
            }
        }
    }
    RunSummary {
        unfinished: gpu.pending_input().map(|pending| Unfinished {
            pending,
            line: start_line,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_ports_words_comments() {
        let cmds = parse("# header\n\ngp1 00000000\ngp0 e1000400 0x02ffffff # trailing\n").unwrap();
        assert_eq!(cmds.len(), 2);
        assert_eq!(cmds[0].line, 3);
        assert_eq!(cmds[0].port, Port::Gp1);
        assert_eq!(cmds[1].words, [0xE100_0400, 0x02FF_FFFF]);
    }

    #[test]
    fn errors_name_the_line() {
        assert_eq!(parse("gp0 1\ngp2 0").unwrap_err().line, 2);
        assert_eq!(parse("gp0 xyz").unwrap_err().line, 1);
        assert_eq!(parse("gp0").unwrap_err().line, 1);
        assert_eq!(parse("gp0 1\n\ngp1 1 2").unwrap_err().line, 3);
        assert_eq!(parse("gp0 123456789").unwrap_err().line, 1);
        // A timed stream's directive is named as such.
        let e = parse("gp0 1\nwait 28\n").unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("timing directive"), "{}", e.message);
    }

    #[test]
    fn leading_bom_accepted() {
        let cmds = parse("\u{FEFF}gp0 1\n").unwrap();
        assert_eq!(cmds[0].words, [1]);
        assert_eq!(cmds[0].port, Port::Gp0);
    }

    #[test]
    fn only_hex_digits() {
        for bad in ["+1", "-1", "0x+1", "1_0", "0x", "g", " 1\u{663}"] {
            assert!(parse(&alloc::format!("gp0 {bad}")).is_err(), "{bad:?}");
        }
        assert_eq!(parse("gp0 0XaBcD").unwrap()[0].words, [0xABCD]);
    }

    fn run_text(text: &str) -> RunSummary {
        let mut gpu = Gpu::new();
        run(&mut gpu, &parse(text).unwrap())
    }

    #[test]
    fn reports_unfinished_input_with_its_line() {
        assert_eq!(
            run_text("gp0 e3000000\ngp0 02000000 0 00010010\n").unfinished,
            None
        );
        // A flat triangle (4 words) cut after 3, started on line 2.
        let u = run_text("gp0 e3000000\ngp0 20ff0000 0\n# more\ngp0 00100000\n")
            .unfinished
            .unwrap();
        assert_eq!(u.line, 2);
        assert_eq!(
            u.pending,
            PendingInput::Packet {
                command: 0x20FF_0000,
                received: 3,
                expected: 4
            }
        );
        // CPU-to-VRAM 3x3 = 9 pixels = 5 words; 2 sent.
        let u = run_text("gp1 0\ngp0 a0000000 0 00030003\ngp0 1 2\n")
            .unfinished
            .unwrap();
        assert_eq!(
            (u.line, u.pending),
            (2, PendingInput::Transfer { remaining_words: 3 })
        );
        // A polyline without its terminator.
        let u = run_text("gp0 0\ngp0 48ffffff 0 00100010\ngp0 00200020\n")
            .unfinished
            .unwrap();
        assert_eq!((u.line, u.pending), (2, PendingInput::Polyline));
        // GP1(01h) drops the partial packet.
        assert_eq!(run_text("gp0 20ff0000\ngp1 01000000\n").unfinished, None);
    }
}
