//! `[[objects]] type = "model"`: a glTF or OBJ file placed in a scene by reference. The file
//! keeps the reference (path, transform, import choices); the imported meshes hang off it at
//! run time, so saving a scene writes the reference again, never the vertices.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::error::FieldIssue;
use super::light::LightDesc;
use crate::camera::CameraDesc;
use crate::material::MaterialDesc;
use crate::mesh::MeshDesc;
use crate::model::{MaterialSource, Model, ModelCamera};
use crate::transform::Mat4;

/// A model file in a scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelDesc {
    /// The model file (`.gltf`, `.glb`, `.obj`), relative to the scene file's folder.
    pub path: String,
    #[serde(default, skip_serializing_if = "TransformDesc::is_identity", deserialize_with = "crate::tables::table")]
    pub transform: TransformDesc,
    /// The glTF scene to place (default: the file's default scene, else its first).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene_index: Option<u32>,
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub name: String,
    /// Light the scene with the file's own lights (glTF `KHR_lights_punctual`), placed with the
    /// model, beside the scene's `[[lights]]`. Off by default: a lab scene brings its own.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub lights: bool,
    /// The factor from the file's photometric intensities (candela, lux) to I_d and I_s, as
    /// `--exposure` for an opened model file; (0, 1e6], default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exposure: Option<f64>,
    /// What the file held, once loaded (`SceneDesc::load_models`); never written back.
    #[serde(skip)]
    pub loaded: Option<Arc<LoadedModel>>,
}

/// Two references are equal when they say the same; the loaded data follows from that.
impl PartialEq for ModelDesc {
    fn eq(&self, other: &Self) -> bool {
        self.path == other.path
            && self.transform == other.transform
            && self.scene_index == other.scene_index
            && self.name == other.name
            && self.lights == other.lights
            && self.exposure == other.exposure
    }
}

/// A model file as placed: meshes in scene space (the object's transform applied) whose
/// materials are named `OBJECT/MATERIAL`, and those materials as the file gave them.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadedModel {
    /// The file that was read (the reference resolved against the scene's folder).
    pub file: PathBuf,
    pub meshes: Vec<MeshDesc>,
    pub materials: BTreeMap<String, MaterialDesc>,
    /// What the file said of each material, by the same names.
    pub sources: BTreeMap<String, MaterialSource>,
    /// The file's cameras, placed with the model (the viewer offers to look through them).
    pub cameras: Vec<ModelCamera>,
    /// The file's lights, placed with the model; they light the scene where the reference
    /// says `lights = true` (`SceneDesc::traced_lights`).
    pub lights: Vec<LightDesc>,
    pub warnings: Vec<FieldIssue>,
}

/// The largest angle `rotate` takes, in degrees: f64 holds it to 1.2e-10° (4e-7 of a second of
/// arc), and any larger is one written by mistake.
pub const MAX_ROTATE_DEGREES: f64 = 1e6;

/// Placement of a model: scale, then rotate, then translate (or one matrix instead).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TransformDesc {
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub translate: [f64; 3],
    /// Degrees about x, then y, then z (each about the fixed scene axes).
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_array")]
    pub rotate: Option<[f64; 3]>,
    /// A rotation as a unit quaternion [x, y, z, w]; exclusive with `rotate`.
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_array")]
    pub quaternion: Option<[f64; 4]>,
    /// A uniform factor or one per axis.
    pub scale: Scale,
    /// A 4×4 matrix, column-major as glTF writes it; exclusive with the fields above.
    #[serde(skip_serializing_if = "Option::is_none", deserialize_with = "crate::exact_len::option_array")]
    pub matrix: Option<[f64; 16]>,
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Scale {
    Uniform(f64),
    PerAxis([f64; 3]),
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use crate::exact_len::{OneOrThree, one_or_three};
        Ok(match one_or_three(d, "a number (uniform) or an array of three numbers [x, y, z]")? {
            OneOrThree::One(v) => Scale::Uniform(v),
            OneOrThree::Three(xyz) => Scale::PerAxis(xyz),
        })
    }
}

