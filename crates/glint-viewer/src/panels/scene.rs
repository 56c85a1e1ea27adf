//! Scene panel: camera, world and render settings.

use egui::Ui;
use glint_core::scene::{EpsilonMode, SpecularModel, ranges};

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
