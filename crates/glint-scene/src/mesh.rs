//! Triangle meshes as a scene (or an importer) gives them.

use serde::{Deserialize, Serialize};

/// An indexed triangle mesh, optionally with per-vertex shading normals and texture
/// coordinates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[u32; 3]>,
    #[serde(default)]
    pub normals: Option<Vec<[f64; 3]>>,
    /// Texture coordinates (u, v) per vertex, glTF's convention: (0, 0) is the image's
    /// top-left corner. Without them a texture is mapped in planar coordinates.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uvs: Option<Vec<[f64; 2]>>,
    pub material: String,
    #[serde(default)]
    pub name: String,
}
