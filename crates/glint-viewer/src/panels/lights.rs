//! Lights panel: the list with add, duplicate and remove, and the selected light's fields.

use egui::Ui;
use glint_core::glam::DVec3;
use glint_core::scene::{
    Attenuation, AttenuationModel, DEFAULT_INNER_CONE, DEFAULT_OUTER_CONE, LightDesc, LightKind, NO_CONE_CUTOFF,
    SpotFalloff, ranges,
};

use crate::document::Document;
use crate::widgets::{choice, log_slider, number, rgb_edit, slider, vec3_edit};

/// The cone a light gets when it becomes a spot light or leaves "no cone".
const NEW_CONE_CUTOFF: f64 = 30.0;

/// How far from the scene centre a light that had no position (a directional one) is put when
/// no camera distance gives a scale.
const FALLBACK_DISTANCE: f64 = 5.0;

/// The fields a light's current type does not have, set aside when the user switched it away
/// from a type that had them and given back when it switches back (one per light of the
/// document): a light of every type stays valid, and a round trip of types loses nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SetAside {
    position: Option<[f64; 3]>,
    direction: Option<[f64; 3]>,
    /// A point or spot light's f_att (a directional light has none).
    attenuation: Option<Attenuation>,
    cone: Option<Cone>,
}

/// A spot light's cone, all of its fields.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Cone {
    falloff: SpotFalloff,
    exponent: f64,
    cutoff: f64,
    inner_cone: Option<f64>,
    outer_cone: Option<f64>,
}

impl Cone {
    /// The cone every point and directional light has: none (validation refuses any other).
    const NONE: Self =
        Self { falloff: SpotFalloff::Power, exponent: 0.0, cutoff: NO_CONE_CUTOFF, inner_cone: None, outer_cone: None };

    fn of(l: &LightDesc) -> Self {
        Self {
            falloff: l.falloff,
            exponent: l.exponent,
            cutoff: l.cutoff,
            inner_cone: l.inner_cone,
            outer_cone: l.outer_cone,
        }
    }

    fn apply(self, l: &mut LightDesc) {
        (l.falloff, l.exponent, l.cutoff, l.inner_cone, l.outer_cone) =
            (self.falloff, self.exponent, self.cutoff, self.inner_cone, self.outer_cone);
    }
}

/// Makes `light` a light of `kind` that validates. What the new type lacks goes to `aside`;
/// what it needs comes back from `aside`, or else is made up: a direction from the light's
/// position toward `centre` (the camera's look-at point), a position `distance` back along the
/// direction, a 30° cone.
pub fn switch_kind(light: &mut LightDesc, kind: LightKind, aside: &mut SetAside, centre: DVec3, distance: f64) {
    if kind == light.kind {
        return;
    }
    // First what the new type needs, while the old position is still there to aim from.
    if kind != LightKind::Point && light.direction.is_none() {
        let from = light.position.or(aside.position).map_or(centre + DVec3::Y, DVec3::from);
        let toward = aside.direction.take().map(DVec3::from).unwrap_or((centre - from).normalize_or(DVec3::NEG_Y));
        light.direction = Some(toward.to_array());
    }
    if kind != LightKind::Directional && light.position.is_none() {
        let back = light.direction.map_or(DVec3::NEG_Y, DVec3::from).normalize_or(DVec3::NEG_Y);
        let d = if distance.is_finite() && distance > 0.0 { distance } else { FALLBACK_DISTANCE };
        light.position = Some(aside.position.take().unwrap_or((centre - back * d).to_array()));
    }
    // Then what it lacks, set aside.
    if light.kind == LightKind::Spot {
        aside.cone = Some(Cone::of(light));
        Cone::NONE.apply(light);
    }
    if kind == LightKind::Directional {
        aside.position = light.position.take().or(aside.position);
        if !light.attenuation.is_none() {
            aside.attenuation = Some(light.attenuation);
        }
        light.attenuation = Attenuation::NONE;
    }
    if kind == LightKind::Point {
        aside.direction = light.direction.take().or(aside.direction);
    }
    // And what it had before, given back.
    if light.kind == LightKind::Directional
        && let Some(a) = aside.attenuation.take()
    {
        light.attenuation = a;
    }
    if kind == LightKind::Spot {
        match aside.cone.take() {
            Some(c) => c.apply(light),
            None => light.cutoff = NEW_CONE_CUTOFF,
        }
    }
    light.kind = kind;
}

