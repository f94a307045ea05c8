//! docs/architecture.md lists every module of every crate.
//!
//! The modules of a crate are the `mod NAME;` declarations reachable from its root
//! (`src/lib.rs`, `src/main.rs`), each file's own declarations followed into the file they
//! name; a declaration under `#[cfg(test)]` is a test, not a module of the crate. The
//! document's module table has one row per group of modules: `| crate | modules | owns |`,
//! the modules written in backticks as paths from the crate's `src/` (`commands/rtp`), a
//! folder module by its folder name (`commands` or `commands/`). Every module must be in a
//! row of its crate, and every path in the modules column must be a module.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The page the test checks.
const PAGE: &str = "docs/architecture.md";

/// One `mod NAME;` declaration: its name, and whether `#[cfg(test)]` comes before it.
#[derive(Debug, PartialEq, Eq)]
struct Declaration {
    name: String,
    test_only: bool,
}

/// The file modules `text` declares (`mod a;`, `pub mod b;`, `pub(crate) mod c;`); inline
/// modules (`mod d { ... }`) are part of their file.
fn declarations(text: &str) -> Vec<Declaration> {
    let mut found = Vec::new();
    let mut test_only = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with("#[") {
            test_only |= line == "#[cfg(test)]";
            continue;
        }
        let rest = match line.strip_prefix("pub") {
            Some(after) if after.starts_with(' ') || after.starts_with('(') => {
                let after = after.trim_start();
                match after.strip_prefix('(') {
                    Some(scoped) => scoped.split_once(')').map_or("", |(_, r)| r.trim_start()),
                    None => after,
                }
            }
            _ => line,
        };
        if let Some(name) = rest
            .strip_prefix("mod ")
            .and_then(|r| r.trim_end().strip_suffix(';'))
            .map(str::trim)
            .filter(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'))
        {
            found.push(Declaration {
                name: name.to_owned(),
                test_only,
            });
        }
        if !line.is_empty() && !line.starts_with("//") {
            test_only = false;
        }
    }
    found
}

/// The file that holds module `name` declared in `parent` (a crate root or `mod.rs` holds
/// its children beside it; `a.rs` holds them in `a/`).
fn module_file(parent: &Path, name: &str) -> Option<PathBuf> {
    let stem = parent.file_stem()?.to_str()?;
    let dir = parent.parent()?;
    let dir = if matches!(stem, "lib" | "main" | "mod") {
        dir.to_path_buf()
    } else {
        dir.join(stem)
    };
    [
        dir.join(format!("{name}.rs")),
        dir.join(name).join("mod.rs"),
    ]
    .into_iter()
    .find(|f| f.is_file())
}

/// Every module of the crate whose root file is `root`, as paths from its `src/`
/// (`commands`, `commands/rtp`), and the problems met (a declared module with no file).
fn crate_modules(root: &Path) -> (BTreeSet<String>, Vec<String>) {
    let mut modules = BTreeSet::new();
    let mut problems = Vec::new();
    let mut pending = vec![(root.to_path_buf(), String::new())];
    while let Some((file, path)) = pending.pop() {
        let text = fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        for d in declarations(&text) {
            if d.test_only {
                continue;
            }
            let module = if path.is_empty() {
                d.name.clone()
            } else {
                format!("{path}/{}", d.name)
            };
            match module_file(&file, &d.name) {
                Some(child) => pending.push((child, module.clone())),
                None => problems.push(format!("{}: mod {} has no file", file.display(), d.name)),
            }
            modules.insert(module);
        }
    }
    (modules, problems)
}

/// The modules column of the page's table, by crate: every backticked path in the second
/// cell of a row whose first cell names a crate, a trailing `/` dropped. Lines inside code
/// blocks (a diagram) are not rows.
fn documented(page: &str) -> BTreeMap<String, BTreeSet<String>> {
    let mut by_crate: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut in_code = false;
    for line in page.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        let Some(row) = line.strip_prefix('|').filter(|_| !in_code) else {
            continue;
        };
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        let (Some(&krate), Some(&modules)) = (cells.first(), cells.get(1)) else {
            continue;
        };
        if krate.is_empty() || krate == "crate" || krate.starts_with('-') {
            continue;
        }
        let entry = by_crate.entry(krate.to_owned()).or_default();
        for (k, piece) in modules.split('`').enumerate() {
            if k % 2 == 1 {
                entry.insert(piece.trim_end_matches('/').to_owned());
            }
        }
    }
    by_crate
}

