//! Atomic file output, the one implementation every writer uses (images, report files, the
//! viewer's scene files and recent list): a reader never sees a half-written file, and a failed
//! or interrupted write leaves neither the target nor a temporary behind.
//!
//! The temporary is created beside the target (so the rename stays on one file system) with
//! `O_CREAT | O_EXCL` under a short random name (tempfile): it never opens an existing file
//! or follows a symbolic link planted in the folder, and its name fits beside any target name
//! the file system allows.

use std::cell::RefCell;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::interrupt::{self, Interrupted};

/// A file-system failure of an atomic write, naming the target (not the temporary).
/// The I/O error is part of the message, not a `source()`: see `SceneError::Io`.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {error}")]
pub struct AtomicWriteError {
    pub path: PathBuf,
    pub error: std::io::Error,
}

impl AtomicWriteError {
    /// Whether the write was stopped by `interrupt::requested`.
    pub fn is_interrupted(&self) -> bool {
        interrupt::is_interrupted(&self.error)
    }
}

/// Random characters of a temporary's name: 62^10 names, so a guess is hopeless, and the
/// whole name (`.glint-` + 10 + `.tmp`, 21 bytes) is far below the 255 bytes a name may have.
const RANDOM_CHARS: usize = 10;

/// A new, empty temporary in `folder`, created exclusively (`O_EXCL`: an existing file or
/// link of that name is an error, and tempfile then draws another name). Readable as
/// `File::create` would make it (0666 less the umask), not tempfile's private 0600.
fn create_temporary(folder: &Path, random_chars: usize) -> std::io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".glint-").suffix(".tmp").rand_bytes(random_chars);
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    // tempfile's error names the temporary ("at path /proc/.glint-WpS6LXsQwP.tmp"), a name
    // the user never gave: say which folder refused a new file, and why.
    builder.tempfile_in(folder).map_err(|e| {
        let kind = e.kind();
        std::io::Error::new(kind, format!("cannot create a file in the folder {}: {kind}", folder.display()))
    })
}

/// The temporary as the writer sees it: writes stop with `Interrupted` once a stop is
/// requested, and the first file-system error is kept, so that an encoder that wraps it in
/// its own error (the EXR encoder calls a full disk a format error) is not believed.
#[derive(Debug)]
pub struct TemporaryFile<'a> {
    file: &'a mut File,
    io_error: Option<std::io::Error>,
}

impl TemporaryFile<'_> {
    fn check<T>(&mut self, result: std::io::Result<T>) -> std::io::Result<T> {
        if let Err(e) = &result
            && self.io_error.is_none()
        {
            self.io_error = Some(std::io::Error::new(e.kind(), e.to_string()));
        }
        result
    }
}

impl Write for TemporaryFile<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if interrupt::requested() {
            return Err(std::io::Error::other(Interrupted));
        }
        let result = self.file.write(buf);
        self.check(result)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let result = self.file.flush();
        self.check(result)
    }
}

/// Read back what was written: a writer that fixes up its own header (`exr_order`).
impl Read for TemporaryFile<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let result = self.file.read(buf);
        self.check(result)
    }
}

impl Seek for TemporaryFile<'_> {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        let result = self.file.seek(pos);
        self.check(result)
    }
}

/// Creates a temporary file beside `path`, lets `write` fill it, syncs it to disk and renames it
/// over `path`. If any step fails, or a stop is requested (`interrupt`), the temporary is
/// removed and `path` is left as it was. `write`'s own errors pass through, except where the
/// file system failed under it or a stop was requested: those, and the file system's own
/// errors, become `E` by `From<AtomicWriteError>`.
pub fn write_atomically<E: From<AtomicWriteError>>(
    path: &Path,
    write: impl FnOnce(&mut TemporaryFile) -> Result<(), E>,
) -> Result<(), E> {
    let io = |error| E::from(AtomicWriteError { path: path.to_owned(), error });
    let folder = folder_of(path);
    // The temporary is removed when `tmp` drops, on every early return.
    let mut tmp = create_temporary(folder, RANDOM_CHARS).map_err(io)?;
    let mut file = TemporaryFile { file: tmp.as_file_mut(), io_error: None };
    let written = write(&mut file);
    let io_error = file.io_error.take();
    if interrupt::requested() {
        return Err(io(std::io::Error::other(Interrupted)));
    }
    match (written, io_error) {
        (Err(_), Some(error)) => return Err(io(error)),
        (Err(e), None) => return Err(e),
        (Ok(()), _) => {}
    }
    tmp.as_file().sync_all().map_err(io)?;
    if interrupt::requested() {
        return Err(io(std::io::Error::other(Interrupted)));
    }
    // Inside `all_or_nothing`: the synced temporary waits for the batch's other files.
    if let Some(tmp) = BATCH.with_borrow_mut(|batch| match batch {
        Some(staged) => {
            staged.push((tmp.into_temp_path(), path.to_owned()));
            None
        }
        None => Some(tmp),
    }) {
        tmp.persist(path).map_err(|e| io(e.error))?;
    }
    Ok(())
}

