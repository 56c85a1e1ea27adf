//! The human-editable scene description, exactly as a scene file spells it.
//!
//! Field names and defaults are documented in `docs/scene-format.md`; every struct rejects
//! unknown fields so that a typo is an error instead of a silently ignored setting.

use std::collections::BTreeMap;

use glint_types::{EpsilonMode, Fresnel, SpecularModel};
use serde::{Deserialize, Serialize};

use super::light::LightDesc;
use super::model_ref::ModelDesc;
use super::number::shorten;
use super::rgb::Rgb;
use super::texture::TextureDesc;

/// A whole scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// Free text shown by `glint render --list` and in the viewer.
    #[serde(default)]
    pub description: String,
    /// Where the scene comes from (paper, figure, author).
    #[serde(default)]
    pub provenance: String,
    #[serde(default)]
    pub render: RenderSettings,
    pub camera: CameraDesc,
    #[serde(default)]
    pub world: WorldDesc,
    /// Named materials; objects refer to them by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDesc>,
    #[serde(default, deserialize_with = "lights_as_tables")]
    pub lights: Vec<LightDesc>,
    #[serde(default, deserialize_with = "objects_by_index")]
    pub objects: Vec<ObjectDesc>,
}

/// `lights`, each entry a table: an entry that is not (`lights = [[{ … }]]`) says that a light
/// is a table, instead of serde's "wanted exactly 1 element" (a struct can be read from a
/// sequence of its fields). A table is read by `LightDesc`'s derive as before, so an error in it
/// keeps the parser's position of the field.
fn lights_as_tables<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<LightDesc>, D::Error> {
    struct Entry(LightDesc);
    impl<'de> Deserialize<'de> for Entry {
        fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
            deserializer.deserialize_any(EntryVisitor)
        }
    }
    struct EntryVisitor;
    impl<'de> serde::de::Visitor<'de> for EntryVisitor {
        type Value = Entry;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a light: a table ([[lights]] or { type = \"point\", … })")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<Entry, A::Error> {
            LightDesc::deserialize(serde::de::value::MapAccessDeserializer::new(map)).map(Entry)
        }
    }
    Ok(Vec::<Entry>::deserialize(deserializer)?.into_iter().map(|e| e.0).collect())
}

/// `objects` one by one, so that an error names its index (`objects[2].type`), which the
/// parser's own position cannot: an object is read as a table first (`ObjectDesc::from_table`).
fn objects_by_index<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<ObjectDesc>, D::Error> {
    use serde::de::Error;
    let entries = Vec::<toml::Value>::deserialize(deserializer)?;
    entries
        .into_iter()
        .enumerate()
        .map(|(i, entry)| match entry {
            toml::Value::Table(table) => {
                ObjectDesc::from_table(table).map_err(|e| D::Error::custom(format!("objects[{i}]{e}")))
            }
            other => Err(D::Error::custom(format!(
                "objects[{i}]: an object is a table ([[objects]] or {{ type = \"sphere\", … }}), not {} {}",
                article(other.type_str()),
                other.type_str()
            ))),
        })
        .collect()
}

fn article(noun: &str) -> &'static str {
    if noun.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" }
}

/// toml puts the field on a line of its own ("…\nin `radius`"): one line reads better.
fn one_line(e: &impl std::fmt::Display) -> String {
    e.to_string().trim().replace('\n', " ")
}