/// What is wrong between the modules in the code and those in the page.
fn compare(
    code: &BTreeMap<String, BTreeSet<String>>,
    page: &BTreeMap<String, BTreeSet<String>>,
) -> Vec<String> {
    let mut problems = Vec::new();
    let empty = BTreeSet::new();
    for (krate, modules) in code {
        let listed = page.get(krate).unwrap_or(&empty);
        for m in modules.difference(listed) {
            problems.push(format!("{PAGE}: crate {krate}: module `{m}` is not listed"));
        }
        for m in listed.difference(modules) {
            problems.push(format!(
                "{PAGE}: crate {krate}: `{m}` is listed but is no module"
            ));
        }
    }
    for krate in page.keys().filter(|k| !code.contains_key(*k)) {
        problems.push(format!("{PAGE}: `{krate}` is no crate of the workspace"));
    }
    problems
}

#[test]
fn architecture_lists_every_module() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut code = BTreeMap::new();
    let mut problems = Vec::new();
    let mut crates: Vec<PathBuf> = fs::read_dir(root.join("crates"))
        .expect("crates/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("Cargo.toml").is_file())
        .collect();
    crates.sort();
    for dir in &crates {
        let name = dir
            .file_name()
            .and_then(|n| n.to_str())
            .expect("crate folder name")
            .to_owned();
        let mut modules = BTreeSet::new();
        for root_file in ["src/lib.rs", "src/main.rs"].map(|f| dir.join(f)) {
            if root_file.is_file() {
                let (found, missing) = crate_modules(&root_file);
                modules.extend(found);
                problems.extend(missing);
            }
        }
        code.insert(name, modules);
    }
    // The four crates have modules; a single-file package (mini-emulator) has none.
    assert!(
        ["gte", "gpu", "wobble", "wobble-cli"]
            .iter()
            .all(|k| code.get(*k).is_some_and(|m| !m.is_empty())),
        "crates found: {code:?}"
    );
    let page = fs::read_to_string(root.join(PAGE)).expect(PAGE);
    problems.extend(compare(&code, &documented(&page)));
    assert!(
        problems.is_empty(),
        "{} problem(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
}

mod scanner {
    use super::*;

    fn names(text: &str) -> Vec<(String, bool)> {
        declarations(text)
            .into_iter()
            .map(|d| (d.name, d.test_only))
            .collect()
    }

    #[test]
    fn finds_file_modules_of_every_visibility() {
        let text = "mod a;\npub mod b;\npub(crate) mod c;\npub(in crate::x) mod d;\n\
                    #[cfg(feature = \"serde\")]\npub mod e;\n    mod f;";
        let found: Vec<String> = names(text).into_iter().map(|(n, _)| n).collect();
        assert_eq!(found, ["a", "b", "c", "d", "e", "f"]);
    }

    #[test]
    fn inline_modules_and_other_items_are_not_file_modules() {
        let text = "mod tests {\n    use super::*;\n}\npub use a::b;\n// mod c;\n\
                    fn module() {}\nmodule;\npub mod;";
        assert!(names(text).is_empty(), "{:?}", names(text));
    }

    #[test]
    fn a_module_under_cfg_test_is_a_test() {
        let text = "#[cfg(test)]\nmod tests;\nmod real;\n#[cfg(test)]\n/// doc\n#[allow(x)]\nmod \
                    helper;\n#[cfg(test)]\nfn f() {}\nmod after;";
        assert_eq!(
            names(text),
            [
                ("tests".to_owned(), true),
                ("real".to_owned(), false),
                ("helper".to_owned(), true),
                ("after".to_owned(), false)
            ]
        );
    }

    #[test]
    fn reads_the_modules_column_by_crate() {
        let page = "| crate | module | owns |\n|---|---|---|\n\
                    | gte | `commands/`, `commands/rtp` | the `Flag` type |\n\
                    | gte | `mac` | |\nnot a row `x`\n| wobble | `pipeline/gte_stage` | |\n\
                    ```text\n| diagram | `gte_stage` |\n```\n   | gte | `indented` |";
        let by_crate = documented(page);
        let gte: Vec<&str> = by_crate["gte"].iter().map(String::as_str).collect();
        assert_eq!(gte, ["commands", "commands/rtp", "mac"]);
        assert_eq!(by_crate.len(), 2);
    }

    #[test]
    fn a_module_missing_or_invented_fails() {
        let set = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
        let code = BTreeMap::from([
            ("gte".to_owned(), set(&["mac", "commands", "commands/rtp"])),
            ("gpu".to_owned(), set(&["dma"])),
        ]);
        let page = BTreeMap::from([
            ("gte".to_owned(), set(&["mac", "commands", "commands/rpt"])),
            ("gpu".to_owned(), set(&["dma"])),
            ("gpux".to_owned(), set(&["dma"])),
        ]);
        let problems = compare(&code, &page);
        assert_eq!(problems.len(), 3, "{problems:#?}");
        assert!(problems[0].contains("`commands/rtp` is not listed"));
        assert!(problems[1].contains("`commands/rpt` is listed but is no module"));
        assert!(problems[2].contains("`gpux` is no crate"));
        assert!(compare(&code, &code).is_empty());
    }
}