thread_local! {
    /// The written and synced temporaries of an `all_or_nothing` on this thread, each with its
    /// target, waiting to be renamed (`None` outside one).
    static BATCH: RefCell<Option<Vec<(tempfile::TempPath, PathBuf)>>> = const { RefCell::new(None) };
}

/// Why `all_or_nothing` changed nothing, or (rarely) only some of its targets.
#[derive(Debug, thiserror::Error)]
pub enum BatchError<E> {
    /// A write failed (or a stop was requested): every temporary was removed, no target changed.
    #[error("{0}")]
    Written(E),
    /// Every file was written, and a rename then failed (checked beforehand, so rare): the
    /// targets in `replaced` hold the new files, the others are as they were.
    #[error("{error}")]
    Renamed { error: AtomicWriteError, replaced: Vec<PathBuf> },
}

/// Runs `write`, whose atomic writes (`write_atomically`, on this thread) then each leave a
/// synced temporary beside its target instead of replacing it; when `write` has succeeded, all
/// are renamed over their targets, so that a set of files (`glint render --backend both`'s
/// three images) appears together or not at all: a full disk on the last one removes the
/// temporaries of the first ones too. A nested call joins the outer batch.
pub fn all_or_nothing<T, E: From<AtomicWriteError>>(write: impl FnOnce() -> Result<T, E>) -> Result<T, BatchError<E>> {
    if BATCH.with_borrow(Option::is_some) {
        return write().map_err(BatchError::Written);
    }
    /// Ends the batch on every way out, a panic included; dropping a `TempPath` removes it.
    struct Batch;
    impl Drop for Batch {
        fn drop(&mut self) {
            BATCH.with_borrow_mut(Option::take);
        }
    }
    let batch = Batch;
    BATCH.set(Some(Vec::new()));
    let written = write();
    let staged = BATCH.with_borrow_mut(Option::take).unwrap_or_default();
    drop(batch);
    let value = written.map_err(BatchError::Written)?;
    if interrupt::requested() {
        let path = staged.first().map(|(_, target)| target.clone()).unwrap_or_default();
        return Err(BatchError::Written(E::from(AtomicWriteError { path, error: std::io::Error::other(Interrupted) })));
    }
    let mut replaced = Vec::new();
    for (tmp, target) in staged {
        // The temporaries not yet renamed are removed as the rest of `staged` drops.
        if let Err(e) = tmp.persist(&target) {
            return Err(BatchError::Renamed { error: AtomicWriteError { path: target, error: e.error }, replaced });
        }
        replaced.push(target);
    }
    Ok(value)
}

/// The folder an atomic write of `path` makes its temporary in (`.` for a bare file name).
pub fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Why `write_atomically` could not replace a file in a folder, found before any writing.
#[derive(Debug)]
pub enum FolderRefuses {
    /// No file can be made there (a read-only mount, no permission).
    Create(std::io::Error),
    /// A file made there cannot be removed or renamed (append-only); it is left at `leftover`.
    Remove { leftover: PathBuf, error: std::io::Error },
}

