//! Materials panel: the material of the picked object (or any material by name).

use egui::Ui;
use glint_core::scene::{CheckerDesc, Rgb, SpecularModel, ranges};

use crate::document::Document;
use crate::widgets::{choice, rgb_edit, slider};

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
            *selected_material = Some(o.material().to_string());
        }
    } else {
        ui.weak("Click an object in the view to select it.");
    }
    let names: Vec<String> = doc.desc.materials.keys().cloned().collect();
    let current = selected_material.clone().filter(|n| doc.desc.materials.contains_key(n));
    egui::ComboBox::from_label("Material").selected_text(current.clone().unwrap_or_else(|| "—".into())).show_ui(
        ui,
        |ui| {
            for n in &names {
                if ui.selectable_label(current.as_deref() == Some(n), n).clicked() {
                    *selected_material = Some(n.clone());
                }
            }
        },
    );
    let Some(name) = current else { return changed };
    let users = doc.desc.objects.iter().filter(|o| o.material() == name).count();
    if users > 1 {
        ui.weak(format!("Shared by {users} objects."));
    }
    let Some(m) = doc.desc.materials.get_mut(&name) else { return changed };
    changed |= rgb_edit(ui, "k_a", &mut m.ka);
    changed |= rgb_edit(ui, "k_d", &mut m.kd);
    changed |= rgb_edit(ui, "k_s", &mut m.ks);
    changed |= slider(ui, "Shininess n", &mut m.shininess, ranges::SHININESS);
    changed |=
        choice(ui, "Specular model", &mut m.specular_model, &[SpecularModel::Blinn, SpecularModel::Phong], |s| {
            if s == SpecularModel::Blinn { "Blinn (N·H)" } else { "Phong (R·V)" }
        });
    changed |= rgb_edit(ui, "k_r", &mut m.kr);
    changed |= rgb_edit(ui, "k_t", &mut m.kt);
    // The whole valid range: ior < 1 (a bubble) and 100 (stiff case 13) too.
    changed |= slider(ui, "Index of refraction", &mut m.ior, ranges::IOR);
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
    let checker = ui.add_enabled(m.texture.is_none(), egui::Checkbox::new(&mut has_checker, "Checker"));
    if checker.changed() {
        m.checker = has_checker.then(|| CheckerDesc { kd: Rgb::splat(0.1), size: 1.0 });
        changed = true;
    }
    if let Some(c) = &mut m.checker {
        changed |= rgb_edit(ui, "Checker k_d", &mut c.kd);
        changed |= slider(ui, "Checker size", &mut c.size, ranges::SIZE);
    }
    changed
}
