//! Triangle meshes as a scene (or an importer) gives them.

use serde::{Deserialize, Serialize};

/// An indexed triangle mesh, optionally with per-vertex shading normals, texture coordinates
/// and colours.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    #[serde(deserialize_with = "crate::exact_len::arrays")]
    pub vertices: Vec<[f64; 3]>,
    #[serde(deserialize_with = "crate::exact_len::arrays")]
    pub triangles: Vec<[u32; 3]>,
    #[serde(default, deserialize_with = "crate::exact_len::option_arrays")]
    pub normals: Option<Vec<[f64; 3]>>,
    /// Texture coordinates (u, v) per vertex, glTF's convention: (0, 0) is the image's
    /// top-left corner. Without them a texture is mapped in planar coordinates.
    #[serde(default, skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_arrays")]
    pub uvs: Option<Vec<[f64; 2]>>,
    /// A linear RGB colour per vertex (glTF's COLOR_0, an OBJ file's `v x y z r g b`),
    /// interpolated across each triangle: it multiplies k_a and k_d, as a texture's colour does.
    #[serde(
        default,
        alias = "colors",
        skip_serializing_if = "Option::is_none",
        deserialize_with = "crate::exact_len::option_arrays"
    )]
    pub colours: Option<Vec<[f64; 3]>>,
    pub material: String,
    #[serde(default)]
    pub name: String,
}

/// Whether a triangle of these corners has area, in f64 as written: validation's degenerate
/// triangles and an imported model with nothing to trace are judged alike.
pub fn has_area([a, b, c]: [[f64; 3]; 3]) -> bool {
    let (a, b, c) = (glam::DVec3::from(a), glam::DVec3::from(b), glam::DVec3::from(c));
    (b - a).cross(c - a).length() != 0.0
}

impl MeshDesc {
    /// A mesh of positions and triangles alone: no normals (its faces' own), no texture
    /// coordinates, no colours.
    pub fn new(
        vertices: Vec<[f64; 3]>,
        triangles: Vec<[u32; 3]>,
        material: impl Into<String>,
        name: impl Into<String>,
    ) -> Self {
        Self {
            vertices,
            triangles,
            normals: None,
            uvs: None,
            colours: None,
            material: material.into(),
            name: name.into(),
        }
    }
}
