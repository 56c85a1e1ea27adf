//! Atomic file output, the one implementation every writer uses (images, report files, the
//! viewer's scene files and recent list): a reader never sees a half-written file, and a failed
//! write leaves neither the target nor a temporary behind.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A file-system failure of an atomic write, naming the target (not the temporary).
/// The I/O error is part of the message, not a `source()`: see `SceneError::Io`.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {error}")]
pub struct AtomicWriteError {
    pub path: PathBuf,
    pub error: std::io::Error,
}

/// The temporary beside `path`: same folder (so the rename stays on one file system), hidden,
/// and named after the target and this process.
fn temporary_for(path: &Path) -> PathBuf {
    let name = path.file_name().map_or_else(|| "file".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}

/// Creates a temporary file beside `path`, lets `write` fill it, syncs it to disk and renames it
/// over `path`. If any step fails the temporary is removed and `path` is left as it was.
/// `write`'s own errors pass through; those of the file system become `E` by `From`.
pub fn write_atomically<E: From<AtomicWriteError>>(
    path: &Path,
    write: impl FnOnce(&mut File) -> Result<(), E>,
) -> Result<(), E> {
    let tmp = temporary_for(path);
    let io = |error| E::from(AtomicWriteError { path: path.to_owned(), error });
    let result = File::create(&tmp).map_err(io).and_then(|mut file| {
        write(&mut file)?;
        file.sync_all().map_err(io)?;
        drop(file);
        std::fs::rename(&tmp, path).map_err(io)
    });
    if result.is_err() {
        // The temporary may not exist (its creation failed): nothing to report then.
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// `bytes` as the whole content of `path`, atomically.
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> Result<(), AtomicWriteError> {
    write_atomically(path, |file| {
        file.write_all(bytes).map_err(|error| AtomicWriteError { path: path.to_owned(), error })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder for one test, removed at the end.
    fn folder(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("glint-core-atomic-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create test folder");
        dir
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .expect("read test folder")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_replaces_the_target_and_leaves_no_temporary() {
        let dir = folder("ok");
        let path = dir.join("out.txt");
        std::fs::write(&path, "old").unwrap();
        write_file_atomically(&path, b"new").expect("write");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(listing(&dir), ["out.txt"]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_failing_writer_leaves_neither_the_target_nor_a_temporary() {
        let dir = folder("writer");
        let path = dir.join("out.txt");
        let result = write_atomically(&path, |file| {
            file.write_all(b"half").expect("the temporary is writable");
            Err(AtomicWriteError { path: path.clone(), error: std::io::Error::other("encoder failed") })
        });
        assert_eq!(result.expect_err("the writer failed").to_string(), format!("{}: encoder failed", path.display()));
        assert!(listing(&dir).is_empty(), "left behind: {:?}", listing(&dir));
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_failing_rename_names_the_target_and_leaves_no_temporary() {
        // A folder in the target's place: the temporary is written, the rename over it fails.
        let dir = folder("rename");
        let path = dir.join("taken");
        std::fs::create_dir(&path).unwrap();
        std::fs::write(path.join("inside"), "kept").unwrap();
        let error = write_file_atomically(&path, b"new").expect_err("cannot replace a folder");
        assert_eq!(error.path, path);
        assert!(error.to_string().starts_with(&format!("{}: ", path.display())), "{error}");
        assert_eq!(listing(&dir), ["taken"]);
        assert_eq!(std::fs::read_to_string(path.join("inside")).unwrap(), "kept");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_missing_folder_fails_without_creating_anything() {
        let dir = folder("missing");
        let path = dir.join("nowhere").join("out.txt");
        let error = write_file_atomically(&path, b"new").expect_err("no such folder");
        assert_eq!(error.error.kind(), std::io::ErrorKind::NotFound);
        assert!(listing(&dir).is_empty());
        std::fs::remove_dir_all(dir).unwrap();
    }
}
