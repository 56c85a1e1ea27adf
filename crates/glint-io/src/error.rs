//! Errors of scene loading; every one names the file (and, through `FieldIssue`, the field).

use std::path::PathBuf;

use glint_core::image::Unrepresentable;

use glint_scene::FieldIssue;

use crate::atomic::AtomicWriteError;

#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The message carries the I/O error itself (not as `source()`): it is shown as one line,
    /// in the viewer too, and a caller printing the chain would repeat it.
    #[error("{file}: cannot read the scene file: {error}")]
    Io { file: PathBuf, error: std::io::Error },
    #[error("{file}: {message}")]
    Parse { file: PathBuf, message: String },
    #[error("{file}: invalid scene:\n{}", list(.issues))]
    Invalid { file: PathBuf, issues: Vec<FieldIssue> },
    #[error("unknown built-in scene '{name}' and no such file{}built-in scenes: {available}", .suggestion.as_ref().map_or("; ".to_string(), |s| format!("; did you mean '{s}'? The ")))]
    UnknownScene { name: String, available: String, suggestion: Option<String> },
    #[error("resolution {value} of the generated scene '{name}' is outside {min}..={max}")]
    Resolution { name: String, value: u32, min: u32, max: u32 },
    #[error(
        "'{name}' is not a generated scene: a resolution ({value}) applies only to the generated \
         built-in scenes ({generated})"
    )]
    NotGenerated { name: String, value: u32, generated: String },
    #[error(
        "'{name}' is not a model file: --scene-index, --camera, --exposure and --ground apply only to \
         model files (.gltf, .glb, .obj)"
    )]
    NotAModel { name: String },
    #[error(
        "{file}: a .{extension} file, a format glint does not read: scenes are TOML files (.toml), models glTF 2.0 \
         (.gltf, .glb) or OBJ (.obj); convert it to glTF (Blender, assimp export)"
    )]
    Unsupported { file: PathBuf, extension: String },
    #[error(
        "{file}: a {format} image, not a scene: glint renders scene files (.toml), model files (.gltf, .glb, \
         .obj) and built-in scenes (glint render --list)"
    )]
    Image { file: PathBuf, format: &'static str },
    /// A model file that did not import (the error names the file and what is wrong).
    #[error(transparent)]
    Model(#[from] crate::model::ModelError),
}

impl SceneError {
    /// The field problems of a validation error (empty for other errors).
    pub fn issues(&self) -> &[FieldIssue] {
        match self {
            Self::Invalid { issues, .. } => issues,
            _ => &[],
        }
    }
}

fn list(issues: &[FieldIssue]) -> String {
    issues.iter().map(|i| format!("  {i}")).collect::<Vec<_>>().join("\n")
}

/// Why a rendered image was not written.
#[derive(Debug, thiserror::Error)]
pub enum ImageWriteError {
    /// The I/O error is part of the message, not a `source()`: see `SceneError::Io`.
    #[error("{path}: {error}")]
    Io { path: PathBuf, error: std::io::Error },
    #[error("{path}: PNG encoding failed: {message}")]
    Png { path: PathBuf, message: String },
    #[error("{path}: EXR encoding failed: {message}")]
    Exr { path: PathBuf, message: String },
    #[error("{path}: unsupported output format; use .png or .exr")]
    Format { path: PathBuf },
    /// Never written: a non-finite pixel in a file is a wrong image that looks like a result.
    #[error("{path}: not written: {found}")]
    Unrepresentable { path: PathBuf, found: Unrepresentable },
}

impl From<AtomicWriteError> for ImageWriteError {
    fn from(AtomicWriteError { path, error }: AtomicWriteError) -> Self {
        Self::Io { path, error }
    }
}
