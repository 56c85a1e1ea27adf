//! Glint's loaders: scene files (TOML), the built-in scenes, model files (glTF 2.0, OBJ/MTL)
//! and the images they name, read into glint-scene's description and validated. Every path a
//! file names is resolved and contained by `model::uri`.
//!
//! The format is TOML: it has comments (scenes carry their provenance), it is the format Rust
//! users already edit every day (Cargo.toml), and its parser reports line and column. RON reads
//! enums more naturally but is little known outside Rust; lights and objects here use a `type`
//! key instead.

pub mod atomic;
mod builtin;
mod error;
pub mod exr_file;
mod exr_order;
pub mod image_file;
pub mod interrupt;
pub mod model;
mod model_ref;
mod texture;
mod toml_message;
mod toml_position;
pub mod uri;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};

use glint_scene::{FieldIssue, SceneDesc, validate, without_imported_materials};

pub use builtin::{BUILTIN_SCENES, BuiltinScene, BuiltinSource, DEFAULT_RESOLUTION, RESOLUTIONS, builtin};
pub use error::SceneError;
pub use model::{ImportOptions, ModelError, ModelFormat};
pub use model_ref::{load_model_ref, load_models};
pub use texture::{decode_texture, load_textures};

/// A parsed and validated scene with where it came from.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub desc: SceneDesc,
    /// The file path, or `builtin:NAME`.
    pub source: PathBuf,
    /// A short name for output files and reports (file stem or built-in name).
    pub name: String,
    /// Every warning of the load: the importer's and the model references' first, then
    /// validation's (`scene_warnings`).
    pub warnings: Vec<FieldIssue>,
    /// Validation's part of `warnings`, kept apart so that an editor need not validate the
    /// scene again to tell them from the importer's (on a million-triangle model that doubled
    /// the viewer's load).
    pub scene_warnings: Vec<FieldIssue>,
}

/// Parses scene text, loads its model objects and decodes its textures (paths relative to
/// `file`, the scene file's path, also named in messages), and validates it.
pub fn parse_scene(text: &str, file: &Path) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
    parse_scene_parts(text, file).map(|(desc, mut loaded, validated)| {
        loaded.extend(validated);
        (desc, loaded)
    })
}

/// `parse_scene` with its warnings in two: the model references' and validation's.
fn parse_scene_parts(text: &str, file: &Path) -> Result<(SceneDesc, Vec<FieldIssue>, Vec<FieldIssue>), SceneError> {
    let mut desc: SceneDesc = toml::from_str(text)
        .map_err(|e| SceneError::Parse { file: file.to_owned(), message: toml_message::parse_message(&e, text) })?;
    let folder = file.parent().unwrap_or(Path::new("."));
    let warnings =
        load_models(&mut desc, folder).map_err(|issues| SceneError::Invalid { file: file.to_owned(), issues })?;
    // A texture that does not load is one error among the scene's others, all said at once
    // (it stopped validation, hiding every other broken rule); validation's own "not decoded"
    // for that field would say it twice.
    let texture_issues = load_textures(&mut desc, file).err().unwrap_or_default();
    if texture_issues.is_empty() {
        let (desc, scene_warnings) = validated(desc, file)?;
        return Ok((desc, warnings, scene_warnings));
    }
    let others: Vec<FieldIssue> =
        validate(&desc).errors.into_iter().filter(|e| texture_issues.iter().all(|t| t.field != e.field)).collect();
    Err(SceneError::Invalid { file: file.to_owned(), issues: texture_issues.into_iter().chain(others).collect() })
}

/// `desc` with its warnings if it passes validation, else the errors naming `file`.
pub fn validated(desc: SceneDesc, file: &Path) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
    let report = validate(&desc);
    if report.errors.is_empty() {
        Ok((desc, report.warnings))
    } else {
        Err(SceneError::Invalid { file: file.to_owned(), issues: report.errors })
    }
}

