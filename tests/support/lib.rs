//! Shared helpers for the workspace integration tests in `tests/`.

use std::path::{Path, PathBuf};

/// The scratch directory of one test: a fresh, empty directory in `std::env::temp_dir()`
/// named for the process and the test (`wobble-suite-<pid>-<name>`), removed with everything
/// under it when dropped, also when the test panics, so repeated runs leave nothing in the
/// system's temporary directory.
pub struct Scratch(PathBuf);

impl Scratch {
    /// Creates the directory for the test `name` (unique within the test binary), removing a
    /// stale one of the same name first.
    pub fn new(name: &str) -> Scratch {
        let path = std::env::temp_dir().join(format!("wobble-suite-{}-{name}", std::process::id()));
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
