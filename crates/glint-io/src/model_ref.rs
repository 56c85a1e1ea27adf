//! The model files a scene's `type = "model"` objects refer to, read and placed.

use std::collections::btree_map::Entry;
use std::path::Path;
use std::sync::Arc;

use glint_scene::{FieldIssue, LoadedModel, MaterialDesc, ModelDesc, ObjectDesc, SceneDesc};

use crate::model::{ImportOptions, ModelError, load_model_file};

/// Reads the model file `reference` refers to (relative to `folder`) and places it
/// (`LoadedModel::place`).
pub fn load_model_ref(reference: &ModelDesc, folder: &Path, prefix: &str) -> Result<LoadedModel, ModelError> {
    let file = folder.join(&reference.path);
    let exposure = reference.exposure.unwrap_or(ImportOptions::default().exposure);
    let options = ImportOptions {
        scene_index: reference.scene_index,
        exposure,
        lights: reference.lights,
        ..ImportOptions::default()
    };
    let model = load_model_file(&file, &options)?;
    Ok(LoadedModel::place(file, model, &reference.transform, prefix))
}

/// Loads every `type = "model"` object of `desc` (paths relative to `folder`) and adds its
/// materials to the scene's, except those the scene defines itself: a scene material named
/// `OBJECT/MATERIAL` overrides the model's. Returns the models' warnings, or every error.
pub fn load_models(desc: &mut SceneDesc, folder: &Path) -> Result<Vec<FieldIssue>, Vec<FieldIssue>> {
    let (mut warnings, mut errors) = (Vec::new(), Vec::new());
    for (i, object) in desc.objects.iter_mut().enumerate() {
        let ObjectDesc::Model(model) = object else { continue };
        let problems = model.transform.problems();
        if !problems.is_empty() {
            errors.extend(
                problems
                    .into_iter()
                    .map(|(f, problem)| FieldIssue { field: format!("objects[{i}].transform.{f}"), problem }),
            );
            continue;
        }
        match load_model_ref(model, folder, &model.prefix()) {
            Ok(loaded) => {
                warnings.extend(loaded.warnings.iter().map(|w| FieldIssue {
                    field: format!("objects[{i}] ({}): {}", model.path, w.field),
                    problem: w.problem.clone(),
                }));
                for (name, material) in &loaded.materials {
                    match desc.materials.entry(name.clone()) {
                        Entry::Vacant(e) => {
                            e.insert(material.clone());
                        }
                        Entry::Occupied(mut e) => share_model_images(e.get_mut(), material),
                    }
                }
                model.loaded = Some(Arc::new(loaded));
            }
            Err(e) => errors.push(FieldIssue { field: format!("objects[{i}].path"), problem: e.to_string() }),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    warnings.extend(overrides_of_nothing(desc));
    Ok(warnings)
}

/// How many of a model's material names a warning lists.
const LISTED_MATERIALS: usize = 8;

/// Scene materials named as a model's (`OBJECT/MATERIAL`) that the model does not have and no
/// object of the scene uses: a misspelt override, which would otherwise change nothing,
/// silently.
fn overrides_of_nothing(desc: &SceneDesc) -> Vec<FieldIssue> {
    let models: Vec<(String, &LoadedModel)> = desc
        .objects
        .iter()
        .filter_map(|o| match o {
            ObjectDesc::Model(m) => m.loaded.as_deref().map(|loaded| (format!("{}/", m.prefix()), loaded)),
            ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) => None,
        })
        .collect();
    let mut warnings = Vec::new();
    for name in desc.materials.keys() {
        let Some((prefix, model)) = models.iter().find(|(prefix, _)| name.starts_with(prefix.as_str())) else {
            continue;
        };
        if models.iter().any(|(_, m)| m.materials.contains_key(name))
            || desc.objects.iter().any(|o| o.material() == name)
        {
            continue;
        }
        let own: Vec<&str> = model.materials.keys().filter_map(|n| n.strip_prefix(prefix.as_str())).collect();
        let listed = own.iter().take(LISTED_MATERIALS).map(|n| format!("\"{n}\"")).collect::<Vec<_>>().join(", ");
        let more = if own.len() > LISTED_MATERIALS { format!(", … ({} in all)", own.len()) } else { String::new() };
        let listed = if own.is_empty() { "it has none".to_string() } else { format!("its materials: {listed}{more}") };
        warnings.push(FieldIssue {
            field: format!("materials.\"{name}\""),
            problem: format!(
                "overrides nothing: the model {} has no material \"{}\" ({listed})",
                model.file.display(),
                &name[prefix.len()..]
            ),
        });
    }
    warnings
}

/// A scene material that overrides an imported one keeps the model's decoded image where its
/// texture names the same image: the name is the model's own (`images[0]` for an image inside
/// the file, a URI relative to the model's folder), which cannot be read from the scene's
/// folder. So a saved edit of a textured model material loads again.
fn share_model_images(over: &mut MaterialDesc, imported: &MaterialDesc) {
    for (mine, theirs) in
        [(&mut over.texture, &imported.texture), (&mut over.emission_texture, &imported.emission_texture)]
    {
        if let (Some(mine), Some(theirs)) = (mine.as_mut(), theirs)
            && mine.image.is_none()
            && mine.path == theirs.path
        {
            mine.image.clone_from(&theirs.image);
        }
    }
}
