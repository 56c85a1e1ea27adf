//! Materials panel: the material of the picked object (or any material by name).

use egui::Ui;
use glint_scene::{CheckerDesc, Fresnel, ObjectDesc, Rgb, SpecularModel, format_number, ranges};

use crate::document::Document;
use crate::widgets::{choice, log_slider, rgb_edit};

pub fn ui(
    ui: &mut Ui,
    doc: &mut Document,
    selected_object: Option<usize>,
    selected_material: &mut Option<String>,
) -> bool {
    let mut changed = false;
    if let Some(i) = selected_object {
        let label = doc.object_label(i);
        if let Some(o) = doc.desc.objects.get(i) {
            ui.label(format!("Selected: {label} ({})", o.kind_name()));
            // Picking chose the material clicked; any other is the user's choice in the list,
            // kept (set every frame, a model's other materials could not be chosen).
            if selected_material.as_ref().is_none_or(|m| !doc.desc.materials.contains_key(m)) {
                *selected_material = Some(o.material().to_string());
            }
        }
    } else {
        ui.weak("Click an object in the view to select it.");
    }
    let names: Vec<String> = doc.desc.materials.keys().cloned().collect();
    let current = selected_material.clone().filter(|n| doc.desc.materials.contains_key(n));
    let combo = egui::ComboBox::from_label("Material")
        .selected_text(current.clone().unwrap_or_else(|| "—".into()))
        .show_ui(ui, |ui| {
            for n in &names {
                if ui.selectable_label(current.as_deref() == Some(n), n).clicked() {
                    *selected_material = Some(n.clone());
                }
            }
        });
    crate::help::hint(combo.response, "Material");
    let Some(name) = current else { return changed };
    let users = doc.desc.objects.iter().filter(|o| o.material() == name).count();
    if users > 1 {
        ui.weak(format!("Shared by {users} objects."));
    }
    imported_ui(ui, doc, &name);
    let Some(m) = doc.desc.materials.get_mut(&name) else { return changed };
    changed |= rgb_edit(ui, "k_a", &mut m.ka);
    changed |= rgb_edit(ui, "k_d", &mut m.kd);
    changed |= rgb_edit(ui, "k_s", &mut m.ks);
    changed |= choice(ui, "Specular model", &mut m.specular_model, &SpecularModel::ALL, model_label);
    // Each model's own parameters; the others' stay in the material, unused.
    match m.specular_model {
        SpecularModel::Blinn | SpecularModel::Phong => {
            changed |= log_slider(ui, "Shininess n", &mut m.shininess, ranges::SHININESS, (1.0, 1e3));
        }
        SpecularModel::CookTorrance => {
            changed |= log_slider(ui, "Roughness m", &mut m.roughness, ranges::ROUGHNESS, (1e-3, 1.0));
            changed |= choice(ui, "Fresnel", &mut m.fresnel, &Fresnel::ALL, fresnel_label);
        }
    }
    changed |= rgb_edit(ui, "k_r", &mut m.kr);
    changed |= rgb_edit(ui, "k_t", &mut m.kt);
    // The whole valid range: ior < 1 (a bubble) and 100 (stiff case 13) too.
    changed |= log_slider(ui, "Index of refraction", &mut m.ior, ranges::IOR, (0.5, 5.0));
    changed |= rgb_edit(ui, "E_m", &mut m.emission);
    // Image textures are shown, not edited (their file is the scene's); a checker and a base
    // colour texture exclude each other.
    for (label, texture) in [("Texture (× k_a, k_d)", &m.texture), ("Emission texture (× E_m)", &m.emission_texture)]
    {
        if let Some(t) = texture {
            let size = t.image.as_ref().map_or_else(String::new, |i| format!(", {}×{}", i.width(), i.height()));
            ui.label(format!("{label}: {}{size}", t.path));
        }
    }
    let mut has_checker = m.checker.is_some();
    let checker = crate::help::hint(
        ui.add_enabled(m.texture.is_none(), egui::Checkbox::new(&mut has_checker, "Checker")),
        "Checker",
    );
    if checker.changed() {
        m.checker = has_checker.then(|| CheckerDesc { kd: Rgb::splat(0.1), size: 1.0 });
        changed = true;
    }
    if let Some(c) = &mut m.checker {
        changed |= rgb_edit(ui, "Checker k_d", &mut c.kd);
        changed |= log_slider(ui, "Checker size", &mut c.size, ranges::CHECKER_SIZE, (0.01, 100.0));
    }
    changed
}

fn model_label(model: SpecularModel) -> &'static str {
    match model {
        SpecularModel::Blinn => "Blinn (N·H)^n",
        SpecularModel::Phong => "Phong (R·V)^n",
        SpecularModel::CookTorrance => "Cook–Torrance F·D·G/(N·V)",
    }
}

fn fresnel_label(fresnel: Fresnel) -> &'static str {
    match fresnel {
        Fresnel::Exact => "exact (from the ior)",
        Fresnel::Schlick => "Schlick (from the ior)",
    }
}

fn numbers(values: &[f64]) -> String {
    values.iter().map(|v| format_number(*v)).collect::<Vec<_>>().join(" ")
}

/// Values the import computed, to 7 significant digits, as the file's f32 factors are shown:
/// a roughness of 0.05 maps to n = 319998, which f64 arithmetic gives as 319997.9999999999.
fn computed(values: &[f64]) -> String {
    values.iter().map(|v| glint_scene::format_rounded(*v, 7)).collect::<Vec<_>>().join(" ")
}

/// For a material a model file brought in: what the file said (glTF factors, MTL statements)
/// beside the seed's coefficients they were mapped to on import; the editors below hold the
/// current values.
fn imported_ui(ui: &mut Ui, doc: &Document, name: &str) {
    let imported = doc.desc.objects.iter().find_map(|o| match o {
        ObjectDesc::Model(m) => {
            let loaded = m.loaded.as_ref()?;
            Some((&loaded.file, loaded.sources.get(name)?, loaded.materials.get(name)?))
        }
        _ => None,
    });
    let Some((file, source, mapped)) = imported else { return };
    let file = file.file_name().map_or_else(|| file.display().to_string(), |f| f.to_string_lossy().into_owned());
    ui.separator();
    // Each column left-aligned, not justified: a justified column spread a wrapped heading
    // letter by letter across its width ("g l T F   i n").
    ui.columns(2, |columns| {
        columns[0].vertical(|ui| {
            ui.strong(format!("{} in {file}", source.format));
            for (field, values) in &source.fields {
                ui.label(format!("{field} = {}", numbers(values)));
            }
        });
        columns[1].vertical(|ui| {
            ui.strong("Mapped on import");
            let rgb = |r: &Rgb| computed(&r.0);
            for (label, value) in [
                ("k_a", rgb(&mapped.ka)),
                ("k_d", rgb(&mapped.kd)),
                ("k_s", rgb(&mapped.ks)),
                ("n", computed(&[mapped.shininess])),
                ("k_r", rgb(&mapped.kr)),
                ("k_t", rgb(&mapped.kt)),
                ("ior", computed(&[mapped.ior])),
                ("E_m", rgb(&mapped.emission)),
            ] {
                ui.label(format!("{label} = {value}"));
            }
        });
    });
    if doc.desc.materials.get(name) != Some(mapped) {
        ui.weak("Edited since the import (the values below).");
    }
    ui.separator();
}
