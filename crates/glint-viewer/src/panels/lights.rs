//! Lights panel: the list with add, duplicate and remove, and the selected light's fields.

use egui::Ui;
use glint_core::glam::DVec3;
use glint_scene::{
    Attenuation, AttenuationModel, DEFAULT_INNER_CONE, DEFAULT_OUTER_CONE, LightDesc, LightKind, NO_CONE_CUTOFF,
    SpotFalloff, ranges,
};

use crate::document::Document;
use crate::light_kind::{NEW_CONE_CUTOFF, SetAside, switch_kind};
use crate::widgets::{choice, log_slider, number, rgb_edit, slider, vec3_edit};

/// The range an inverse-square light gets when its range window is switched on.
const NEW_RANGE: f64 = 10.0;

pub fn ui(ui: &mut Ui, doc: &mut Document, selected: &mut usize) -> bool {
    let mut changed = false;
    let camera = &doc.desc.camera;
    let centre = DVec3::from(camera.look_at);
    let distance = (DVec3::from(camera.position) - centre).length();
    let labels: Vec<String> = (0..doc.desc.lights.len()).map(|i| doc.light_label(i)).collect();
    let lights = &mut doc.desc.lights;
    let set_aside = &mut doc.light_set_aside;
    // One entry per light, whoever changed the list (an edit here, a test, a new document).
    set_aside.resize_with(lights.len(), SetAside::default);
    ui.horizontal_wrapped(|ui| {
        for (i, name) in labels.into_iter().enumerate() {
            ui.selectable_value(selected, i, name);
        }
    });
    ui.horizontal_wrapped(|ui| {
        if ui.button("Add light").clicked() {
            lights.push(LightDesc::new(LightKind::Point, [0.0, 5.0, -3.0], [0.0, -1.0, 0.0]));
            set_aside.push(SetAside::default());
            *selected = lights.len() - 1;
            changed = true;
        }
        if ui.add_enabled(*selected < lights.len(), egui::Button::new("Duplicate")).clicked() {
            let copy = lights[*selected].clone();
            lights.push(copy);
            set_aside.push(set_aside[*selected].clone());
            *selected = lights.len() - 1;
            changed = true;
        }
        if ui.add_enabled(*selected < lights.len(), egui::Button::new("Remove")).clicked() {
            lights.remove(*selected);
            set_aside.remove(*selected);
            *selected = selected.saturating_sub(1);
            changed = true;
        }
    });
    let Some(light) = lights.get_mut(*selected) else {
        ui.weak("No light selected.");
        return changed;
    };
    ui.separator();
    let mut kind = light.kind;
    if choice(ui, "Type", &mut kind, &LightKind::ALL, LightKind::name) && kind != light.kind {
        switch_kind(light, kind, &mut set_aside[*selected], centre, distance);
        changed = true;
    }
    if light.kind != LightKind::Directional {
        let p = light.position.get_or_insert([0.0, 5.0, -3.0]);
        changed |= vec3_edit(ui, "Position", p, 0.05);
    }
    if light.kind != LightKind::Point {
        let label = if light.kind == LightKind::Spot { "Spot axis" } else { "Direction" };
        let d = light.direction.get_or_insert([0.0, -1.0, 0.0]);
        changed |= vec3_edit(ui, label, d, 0.01);
    }
    changed |= rgb_edit(ui, "I_d", &mut light.diffuse);
    changed |= rgb_edit(ui, "I_s", &mut light.specular);
    changed |= rgb_edit(ui, "I_a,j", &mut light.ambient);
    if light.kind != LightKind::Directional {
        changed |= attenuation_ui(ui, &mut light.attenuation);
    }
    if light.kind == LightKind::Spot {
        changed |= spot_ui(ui, light);
    }
    changed |= crate::help::hint(ui.checkbox(&mut light.casts_shadows, "Casts shadows"), "Casts shadows").changed();
    changed
}