/// The range an inverse-square light gets when its range window is switched on.
const NEW_RANGE: f64 = 10.0;

pub fn ui(ui: &mut Ui, doc: &mut Document, selected: &mut usize) -> bool {
    let mut changed = false;
    let camera = &doc.desc.camera;
    let centre = DVec3::from(camera.look_at);
    let distance = (DVec3::from(camera.position) - centre).length();
    let lights = &mut doc.desc.lights;
    let set_aside = &mut doc.light_set_aside;
    // One entry per light, whoever changed the list (an edit here, a test, a new document).
    set_aside.resize_with(lights.len(), SetAside::default);
    ui.horizontal_wrapped(|ui| {
        for (i, l) in lights.iter().enumerate() {
            let name = if l.name.is_empty() { format!("{} {i}", l.kind.name()) } else { l.name.clone() };
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

#[cfg(test)]
mod tests {
    use glint_core::scene::{SceneDesc, validate};

    use super::*;

    fn valid(light: &LightDesc) -> bool {
        let mut desc: SceneDesc = Document::empty().desc;
        desc.lights = vec![light.clone()];
        let errors = validate(&desc).errors;
        errors.iter().all(|e| !e.field.starts_with("lights"))
    }

    #[test]
    fn every_sequence_of_types_gives_a_valid_light_and_a_round_trip_restores_it() {
        let mut spot = LightDesc::new(LightKind::Spot, [1.0, 4.0, -2.0], [0.0, -1.0, 0.2]);
        (spot.falloff, spot.cutoff, spot.inner_cone, spot.outer_cone) =
            (SpotFalloff::Smooth, NO_CONE_CUTOFF, Some(10.0), Some(25.0));
        spot.attenuation = Attenuation::inverse_square(Some(8.0));
        let point = LightDesc {
            attenuation: Attenuation::Polynomial { c: 1.0, l: 0.1, q: 0.01 },
            ..LightDesc::new(LightKind::Point, [-4.0, 7.0, -5.0], [0.0; 3])
        };
        let directional = LightDesc::new(LightKind::Directional, [0.0; 3], [1.0, -1.0, 0.0]);
        for start in [point, spot, directional] {
            assert!(valid(&start), "{start:?}");
            // Every pair of successive types, back to the first.
            for path in [
                [LightKind::Point, LightKind::Directional, LightKind::Spot],
                [LightKind::Spot, LightKind::Directional, LightKind::Point],
            ] {
                let (mut light, mut aside) = (start.clone(), SetAside::default());
                for kind in path.into_iter().chain(path).chain([start.kind]) {
                    switch_kind(&mut light, kind, &mut aside, DVec3::new(0.0, 1.0, 0.0), 5.0);
                    assert_eq!(light.kind, kind);
                    assert!(valid(&light), "{:?} after {path:?}: {light:?}", start.kind);
                }
                assert_eq!(light, start, "a round trip of types restores the light");
            }
        }
    }

    #[test]
    fn made_up_fields_aim_at_the_centre() {
        let centre = DVec3::new(0.0, 1.0, 0.0);
        let mut light = LightDesc::new(LightKind::Point, [-4.0, 7.0, -5.0], [0.0; 3]);
        let mut aside = SetAside::default();
        switch_kind(&mut light, LightKind::Directional, &mut aside, centre, 5.0);
        let d = DVec3::from(light.direction.expect("a direction"));
        let expected = (centre - DVec3::new(-4.0, 7.0, -5.0)).normalize();
        assert!((d - expected).length() < 1e-12, "{d}");
        // A directional light that never had a position gets one upstream of the centre.
        let mut sun = LightDesc::new(LightKind::Directional, [0.0; 3], [0.0, -2.0, 0.0]);
        switch_kind(&mut sun, LightKind::Spot, &mut SetAside::default(), centre, 5.0);
        assert_eq!(sun.position, Some([0.0, 6.0, 0.0]));
        assert_eq!((sun.direction, sun.cutoff), (Some([0.0, -2.0, 0.0]), NEW_CONE_CUTOFF));
    }
}
