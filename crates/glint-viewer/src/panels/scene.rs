//! Scene panel: camera, world and render settings.

use egui::Ui;
use glint_core::scene::{EpsilonMode, MAX_DEPTH, MAX_INTENSITY, MAX_SPP, SpecularModel};

use crate::document::Document;
use crate::widgets::{choice, int_log_slider, log_slider, rgb_edit, slider};

pub fn ui(ui: &mut Ui, doc: &mut Document) -> bool {
    let mut changed = false;
    egui::CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
        changed |= slider(ui, "Field of view", &mut doc.desc.camera.fov_y, 1.0..=179.0);
        if ui.button("Reset camera").clicked() {
            doc.desc.camera = doc.initial_camera.clone();
            changed = true;
        }
        ui.weak("In the view: drag to orbit, Shift+drag or middle drag to pan, wheel to zoom.");
    });
    egui::CollapsingHeader::new("World").default_open(true).show(ui, |ui| {
        changed |= rgb_edit(ui, "Ambient I_a", &mut doc.desc.world.ambient, MAX_INTENSITY);
        changed |= rgb_edit(ui, "Background", &mut doc.desc.world.background, MAX_INTENSITY);
    });
    egui::CollapsingHeader::new("Render").default_open(true).show(ui, |ui| {
        let r = &mut doc.desc.render;
        // The whole valid range: depths past the GPU's ray stack are for checking its report.
        changed |= int_log_slider(ui, "Max depth", &mut r.max_depth, 0..=MAX_DEPTH);
        changed |= slider(ui, "Bailout", &mut r.bailout, 0.0..=0.25);
        changed |= log_slider(ui, "Epsilon", &mut r.epsilon, 1e-9..=1.0);
        changed |= choice(ui, "Epsilon strategy", &mut r.epsilon_mode, &EpsilonMode::ALL, EpsilonMode::name);
        changed |= int_log_slider(ui, "Samples per pixel", &mut r.spp, 1..=MAX_SPP);
        changed |= slider(ui, "Width", &mut r.width, 16..=1920);
        changed |= slider(ui, "Height", &mut r.height, 16..=1080);
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