impl Default for TransformDesc {
    fn default() -> Self {
        Self { translate: [0.0; 3], rotate: None, quaternion: None, scale: Scale::Uniform(1.0), matrix: None }
    }
}

impl TransformDesc {
    pub fn is_identity(&self) -> bool {
        *self == Self::default()
    }

    /// The transform's problems, as (field under `transform`, problem).
    pub fn problems(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        let finite = |v: &[f64]| v.iter().all(|c| c.is_finite());
        if let Some(m) = &self.matrix {
            let others = self.translate != [0.0; 3]
                || self.rotate.is_some()
                || self.quaternion.is_some()
                || self.scale != Scale::Uniform(1.0);
            if others {
                out.push((
                    "matrix".into(),
                    "a matrix replaces translate, rotate, quaternion and scale: give one or the other".into(),
                ));
            }
            if !finite(m) {
                out.push(("matrix".into(), "every entry must be finite".into()));
            }
            // Column-major: entries 3, 7, 11 and 15 are the bottom row. Anything but
            // (0, 0, 0, 1) is a projection, which a placement cannot be (and was used as affine).
            let bottom = [m[3], m[7], m[11], m[15]];
            if finite(m) && bottom != [0.0, 0.0, 0.0, 1.0] {
                out.push((
                    "matrix".into(),
                    format!(
                        "its bottom row (entries 3, 7, 11, 15 column-major) is {bottom:?}; a placement's is \
                         [0, 0, 0, 1] (an affine transform, as glTF requires of a node's matrix)"
                    ),
                ));
            }
        }
        if !finite(&self.translate) {
            out.push(("translate".into(), "must be finite".into()));
        }
        if self.rotate.is_some() && self.quaternion.is_some() {
            out.push(("quaternion".into(), "give rotate (degrees) or quaternion, not both".into()));
        }
        if self.rotate.is_some_and(|r| !finite(&r)) {
            out.push(("rotate".into(), "must be finite (degrees)".into()));
        } else if let Some(&angle) = self.rotate.iter().flatten().find(|a| a.abs() > MAX_ROTATE_DEGREES) {
            // f64 holds 1e30 only to 1.4e14 degrees: any rotation at all (accepted silently).
            out.push((
                "rotate".into(),
                format!(
                    "each angle must lie in [-{MAX_ROTATE_DEGREES:e}, {MAX_ROTATE_DEGREES:e}] degrees; {} is beyond, \
                     where f64 holds it only to about {} degrees",
                    crate::number::format_number(angle),
                    crate::number::format_rounded(crate::number::f64_spacing(angle), 2)
                ),
            ));
        }
        if let Some(len) = self.quaternion.and_then(crate::transform::not_unit_quaternion) {
            out.push(("quaternion".into(), format!("must be a unit quaternion [x, y, z, w]; its length is {len}")));
        }
        let s = match self.scale {
            Scale::Uniform(s) => [s; 3],
            Scale::PerAxis(s) => s,
        };
        if !s.iter().all(|c| c.is_finite() && *c != 0.0) {
            out.push(("scale".into(), "every factor must be finite and non-zero".into()));
        }
        if out.is_empty() && self.matrix().determinant3() == 0.0 {
            // Named as the file wrote it: a scale whose factors' product underflows has no matrix.
            out.push(match self.matrix {
                Some(_) => ("matrix".into(), "is singular (flattens the model)".into()),
                None => (
                    "scale".into(),
                    "its factors' product underflows to 0 in f64, which flattens the model; scale it less".into(),
                ),
            });
        }
        out
    }

