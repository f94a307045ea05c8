//! The scratch directory of one test: the files a test writes and the outputs it checks
//! live in it, and it goes away with the test, so repeated runs leave nothing in the
//! system's temporary directory. One source for every test crate of the workspace: the root
//! package's support library includes it, and so do the `common` modules of the `wobble` and
//! `wobble-cli` tests and the `mini-emulator` test (by path).

use std::path::{Path, PathBuf};

/// A fresh, empty directory in `std::env::temp_dir()` named for the test crate, the process
/// and the test (`wobble-<crate>-<pid>-<name>`, e.g. `wobble-usage-<pid>-<name>`), removed
/// with everything under it when dropped, also when the test panics.
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
        remove(&path);
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
        remove(&self.0);
    }
}

/// Removes `path` and everything under it, ignoring errors. A test may leave a directory
/// without write permission (outputs.rs makes one read-only): where the first attempt
/// fails, directories get write permission back and removal is tried once more.
fn remove(path: &Path) {
    if std::fs::remove_dir_all(path).is_err() && path.is_dir() {
        writable(path);
        let _ = std::fs::remove_dir_all(path);
    }
}

/// Gives `dir` and every directory under it (not following symbolic links) owner read,
/// write and search permission.
#[cfg(unix)]
fn writable(dir: &Path) {
    use std::os::unix::fs::PermissionsExt;
    let _ = std::fs::set_permissions(dir, std::fs::Permissions::from_mode(0o755));
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            writable(&entry.path());
        }
    }
}

#[cfg(not(unix))]
fn writable(_: &Path) {}

#[cfg(all(test, unix))]
mod tests {
    use super::{Scratch, remove, writable};
    use std::os::unix::fs::PermissionsExt;

    fn mode(p: &std::path::Path) -> u32 {
        std::fs::metadata(p).unwrap().permissions().mode() & 0o777
    }

    /// Directories made read-only get owner read, write and search back, the nested ones too,
    /// and a read-only tree is removed whole (for a user other than root, only after that).
    #[test]
    fn read_only_trees_are_made_writable_and_removed() {
        let dir = Scratch::new("read-only-tree");
        let (a, b) = (dir.join("a"), dir.join("a").join("b"));
        std::fs::create_dir_all(&b).unwrap();
        std::fs::write(b.join("f"), b"x").unwrap();
        for p in [&b, &a] {
            std::fs::set_permissions(p, std::fs::Permissions::from_mode(0o500)).unwrap();
        }
        writable(&a);
        assert_eq!((mode(&a), mode(&b)), (0o755, 0o755));
        std::fs::set_permissions(&b, std::fs::Permissions::from_mode(0o500)).unwrap();
        std::fs::set_permissions(&a, std::fs::Permissions::from_mode(0o500)).unwrap();
        remove(&a);
        assert!(!a.exists());
    }
}
