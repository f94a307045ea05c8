//! Input files: read with errors that name the file, the operating system's reason and, for a
//! file of the wrong kind, the format the command expected; and the default output name
//! derived from an input.

use std::path::{Path, PathBuf};

/// The text of `path`; a binary file (not UTF-8) is reported as not being `what`.
pub fn read_text(path: &Path, what: &str) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    String::from_utf8(bytes).map_err(|e| crate::gpu_input::binary_error(path, e.as_bytes(), what))
}

/// The default image output of a command reading `input`: its file name with the last
/// extension replaced by `.png`, in the current directory (`quad.gpu` -> `quad.png`,
/// `x.vram.bin` -> `x.png`).
pub fn default_output(input: &Path) -> PathBuf {
    let stem = input.file_stem().unwrap_or_default();
    PathBuf::from(stem).with_extension("png")
}

/// Refuse an output that is the input file itself (the same file through any path).
pub fn not_the_input(output: &Path, input: &Path) -> Result<(), String> {
    let same = match (std::fs::canonicalize(output), std::fs::canonicalize(input)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    if same {
        return Err(format!(
            "{}: this is the input file; name another output with -o",
            output.display()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_output_replaces_the_last_extension() {
        assert_eq!(
            default_output(Path::new("dir/quad.gpu")),
            Path::new("quad.png")
        );
        assert_eq!(
            default_output(Path::new("/a/x.vram.bin")),
            Path::new("x.png")
        );
        assert_eq!(default_output(Path::new("noext")), Path::new("noext.png"));
    }
}
