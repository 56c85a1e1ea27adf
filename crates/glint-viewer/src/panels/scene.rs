//! Scene panel: camera, world and render settings.

use egui::Ui;
use glint_core::scene::{CameraDesc, EpsilonMode, ObjectDesc, SpecularModel, ranges};

use crate::document::Document;
use crate::widgets::{choice, int_slider, rgb_edit, slider};

pub fn ui(ui: &mut Ui, doc: &mut Document) -> bool {
    let mut changed = false;
    egui::CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
        changed |= slider(ui, "Field of view", &mut doc.desc.camera.fov_y, ranges::FOV_Y);
        if ui.button("Reset camera").clicked() {
            doc.desc.camera = doc.initial_camera.clone();
            changed = true;
        }
        changed |= model_cameras(ui, doc);
        ui.weak("In the view: drag to orbit, Shift+drag or middle drag to pan, wheel to zoom.");
    });
    egui::CollapsingHeader::new("World").default_open(true).show(ui, |ui| {
        changed |= rgb_edit(ui, "Ambient I_a", &mut doc.desc.world.ambient);
        changed |= rgb_edit(ui, "Background", &mut doc.desc.world.background);
    });
    egui::CollapsingHeader::new("Render").default_open(true).show(ui, |ui| {
        let r = &mut doc.desc.render;
        // The whole valid range: depths past the GPU's ray stack are for checking its report.
        changed |= int_slider(ui, "Max depth", &mut r.max_depth, ranges::DEPTH);
        changed |= slider(ui, "Bailout", &mut r.bailout, ranges::BAILOUT);
        changed |= slider(ui, "Epsilon", &mut r.epsilon, ranges::EPSILON);
        changed |= choice(ui, "Epsilon strategy", &mut r.epsilon_mode, &EpsilonMode::ALL, EpsilonMode::name);
        changed |= int_slider(ui, "Samples per pixel", &mut r.spp, ranges::SPP);
        changed |= int_slider(ui, "Width", &mut r.width, ranges::IMAGE_SIDE);
        changed |= int_slider(ui, "Height", &mut r.height, ranges::IMAGE_SIDE);
        ui.horizontal(|ui| {
            ui.label("Specular model of all materials");
            for model in [SpecularModel::Blinn, SpecularModel::Phong] {
                let name = if model == SpecularModel::Blinn { "Blinn" } else { "Phong" };
                if ui.button(name).on_hover_text(format!("Set every material to {name}")).clicked() {
                    for m in doc.desc.materials.values_mut() {
                        m.specular_model = model;
                    }
                    changed = true;
                }
            }
        });
    });
    changed
}

/// The cameras of the scene's model files (glTF perspective cameras, placed with the model):
/// choosing one looks through it, as `--camera N` does on the command line.
fn model_cameras(ui: &mut Ui, doc: &mut Document) -> bool {
    let cameras: Vec<(String, CameraDesc)> = doc
        .desc
        .objects
        .iter()
        .filter_map(|o| match o {
            ObjectDesc::Model(m) => m.loaded.as_ref(),
            ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) => None,
        })
        .flat_map(|loaded| loaded.cameras.iter().enumerate().map(|(i, c)| (camera_label(i, &c.name), c.camera.clone())))
        .collect();
    if cameras.is_empty() {
        return false;
    }
    let current = cameras.iter().position(|(_, c)| *c == doc.desc.camera);
    let mut chosen = current;
    egui::ComboBox::from_label("Model camera")
        .selected_text(current.map_or("(moved)", |i| cameras[i].0.as_str()))
        .show_ui(ui, |ui| {
            for (i, (label, _)) in cameras.iter().enumerate() {
                ui.selectable_value(&mut chosen, Some(i), label);
            }
        });
    match chosen {
        Some(i) if chosen != current => {
            doc.desc.camera = cameras[i].1.clone();
            true
        }
        _ => false,
    }
}

fn camera_label(index: usize, name: &str) -> String {
    if name.is_empty() { format!("camera {index}") } else { format!("{index}: {name}") }
}
