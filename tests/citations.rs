//! Citations of the hardware reference resolve.
//!
//! Every `docs/hardware/<page>.md` citation followed by a section sign and a number, in the
//! Rust sources under `crates/` and `tests/`, the Markdown under `docs/` and `README.md`, must
//! name a page that exists and a section it has (`## N.` or `### N.M`). A citation of
//! `gte.md`/`gpu.md` with a section that does not start with `docs/hardware/` points at a
//! page outside the repository and fails too.

use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

/// The section sign, written as an escape so this file holds no citation of its own.
const SECTION_SIGN: char = '\u{a7}';
const PREFIX: &str = "docs/hardware/";
const LEGACY_PAGES: [&str; 2] = ["gte.md", "gpu.md"];

/// One `docs/hardware/<page>.md <section sign><section>` citation.
#[derive(Debug, PartialEq, Eq)]
struct Citation {
    page: String,
    /// "3" or "3.4"; empty when the section sign has no number after it.
    section: String,
    /// 1-based line of the page name.
    line: usize,
}

fn line_of(text: &str, index: usize) -> usize {
    text[..index].matches('\n').count() + 1
}

/// Steps over what may separate a page name from its section sign: a closing backtick,
/// blanks, and one line break followed by a `//`, `///` or `//!` comment marker. Returns the
/// text after the section sign, if one follows.
fn after_section_sign(rest: &str) -> Option<&str> {
    let rest = rest.strip_prefix('`').unwrap_or(rest);
    let rest = rest.trim_start_matches([' ', '\t']);
    let rest = match rest
        .strip_prefix("\r\n")
        .or_else(|| rest.strip_prefix('\n'))
    {
        Some(next_line) => {
            let next_line = next_line.trim_start_matches([' ', '\t']);
            let next_line = next_line
                .strip_prefix("///")
                .or_else(|| next_line.strip_prefix("//!"))
                .or_else(|| next_line.strip_prefix("//"))
                .unwrap_or(next_line);
            next_line.trim_start_matches([' ', '\t'])
        }
        None => rest,
    };
    rest.strip_prefix(SECTION_SIGN)
}

/// `N` or `N.M` at the start of `s`; a trailing full stop without digits ends the number.
fn section_number(s: &str) -> String {
    let major: String = s.chars().take_while(char::is_ascii_digit).collect();
    if major.is_empty() {
        return major;
    }
    let rest = &s[major.len()..];
    if let Some(after_dot) = rest.strip_prefix('.') {
        let minor: String = after_dot.chars().take_while(char::is_ascii_digit).collect();
        if !minor.is_empty() {
            return format!("{major}.{minor}");
        }
    }
    major
}

/// Every hardware-reference citation in `text`.
fn find_citations(text: &str) -> Vec<Citation> {
    let mut found = Vec::new();
    for (start, _) in text.match_indices(PREFIX) {
        let rest = &text[start + PREFIX.len()..];
        let name_len = rest
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-' || c == '_'))
            .unwrap_or(rest.len());
        if name_len == 0 {
            continue;
        }
        let Some(after_name) = rest[name_len..].strip_prefix(".md") else {
            continue;
        };
        if let Some(after_sign) = after_section_sign(after_name) {
            found.push(Citation {
                page: format!("{}.md", &rest[..name_len]),
                section: section_number(after_sign),
                line: line_of(text, start),
            });
        }
    }
    found
}

/// Lines holding a `gte.md`/`gpu.md` citation with a section that is not under
/// `docs/hardware/`: such a citation points at a page outside the repository.
fn find_legacy(text: &str) -> Vec<(&'static str, usize)> {
    let mut found = Vec::new();
    for page in LEGACY_PAGES {
        for (start, _) in text.match_indices(page) {
            if text[..start].ends_with(PREFIX) {
                continue;
            }
            if after_section_sign(&text[start + page.len()..]).is_some() {
                found.push((page, line_of(text, start)));
            }
        }
    }
    found.sort_by_key(|&(_, line)| line);
    found
}

/// Whether `page` has the heading `## N.` (for "N") or `### N.M` (for "N.M").
fn has_section(page: &str, section: &str) -> bool {
    if section.is_empty() {
        return false;
    }
    let (marker, wanted) = if section.contains('.') {
        ("### ", section.to_owned())
    } else {
        ("## ", format!("{section}."))
    };
    page.lines().any(|line| {
        line.strip_prefix(marker)
            .and_then(|heading| heading.strip_prefix(wanted.as_str()))
            .is_some_and(|after| after.is_empty() || after.starts_with(' '))
    })
}

/// The problems with `text` (from `origin`): unresolved citations and legacy ones.
/// `load_page` returns a reference page's text by file name, or `None` if it does not exist.
fn check_text(
    origin: &str,
    text: &str,
    load_page: &mut dyn FnMut(&str) -> Option<String>,
) -> (usize, Vec<String>) {
    let mut problems = Vec::new();
    let citations = find_citations(text);
    for citation in &citations {
        let Citation {
            page,
            section,
            line,
        } = citation;
        match load_page(page) {
            None => problems.push(format!(
                "{origin}:{line}: docs/hardware/{page} does not exist"
            )),
            Some(body) if !has_section(&body, section) => problems.push(format!(
                "{origin}:{line}: docs/hardware/{page} has no section {SECTION_SIGN}{section:?}"
            )),
            Some(_) => {}
        }
    }
    for (page, line) in find_legacy(text) {
        problems.push(format!(
            "{origin}:{line}: {page} cited with a section but not as docs/hardware/{page}"
        ));
    }
    (citations.len(), problems)
}