/// How a scene argument is opened: the resolution of a generated built-in scene (`bumpy`),
/// and the choices made when a model file is imported. Each applies only where it means
/// something, and is an error elsewhere, never ignored.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoadOptions {
    pub resolution: Option<u32>,
    pub import: ImportOptions,
    /// The most bytes a scene file without a size (a pipe, a device) is read to, below
    /// `uri::MAX_RESOURCE_BYTES` (1 GiB, the default): what a memory limit leaves for parsing it.
    pub stream_cap: Option<u64>,
}

/// Loads `arg`: a scene or model file if such a file exists, otherwise a built-in scene name.
pub fn load_scene(arg: impl AsRef<OsStr>) -> Result<LoadedScene, SceneError> {
    load_scene_with(arg, &LoadOptions::default())
}

/// `load_scene` with `options`: the resolution of a generated built-in scene (its default
/// without one), the import options of a model file (`.gltf`, `.glb`, `.obj`).
/// `arg` is a path as the system gives it (not UTF-8 on every file system); only a built-in
/// scene's name must be UTF-8.
pub fn load_scene_with(arg: impl AsRef<OsStr>, options: &LoadOptions) -> Result<LoadedScene, SceneError> {
    let resolution = options.resolution;
    let path = Path::new(arg.as_ref());
    let arg = arg.as_ref().to_string_lossy();
    let arg = arg.as_ref();
    let is_model = ModelFormat::of(path).is_some();
    // Any readable thing but a folder is a file here: a named pipe (`<(…)`), /dev/stdin.
    let is_file = std::fs::metadata(path).is_ok_and(|m| !m.is_dir());
    // Said of a scene file or a built-in scene; a name that is neither is "no such file" below
    // (a missing `example.toml --camera 0` was called "not a model file").
    let exists = is_file || path.to_str().and_then(builtin).is_some();
    if !(options.import.is_default() || is_model && is_file) && exists {
        return Err(SceneError::NotAModel { name: arg.to_string() });
    }
    if path.is_dir() {
        return Err(SceneError::Io {
            file: path.to_owned(),
            error: std::io::Error::new(std::io::ErrorKind::IsADirectory, "a folder, not a scene file"),
        });
    }
    if is_file {
        if let Some(value) = resolution {
            return Err(SceneError::NotGenerated {
                name: arg.to_string(),
                value,
                generated: builtin::generated_names(),
            });
        }
        let name = path.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        if is_model {
            let (desc, mut warnings, scene_warnings) = load_model(path, &options.import)?;
            warnings.extend(scene_warnings.iter().cloned());
            return Ok(LoadedScene { desc, source: path.to_owned(), name, warnings, scene_warnings });
        }
        if let Some(extension) = ModelFormat::other(path) {
            return Err(SceneError::Unsupported { file: path.to_owned(), extension });
        }
        let cap = options.stream_cap.map_or(uri::MAX_RESOURCE_BYTES, |c| c.min(uri::MAX_RESOURCE_BYTES));
        let bytes = read_capped(path, cap).map_err(|error| SceneError::Io { file: path.to_owned(), error })?;
        let text = utf8(&bytes, path)?;
        if text.trim().is_empty() {
            let message = "the file is empty: a scene needs at least a [camera] table (docs/scene-format.md)";
            return Err(SceneError::Parse { file: path.to_owned(), message: message.to_string() });
        }
        let (desc, mut warnings, scene_warnings) = parse_scene_parts(text, path)?;
        warnings.extend(scene_warnings.iter().cloned());
        return Ok(LoadedScene { desc, source: path.to_owned(), name, warnings, scene_warnings });
    }
    if let Some(b) = path.to_str().and_then(builtin) {
        let source = PathBuf::from(format!("builtin:{}", b.name));
        // A built-in scene has no models: every warning is validation's.
        let (desc, warnings) = b.load(resolution)?;
        let scene_warnings = warnings.clone();
        return Ok(LoadedScene { desc, source, name: b.name.to_string(), warnings, scene_warnings });
    }
    if path.extension().is_some() || arg.contains(std::path::MAIN_SEPARATOR) {
        // What the file system says where it is more than "missing": a loop of links, a
        // folder that may not be entered (a loop was called "no such file").
        let error = std::fs::metadata(path)
            .err()
            .filter(|e| e.kind() != std::io::ErrorKind::NotFound)
            .unwrap_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"));
        return Err(SceneError::Io { file: path.to_owned(), error });
    }
    let available = BUILTIN_SCENES.iter().map(|b| b.name).collect::<Vec<_>>().join(", ");
    Err(SceneError::UnknownScene { name: arg.to_string(), available, suggestion: closest_builtin(arg) })
}

