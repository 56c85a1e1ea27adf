//! The report's files are written into a hidden folder inside `--out` and moved into place
//! together at the end, so a sweep or merge that fails part-way (a full disk, an interrupt, a
//! render error) leaves `--out` as it was: never this run's first plots beside an earlier run's
//! report. Each move is a rename within one folder, so each file appears whole.

use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

use crate::cli::console::tell;
use tempfile::TempDir;

pub struct Staging {
    dir: TempDir,
    out: PathBuf,
    /// The folders this run made for `out`, `out` first, then each parent it made: a run that
    /// fails removes them again.
    made: Vec<PathBuf>,
}

impl Staging {
    /// A staging folder in `out` (created if missing), for a run that will write `files` there:
    /// a name that is a folder, or a read-only file without `force`, is refused now, before the
    /// sweep, instead of when its minutes of results are published.
    pub fn new(out: &Path, files: &[String], force: bool) -> anyhow::Result<Self> {
        for name in files {
            check_destination(&out.join(name), force, "nothing was run")?;
        }
        let made: Vec<PathBuf> =
            out.ancestors().take_while(|a| !a.as_os_str().is_empty() && !a.exists()).map(Path::to_path_buf).collect();
        crate::cli::output_path::create_folder("--out", out)?;
        let dir = TempDir::with_prefix_in(".glint-report-", out)
            .with_context(|| format!("cannot create a folder in {}", out.display()))?;
        Ok(Self { dir, out: out.to_path_buf(), made })
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
    /// moves, unless `force`, as `glint render` and `glint merge` refuse one. With `supersede`
    /// (a whole report, not a shard), the files of an earlier report in `--out` that this one
    /// does not write (`error_vs_time_OTHER.png` of a scene it leaves out) are removed after
    /// the move and named on stderr: left, they sat beside the new report.md as if part of it.
    /// Only names a report writes (`is_report_file`) are removed, never other files.
    pub fn publish(mut self, force: bool, supersede: bool) -> anyhow::Result<()> {
        let mut names = Vec::new();
        for entry in std::fs::read_dir(self.dir.path()).context("reading the report's staging folder")? {
            names.push(entry.context("reading the report's staging folder")?.file_name());
        }
        names.sort();
        for name in &names {
            check_destination(&self.out.join(name), force, "nothing was written")?;
        }
        let stale = if supersede { self.stale(&names)? } else { Vec::new() };
        for name in &stale {
            let path = self.out.join(name);
            if std::fs::metadata(&path).is_ok_and(|m| m.permissions().readonly()) && !force {
                bail!(
                    "{}: a file of an earlier report that this one does not write, read-only; pass --force to \
                     remove it, or move it away; nothing was written",
                    path.display()
                );
            }
        }
        for name in &names {
            let dest = self.out.join(name);
            std::fs::rename(self.dir.path().join(name), &dest)
                .with_context(|| format!("cannot move the new {} into place", dest.display()))?;
        }
        // Published, `out` is the run's result even where the run made it.
        self.made.clear();
        let mut removed = Vec::new();
        for name in &stale {
            let path = self.out.join(name);
            match std::fs::remove_file(&path) {
                Ok(()) => removed.push(name.to_string_lossy().into_owned()),
                Err(e) => tell!(
                    "warning: {}: a file of an earlier report that this one does not write, and it cannot be \
                     removed ({}); remove it",
                    path.display(),
                    e.kind()
                ),
            }
        }
        if !removed.is_empty() {
            tell!(
                "removed {} of an earlier report in {} that this one does not write: {}",
                if removed.len() == 1 { "1 file".to_string() } else { format!("{} files", removed.len()) },
                self.out.display(),
                removed.join(", ")
            );
        }
        Ok(())
    }

    /// The files in `--out` that a report writes (`is_report_file`) and this run, which
    /// staged `staged`, does not: an earlier report's. Sorted.
    fn stale(&self, staged: &[std::ffi::OsString]) -> anyhow::Result<Vec<std::ffi::OsString>> {
        let read = || format!("reading {}", self.out.display());
        let mut stale = Vec::new();
        for entry in std::fs::read_dir(&self.out).with_context(read)? {
            let entry = entry.with_context(read)?;
            let name = entry.file_name();
            // A folder of such a name is not a report's file (a link is: the report's rename
            // would replace it).
            let folder = entry.file_type().is_ok_and(|t| t.is_dir());
            if !folder && name.to_str().is_some_and(is_report_file) && !staged.contains(&name) {
                stale.push(name);
            }
        }
        stale.sort();
        Ok(stale)
    }
}

/// Whether `name` is one a whole report writes: its tables, and its plots of any scene.
pub fn is_report_file(name: &str) -> bool {
    let plot = |prefix: &str| {
        name.strip_prefix(prefix).and_then(|rest| rest.strip_suffix(".png")).is_some_and(|scene| !scene.is_empty())
    };
    super::TABLES.contains(&name) || plot("error_vs_time_") || plot("gi_vs_time_")
}

impl Drop for Staging {
    /// A run that did not publish leaves `out` as it was: without the staging folder (the
    /// `TempDir` removes it after this), and not there at all where the run made it.
    fn drop(&mut self) {
        if !self.made.is_empty() {
            let _ = std::fs::remove_dir_all(self.dir.path());
        }
        // Only those still empty: remove_dir refuses a folder with files (made meanwhile).
        for folder in &self.made {
            let _ = std::fs::remove_dir(folder);
        }
    }
}

/// Whether a file may be moved to `dest`: not over a folder (the rename fails), and not over a
/// read-only file unless `force`; `outcome` says what the refusal left undone.
fn check_destination(dest: &Path, force: bool, outcome: &str) -> anyhow::Result<()> {
    let Ok(meta) = std::fs::metadata(dest) else { return Ok(()) };
    // A link to a folder is not refused: the rename replaces the link.
    if meta.is_dir() && !std::fs::symlink_metadata(dest).is_ok_and(|m| m.file_type().is_symlink()) {
        bail!(
            "{}: is a folder, not a file, and the report writes this name: move it or choose another --out; {outcome}",
            dest.display()
        );
    }
    if meta.permissions().readonly() && !force {
        bail!("{}: read-only; pass --force to replace it; {outcome}", dest.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_that_fails_removes_the_out_folder_it_made_and_keeps_one_it_found() {
        let root = tempfile::tempdir().expect("temp folder");
        let out = root.path().join("new");
        let staging = Staging::new(&out.join("deeper"), &[], false).expect("staging");
        std::fs::write(staging.path().join("report.md"), "half").expect("write");
        drop(staging);
        assert!(!out.exists(), "an interrupted run left the --out it made, or its parent");
        std::fs::create_dir(&out).expect("mkdir");
        drop(Staging::new(&out, &[], false).expect("staging"));
        assert!(out.is_dir() && std::fs::read_dir(&out).expect("out").count() == 0, "a found --out is kept, empty");
    }

    #[test]
    fn files_appear_only_when_published_and_a_read_only_one_is_kept_without_force() {
        let root = tempfile::tempdir().expect("temp folder");
        let out = root.path().join("out");
        let staging = Staging::new(&out, &[], false).expect("staging");
        std::fs::write(staging.path().join("report.md"), "new").expect("write");
        assert!(!out.join("report.md").exists(), "a staged file is not in --out yet");
        staging.publish(false, true).expect("publish");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("published"), "new");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1, "the staging folder is gone");

        // A read-only report is refused, and nothing of the run moves.
        let mut permissions = std::fs::metadata(out.join("report.md")).expect("meta").permissions();
        permissions.set_readonly(true);
        std::fs::set_permissions(out.join("report.md"), permissions).expect("chmod");
        let staging = Staging::new(&out, &[], false).expect("staging");
        std::fs::write(staging.path().join("a.png"), "plot").expect("write");
        std::fs::write(staging.path().join("report.md"), "newer").expect("write");
        let e = staging.publish(false, true).expect_err("read-only").to_string();
        assert!(e.contains("report.md: read-only; pass --force"), "{e}");
        assert!(!out.join("a.png").exists(), "a refused run moved a file");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1, "the staging folder is gone");

        let staging = Staging::new(&out, &[], false).expect("staging");
        std::fs::write(staging.path().join("report.md"), "forced").expect("write");
        staging.publish(true, true).expect("--force");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("published"), "forced");

