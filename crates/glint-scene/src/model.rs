//! What an importer read from a model file (glTF 2.0, OBJ/MTL), already decoded: the meshes,
//! materials, lights and cameras a scene's model object places (`LoadedModel::place`). The
//! importers themselves are glint-io's.

use std::collections::BTreeMap;

use crate::camera::CameraDesc;
use crate::error::FieldIssue;
use crate::light::LightDesc;
use crate::material::MaterialDesc;
use crate::mesh::MeshDesc;

/// What an importer read from a model file, in world space, and what it set aside with a
/// warning.
#[derive(Clone, Debug, Default)]
pub struct Model {
    pub meshes: Vec<MeshDesc>,
    pub materials: BTreeMap<String, MaterialDesc>,
    /// What the file said of each material, by the same names (shown beside the mapping).
    pub sources: BTreeMap<String, MaterialSource>,
    pub lights: Vec<LightDesc>,
    pub cameras: Vec<ModelCamera>,
    pub warnings: Vec<FieldIssue>,
}

/// A material as the model file wrote it, before `map_material` turned it into the seed's
/// coefficients: kept so that the mapping can be shown and checked (the viewer's Materials
/// panel), never written to a scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct MaterialSource {
    /// "glTF" or "MTL".
    pub format: &'static str,
    /// The fields the file gave, in its own terms (`baseColorFactor`, `Kd`, `illum`, …) and
    /// order, with their values (one to four numbers); fields the file left out are absent.
    pub fields: Vec<(&'static str, Vec<f64>)>,
}

/// A camera of the file (glTF perspective and orthographic cameras).
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCamera {
    pub name: String,
    pub camera: CameraDesc,
    /// The width/height ratio the camera was made for, if the file gives one.
    pub aspect: Option<f64>,
}