/// The attenuation model and its parameters. Changing the model starts from its neutral
/// parameters (f_att = 1, or plain 1/d²).
fn attenuation_ui(ui: &mut Ui, attenuation: &mut Attenuation) -> bool {
    let mut model = attenuation.model();
    let mut changed = false;
    if choice(ui, "Attenuation", &mut model, &AttenuationModel::ALL, AttenuationModel::name) {
        *attenuation = match model {
            AttenuationModel::Polynomial => Attenuation::NONE,
            AttenuationModel::InverseSquare => Attenuation::inverse_square(None),
        };
        changed = true;
    }
    match attenuation {
        Attenuation::Polynomial { c, l, q } => {
            ui.label("f_att = 1 / (c + l·d + q·d²)");
            ui.horizontal_wrapped(|ui| {
                changed |= number(ui, "c", c, 0.01, ranges::ATTENUATION);
                changed |= number(ui, "l", l, 0.01, ranges::ATTENUATION);
                changed |= number(ui, "q", q, 0.01, ranges::ATTENUATION);
            });
        }
        Attenuation::InverseSquare { range } => {
            let mut windowed = range.is_some();
            let text = if windowed { "f_att = clamp(1 − (d/range)⁴, 0, 1) / d²" } else { "f_att = 1 / d²" };
            ui.label(text);
            if crate::help::hint(ui.checkbox(&mut windowed, "Range window"), "Range window").changed() {
                *range = windowed.then_some(NEW_RANGE);
                changed = true;
            }
            if let Some(r) = range {
                changed |= log_slider(ui, "Range", r, ranges::LIGHT_RANGE, (0.1, 1e3));
            }
        }
    }
    changed
}

/// A spot light's falloff and its cone. Changing the falloff gives the new one the old cone's
/// size and clears the fields the new one does not have (validation refuses them).
fn spot_ui(ui: &mut Ui, light: &mut LightDesc) -> bool {
    let mut changed = false;
    let before = light.falloff;
    if choice(ui, "Falloff", &mut light.falloff, &SpotFalloff::ALL, SpotFalloff::name) && light.falloff != before {
        match light.falloff {
            SpotFalloff::Smooth => {
                let outer = if light.cutoff < NO_CONE_CUTOFF { light.cutoff } else { DEFAULT_OUTER_CONE };
                light.inner_cone = Some(DEFAULT_INNER_CONE);
                light.outer_cone = Some(outer);
                light.exponent = 0.0;
                light.cutoff = NO_CONE_CUTOFF;
            }
            SpotFalloff::Power => {
                light.cutoff = light.outer_cone.unwrap_or(NEW_CONE_CUTOFF);
                light.inner_cone = None;
                light.outer_cone = None;
            }
        }
        changed = true;
    }
    match light.falloff {
        SpotFalloff::Power => {
            changed |= log_slider(ui, "Spot exponent", &mut light.exponent, ranges::SPOT_EXPONENT, (0.1, 1e3));
            // The slider covers the cones proper; "no cone" is a value of its own.
            let mut no_cone = light.cutoff >= NO_CONE_CUTOFF;
            let label = format!("No cone (cutoff {NO_CONE_CUTOFF}°)");
            if crate::help::hint(ui.checkbox(&mut no_cone, &label), &label).changed() {
                light.cutoff = if no_cone { NO_CONE_CUTOFF } else { NEW_CONE_CUTOFF };
                changed = true;
            }
            if !no_cone {
                changed |= slider(ui, "Cutoff", &mut light.cutoff, ranges::CUTOFF);
            }
        }
        SpotFalloff::Smooth => {
            ui.label("S = t², t = saturate((cos θ − cos outer) / (cos inner − cos outer))");
            let (inner, outer) = light.cone_angles();
            let (mut inner, mut outer) = (inner, outer);
            let inner_changed = slider(ui, "Inner cone", &mut inner, ranges::CONE);
            let outer_changed = slider(ui, "Outer cone", &mut outer, ranges::CONE);
            if inner_changed {
                light.inner_cone = Some(inner);
            }
            if outer_changed {
                light.outer_cone = Some(outer);
            }
            changed |= inner_changed | outer_changed;
        }
    }
    changed
}
