//! Scene files: the serde description, validation and the built-in scenes.
//!
//! The format is TOML: it has comments (scenes carry their provenance), it is the format Rust
//! users already edit every day (Cargo.toml), and its parser reports line and column. RON reads
//! enums more naturally but is little known outside Rust; lights and objects here use a `type`
//! key instead.

mod builtin;
pub mod bumpy;
mod desc;
mod error;
mod rgb;
mod texture;
mod validate;

use std::path::{Path, PathBuf};

pub use builtin::{BUILTIN_SCENES, BuiltinScene, BuiltinSource, DEFAULT_RESOLUTION, RESOLUTIONS, builtin};
pub use desc::{
    Attenuation, CameraDesc, CheckerDesc, EpsilonMode, LightDesc, LightKind, MaterialDesc, MeshDesc, NO_CONE_CUTOFF,
    ObjectDesc, PlaneDesc, RenderSettings, SceneDesc, SpecularModel, SphereDesc, WorldDesc,
};
pub use error::{FieldIssue, SceneError};
pub use rgb::Rgb;
pub use texture::{
    ColorSpace, Filter, MAX_TEXTURE_SIDE, MAX_TEXTURE_TEXELS, TextureDesc, TextureError, TextureImage, UvTransform,
    Wrap, load_textures, material_textures, srgb_to_linear,
};
pub use validate::{
    MAX_COORD, MAX_DEPTH, MAX_EPSILON, MAX_IMAGE_SIDE, MAX_INTENSITY, MAX_IOR, MAX_SHININESS, MAX_SPOT_EXPONENT,
    MAX_SPP, MIN_ATTENUATION_DENOMINATOR, Range, Report, ranges, validate, validate_settings,
};

/// A parsed and validated scene with where it came from.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    pub desc: SceneDesc,
    /// The file path, or `builtin:NAME`.
    pub source: PathBuf,
    /// A short name for output files and reports (file stem or built-in name).
    pub name: String,
    pub warnings: Vec<FieldIssue>,
}

/// Parses scene text, decodes its textures (paths relative to `file`, the scene file's path,
/// also named in messages) and validates it.
pub fn parse_scene(text: &str, file: &Path) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
    let mut desc: SceneDesc =
        toml::from_str(text).map_err(|e| SceneError::Parse { file: file.to_owned(), message: e.to_string() })?;
    load_textures(&mut desc, file)?;
    validated(desc, file)
}

/// `desc` with its warnings if it passes validation, else the errors naming `file`.
fn validated(desc: SceneDesc, file: &Path) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
    let report = validate(&desc);
    if report.errors.is_empty() {
        Ok((desc, report.warnings))
    } else {
        Err(SceneError::Invalid { file: file.to_owned(), issues: report.errors })
    }
}

/// Loads `arg`: a scene file if such a file exists, otherwise a built-in scene name.
pub fn load_scene(arg: &str) -> Result<LoadedScene, SceneError> {
    load_scene_at(arg, None)
}

/// `load_scene`, with the resolution of a generated built-in scene (`bumpy`; its default
/// without one). A resolution for a scene file or a TOML built-in is an error, not ignored.
pub fn load_scene_at(arg: &str, resolution: Option<u32>) -> Result<LoadedScene, SceneError> {
    let path = Path::new(arg);
    if path.is_dir() {
        return Err(SceneError::Io {
            file: path.to_owned(),
            error: std::io::Error::new(std::io::ErrorKind::IsADirectory, "a folder, not a scene file"),
        });
    }
    if path.is_file() {
        if let Some(value) = resolution {
            return Err(SceneError::NotGenerated { name: arg.to_string(), value });
        }
        let name = path.file_stem().map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("obj")) {
            let (desc, warnings) = load_model(path)?;
            return Ok(LoadedScene { desc, source: path.to_owned(), name, warnings });
        }
        let text = std::fs::read_to_string(path).map_err(|error| SceneError::Io { file: path.to_owned(), error })?;
        let (desc, warnings) = parse_scene(&text, path)?;
        return Ok(LoadedScene { desc, source: path.to_owned(), name, warnings });
    }
    if let Some(b) = builtin(arg) {
        let source = PathBuf::from(format!("builtin:{}", b.name));
        let (desc, warnings) = b.load(resolution)?;
        return Ok(LoadedScene { desc, source, name: b.name.to_string(), warnings });
    }
    if path.extension().is_some() || arg.contains(std::path::MAIN_SEPARATOR) {
        return Err(SceneError::Io {
            file: path.to_owned(),
            error: std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
        });
    }
    let available = BUILTIN_SCENES.iter().map(|b| b.name).collect::<Vec<_>>().join(", ");
    Err(SceneError::UnknownScene { name: arg.to_string(), available })
}

/// An OBJ model in the lab scene `model::scene_around` makes for it, validated like a scene
/// file; the importer's warnings come first.
fn load_model(path: &Path) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
    let mut model = crate::model::load_obj(path).map_err(|e| SceneError::Model { message: e.to_string() })?;
    let mut warnings = std::mem::take(&mut model.warnings);
    let (desc, scene_warnings) =
        validated(crate::model::scene_around(model, format!("the model {}", path.display())), path)?;
    warnings.extend(scene_warnings);
    Ok((desc, warnings))
}

/// Serialises a scene back to the file format (used by the viewer's "Save scene").
pub fn to_toml(desc: &SceneDesc) -> Result<String, toml::ser::Error> {
    toml::to_string_pretty(desc)
}
