//! The human-editable scene description, exactly as a scene file spells it.
//!
//! Field names and defaults are documented in `docs/scene-format.md`; every struct rejects
//! unknown fields so that a typo is an error instead of a silently ignored setting.

use std::collections::BTreeMap;

use glint_types::{EpsilonMode, Integrator};
use serde::{Deserialize, Serialize};

use super::buffered::Content;
use super::camera::CameraDesc;
use super::light::LightDesc;
use super::material::MaterialDesc;
use super::mesh::MeshDesc;
use super::model_ref::ModelDesc;
use super::number::shorten;
use super::rgb::Rgb;

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
    #[serde(default, deserialize_with = "crate::tables::table")]
    pub render: RenderSettings,
    #[serde(deserialize_with = "crate::tables::table")]
    pub camera: CameraDesc,
    #[serde(default, deserialize_with = "crate::tables::table")]
    pub world: WorldDesc,
    /// Named materials; objects refer to them by name.
    #[serde(default, deserialize_with = "crate::tables::tables_by_name")]
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
            super::tables::table_of(deserializer, "a light: a table ([[lights]] or { type = \"point\", … })").map(Entry)
        }
    }
    let lights: Vec<Entry> = super::tables::array_of(
        deserializer,
        "an array of lights ([[lights]], or lights = [{ type = \"point\", … }])",
    )?;
    Ok(lights.into_iter().map(|e| e.0).collect())
}

/// `objects` one by one, so that an error names its index (`objects[2].type`), which the
/// parser's own position cannot: an object is read as a table first (`ObjectDesc::from_table`).
fn objects_by_index<'de, D: serde::Deserializer<'de>>(deserializer: D) -> Result<Vec<ObjectDesc>, D::Error> {
    use serde::de::Error;
    let entries: Vec<Content> = super::tables::array_of(
        deserializer,
        "an array of objects ([[objects]], or objects = [{ type = \"sphere\", … }])",
    )?;
    entries
        .into_iter()
        .enumerate()
        .map(|(i, entry)| match entry {
            Content::Map(table) => {
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

/// An error on one line, however its format wrote it.
fn one_line(e: &impl std::fmt::Display) -> String {
    crate::number::serde_words(e.to_string().trim()).replace('\n', " ")
}

/// Render settings a scene suggests; command-line flags override each of them.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    #[serde(deserialize_with = "crate::whole::image_side")]
    pub width: u32,
    #[serde(deserialize_with = "crate::whole::image_side")]
    pub height: u32,
    #[serde(deserialize_with = "crate::whole::spp")]
    pub spp: u32,
    #[serde(deserialize_with = "crate::whole::depth")]
    pub max_depth: u32,
    pub bailout: f64,
    pub epsilon: f64,
    pub epsilon_mode: EpsilonMode,
    #[serde(deserialize_with = "crate::whole::seed")]
    pub seed: u32,
    /// What the render computes; Whitted's ray tree unless a scene asks for paths.
    #[serde(skip_serializing_if = "Integrator::is_whitted")]
    pub integrator: Integrator,
    /// Path tracing only: follow the diffuse and glossy lobes (global illumination), or only
    /// k_r and k_t with direct light, the transport Whitted computes (`false`).
    #[serde(skip_serializing_if = "is_true")]
    pub indirect: bool,
}

fn is_true(b: &bool) -> bool {
    *b
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
            integrator: Integrator::Whitted,
            indirect: true,
        }
    }
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
    #[serde(skip_serializing_if = "GlobalAttenuation::is_none", deserialize_with = "crate::tables::table")]
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
    #[serde(deserialize_with = "crate::exact_len::array")]
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
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub point: [f64; 3],
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub normal: [f64; 3],
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
        let table = match Content::deserialize(deserializer)? {
            Content::Map(table) => table,
            other => return Err(D::Error::custom(format!("an object is a table, not {}", other.type_str()))),
        };
        Self::from_table(table).map_err(|e| D::Error::custom(e.trim_start_matches(['.', ' ']).to_string()))
    }
}

