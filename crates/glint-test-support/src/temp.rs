//! Temporary folders for tests that write files (tempfile: a unique name, removed when dropped,
//! also when the test panics).

use std::ops::Deref;
use std::path::Path;

/// A fresh, empty folder under the system temp dir, removed when dropped. It derefs to its
/// path: `dir.join("out.png")`.
#[derive(Debug)]
pub struct TempDir(tempfile::TempDir);

impl TempDir {
    /// A folder whose name starts with `glint-TAG-` (to tell leftovers of a killed run apart).
    pub fn new(tag: &str) -> Self {
        let dir = tempfile::Builder::new().prefix(&format!("glint-{tag}-")).tempdir().expect("create a temp dir");
        Self(dir)
    }

    /// File names in the folder, sorted.
    pub fn listing(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(self.0.path())
            .expect("read temp dir")
            .map(|e| e.expect("dir entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Deref for TempDir {
    type Target = Path;

    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for TempDir {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}