    /// The transform as a matrix (T·R·S); call after `problems()` came back empty.
    pub(crate) fn matrix(&self) -> Mat4 {
        if let Some(m) = self.matrix {
            return Mat4(std::array::from_fn(|c| std::array::from_fn(|r| m[4 * c + r])));
        }
        let [sx, sy, sz] = match self.scale {
            Scale::Uniform(s) => [s; 3],
            Scale::PerAxis(s) => s,
        };
        let scale = Mat4([[sx, 0.0, 0.0, 0.0], [0.0, sy, 0.0, 0.0], [0.0, 0.0, sz, 0.0], [0.0, 0.0, 0.0, 1.0]]);
        let rotation = match (self.quaternion, self.rotate) {
            (Some(q), _) => Mat4::from_quaternion(q),
            (None, Some([x, y, z])) => {
                let axis = |k: usize, degrees: f64| {
                    let (s, c) = degrees.to_radians().sin_cos();
                    let mut m = Mat4::IDENTITY;
                    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                    m.0[i][i] = c;
                    m.0[i][j] = s;
                    m.0[j][i] = -s;
                    m.0[j][j] = c;
                    m
                };
                axis(2, z).mul(&axis(1, y)).mul(&axis(0, x))
            }
            (None, None) => Mat4::IDENTITY,
        };
        let mut translation = Mat4::IDENTITY;
        translation.0[3] = [self.translate[0], self.translate[1], self.translate[2], 1.0];
        translation.mul(&rotation).mul(&scale)
    }
}

impl ModelDesc {
    /// The prefix of the model's material names: the object's name, else the file's stem.
    pub fn prefix(&self) -> String {
        if !self.name.is_empty() {
            return self.name.clone();
        }
        Path::new(&self.path).file_stem().map_or_else(|| "model".into(), |s| s.to_string_lossy().into_owned())
    }
}

/// `moved` (the normal `n` through the cofactor matrix) at `n`'s length where the transform
/// took it more than 1000-fold from it: the cofactor matrix scales a normal by the square of a
/// uniform scale, and at 1e-6 or 4e4 validation refused every normal as (near) zero or too
/// long, though the same scale as a glTF node's was taken. Nearer, `moved` is kept bit for bit
/// (the tracer normalises each vertex normal itself; a model's images stay as they were).
fn kept_length(n: [f64; 3], moved: [f64; 3]) -> [f64; 3] {
    let length = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (before, after) = (length(n), length(moved));
    let ratio = after / before;
    if ratio.is_finite() && ratio > 0.0 && !(1e-3..=1e3).contains(&ratio) { moved.map(|x| x / ratio) } else { moved }
}