/// Render settings a scene suggests; command-line flags override each of them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: u32,
    pub bailout: f64,
    pub epsilon: f64,
    pub epsilon_mode: EpsilonMode,
    pub seed: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 640,
            height: 480,
            spp: 1,
            max_depth: 5,
            bailout: 1.0 / 255.0,
            epsilon: 1e-6,
            epsilon_mode: EpsilonMode::Robust,
            seed: 0,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    pub position: [f64; 3],
    pub look_at: [f64; 3],
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees, in [1e-6, 179].
    #[serde(default = "default_fov")]
    pub fov_y: f64,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_fov() -> f64 {
    45.0
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldDesc {
    /// Global ambient intensity I_a.
    pub ambient: Rgb,
    /// Radiance of rays that miss everything.
    pub background: Rgb,
    /// Attenuation of the reflected and transmitted terms by the distance their ray travelled
    /// (the seed's "distance attenuation coefficients with k_rg and k_s"); (1, 0, 0) is off.
    #[serde(skip_serializing_if = "GlobalAttenuation::is_none")]
    pub global_attenuation: GlobalAttenuation,
}

impl Default for WorldDesc {
    fn default() -> Self {
        Self { ambient: Rgb::splat(0.1), background: Rgb::splat(0.0), global_attenuation: GlobalAttenuation::NONE }
    }
}

/// f_att = 1 / (c + l·d + q·d²) of a child ray that travelled d before its hit, multiplying
/// what it brings back (`world.global_attenuation = { c, l, q }`, validated as a light's).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GlobalAttenuation {
    #[serde(default = "one")]
    pub c: f64,
    #[serde(default)]
    pub l: f64,
    #[serde(default)]
    pub q: f64,
}

fn one() -> f64 {
    1.0
}

impl GlobalAttenuation {
    /// f_att = 1: no attenuation, the default.
    pub const NONE: Self = Self { c: 1.0, l: 0.0, q: 0.0 };

    pub fn is_none(&self) -> bool {
        *self == Self::NONE
    }
}

impl Default for GlobalAttenuation {
    fn default() -> Self {
        Self::NONE
    }
}

/// The Beckmann roughness m of a material that does not set it: the lobe width of the default
/// shininess 32, since (N·H)^n ≈ exp(−n·α²/2) and the Beckmann lobe ≈ exp(−α²/m²) near the
/// peak give m = √(2/n) = 0.25.
pub const DEFAULT_ROUGHNESS: f64 = 0.25;

fn default_roughness() -> f64 {
    DEFAULT_ROUGHNESS
}

fn is_default_fresnel(f: &Fresnel) -> bool {
    *f == Fresnel::default()
}