/// Makes and removes a temporary where `write_atomically` would make the one of `path`: a
/// command that must not learn after minutes of work that its output folder refuses it.
pub fn probe_folder(path: &Path) -> Result<(), FolderRefuses> {
    let tmp = create_temporary(folder_of(path), RANDOM_CHARS).map_err(FolderRefuses::Create)?;
    let leftover = tmp.path().to_owned();
    tmp.close().map_err(|error| FolderRefuses::Remove { leftover, error })
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
    fn a_folder_that_takes_no_new_file_is_named_not_the_temporary() {
        // /proc takes no regular file; tempfile's own message named `/proc/.glint-….tmp`.
        let e = write_file_atomically(Path::new("/proc/x.png"), b"image").unwrap_err().to_string();
        assert!(e.contains("cannot create a file in the folder /proc"), "{e}");
        assert!(!e.contains(".glint-"), "{e}");
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

    /// A victim file outside the folder and a symbolic link to it at `link`.
    #[cfg(unix)]
    fn plant_link(dir: &Path, link: &Path) -> PathBuf {
        let victim = dir.with_extension("victim");
        std::fs::write(&victim, "precious").unwrap();
        std::os::unix::fs::symlink(&victim, link).unwrap();
        victim
    }

    #[cfg(unix)]
    #[test]
    fn a_link_planted_at_the_old_predictable_temporary_name_is_not_followed() {
        // Before: `.NAME.tmp-PID`, opened with File::create, which follows the link.
        let dir = folder("old-name");
        let path = dir.join("out.png");
        let link = dir.join(format!(".out.png.tmp-{}", std::process::id()));
        let victim = plant_link(&dir, &link);
        write_file_atomically(&path, b"image").expect("write");
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "image");
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink(), "the planted link is left alone");
        std::fs::remove_dir_all(dir).unwrap();
        std::fs::remove_file(victim).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_temporary_is_never_opened_through_a_link_at_a_guessed_name() {
        // With no random characters the name is known in advance (`.glint-.tmp`): a link
        // planted there makes the creation fail (O_EXCL) instead of writing through it. With
        // them, tempfile draws another name on that failure.
        let dir = folder("guessed");
        let victim = plant_link(&dir, &dir.join(".glint-.tmp"));
        let error = create_temporary(&dir, 0).expect_err("an existing name is never opened");
        assert_eq!(error.kind(), std::io::ErrorKind::AlreadyExists);
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        let mut tmp = create_temporary(&dir, RANDOM_CHARS).expect("another name");
        tmp.write_all(b"data").unwrap();
        let name = tmp.path().file_name().unwrap().to_string_lossy().into_owned();
        assert!(name.starts_with(".glint-") && name.len() == ".glint-.tmp".len() + RANDOM_CHARS, "{name}");
        drop(tmp);
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        assert_eq!(listing(&dir), [".glint-.tmp"], "the temporary is removed, the planted link kept");
        std::fs::remove_dir_all(dir).unwrap();
        std::fs::remove_file(victim).unwrap();
    }

    #[test]
    fn a_batch_whose_last_write_fails_leaves_every_target_as_it_was() {
        // `--backend both` on a nearly full disk: the -gpu image failed after -cpu was in place.
        let dir = folder("batch-fails");
        std::fs::write(dir.join("a.txt"), "old a").unwrap();
        let result = all_or_nothing(|| {
            write_file_atomically(&dir.join("a.txt"), b"new a")?;
            write_file_atomically(&dir.join("b.txt"), b"new b")?;
            assert_eq!(listing(&dir).len(), 3, "two temporaries beside a.txt: {:?}", listing(&dir));
            write_atomically(&dir.join("c.txt"), |file| {
                file.write_all(b"half").expect("the temporary is writable");
                Err(AtomicWriteError { path: dir.join("c.txt"), error: std::io::ErrorKind::StorageFull.into() })
            })
        });
        let e = result.expect_err("the last write failed");
        assert!(matches!(e, BatchError::Written(_)), "{e:?}");
        assert_eq!(listing(&dir), ["a.txt"], "a temporary or a new file is left");
        assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "old a");
        // The batch is over: a later write replaces its target at once.
        write_file_atomically(&dir.join("b.txt"), b"later").expect("write");
        assert_eq!(listing(&dir), ["a.txt", "b.txt"]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_batch_that_succeeds_replaces_every_target_and_says_which_a_failed_rename_left() {
        let dir = folder("batch-ok");
        std::fs::write(dir.join("a.txt"), "old a").unwrap();
        let value = all_or_nothing(|| -> Result<u8, AtomicWriteError> {
            write_file_atomically(&dir.join("a.txt"), b"new a")?;
            write_file_atomically(&dir.join("b.txt"), b"new b")?;
            assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "old a", "replaced before the end");
            Ok(7)
        });
        assert_eq!(value.expect("written"), 7);
        assert_eq!(listing(&dir), ["a.txt", "b.txt"]);
        assert_eq!(std::fs::read_to_string(dir.join("a.txt")).unwrap(), "new a");
        // A folder made in c's place after its write: the rename fails and says what was replaced.
        let e = all_or_nothing(|| -> Result<(), AtomicWriteError> {
            write_file_atomically(&dir.join("a.txt"), b"newer a")?;
            write_file_atomically(&dir.join("c"), b"c")?;
            write_file_atomically(&dir.join("d.txt"), b"d")?;
            std::fs::create_dir(dir.join("c")).unwrap();
            Ok(())
        })
        .expect_err("c is a folder");
        let BatchError::Renamed { error, replaced } = e else { panic!("{e:?}") };
        assert_eq!((error.path, replaced), (dir.join("c"), vec![dir.join("a.txt")]));
        assert_eq!(listing(&dir), ["a.txt", "b.txt", "c"], "d's temporary is left");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn a_target_name_of_250_bytes_is_written() {
        // 250 bytes is a legal name (the limit is 255); the temporary's name must not grow with it.
        let dir = folder("long");
        let name = format!("{}.png", "n".repeat(246));
        assert_eq!(name.len(), 250);
        write_file_atomically(&dir.join(&name), b"image").expect("write");
        assert_eq!(listing(&dir), [name]);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn the_output_is_readable_as_file_create_makes_it_not_private() {
        use std::os::unix::fs::PermissionsExt;
        let dir = folder("mode");
        let path = dir.join("out.txt");
        write_file_atomically(&path, b"new").expect("write");
        std::fs::write(dir.join("reference.txt"), "x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&path), mode(&dir.join("reference.txt")));
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
