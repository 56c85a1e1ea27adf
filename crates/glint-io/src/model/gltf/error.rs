//! What can go wrong importing a glTF file, and the extensions Glint reads.

use std::path::PathBuf;

use crate::uri::UriError;

/// The extensions Glint reads; a file that requires any other is refused.
pub const SUPPORTED_EXTENSIONS: &[&str] = &[
    "EXT_mesh_gpu_instancing",
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
];

/// Why a glTF file did not load. Each names the file; `At` also the JSON path.
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    #[error("{file}: cannot read the model: {error}")]
    Io { file: PathBuf, error: std::io::Error },
    #[error("{file}: not a valid glTF 2.0 file: {reason}")]
    Parse { file: PathBuf, reason: String },
    #[error(
        "{file}: {where_} is {version}: Glint reads glTF 2.0 only (convert the file first, \
         e.g. with Blender's importer and exporter)"
    )]
    Version { file: PathBuf, where_: &'static str, version: String },
    #[error(
        "{file}: extensionsRequired[{index}] is `{extension}`, which Glint does not support \
         (supported: {})", SUPPORTED_EXTENSIONS.join(", ")
    )]
    RequiredExtension { file: PathBuf, index: usize, extension: String },
    #[error("{file}: {path}: {problem}")]
    At { file: PathBuf, path: String, problem: String },
    #[error("{file}: {path}: {error}")]
    Uri { file: PathBuf, path: String, error: UriError },
}
