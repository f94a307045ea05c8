//! The command line as a user meets it: help texts, the README's usage lines, default output
//! names, `render --inspect`, counts and numbers in messages, and files of the wrong kind.

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Run `wobble` in directory `cwd`.
fn wobble_in(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wobble"))
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("binary runs")
}

/// Run `wobble` in a fresh directory of its own, removed afterwards: a command that writes
/// into the current directory leaves nothing behind.
fn wobble(args: &[&str]) -> Output {
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let cwd = Scratch::new(&format!("run{}", RUNS.fetch_add(1, Ordering::Relaxed)));
    wobble_in(&cwd, args)
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn entries(d: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// The subcommands `wobble --help` lists under "Commands:" (without `help`).
fn subcommands() -> Vec<String> {
    let help = stdout(&wobble(&["--help"]));
    help.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect()
}

/// The top-level help's first line names every command the tool has.
#[test]
fn top_level_help_names_every_command() {
    let commands = subcommands();
    assert_eq!(
        commands,
        [
            "render", "gte", "replay", "inspect", "convert", "dump", "trade"
        ]
    );
    let help = stdout(&wobble(&["--help"]));
    let about = help.lines().next().unwrap();
    for c in &commands {
        assert!(about.contains(c.as_str()), "{c} missing from {about:?}");
    }
}

/// `render -o`'s help says what a .gif does, and that --inspect writes no image by default.
#[test]
fn render_output_help_says_what_happens() {
    let help = stdout(&wobble(&["render", "--help"]));
    let o = help
        .split("\n\n")
        .find(|block| block.contains("-o, --output"))
        .unwrap_or_else(|| panic!("{help}"));
    let o = o.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        o.contains("last frame") && o.contains(".gif") && o.contains("whole animation"),
        "{o}"
    );
    assert!(o.contains("none with --inspect"), "{o}");
}

/// The long options of a command's help (`--help` and `--version` aside).
fn long_options(args: &[&str]) -> Vec<String> {
    let mut a = args.to_vec();
    a.push("--help");
    let help = stdout(&wobble(&a));
    let mut v: Vec<String> = help
        .lines()
        .filter_map(|l| {
            let t = l.trim_start();
            let t = t.strip_prefix("-o, ").unwrap_or(t);
            t.starts_with("--").then(|| {
                t.split([' ', '<', ','])
                    .next()
                    .unwrap_or_default()
                    .to_string()
            })
        })
        .filter(|o| o != "--help" && o != "--version")
        .collect();
    v.sort();
    v.dedup();
    v
}

/// Every usage line of the README names a real command, and the lines of each command name
/// exactly the options its help lists.
#[test]
fn readme_usage_lines_match_the_cli() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let block = readme
        .split("## Usage\n\n```sh\n")
        .nth(1)
        .and_then(|b| b.split("```").next())
        .expect("the README's usage block");
    // Lines starting with `wobble`, each with its indented continuation lines.
    let mut usages: Vec<String> = Vec::new();
    for line in block.lines() {
        if line.starts_with("wobble ") {
            usages.push(line.to_string());
        } else if let Some(last) = usages.last_mut() {
            last.push(' ');
            last.push_str(line.trim());
        }
    }
    let mut by_command: std::collections::BTreeMap<String, Vec<String>> = Default::default();
    for usage in &usages {
        let words: Vec<&str> = usage.split_whitespace().collect();
        let command = if words[1] == "gte" {
            format!("gte {}", words[2])
        } else {
            words[1].to_string()
        };
        let options = by_command.entry(command).or_default();
        for w in &words {
            let w = w.trim_matches(|c| c == '[' || c == ']' || c == '|');
            if let Some(name) = w.strip_prefix("--") {
                let name = name.split(['|', ']']).next().unwrap_or_default();
                options.push(format!("--{name}"));
            } else if w == "-o" {
                options.push("--output".into());
            }
        }
    }
    let mut commands: Vec<String> = subcommands()
        .into_iter()
        .map(|c| if c == "gte" { "gte replay".into() } else { c })
        .collect();
    commands.sort();
    let mut documented: Vec<String> = by_command.keys().cloned().collect();
    documented.sort();
    assert_eq!(documented, commands, "commands in the README usage");
    for (command, mut options) in by_command {
        options.sort();
        options.dedup();
        let args: Vec<&str> = command.split(' ').collect();
        assert_eq!(
            options,
            long_options(&args),
            "options of `wobble {command}`"
        );
    }
}