fn collect(dir: &Path, extension: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                collect(&path, extension, out);
            }
        } else if path.extension().is_some_and(|e| e == extension) {
            out.push(path);
        }
    }
}

#[test]
fn every_hardware_citation_resolves() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    collect(&root.join("crates"), "rs", &mut files);
    collect(&root.join("tests"), "rs", &mut files);
    collect(&root.join("docs"), "md", &mut files);
    files.push(root.join("README.md"));
    files.sort();

    let mut pages: HashMap<String, Option<String>> = HashMap::new();
    let mut load_page = |name: &str| {
        pages
            .entry(name.to_owned())
            .or_insert_with(|| fs::read_to_string(root.join(PREFIX).join(name)).ok())
            .clone()
    };
    let mut total = 0;
    let mut problems = Vec::new();
    for file in &files {
        let text = fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let origin = file
            .strip_prefix(root)
            .unwrap_or(file)
            .display()
            .to_string();
        let (count, found) = check_text(&origin, &text, &mut load_page);
        total += count;
        problems.extend(found);
    }
    assert!(
        problems.is_empty(),
        "{} citation problem(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
    assert!(
        total >= 100,
        "only {total} hardware citations found: is the scanner still finding them?"
    );
}

mod scanner {
    use super::*;

    fn s(text: &str) -> String {
        text.replace('$', &SECTION_SIGN.to_string())
    }

    fn pages(name: &str) -> Option<String> {
        match name {
            "gpu.md" => {
                Some("# GPU\n\n## 1. One\n## 3. Three\n### 3.4 Step four\n## 10. Ten\n".into())
            }
            "dma.md" => Some("## 6. End of list\n".into()),
            _ => None,
        }
    }

    #[test]
    fn finds_citations_with_their_sections() {
        let text = s(
            "see docs/hardware/gpu.md $3.4, and docs/hardware/dma.md $6.\n\
                      next line: (docs/hardware/gte.md $2).",
        );
        let found = find_citations(&text);
        let got: Vec<(&str, &str, usize)> = found
            .iter()
            .map(|c| (c.page.as_str(), c.section.as_str(), c.line))
            .collect();
        assert_eq!(
            got,
            [("gpu.md", "3.4", 1), ("dma.md", "6", 1), ("gte.md", "2", 2)]
        );
    }

    #[test]
    fn follows_a_citation_across_a_comment_line_break_and_a_backtick() {
        let text =
            s("/// the factor (docs/hardware/gte.md\n/// $8) and `docs/hardware/gpu.md` $1-$9");
        let found = find_citations(&text);
        assert_eq!(found.len(), 2);
        assert_eq!(
            (found[0].page.as_str(), found[0].section.as_str()),
            ("gte.md", "8")
        );
        assert_eq!(
            (found[1].page.as_str(), found[1].section.as_str()),
            ("gpu.md", "1")
        );
    }

    #[test]
    fn a_link_without_a_section_is_not_a_citation() {
        let text = s("[timing](docs/hardware/timing.md) and docs/hardware/README.md $1");
        assert!(find_citations(&text).is_empty());
        assert!(find_legacy("see docs/gpu.md and (gpu.md) for the crate").is_empty());
    }

    #[test]
    fn flags_bare_gte_and_gpu_citations_only() {
        let text = s(
            "a gpu.md $3 b\nc docs/hardware/gpu.md $3 d\ne (`gte.md` $1-$8)\n\
                      f (gte.md\n/// $8)\n[gpu.md](gpu.md) $2\nshared/docs/gte.md $4",
        );
        assert_eq!(
            find_legacy(&text),
            [("gpu.md", 1), ("gte.md", 3), ("gte.md", 4), ("gte.md", 7)]
        );
    }

    #[test]
    fn headings_match_whole_numbers_only() {
        let page = pages("gpu.md").unwrap_or_default();
        for present in ["1", "3", "3.4", "10"] {
            assert!(has_section(&page, present), "{present}");
        }
        for absent in ["", "0", "2", "3.5", "4", "34", "1.0"] {
            assert!(!has_section(&page, absent), "{absent}");
        }
    }

    #[test]
    fn a_good_citation_passes_and_bad_ones_fail() {
        let mut load = |name: &str| pages(name);
        let good = s("docs/hardware/gpu.md $3.4 and docs/hardware/dma.md $6");
        assert_eq!(check_text("good.rs", &good, &mut load), (2, vec![]));

        let bad = s("docs/hardware/gpu.md $2\ndocs/hardware/gpu.md $3.5\n\
                     docs/hardware/nosuch.md $1\ndocs/hardware/gpu.md $x\ngte.md $5");
        let (count, problems) = check_text("bad.rs", &bad, &mut load);
        assert_eq!(count, 4);
        assert_eq!(problems.len(), 5, "{problems:#?}");
        assert!(problems[0].starts_with("bad.rs:1:"), "{}", problems[0]);
        assert!(
            problems[2].contains("nosuch.md does not exist"),
            "{}",
            problems[2]
        );
        assert!(
            problems[4].starts_with("bad.rs:5: gte.md"),
            "{}",
            problems[4]
        );
    }
}