fn is_default_roughness(m: &f64) -> bool {
    *m == DEFAULT_ROUGHNESS
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialDesc {
    pub ka: Rgb,
    pub kd: Rgb,
    pub ks: Rgb,
    /// Specular exponent n, in [0, 1e6].
    pub shininess: f64,
    pub specular_model: SpecularModel,
    /// Beckmann roughness m (RMS slope of the microfacets) of the Cook–Torrance lobe, in
    /// [1e-3, 1]; kept, unused, under the other models.
    #[serde(default = "default_roughness", skip_serializing_if = "is_default_roughness")]
    pub roughness: f64,
    /// The Cook–Torrance lobe's Fresnel factor; kept, unused, under the other models.
    #[serde(skip_serializing_if = "is_default_fresnel")]
    pub fresnel: Fresnel,
    pub kr: Rgb,
    pub kt: Rgb,
    pub ior: f64,
    pub emission: Rgb,
    /// A two-colour checker (k_d and `checker.kd`) in planar coordinates: stored as a 2×2
    /// texture, so it colours k_a as well as k_d, as `texture` does.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub checker: Option<CheckerDesc>,
    /// Base-colour texture: its colour multiplies k_a and k_d (POV-Ray's pigment, OpenGL's
    /// ambient-and-diffuse colour material, glTF's base colour × factor).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureDesc>,
    /// Emission texture: its colour multiplies E_m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub emission_texture: Option<TextureDesc>,
}

impl Default for MaterialDesc {
    fn default() -> Self {
        Self {
            ka: Rgb::splat(1.0),
            kd: Rgb::splat(0.8),
            ks: Rgb::splat(0.0),
            shininess: 32.0,
            specular_model: SpecularModel::Blinn,
            roughness: DEFAULT_ROUGHNESS,
            fresnel: Fresnel::Exact,
            kr: Rgb::splat(0.0),
            kt: Rgb::splat(0.0),
            ior: 1.5,
            emission: Rgb::splat(0.0),
            checker: None,
            texture: None,
            emission_texture: None,
        }
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckerDesc {
    /// The second colour of the checker (the first is the material's k_d).
    pub kd: Rgb,
    /// Edge length of one square in scene units, > 0.
    pub size: f64,
}

/// An object: `type = "sphere" | "plane" | "mesh" | "model"` and that kind's fields.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ObjectDesc {
    Sphere(SphereDesc),
    Plane(PlaneDesc),
    Mesh(MeshDesc),
    /// Boxed: a reference with its transform is three times the size of the other kinds.
    Model(Box<ModelDesc>),
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereDesc {
    pub center: [f64; 3],
    pub radius: f64,
    pub material: String,
    #[serde(default)]
    pub name: String,
}

/// The infinite plane through `point` with normal `normal`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneDesc {
    pub point: [f64; 3],
    pub normal: [f64; 3],
    pub material: String,
    #[serde(default)]
    pub name: String,
}

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

/// By hand rather than serde's internally tagged derive: that one buffers the object before
/// choosing its kind, and its errors lose the field ("expected f64" without saying where).
/// Here the kind's own struct reads the fields, and an error names the one at fault.
impl<'de> Deserialize<'de> for ObjectDesc {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let table = toml::Table::deserialize(deserializer)?;
        Self::from_table(table).map_err(|e| D::Error::custom(e.trim_start_matches(['.', ' ']).to_string()))
    }
}

impl ObjectDesc {
    /// The kinds `type` takes.
    pub const KINDS: [&str; 4] = ["sphere", "plane", "mesh", "model"];

    /// The object a table describes; an error is the rest of a message after the object's own
    /// path: `.type: …` for its kind, ` (sphere): …` for a field of that kind.
    fn from_table(mut table: toml::Table) -> Result<Self, String> {
        let allowed = Self::KINDS.join(", ");
        let kind = match table.remove("type") {
            Some(toml::Value::String(kind)) => kind,
            Some(other) => {
                return Err(format!(".type: must be a string, one of: {allowed}; got {}", shorten(&other.to_string())));
            }
            None => return Err(format!(".type: missing; an object needs a type, one of: {allowed}")),
        };
        let fields = toml::Value::Table(table);
        let object = match kind.as_str() {
            "sphere" => fields.try_into().map(Self::Sphere),
            "plane" => fields.try_into().map(Self::Plane),
            "mesh" => fields.try_into().map(Self::Mesh),
            "model" => fields.try_into().map(|m| Self::Model(Box::new(m))),
            other => return Err(format!(".type: unknown object type \"{}\"; allowed: {allowed}", shorten(other))),
        };
        object.map_err(|e| format!(" ({kind}): {}", one_line(&e)))
    }
}

impl ObjectDesc {
    /// The object's material; a model's first (it has one per mesh: `materials()`).
    pub fn material(&self) -> &str {
        match self {
            Self::Sphere(o) => &o.material,
            Self::Plane(o) => &o.material,
            Self::Mesh(o) => &o.material,
            Self::Model(o) => o.loaded.as_ref().and_then(|m| m.meshes.first()).map_or("", |m| m.material.as_str()),
        }
    }

    /// Every material the object uses, in the order of its meshes.
    pub fn materials(&self) -> Vec<&str> {
        match self {
            Self::Sphere(_) | Self::Plane(_) | Self::Mesh(_) => vec![self.material()],
            Self::Model(o) => {
                o.loaded.as_ref().map_or_else(Vec::new, |m| m.meshes.iter().map(|x| x.material.as_str()).collect())
            }
        }
    }

    pub fn name(&self) -> &str {
        match self {
            Self::Sphere(o) => &o.name,
            Self::Plane(o) => &o.name,
            Self::Mesh(o) => &o.name,
            Self::Model(o) => &o.name,
        }
    }

    pub fn kind_name(&self) -> &'static str {
        match self {
            Self::Sphere(_) => "sphere",
            Self::Plane(_) => "plane",
            Self::Mesh(_) => "mesh",
            Self::Model(_) => "model",
        }
    }
}
