//! Built-in scenes, embedded in the binary so that they work from any folder: TOML text, or
//! a generator that makes the scene in code at a resolution (`bumpy`: millions of triangles
//! would be a file of hundreds of megabytes).

use std::ops::RangeInclusive;
use std::path::Path;

use glint_scene::{FieldIssue, SceneDesc, bumpy, validate};

use crate::error::SceneError;
use crate::parse_scene;

/// Resolutions N a generated scene accepts (4·N² triangles for `bumpy`: 16 to 9,000,000; the
/// GPU buffer limits end lower, and say so).
pub const RESOLUTIONS: RangeInclusive<u32> = 2..=1500;

/// The resolution of a generated scene when none is asked for: 1,000,000 sphere triangles.
pub const DEFAULT_RESOLUTION: u32 = 500;

/// Where a built-in scene's description comes from.
#[derive(Clone, Copy, Debug)]
pub enum BuiltinSource {
    /// Scene file text (`assets/scenes/NAME.toml`).
    Toml(&'static str),
    /// Made in code at a resolution in `RESOLUTIONS` (default `DEFAULT_RESOLUTION`), with the
    /// vertices and triangles its meshes will have, told without making them.
    Generated { make: fn(u32) -> SceneDesc, mesh_size: fn(u32) -> (u64, u64) },
}

#[derive(Clone, Copy, Debug)]
pub struct BuiltinScene {
    pub name: &'static str,
    pub source: BuiltinSource,
}

macro_rules! scene {
    ($name:literal) => {
        BuiltinScene {
            name: $name,
            source: BuiltinSource::Toml(include_str!(concat!("../../../assets/scenes/", $name, ".toml"))),
        }
    };
}

pub const BUILTIN_SCENES: &[BuiltinScene] = &[
    scene!("whitted"),
    scene!("cornell"),
    scene!("spotlights"),
    scene!("highlights"),
    scene!("lights"),
    BuiltinScene {
        name: "bumpy",
        source: BuiltinSource::Generated { make: bumpy::bumpy, mesh_size: bumpy::bumpy_mesh_size },
    },
    BuiltinScene {
        name: "bumpy-glass",
        source: BuiltinSource::Generated { make: bumpy::bumpy_glass, mesh_size: bumpy::bumpy_mesh_size },
    },
    // Last: test suites key their recorded images by the order they render the scenes in.
    scene!("cornell-gi"),
];

pub fn builtin(name: &str) -> Option<&'static BuiltinScene> {
    BUILTIN_SCENES.iter().find(|b| b.name == name)
}

/// The names of the generated scenes, comma-separated (for messages).
pub fn generated_names() -> String {
    BUILTIN_SCENES.iter().filter(|b| b.is_generated()).map(|b| b.name).collect::<Vec<_>>().join(", ")
}

impl BuiltinScene {
    /// The scene file text of a TOML scene (`None` for a generated one).
    pub fn toml(&self) -> Option<&'static str> {
        match self.source {
            BuiltinSource::Toml(text) => Some(text),
            BuiltinSource::Generated { .. } => None,
        }
    }

    pub fn is_generated(&self) -> bool {
        matches!(self.source, BuiltinSource::Generated { .. })
    }

    /// A generated scene's resolution (`resolution` or the default) and the vertices and
    /// triangles its meshes will have there, before it is made; `None` for a TOML scene or a
    /// resolution out of range (which `load` refuses).
    pub fn generated_size(&self, resolution: Option<u32>) -> Option<(u32, u64, u64)> {
        match self.source {
            BuiltinSource::Toml(_) => None,
            BuiltinSource::Generated { mesh_size, .. } => {
                let n = resolution.unwrap_or(DEFAULT_RESOLUTION);
                RESOLUTIONS.contains(&n).then(|| {
                    let (vertices, triangles) = mesh_size(n);
                    (n, vertices, triangles)
                })
            }
        }
    }

    /// The validated description. `resolution` is for generated scenes only: asking a TOML
    /// scene for one is an error rather than a silently ignored flag.
    pub fn load(&self, resolution: Option<u32>) -> Result<(SceneDesc, Vec<FieldIssue>), SceneError> {
        let source = format!("builtin:{}", self.name);
        match self.source {
            BuiltinSource::Toml(text) => match resolution {
                Some(value) => {
                    Err(SceneError::NotGenerated { name: self.name.to_string(), value, generated: generated_names() })
                }
                None => parse_scene(text, Path::new(&source)),
            },
            BuiltinSource::Generated { make: generate, .. } => {
                let n = resolution.unwrap_or(DEFAULT_RESOLUTION);
                if !RESOLUTIONS.contains(&n) {
                    return Err(SceneError::Resolution {
                        name: self.name.to_string(),
                        value: n,
                        min: *RESOLUTIONS.start(),
                        max: *RESOLUTIONS.end(),
                    });
                }
                let desc = generate(n);
                let report = validate(&desc);
                if report.errors.is_empty() {
                    Ok((desc, report.warnings))
                } else {
                    Err(SceneError::Invalid { file: source.into(), issues: report.errors })
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_generated_scenes_take_a_resolution() {
        for (i, b) in BUILTIN_SCENES.iter().enumerate() {
            assert!(BUILTIN_SCENES[..i].iter().all(|o| o.name != b.name), "{} twice", b.name);
        }
        let bumpy = builtin("bumpy").expect("bumpy is built in");
        assert!(bumpy.is_generated() && bumpy.toml().is_none());
        let (desc, _) = bumpy.load(Some(4)).expect("N = 4 loads");
        assert!(desc.description.contains("4·N² triangles"), "{}", desc.description);
        let mesh_triangles = |d: &SceneDesc| -> usize {
            d.objects.iter().map(|o| if let glint_scene::ObjectDesc::Mesh(m) = o { m.triangles.len() } else { 0 }).sum()
        };
        assert_eq!(mesh_triangles(&desc), 4 * 4 * 4 + 2);
        for bad in [0, 1, 1501] {
            let e = bumpy.load(Some(bad)).expect_err("outside the range").to_string();
            assert!(e.contains(&bad.to_string()) && e.contains("2..=1500"), "{e}");
        }
        let e = builtin("whitted").unwrap().load(Some(20)).expect_err("not generated").to_string();
        assert!(e.contains("whitted") && e.contains("bumpy"), "{e}");
    }

    #[test]
    fn a_generated_scenes_size_is_told_before_it_is_made() {
        for b in BUILTIN_SCENES.iter().filter(|b| b.is_generated()) {
            for n in [2, 3, 17] {
                let (desc, _) = b.load(Some(n)).expect("generated");
                let meshes = desc.objects.iter().filter_map(|o| match o {
                    glint_scene::ObjectDesc::Mesh(m) => Some((m.vertices.len() as u64, m.triangles.len() as u64)),
                    _ => None,
                });
                let made = meshes.fold((0, 0), |(v, t), (mv, mt)| (v + mv, t + mt));
                let (_, vertices, triangles) = b.generated_size(Some(n)).expect("a generated scene's size");
                assert_eq!((vertices, triangles), made, "{} at {n}", b.name);
            }
            assert_eq!(b.generated_size(None).map(|s| s.0), Some(DEFAULT_RESOLUTION));
            assert_eq!(b.generated_size(Some(*RESOLUTIONS.end() + 1)), None);
        }
        assert!(builtin("whitted").expect("built-in").generated_size(None).is_none());
    }
}
