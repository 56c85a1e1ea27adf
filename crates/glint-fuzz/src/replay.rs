//! Replaying a corpus folder on stable: every file through its target's check, each panic
//! caught and named, so one test reports all failing inputs at once.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use crate::Target;

/// What a replay found.
#[derive(Debug, Default)]
pub struct ReplayReport {
    /// Inputs replayed.
    pub inputs: usize,
    /// The inputs whose check panicked, with the panic's message.
    pub failures: Vec<(PathBuf, String)>,
}

/// Replays every file of `folder` (not recursing) through `target`'s check. A missing folder
/// is an error: a corpus that silently vanished would make the replay pass on nothing.
pub fn replay_folder(target: Target, folder: &Path) -> std::io::Result<ReplayReport> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(folder)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    let mut report = ReplayReport::default();
    for file in files {
        let data = std::fs::read(&file)?;
        report.inputs += 1;
        if let Err(panic) = catch_unwind(AssertUnwindSafe(|| target.check(&data))) {
            let message = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| (*s).to_string()))
                .unwrap_or_else(|| "a panic without a message".into());
            report.failures.push((file, message));
        }
    }
    Ok(report)
}