/// The built-in scene a mistyped name most likely meant: the most similar by Jaro–Winkler
/// (clap's measure for flags), if similar enough ("whited" → whitted, "cornel-gi" → cornell-gi).
fn closest_builtin(name: &str) -> Option<String> {
    let lower = name.to_lowercase();
    BUILTIN_SCENES
        .iter()
        .map(|b| (strsim::jaro_winkler(&lower, b.name), b.name))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, n)| n.to_string())
}

/// A scene file's bytes, at most `cap` of them (`uri::MAX_RESOURCE_BYTES`, or what a memory
/// limit leaves: `LoadOptions::stream_cap`): a device or a pipe (`/dev/zero`, a generator behind
/// `<(…)`) has no size to check beforehand, and is read only that far.
fn read_capped(path: &Path, cap: u64) -> std::io::Result<Vec<u8>> {
    let bytes = uri::read_up_to(std::fs::File::open(path)?, cap, 0)?;
    if bytes.len() as u64 > cap {
        let why = if cap < uri::MAX_RESOURCE_BYTES {
            "what the memory limit (--memory-limit, else the memory available) leaves for parsing it"
        } else {
            "the most a scene file may hold"
        };
        return Err(std::io::Error::other(format!("larger than {cap} bytes, {why}")));
    }
    Ok(bytes)
}

/// The scene file's text, or an error giving the byte offset (and line and column) of the
/// first byte that is not UTF-8, as a hex editor or `dd skip=` needs it.
fn utf8<'a>(bytes: &'a [u8], file: &Path) -> Result<&'a str, SceneError> {
    std::str::from_utf8(bytes).map_err(|e| {
        // An image given as the scene was "not UTF-8 text: byte 0x89 …" (a newcomer); by its
        // bytes, not its name: a scene file may be named anything (tests name one scene.png).
        if let Some(format) = image_format(bytes) {
            return SceneError::Image { file: file.to_owned(), format };
        }
        let offset = e.valid_up_to();
        let before = &bytes[..offset];
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let line_start = before.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
        // The column in characters: the line up to here is valid UTF-8.
        let column = std::str::from_utf8(&before[line_start..]).map_or(0, |s| s.chars().count()) + 1;
        SceneError::Parse {
            file: file.to_owned(),
            message: format!(
                "not UTF-8 text: byte 0x{:02x} at byte offset {offset} (line {line}, column {column}) is not valid \
                 UTF-8; scene files are UTF-8",
                bytes[offset]
            ),
        }
    })
}

/// The image format whose signature `bytes` begin with (the formats an image file given as a
/// scene is most likely in: glint's own outputs and textures, and the common others).
fn image_format(bytes: &[u8]) -> Option<&'static str> {
    const SIGNATURES: [(&[u8], &str); 7] = [
        (b"\x89PNG\r\n\x1a\n", "PNG"),
        (b"\x76\x2f\x31\x01", "OpenEXR"),
        (b"\xff\xd8\xff", "JPEG"),
        (b"GIF8", "GIF"),
        (b"BM", "BMP"),
        (b"II*\x00", "TIFF"),
        (b"MM\x00*", "TIFF"),
    ];
    SIGNATURES.iter().find(|(magic, _)| bytes.starts_with(magic)).map(|&(_, format)| format)
}