/// `replay` and `dump` both default to the input's name with .png in the current directory,
/// and refuse to write over their input.
#[test]
fn replay_and_dump_default_to_the_input_name() {
    let d = Scratch::new("defaults");
    let stream = root().join("fixtures/gpu/quad.gpu");
    let o = wobble_in(&d, &["replay", s(&stream), "--raw", "quad.vram.bin"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(entries(&d), ["quad.png", "quad.vram.bin"]);
    std::fs::remove_file(d.join("quad.png")).unwrap();
    let o = wobble_in(&d, &["dump", "quad.vram.bin"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(entries(&d), ["quad.png", "quad.vram.bin"]);
    assert!(stderr(&o).contains("wrote quad.png"), "{}", stderr(&o));
    // A raw file named like its default output: refused, the input intact.
    std::fs::rename(d.join("quad.vram.bin"), d.join("v.png")).unwrap();
    let o = wobble_in(&d, &["dump", "v.png"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("input file"), "{}", stderr(&o));
    assert_eq!(std::fs::metadata(d.join("v.png")).unwrap().len(), 1 << 20);
}

/// `trade` takes `-o` like every other command, and `--out` still works.
#[test]
fn trade_takes_dash_o_and_the_old_spelling() {
    let d = Scratch::new("trade");
    let scene = root().join("fixtures/scenes/face-on.toml");
    for (flag, name) in [("-o", "a"), ("--out", "b")] {
        let out = d.join(name);
        let o = wobble(&[
            "trade",
            s(&scene),
            "--frames",
            "2",
            "--repeats",
            "1",
            "--sweep-step",
            "30000",
            flag,
            s(&out),
        ]);
        assert!(o.status.success(), "{flag}: {}", stderr(&o));
        assert!(out.join("trade.md").is_file(), "{flag}");
    }
}

/// `render --inspect DIR`: no wobble.png in the current directory unless asked, the summary
/// names the report, the stage times are measured (not 0), and the report's writing time is
/// given apart from the rendering.
#[test]
fn render_inspect_names_the_report_and_writes_no_image() {
    let d = Scratch::new("render-inspect");
    let o = wobble_in(&d, &["render", "--inspect", "rep"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(entries(&d), ["rep"]);
    let out = stdout(&o);
    assert!(out.starts_with("1 frame rendered: "), "{out}");
    assert!(
        out.contains("report of frame 0: ") && out.contains("rep/index.html, written in "),
        "{out}"
    );
    // "GTE a ms, OT b ms, GPU c ms": the traced frame is timed.
    let gpu_ms: f64 = out
        .split("GPU ")
        .nth(1)
        .and_then(|t| t.split(" ms").next())
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    assert!(gpu_ms > 0.0, "{out}");
    // With -o, the image is written too.
    let o = wobble_in(&d, &["render", "--inspect", "rep", "-o", "frame.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(entries(&d), ["frame.png", "rep"]);
}

/// One of a thing is singular: the face-on scene draws one polygon (only the front face of
/// its cube survives NCLIP) in one frame; a one-triangle stream has one draw.
#[test]
fn counts_of_one_are_singular() {
    let d = Scratch::new("plurals");
    let scene = root().join("fixtures/scenes/face-on.toml");
    let o = wobble_in(&d, &["render", s(&scene)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.starts_with("1 frame -> wobble.png (last frame): 1 polygon drawn, "),
        "{out}"
    );
    let stream = d.join("one.gpu");
    std::fs::write(&stream, "gp0 20FF0000 00000000 00100000 00000010\n").unwrap();
    let o = wobble_in(&d, &["inspect", "one.gpu", "-o", "rep"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.starts_with("1 command (1 draw, 0 primitives dropped, "),
        "{out}"
    );
}

/// A mesh scaled past the GTE's range: the largest scale is printed as a plain number.
#[test]
fn scale_limit_is_a_plain_number() {
    let d = Scratch::new("scale");
    std::fs::write(
        d.join("big.toml"),
        "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\nscale = 40000\n",
    )
    .unwrap();
    let o = wobble_in(&d, &["render", "big.toml"]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).trim_end().ends_with("use scale <= 32767"),
        "{}",
        stderr(&o)
    );
}

/// A scene naming a missing OBJ: the error gives the path it was looked for at (absolute, the
/// scene's directory resolved) and the system's reason.
#[test]
fn missing_mesh_file_names_the_path_and_reason() {
    let d = Scratch::new("missing");
    std::fs::write(
        d.join("s.toml"),
        "[[mesh]]\nname = \"m\"\nfile = \"missing.obj\"\n[[object]]\nmesh = \"m\"\n",
    )
    .unwrap();
    let o = wobble_in(&d, &["render", "s.toml"]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains(&format!(
            "missing.obj ({})",
            d.join("missing.obj").display()
        )),
        "{e}"
    );
    assert!(e.contains("No such file or directory"), "{e}");
}

/// `gte replay` on a GPU command stream: one error naming the expected format, not one line
/// per stream line.
#[test]
fn gte_replay_of_another_format_is_one_error() {
    let stream = root().join("fixtures/gpu/quad.gpu");
    let o = wobble(&["gte", "replay", s(&stream)]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert_eq!(e.lines().count(), 1, "{e}");
    assert!(
        e.contains("not a GTE vector file") && e.contains("one JSON object a line"),
        "{e}"
    );
    assert!(stdout(&o).is_empty());
}

/// A binary file given as a command stream or a vector file: the error names the format
/// expected.
#[test]
fn binary_input_names_the_expected_format() {
    let d = Scratch::new("binary");
    let bin = d.join("x.gpu");
    std::fs::write(&bin, [0x89u8, b'P', b'N', b'G', 0xFF, 0x00, 0x13]).unwrap();
    for args in [
        vec!["replay", s(&bin), "-o", "/dev/null"],
        vec!["inspect", s(&bin), "-o", "rep"],
    ] {
        let o = wobble_in(&d, &args);
        assert!(!o.status.success());
        let e = stderr(&o);
        assert!(
            e.contains("not a GPU command stream") && e.contains("binary"),
            "{args:?}: {e}"
        );
    }
    let o = wobble_in(&d, &["gte", "replay", s(&bin)]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("not a GTE vector file"),
        "{}",
        stderr(&o)
    );
    assert_eq!(entries(&d), ["x.gpu"]);
}