impl LoadedModel {
    /// An imported model placed by `transform` (meshes moved, normals by the inverse
    /// transpose, winding flipped back under a mirror), its materials renamed `PREFIX/NAME`.
    /// Call with a transform whose `problems()` came back empty.
    pub fn place(file: PathBuf, model: Model, transform: &TransformDesc, prefix: &str) -> Self {
        let m = transform.matrix();
        let mirror = m.determinant3() < 0.0;
        let rename = |name: &str| format!("{prefix}/{name}");
        let meshes = model
            .meshes
            .into_iter()
            .map(|mesh| MeshDesc {
                vertices: mesh.vertices.iter().map(|v| m.point(*v)).collect(),
                normals: mesh.normals.map(|ns| ns.iter().map(|n| kept_length(*n, m.normal(*n))).collect()),
                uvs: mesh.uvs,
                colours: mesh.colours,
                triangles: if mirror {
                    mesh.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect()
                } else {
                    mesh.triangles
                },
                material: rename(&mesh.material),
                name: rename(&mesh.name),
            })
            .collect();
        let materials = model.materials.into_iter().map(|(name, mat)| (rename(&name), mat)).collect();
        let sources = model.sources.into_iter().map(|(name, source)| (rename(&name), source)).collect();
        let cameras = model
            .cameras
            .into_iter()
            .map(|c| ModelCamera {
                camera: CameraDesc {
                    position: m.point(c.camera.position),
                    look_at: m.point(c.camera.look_at),
                    up: m.vector(c.camera.up),
                    // An orthographic view is as tall as the transform stretches the camera's up.
                    view_height: c.camera.view_height.map(|h| {
                        h * glam::DVec3::from(m.vector(c.camera.up)).length() / glam::DVec3::from(c.camera.up).length()
                    }),
                    ..c.camera
                },
                ..c
            })
            .collect();
        // Directions by the linear part, renormalised; a spot's cone and a light's range stay
        // as the file gave them (a non-uniform scale does not reshape them).
        let direction = |d: [f64; 3]| {
            let v = m.vector(d);
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.0 { [v[0] / n, v[1] / n, v[2] / n] } else { v }
        };
        let lights = model
            .lights
            .into_iter()
            .map(|l| LightDesc {
                position: l.position.map(|p| m.point(p)),
                direction: l.direction.map(direction),
                name: if l.name.is_empty() { l.name } else { rename(&l.name) },
                ..l
            })
            .collect();
        Self { file, meshes, materials, sources, cameras, lights, warnings: model.warnings }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MeshDesc;

    #[test]
    fn a_rotation_beyond_a_million_degrees_is_refused_with_what_f64_holds_of_it() {
        let rotated = |r: [f64; 3]| TransformDesc { rotate: Some(r), ..TransformDesc::default() }.problems();
        assert!(rotated([720.0, -1e6, 45.5]).is_empty());
        let problems = rotated([1e30, 0.0, 0.0]);
        assert_eq!(problems.len(), 1, "{problems:?}");
        assert_eq!(problems[0].0, "rotate");
        assert_eq!(
            problems[0].1,
            "each angle must lie in [-1e6, 1e6] degrees; 1e30 is beyond, where f64 holds it only to about 140000000000000 degrees"
        );
    }

    #[test]
    fn a_placed_models_normals_keep_their_length_at_any_scale_and_identity_keeps_them_bit_for_bit() {
        // The cofactor matrix scales a normal by s² (a uniform scale): at 1e-6 and 4e4 every
        // normal was refused by validation.
        let mut mesh = MeshDesc::new(vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2]], "m", "tri");
        let tilted = [0.6, 0.1, 0.8];
        mesh.normals = Some(vec![[0.0, 0.0, 1.0], tilted, [0.3, 0.4, 0.5]]);
        let placed = |scale: Scale| {
            let transform = TransformDesc { scale, ..TransformDesc::default() };
            let model = Model { meshes: vec![mesh.clone()], ..Model::default() };
            LoadedModel::place(PathBuf::from("m.glb"), model, &transform, "m").meshes[0]
                .normals
                .clone()
                .expect("normals")
        };
        assert_eq!(placed(Scale::Uniform(1.0)), mesh.normals.clone().unwrap(), "identity: bit for bit");
        let length = |v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for s in [1e-6, 4e4] {
            for (n, was) in placed(Scale::Uniform(s)).iter().zip(mesh.normals.as_ref().unwrap()) {
                assert!((length(n) / length(was) - 1.0).abs() < 1e-12, "scale {s}: {n:?}");
                assert!((n[0] * was[2] - n[2] * was[0]).abs() < 1e-12, "scale {s}: the direction kept");
            }
        }
        // A scale that keeps the length near: as before (the inverse transpose, unscaled); the
        // tilted normal leans by the inverse of the scale's ratio.
        let n = placed(Scale::PerAxis([2.0, 1.0, 0.5]))[1];
        let expected = (tilted[0] / 2.0) / (tilted[2] / 0.5);
        assert!((n[0] / n[2] - expected).abs() < 1e-12, "{n:?}");
    }
}

#[cfg(test)]
mod scale_tests {
    use super::{Scale, TransformDesc};

    fn read(text: &str) -> Result<Scale, String> {
        toml::from_str::<TransformDesc>(text).map(|t| t.scale).map_err(|e| e.to_string())
    }

    #[test]
    fn a_scale_is_a_number_or_three_and_says_so() {
        assert_eq!(read("scale = 2"), Ok(Scale::Uniform(2.0)));
        assert_eq!(read("scale = [1, 2.5, 3]"), Ok(Scale::PerAxis([1.0, 2.5, 3.0])));
        let wrong = read("scale = \"big\"").unwrap_err();
        assert!(wrong.contains("expected a number (uniform) or an array of three numbers [x, y, z]"), "{wrong}");
        assert!(!wrong.contains("untagged"), "{wrong}");
        assert!(read("scale = [1, 2]").unwrap_err().contains("invalid length 2"));
        assert!(read("scale = [1, 2, 3, 4]").unwrap_err().contains("invalid length 4"));
    }
}
