//! Which output paths `glint render` may write: a known format in an existing folder, never
//! the input scene (the same file by any name: a link, `./`, another path to it), and not a
//! read-only file unless `--force` says to replace it.

use std::path::Path;

use anyhow::bail;

/// Checks every output of one command before any rendering starts.
pub fn check_outputs(outputs: &[&Path], input: &Path, force: bool) -> anyhow::Result<()> {
    for path in outputs {
        check_format_and_folder(path)?;
        if is_same_file(path, input) {
            bail!(
                "{}: this output is the input scene {}; writing it would destroy the scene: choose another output name",
                path.display(),
                input.display()
            );
        }
        // `metadata` follows a link: a link to a read-only file is refused too.
        if !force && std::fs::metadata(path).is_ok_and(|m| m.permissions().readonly()) {
            bail!("{}: the output file is read-only; not replacing it (pass --force to replace it)", path.display());
        }
    }
    Ok(())
}

fn check_format_and_folder(path: &Path) -> anyhow::Result<()> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png" | "exr") => {}
        _ => bail!("{}: unsupported output format; use a .png or .exr file name", path.display()),
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        bail!("{}: the output folder {} does not exist", path.display(), dir.display());
    }
    Ok(())
}

/// Whether both paths name one existing file: the same device and inode on Unix (hard links
/// and symbolic links included), the same canonical path elsewhere.
pub fn is_same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        match (std::fs::metadata(a), std::fs::metadata(b)) {
            (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
            _ => false,
        }
    }
    #[cfg(not(unix))]
    {
        matches!((a.canonicalize(), b.canonicalize()), (Ok(x), Ok(y)) if x == y)
    }
}
