//! Scene panel: camera, world and render settings.

use egui::Ui;
use glint_scene::{
    CameraDesc, EpsilonMode, GlobalAttenuation, Integrator, ObjectDesc, PathKind, Projection, SpecularModel, ranges,
};

use crate::ambient_fit::AmbientFitter;
use crate::document::Document;
use crate::widgets::{choice, int_slider, log_slider, number, rgb_edit, slider};

/// What switching the world's global attenuation on starts from: a gentle linear falloff (a
/// child ray 10 units long brings back half), since (1, 0, 0) is "off".
const NEW_GLOBAL_ATTENUATION: GlobalAttenuation = GlobalAttenuation { c: 1.0, l: 0.1, q: 0.0 };

/// What a view height slider's drag spans, in world units: from a millimetre to a kilometre at
/// a scene's usual scale; typed values reach the whole valid range.
const VIEW_HEIGHT_SPAN: (f64, f64) = (1e-3, 1e3);

/// The projection, and the field of view or the view height it uses. Switching keeps the
/// look-at point's framing: an orthographic view as high as the perspective one at look_at, and
/// back, the field of view that sees the orthographic view's height there.
fn projection_ui(ui: &mut Ui, camera: &mut CameraDesc) -> bool {
    let mut projection = camera.projection;
    let mut changed = choice(ui, "Projection", &mut projection, &Projection::ALL, Projection::name);
    if changed {
        let height = camera.height_at_look_at();
        match projection {
            Projection::Perspective => {
                camera.fov_y = camera.fov_seeing(height).clamp(ranges::FOV_Y.min, ranges::FOV_Y.max);
                camera.view_height = None;
            }
            Projection::Orthographic => camera.view_height = Some(height),
        }
        camera.projection = projection;
    }
    match camera.projection {
        Projection::Perspective => changed |= slider(ui, "Field of view", &mut camera.fov_y, ranges::FOV_Y),
        Projection::Orthographic => {
            let mut height = camera.view_height();
            if log_slider(ui, "View height", &mut height, ranges::VIEW_HEIGHT, VIEW_HEIGHT_SPAN) {
                camera.view_height = Some(height);
                changed = true;
            }
        }
    }
    changed
}

/// `paths_held`: the Whitted vs GI view is shown, which holds the integrator at Paths.
pub fn ui(ui: &mut Ui, doc: &mut Document, fitter: &mut AmbientFitter, paths_held: bool) -> bool {
    let mut changed = false;
    egui::CollapsingHeader::new("Camera").default_open(true).show(ui, |ui| {
        changed |= projection_ui(ui, &mut doc.desc.camera);
        if ui.button("Reset camera").clicked() {
            doc.desc.camera = doc.initial_camera.clone();
            changed = true;
        }
        changed |= model_cameras(ui, doc);
        ui.weak("In the view: drag to orbit, Shift+drag or middle drag to pan, wheel to zoom.");
    });
    egui::CollapsingHeader::new("World").default_open(true).show(ui, |ui| {
        changed |= rgb_edit(ui, "Ambient I_a", &mut doc.desc.world.ambient);
        changed |= crate::ambient_fit::ui(ui, doc, fitter);
        changed |= rgb_edit(ui, "Background", &mut doc.desc.world.background);
        changed |= global_attenuation_ui(ui, &mut doc.desc.world.global_attenuation);
    });
    let mut view_changed = false;
    egui::CollapsingHeader::new("Render").default_open(true).show(ui, |ui| {
        let r = &mut doc.desc.render;
        // As the toolbar's switch: Whitted vs GI's GI side is the scene's own path render.
        changed |= ui
            .add_enabled_ui(!paths_held, |ui| {
                choice(ui, "Integrator", &mut r.integrator, &Integrator::ALL, Integrator::name)
            })
            .inner;
        if paths_held {
            ui.weak("Paths while Whitted vs GI is shown").on_hover_text(crate::whitted_vs_gi::PATHS_HELD);
        }
        if r.integrator == Integrator::Path {
            changed |= crate::help::hint(ui.checkbox(&mut r.indirect, "Indirect light"), "Indirect light").changed();
            // Each kind of light alone: a way of looking, not an edit of the scene.
            let mut shown = PathKind::ALL.into_iter().find(|k| k.alone() == doc.omit_kinds);
            let name = |k: Option<PathKind>| k.map_or("All light", PathKind::label);
            let options: Vec<Option<PathKind>> = std::iter::once(None).chain(PathKind::ALL.map(Some)).collect();
            if choice(ui, "Light shown", &mut shown, &options, name) {
                doc.omit_kinds = shown.map_or(0, PathKind::alone);
                view_changed = true;
            }
        }
        // The whole valid range: depths past the GPU's ray stack are for checking its report.
        changed |= int_slider(ui, "Max depth", &mut r.max_depth, ranges::DEPTH);
        changed |= slider(ui, "Bailout", &mut r.bailout, ranges::BAILOUT);
        changed |= log_slider(ui, "Epsilon", &mut r.epsilon, ranges::EPSILON, (1e-9, 1e-1));
        changed |= choice(ui, "Epsilon strategy", &mut r.epsilon_mode, &EpsilonMode::ALL, EpsilonMode::name);
        changed |= int_slider(ui, "Samples per pixel", &mut r.spp, ranges::SPP);
        changed |= int_slider(ui, "Width", &mut r.width, ranges::IMAGE_SIDE);
        changed |= int_slider(ui, "Height", &mut r.height, ranges::IMAGE_SIDE);
        ui.horizontal_wrapped(|ui| {
            ui.label("Specular model of all materials");
            for model in SpecularModel::ALL {
                let name = model.label();
                if ui.button(name).on_hover_text(format!("Set every material to {name}")).clicked() {
                    for m in doc.desc.materials.values_mut() {
                        m.specular_model = model;
                    }
                    changed = true;
                }
            }
        });
    });
    if view_changed {
        doc.view_changed();
    }
    changed
}

/// The world's attenuation of reflected and transmitted terms by the distance their ray
/// travelled: off is (1, 0, 0); the coefficients are checked as a light's (each in
/// `ranges::ATTENUATION`, and validation refuses a polynomial that reaches 0).
fn global_attenuation_ui(ui: &mut Ui, g: &mut GlobalAttenuation) -> bool {
    let mut changed = false;
    let mut on = !g.is_none();
    if crate::help::hint(
        ui.checkbox(&mut on, "Global attenuation of k_r·I_r, k_t·I_t"),
        "Global attenuation of k_r·I_r, k_t·I_t",
    )
    .changed()
    {
        *g = if on { NEW_GLOBAL_ATTENUATION } else { GlobalAttenuation::NONE };
        changed = true;
    }
    if on {
        ui.label("f_g(d) = 1 / (c_g + l_g·d + q_g·d²), d the child ray's length");
        ui.horizontal_wrapped(|ui| {
            changed |= number(ui, "c_g", &mut g.c, 0.01, ranges::ATTENUATION);
            changed |= number(ui, "l_g", &mut g.l, 0.01, ranges::ATTENUATION);
            changed |= number(ui, "q_g", &mut g.q, 0.01, ranges::ATTENUATION);
        });
    }
    changed
}

/// The cameras of the scene's model files (glTF perspective and orthographic cameras, placed with the model):
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