impl ObjectDesc {
    /// The kinds `type` takes.
    pub const KINDS: [&str; 4] = ["sphere", "plane", "mesh", "model"];

    /// The object a table describes; an error is the rest of a message after the object's own
    /// path: `.type: …` for its kind, ` (sphere): …` for a field of that kind.
    fn from_table(mut table: Vec<(String, Content)>) -> Result<Self, String> {
        let allowed = Self::KINDS.join(", ");
        let kind = match table.iter().position(|(k, _)| k == "type").map(|i| table.remove(i).1) {
            Some(Content::Str(kind)) => kind,
            Some(other) => {
                return Err(format!(".type: must be a string, one of: {allowed}; got {}", shorten(&other.to_string())));
            }
            None => return Err(format!(".type: missing; an object needs a type, one of: {allowed}")),
        };
        let fields = Content::Map(table);
        let object = match kind.as_str() {
            "sphere" => fields.into_value().map(Self::Sphere),
            "plane" => fields.into_value().map(Self::Plane),
            "mesh" => fields.into_value().map(Self::Mesh),
            "model" => fields.into_value().map(|m| Self::Model(Box::new(m))),
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

/// Where a light the tracers see comes from, named as a user finds it: `lights[i]` in the
/// scene file, `objects[k].lights[j]` for the j-th light a model object imported.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightSource {
    Scene(usize),
    Model { object: usize, light: usize },
}

impl std::fmt::Display for LightSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Scene(i) => write!(f, "lights[{i}]"),
            Self::Model { object, light } => write!(f, "objects[{object}].lights[{light}]"),
        }
    }
}

impl SceneDesc {
    /// Every light that shines on the scene, in the flat layout's order: the scene's
    /// `[[lights]]`, then the lights of each model object that says `lights = true` (placed,
    /// after its exposure).
    pub fn traced_lights(&self) -> impl Iterator<Item = &LightDesc> {
        self.sourced_lights().map(|(_, light)| light)
    }

    /// `traced_lights`, each with where it comes from.
    pub fn sourced_lights(&self) -> impl Iterator<Item = (LightSource, &LightDesc)> {
        let own = self.lights.iter().enumerate().map(|(i, l)| (LightSource::Scene(i), l));
        let imported = self.objects.iter().enumerate().flat_map(|(object, o)| {
            let lights = match o {
                ObjectDesc::Model(m) if m.lights => m.loaded.as_deref().map_or(&[][..], |l| l.lights.as_slice()),
                ObjectDesc::Model(_) | ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) => &[][..],
            };
            lights.iter().enumerate().map(move |(light, l)| (LightSource::Model { object, light }, l))
        });
        own.chain(imported)
    }
}

/// `desc` as a file would hold it: materials a model brought in and nobody changed are left
/// out (they come from the model again when the file is loaded).
pub fn without_imported_materials(desc: &SceneDesc) -> SceneDesc {
    let mut out = desc.clone();
    for object in &desc.objects {
        let ObjectDesc::Model(model) = object else { continue };
        let Some(loaded) = &model.loaded else { continue };
        for (name, imported) in &loaded.materials {
            if out.materials.get(name) == Some(imported) {
                out.materials.remove(name);
            }
        }
    }
    out
}

/// A scene of `objects` for this crate's unit tests: a camera 5 back from the origin, one
/// default material `m`, no lights.
#[cfg(test)]
pub(crate) fn test_scene(objects: Vec<ObjectDesc>) -> SceneDesc {
    SceneDesc {
        description: String::new(),
        provenance: String::new(),
        render: RenderSettings::default(),
        camera: CameraDesc::perspective([0.0, 2.0, -5.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0),
        world: WorldDesc::default(),
        materials: [("m".to_string(), MaterialDesc::default())].into(),
        lights: Vec::new(),
        objects,
    }
}
