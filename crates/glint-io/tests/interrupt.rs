//! The atomic writer under a stop request (what SIGINT/SIGTERM raise in the CLI). A test binary
//! of its own: the request is one flag for the whole process, and raising it here must not stop
//! the writes of other tests.

use std::io::Write;
use std::sync::atomic::Ordering;

use glint_io::atomic::{write_atomically, write_file_atomically};

#[test]
fn a_requested_stop_ends_the_write_and_leaves_neither_output_nor_temporary() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("out.exr");
    std::fs::write(&path, "previous").unwrap();
    // The stop arrives in the middle of the write: the writer's next write fails.
    let result = write_atomically(&path, |file| {
        let io = |error| glint_io::atomic::AtomicWriteError { path: path.clone(), error };
        file.write_all(&[0; 4096]).map_err(io)?;
        glint_io::interrupt::flag().store(true, Ordering::Relaxed);
        file.write_all(&[0; 4096]).map_err(io)
    });
    let error = result.expect_err("interrupted");
    assert!(error.is_interrupted(), "{error}");
    assert_eq!(error.to_string(), format!("{}: interrupted", path.display()));
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous", "the target is left as it was");
    // A writer that ignores the failed write (an encoder that swallows it) is stopped all the same.
    let other = dir.path().join("other.png");
    let error = write_atomically(&other, |file| {
        let _ = file.write_all(b"ignored");
        Ok::<(), glint_io::atomic::AtomicWriteError>(())
    })
    .expect_err("interrupted");
    assert!(error.is_interrupted());
    assert!(write_file_atomically(&other, b"x").is_err());
    let names: Vec<String> =
        std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    assert_eq!(names, ["out.exr"], "no temporary, no new output");
}