        // A folder where a file goes: refused when the run starts, and again when it publishes
        // (one made meanwhile), before any file moves.
        std::fs::create_dir(out.join("a.png")).expect("mkdir");
        let e = Staging::new(&out, &["a.png".into()], true).err().expect("a folder").to_string();
        assert!(e.contains("a.png: is a folder, not a file") && e.contains("nothing was run"), "{e}");
        let staging = Staging::new(&out, &[], true).expect("staging");
        std::fs::write(staging.path().join("a.png"), "plot").expect("write");
        std::fs::write(staging.path().join("report.md"), "beside").expect("write");
        let e = staging.publish(true, true).expect_err("a folder").to_string();
        assert!(e.contains("a.png: is a folder") && e.contains("nothing was written"), "{e}");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("kept"), "forced");
        std::fs::remove_dir(out.join("a.png")).expect("rmdir");
        // A link named so, to a folder, is not refused: the move replaces the link.
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(root.path(), out.join("a.png")).expect("link");
            assert!(Staging::new(&out, &["a.png".into()], true).is_ok(), "a link to a folder was refused");
            std::fs::remove_file(out.join("a.png")).expect("unlink");
        }

        // Dropped unpublished (a failed run): --out keeps what it had.
        let staging = Staging::new(&out, &[], false).expect("staging");
        std::fs::write(staging.path().join("report.md"), "half").expect("write");
        drop(staging);
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("kept"), "forced");
        assert_eq!(std::fs::read_dir(&out).expect("out").count(), 1);
    }

    #[test]
    fn a_report_over_an_earlier_one_removes_its_files_that_the_new_one_does_not_write() {
        // `report --out rr` over a report of more scenes kept error_vs_time_bumpy.png and
        // gi_vs_time_bumpy.png beside the new report.md, with no word.
        let root = tempfile::tempdir().expect("temp folder");
        let out = root.path().join("rr");
        std::fs::create_dir(&out).expect("mkdir");
        let earlier = ["report.md", "report.csv", "error_vs_time_bumpy.png", "gi_vs_time_bumpy.png"];
        let unrelated = ["notes.md", "error_vs_time_.png", "bumpy.png", "gi_vs_time_x.txt"];
        for name in earlier.iter().chain(&unrelated) {
            std::fs::write(out.join(name), "earlier").expect("write");
        }
        std::fs::create_dir(out.join("gi_vs_time_dir.png")).expect("mkdir");
        let publish = |force: bool| {
            let staging = Staging::new(&out, &[], force).expect("staging");
            std::fs::write(staging.path().join("report.md"), "new").expect("write");
            std::fs::write(staging.path().join("error_vs_time_whitted.png"), "new").expect("write");
            staging.publish(force, true)
        };
        // A read-only stale file is refused without --force, before anything moves.
        let bumpy = out.join("gi_vs_time_bumpy.png");
        let mut permissions = std::fs::metadata(&bumpy).expect("meta").permissions();
        permissions.set_readonly(true);
        std::fs::set_permissions(&bumpy, permissions).expect("chmod");
        let e = publish(false).expect_err("read-only").to_string();
        assert!(e.contains("gi_vs_time_bumpy.png: a file of an earlier report") && e.contains("--force"), "{e}");
        assert_eq!(std::fs::read_to_string(out.join("report.md")).expect("kept"), "earlier");
        publish(true).expect("--force");
        let mut listing: Vec<String> = std::fs::read_dir(&out)
            .expect("out")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        listing.sort();
        assert_eq!(
            listing,
            [
                "bumpy.png",
                "error_vs_time_.png",
                "error_vs_time_whitted.png",
                "gi_vs_time_dir.png",
                "gi_vs_time_x.txt",
                "notes.md",
                "report.md"
            ]
        );
        // A shard (`supersede` false) removes nothing.
        let staging = Staging::new(&out, &[], false).expect("staging");
        std::fs::write(staging.path().join("shard-0-of-2.toml"), "shard").expect("write");
        staging.publish(false, false).expect("shard");
        assert!(out.join("report.md").exists());
    }
}
