//! Which output paths `glint render` may write: a known format in an existing folder, never
//! the input scene or a file it reads (a texture, a model; the same file by any name: a link,
//! `./`, another path to it), and not a read-only file unless `--force` says to replace it.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::cli::usage::usage;
use anyhow::bail;
use glint_io::LoadedScene;
use glint_io::atomic::{self, FolderRefuses};
use glint_scene::{LoadedModel, MaterialDesc, ObjectDesc, TextureDesc, material_textures};

/// Checks every output of one command before any rendering starts.
pub fn check_outputs(outputs: &[&Path], input: &Path, force: bool) -> anyhow::Result<()> {
    for path in outputs {
        // First, whatever its name: `-o scene.toml` was refused as an unsupported format.
        if is_same_file(path, input) {
            bail!(
                "{}: this output is the input scene {}; writing it would destroy the scene: choose another output name",
                path.display(),
                input.display()
            );
        }
        // Refused before any is written: `--backend both` wrote X-cpu.png and then failed on an
        // X-gpu.png that was a folder. Before the format: `-o adir` was "unsupported output
        // format" (a newcomer).
        // `metadata` follows a link: a link to a folder or a read-only file is refused too.
        let meta = std::fs::metadata(path).ok();
        if meta.as_ref().is_some_and(std::fs::Metadata::is_dir) {
            bail!("{}: is a folder, not a file; choose another output name (a .png or .exr file)", path.display());
        }
        check_format_and_folder(path)?;
        let read_only = meta.as_ref().is_some_and(|m| m.permissions().readonly());
        if !force && read_only {
            bail!("{}: the output file is read-only; not replacing it (pass --force to replace it)", path.display());
        }
        check_replaceable(path, read_only && force, meta.as_ref().is_some_and(std::fs::Metadata::is_file))?;
    }
    Ok(())
}

/// What the file system will refuse when the finished image is written, asked before the
/// render: a read-only mount, a folder that allows no new file or no rename (append-only), a
/// name longer than a file system allows, an immutable file. Each was found only after the
/// whole render (a farm task's render thrown away), and `--backend both` had by then replaced
/// some of its images and not the others.
fn check_replaceable(path: &Path, forced_read_only: bool, existing_file: bool) -> anyhow::Result<()> {
    // NAME_MAX of Linux's file systems (ext4, xfs, btrfs, tmpfs) and of NTFS and APFS.
    const NAME_MAX: usize = 255;
    let name = path.file_name().map_or(0, |n| n.as_encoded_bytes().len());
    if name > NAME_MAX {
        bail!("{}: the file name is {name} bytes long; file systems allow at most {NAME_MAX}", path.display());
    }
    // The image is written as a temporary beside it and renamed over it: make one, and remove it.
    let folder = atomic::folder_of(path);
    match atomic::probe_folder(path) {
        Ok(()) => {}
        // The error of `create_temporary` names the folder and why already.
        Err(FolderRefuses::Create(e)) => bail!("{}: {e}", path.display()),
        Err(FolderRefuses::Remove { leftover, error }) => bail!(
            "{}: the folder {} lets files be created but not removed or renamed ({}), so the image cannot be \
             written there; the test file {} is left in it",
            path.display(),
            folder.display(),
            error.kind(),
            leftover.display()
        ),
    }
    // An immutable file, or one on a read-only mount reached through a link: opening it for
    // writing (without truncating: nothing changes) says so. A read-only one is replaced with
    // --force, by the rename; other kinds (a named pipe) would block and are replaced too.
    if !forced_read_only
        && existing_file
        && let Err(e) = std::fs::OpenOptions::new().write(true).open(path)
    {
        bail!("{}: the existing file cannot be replaced: {}", path.display(), e.kind());
    }
    Ok(())
}

/// Refuses an output that is a file the scene reads besides itself: a texture (`-o` named as
/// a material's image overwrote it without a word) or a model file.
pub fn check_not_read(outputs: &[&Path], loaded: &LoadedScene) -> anyhow::Result<()> {
    let read = files_read(loaded);
    for path in outputs {
        if let Some((what, file)) = read.iter().find(|(_, file)| is_same_file(path, file)) {
            bail!(
                "{}: this output is {what} the scene reads, {}; writing it would destroy it: choose another output name",
                path.display(),
                file.display()
            );
        }
    }
    Ok(())
}