/// A model file in the lab scene `model::scene_around` makes for it, validated like a scene
/// file; the importer's warnings come first.
fn load_model(
    path: &Path,
    options: &ImportOptions,
) -> Result<(SceneDesc, Vec<FieldIssue>, Vec<FieldIssue>), SceneError> {
    let model = model::load_model_file(path, options)?;
    // The scene's camera and lights come from the file's nodes: a problem with them is named
    // by the file's own camera or light too, which the generated scene's fields are not.
    let camera = match options.camera {
        Some(i) => model.cameras.get(i),
        None => model.cameras.first(),
    }
    .map(|c| c.name.clone());
    let lights: Vec<String> = model.lights.iter().map(|l| l.name.clone()).collect();
    let (desc, warnings) = model::scene_around(model, path, options)
        .map_err(|issue| SceneError::Invalid { file: path.to_owned(), issues: vec![issue] })?;
    let (desc, scene_warnings) = validated(desc, path).map_err(|e| match e {
        SceneError::Invalid { file, issues } => SceneError::Invalid {
            file,
            issues: issues.into_iter().map(|i| in_file_terms(i, camera.as_deref(), &lights)).collect(),
        },
        other => other,
    })?;
    Ok((desc, warnings, scene_warnings))
}

/// `issue` of the scene made around a model file, with what of the file it comes from: the
/// camera node (`camera.position`) or the light node (`lights[2].position`).
fn in_file_terms(issue: FieldIssue, camera: Option<&str>, lights: &[String]) -> FieldIssue {
    let placed = "placed by its node's and its parents' transforms";
    let whose = if issue.field.starts_with("camera.") {
        camera.map(|name| format!("the file's camera `{name}`, {placed}"))
    } else if let Some(rest) = issue.field.strip_prefix("lights[") {
        let index: Option<usize> = rest.split(']').next().and_then(|i| i.parse().ok());
        index.and_then(|i| lights.get(i)).map(|name| format!("the file's light `{name}`, {placed}"))
    } else {
        None
    };
    match whose {
        Some(whose) => FieldIssue { field: format!("{} ({whose})", issue.field), problem: issue.problem },
        None => issue,
    }
}

/// Serialises a scene back to the file format (used by the viewer's "Save scene").
/// A model object is written as its reference, and its materials only where they were changed.
pub fn to_toml(desc: &SceneDesc) -> Result<String, toml::ser::Error> {
    toml::to_string_pretty(&without_imported_materials(desc))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_read_from_a_device_stops_at_the_cap() {
        let e = read_capped(Path::new("/dev/zero"), 1024).unwrap_err();
        assert!(e.to_string().contains("larger than 1024 bytes"), "{e}");
        assert_eq!(read_capped(Path::new("/dev/null"), 1024).unwrap(), Vec::<u8>::new());
    }

    #[test]
    fn a_mistyped_builtin_name_or_an_image_is_answered_with_what_was_meant() {
        let said = |name: &str| load_scene(name).err().map(|e| e.to_string()).unwrap_or_default();
        // A newcomer's typo (a tester: it listed the scenes with no suggestion).
        for (typed, meant) in [("whited", "whitted"), ("Cornel", "cornell"), ("cornell-g", "cornell-gi")] {
            let expected = format!("and no such file; did you mean '{meant}'? The built-in scenes: whitted, cornell");
            assert!(said(typed).contains(&expected), "{}", said(typed));
        }
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("render.PNG");
        std::fs::write(&png, b"\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR").unwrap();
        let image = said(png.to_str().unwrap());
        assert!(image.ends_with("render.PNG: a PNG image, not a scene: glint renders scene files (.toml), model files (.gltf, .glb, .obj) and built-in scenes (glint render --list)"), "{image}");
        let far = said("teapot");
        assert!(far.contains("no such file; built-in scenes: whitted") && !far.contains("did you mean"), "{far}");
    }

    #[test]
    fn an_empty_scene_file_is_said_to_be_empty() {
        let dir = tempfile::tempdir().unwrap();
        for text in ["", "\n  \n"] {
            let file = dir.path().join("blank.toml");
            std::fs::write(&file, text).unwrap();
            let said = load_scene(&file).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(
                said.ends_with(
                    "blank.toml: the file is empty: a scene needs at least a [camera] table (docs/scene-format.md)"
                ),
                "{said}"
            );
        }
    }
}
