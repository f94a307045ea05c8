//! The scratch directory of one test: the files a test writes and the outputs it checks
//! live in it, and it goes away with the test, so repeated runs leave nothing in the
//! system's temporary directory.

use std::path::{Path, PathBuf};

/// A fresh, empty directory in `std::env::temp_dir()` named for the test binary, the
/// process and the test (`wobble-scene-<pid>-<name>`), removed with everything under it when
/// dropped, also when the test panics.
pub struct Scratch(PathBuf);

impl Scratch {
    /// Creates the directory for the test `name` (unique within the test binary), removing a
    /// stale one of the same name first.
    pub fn new(name: &str) -> Scratch {
        let path = std::env::temp_dir().join(format!(
            "wobble-{}-{}-{name}",
            env!("CARGO_CRATE_NAME"),
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path)
            .unwrap_or_else(|e| panic!("scratch directory {}: {e}", path.display()));
        Scratch(path)
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