/// The textures and model files `loaded` read (as found: a texture of a scene file's own
/// material beside the scene, a model's beside the model, each through the one resolver that
/// read it, so `t%20x.png` is `t x.png`). A model file is never named .png or .exr, but may be
/// linked under such a name.
fn files_read(loaded: &LoadedScene) -> Vec<(&'static str, PathBuf)> {
    let found = |t: &TextureDesc, beside: &Path| {
        glint_io::uri::uri_file(beside, &t.path).ok().flatten().map(|file| ("a texture", file))
    };
    let textures = |material: &MaterialDesc, beside: &Path| {
        material_textures(material)
            .into_iter()
            .filter_map(|(_, t)| t)
            .filter_map(|t| found(t, beside))
            .collect::<Vec<_>>()
    };
    let models: Vec<&LoadedModel> = loaded
        .desc
        .objects
        .iter()
        .filter_map(|o| match o {
            ObjectDesc::Model(m) => m.loaded.as_deref(),
            _ => None,
        })
        .collect();
    // A model's materials are in the scene's too (under its object's name), their textures
    // decoded by the importer beside the model; one the scene file gives (an override of a
    // model's material, `[materials."OBJ/MAT"]`) was read beside the scene. The importer's
    // texture is the very image the model holds (the scene's loads decode their own).
    let models_texture = |name: &str, slot: usize, t: &TextureDesc| {
        models.iter().filter_map(|m| m.materials.get(name)).any(|m| {
            let own = material_textures(m)[slot].1.and_then(|own| own.image.as_ref());
            matches!((own, &t.image), (Some(a), Some(b)) if Arc::ptr_eq(a, b))
        })
    };
    let mut read: Vec<_> = Vec::new();
    for (name, material) in &loaded.desc.materials {
        for (slot, (_, t)) in material_textures(material).into_iter().enumerate() {
            if let Some(t) = t.filter(|t| !models_texture(name, slot, t)) {
                read.extend(found(t, &loaded.source));
            }
        }
    }
    for model in models {
        read.push(("a model file", model.file.clone()));
        read.extend(model.materials.values().flat_map(|material| textures(material, &model.file)));
    }
    read
}

fn check_format_and_folder(path: &Path) -> anyhow::Result<()> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png" | "exr") => {}
        _ => usage!("{}: unsupported output format; use a .png or .exr file name", path.display()),
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        // What is there, if anything: a file in its place was said not to exist (a tester).
        let what = match std::fs::metadata(dir) {
            Ok(_) => "is a file, not a folder",
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => "does not exist",
            Err(_) if dir.ancestors().skip(1).any(Path::is_file) => "is inside a file, not a folder",
            // Said only "cannot be read" (a tester's `lp1 -> lp2 -> lp1`).
            Err(e) if is_link_loop(&e) => {
                "is a symbolic link loop (too many levels of symbolic links): a link that leads back to itself"
            }
            Err(_) => "cannot be read",
        };
        bail!("{}: the output folder {} {what}", path.display(), dir.display());
    }
    Ok(())
}

/// Whether `e` is ELOOP: too many levels of symbolic links (std's `FilesystemLoop` kind is
/// not stable).
fn is_link_loop(e: &std::io::Error) -> bool {
    #[cfg(any(target_os = "linux", target_os = "android"))]
    const ELOOP: i32 = 40;
    #[cfg(not(any(target_os = "linux", target_os = "android")))]
    const ELOOP: i32 = 62;
    cfg!(unix) && e.raw_os_error() == Some(ELOOP)
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

/// Makes the folder `dir` that `flag` names, with any folders above it that are missing. A
/// file where a folder must be is named as such ("cannot create ok.png: File exists" said
/// neither that ok.png is a file nor that the flag wants a folder).
pub fn create_folder(flag: &str, dir: &Path) -> anyhow::Result<()> {
    if let Some(file) = dir.ancestors().find(|a| std::fs::metadata(a).is_ok_and(|m| !m.is_dir())) {
        bail!("{flag} {}: {} is a file, not a folder; {flag} names a folder", dir.display(), file.display());
    }
    std::fs::create_dir_all(dir).map_err(|e| anyhow::anyhow!("{flag} {}: cannot make the folder: {e}", dir.display()))
}

/// The default output `STEM` + `suffix` in the current folder: the scene file's own stem byte
/// for byte (a name that is not UTF-8 kept its bytes only in the file; `loaded.name` has
/// U+FFFD for them), a built-in scene's name, or `scene` for a scene read from a pipe or a
/// device (`<(generate-scene)` wrote `63.png`, after /dev/fd/63; a newcomer).
pub fn default_output(loaded: &LoadedScene, suffix: &str) -> PathBuf {
    let builtin = loaded.source.to_str().is_some_and(|s| s.starts_with("builtin:"));
    // /dev/stdin stands for a regular file too where one is redirected in (a file under
    // /dev/shm is a file: its own stem names it).
    let streams = ["/dev/stdin", "/dev/fd/", "/proc/self/fd/"];
    let streamed = !builtin
        && (std::fs::metadata(&loaded.source).is_ok_and(|m| !m.is_file())
            || streams.iter().any(|d| loaded.source.to_str().is_some_and(|s| s.starts_with(d))));
    let mut name = match loaded.source.file_stem() {
        Some(_) if streamed => std::ffi::OsString::from("scene"),
        Some(stem) if !builtin => stem.to_os_string(),
        _ => std::ffi::OsString::from(&loaded.name),
    };
    name.push(suffix);
    PathBuf::from(name)
}
