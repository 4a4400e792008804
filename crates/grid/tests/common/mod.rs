//! Helpers shared by the map-reading tests.

use std::path::{Path, PathBuf};

/// A fresh scratch folder for one test of the file `suite` (`io-errors`, …), removed when
/// the test ends (also when it fails).
pub fn scratch(suite: &str, test: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("frontier-{suite}-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch folder");
    Scratch(dir)
}

/// A scratch folder, removed on drop.
pub struct Scratch(PathBuf);

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
