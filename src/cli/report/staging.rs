//! The report's files are written into a hidden folder inside `--out` and moved into place
//! together at the end, so a sweep or merge that fails part-way (a full disk, an interrupt, a
//! render error) leaves `--out` as it was: never this run's first plots beside an earlier run's
//! report. Each move is a rename within one folder, so each file appears whole.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use tempfile::TempDir;

pub struct Staging {
    dir: TempDir,
    out: PathBuf,
}

impl Staging {
    /// A staging folder in `out` (created if missing).
    pub fn new(out: &Path) -> anyhow::Result<Self> {
        std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
        let dir = TempDir::with_prefix_in(".glint-report-", out)
            .with_context(|| format!("cannot create a folder in {}", out.display()))?;
        Ok(Self { dir, out: out.to_path_buf() })
    }

    /// Where the run writes its files.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// Where `staged`, a file written into the staging folder, lies once the run is published.
    pub fn published(&self, staged: &Path) -> PathBuf {
        staged.file_name().map_or_else(|| staged.to_path_buf(), |name| self.out.join(name))
    }

    /// Moves every staged file into `--out`. A read-only file there is refused before anything
    /// moves, unless `force`, as `glint render` and `glint merge` refuse one.
    pub fn publish(self, force: bool) -> anyhow::Result<()> {
        let mut names = Vec::new();
        for entry in std::fs::read_dir(self.dir.path()).context("reading the report's staging folder")? {
            names.push(entry.context("reading the report's staging folder")?.file_name());
        }
        names.sort();
        for name in &names {
            let dest = self.out.join(name);
            let read_only = std::fs::metadata(&dest).is_ok_and(|m| m.permissions().readonly());
            if read_only && !force {
                bail!("{}: read-only; pass --force to replace it; nothing was written", dest.display());
            }
        }
        for name in &names {
            let dest = self.out.join(name);
            std::fs::rename(self.dir.path().join(name), &dest)
                .with_context(|| format!("cannot move the new {} into place", dest.display()))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_appear_only_when_published_and_a_read_only_one_is_kept_without_force() {
        let root = tempfile::tempdir().expect("temp folder");
        let out = root.path().join("out");
        let staging = Staging::new(&out).expect("staging");
        std::fs::write(staging.path().join("report.md"), "new").expect("write");
        assert!(!out.join("report.md").exists(), "a staged file is not in --out yet");
        staging.publish(false).expect("publish");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("published"), "new");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1, "the staging folder is gone");

        // A read-only report is refused, and nothing of the run moves.
        let mut permissions = std::fs::metadata(out.join("report.md")).expect("meta").permissions();
        permissions.set_readonly(true);
        std::fs::set_permissions(out.join("report.md"), permissions).expect("chmod");
        let staging = Staging::new(&out).expect("staging");
        std::fs::write(staging.path().join("a.png"), "plot").expect("write");
        std::fs::write(staging.path().join("report.md"), "newer").expect("write");
        let e = staging.publish(false).expect_err("read-only").to_string();
        assert!(e.contains("report.md: read-only; pass --force"), "{e}");
        assert!(!out.join("a.png").exists(), "a refused run moved a file");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1, "the staging folder is gone");

        let staging = Staging::new(&out).expect("staging");
        std::fs::write(staging.path().join("report.md"), "forced").expect("write");
        staging.publish(true).expect("--force");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("published"), "forced");

        // Dropped unpublished (a failed run): --out keeps what it had.
        let staging = Staging::new(&out).expect("staging");
        std::fs::write(staging.path().join("report.md"), "half").expect("write");
        drop(staging);
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("kept"), "forced");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1);
    }
}
