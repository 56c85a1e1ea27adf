//! Every slider and number field of the panels offers exactly the range validation allows
//! (`glint_scene::ranges`), so no valid value is clamped away; and ε = 0, which validation
//! allows, can be typed and reaches the document as 0.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use glint_scene::{LightKind, Range, ranges};
use glint_viewer::ViewerApp;

use crate::support::{choose, settle, viewer};

/// Validation's range for the editor labelled `label`, as (min, max, logarithmic).
fn validation_range(label: &str) -> Option<(f64, f64, bool)> {
    let real = |r: Range<f64>| Some((r.min, r.max, r.log));
    let whole = |r: Range<u32>| Some((f64::from(r.min), f64::from(r.max), false));
    let channel = [" R", " G", " B"].iter().any(|c| label.ends_with(c));
    let axis = [" x", " y", " z"].iter().any(|a| label.ends_with(a));
    match label {
        "Field of view" => real(ranges::FOV_Y),
        "Max depth" => whole(ranges::DEPTH),
        "Bailout" => real(ranges::BAILOUT),
        "Epsilon" => real(ranges::EPSILON),
        "Samples per pixel" => whole(ranges::SPP),
        "Width" | "Height" => whole(ranges::IMAGE_SIDE),
        "c" | "l" | "q" | "c_g" | "l_g" | "q_g" => real(ranges::ATTENUATION),
        "Spot exponent" => real(ranges::SPOT_EXPONENT),
        "Cutoff" => real(ranges::CUTOFF),
        "Range" => real(ranges::LIGHT_RANGE),
        "Inner cone" | "Outer cone" => real(ranges::CONE),
        "Shininess n" => real(ranges::SHININESS),
        "Roughness m" => real(ranges::ROUGHNESS),
        "Index of refraction" => real(ranges::IOR),
        "Checker size" => real(ranges::SIZE),
        _ if channel => real(ranges::COLOUR),
        _ if axis => real(ranges::COORD),
        _ => None,
    }
}

/// Checks every slider and number field on screen; returns their labels.
fn check_editors(h: &Harness<'static, ViewerApp>, panel: &str) -> Vec<String> {
    let mut labels = Vec::new();
    for role in [Role::Slider, Role::SpinButton] {
        for node in h.query_all_by_role(role) {
            let node = node.accesskit_node();
            let label = node.label().unwrap_or_default();
            let Some((min, max, log)) = validation_range(&label) else {
                panic!("{panel}: the editor {label:?} has no range in validation's table");
            };
            let shown = (node.min_numeric_value(), node.max_numeric_value());
            if log {
                // A logarithmic slider drags over the decades people use, and its field takes
                // any typed value, clamped to validation's range
                // (`a_40_point_drag_moves_shininess_about_a_decade_and_typed_values_beyond_the_span_are_kept`).
                if let (Some(lo), Some(hi)) = shown {
                    assert!(min <= lo && hi <= max, "{panel}: the span of {label:?} {shown:?} leaves [{min}, {max}]");
                } else {
                    assert_eq!((role, shown), (Role::SpinButton, (None, None)), "{panel}: {label:?}");
                }
            } else {
                assert_eq!(shown, (Some(min), Some(max)), "{panel}: the range of {label:?} is not validation's");
            }
            labels.push(label);
        }
    }
    labels
}

#[test]
fn every_editor_offers_the_range_validation_allows() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let scene = check_editors(&h, "Scene");
    for l in ["Field of view", "Max depth", "Bailout", "Epsilon", "Samples per pixel", "Width", "Background B"] {
        assert!(scene.iter().any(|s| s == l), "Scene: no editor {l:?} among {scene:?}");
    }
    h.get_by_label("Global attenuation of k_r·I_r, k_t·I_t").click();
    h.run_steps(2);
    let world = check_editors(&h, "Scene (global attenuation)");
    for l in ["c_g", "l_g", "q_g"] {
        assert!(world.iter().any(|s| s == l), "Scene: no editor {l:?} among {world:?}");
    }

    choose(&mut h, "Lights", "Type", "spot");
    assert_eq!(h.state().doc.desc.lights[0].kind, LightKind::Spot);
    let lights = check_editors(&h, "Lights");
    for l in ["Position x", "Spot axis z", "I_d R", "c", "q", "Spot exponent", "Cutoff"] {
        assert!(lights.iter().any(|s| s == l), "Lights: no editor {l:?} among {lights:?}");
    }
    // The glTF options' editors: the range window and the smooth cone.
    choose(&mut h, "Lights", "Attenuation", "inverse_square");
    h.get_by_label("Range window").click();
    h.run_steps(2);
    choose(&mut h, "Lights", "Falloff", "smooth");
    let gltf = check_editors(&h, "Lights (glTF options)");
    for l in ["Range", "Inner cone", "Outer cone"] {
        assert!(gltf.iter().any(|s| s == l), "Lights: no editor {l:?} among {gltf:?}");
    }

    choose(&mut h, "Materials", "Material", "floor");
    let materials = check_editors(&h, "Materials");
    for l in ["k_d G", "Shininess n", "Index of refraction", "E_m R", "Checker size", "Checker k_d B"] {
        assert!(materials.iter().any(|s| s == l), "Materials: no editor {l:?} among {materials:?}");
    }
    choose(&mut h, "Materials", "Specular model", "Cook–Torrance F·D·G/(N·V)");
    let cook_torrance = check_editors(&h, "Materials (Cook–Torrance)");
    assert!(cook_torrance.iter().any(|s| s == "Roughness m"), "Materials: no editor for m among {cook_torrance:?}");
}

#[test]
fn epsilon_zero_typed_into_its_field_reaches_the_document() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.state().doc.desc.render.epsilon > 0.0);
    // Click the value as a user would, select what it shows, type 0 and press Enter.
    h.get_by_role_and_label(Role::SpinButton, "Epsilon").click();
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.get_by_role_and_label(Role::SpinButton, "Epsilon").type_text("0");
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
    settle(&mut h);
    let doc = &h.state().doc;
    assert_eq!(doc.desc.render.epsilon, 0.0, "ε = 0 is valid and must not be clamped");
    assert!(doc.issues.is_empty(), "{:?}", doc.issues);
}

/// Types `text` into the number field labelled `label` and presses Enter.
fn type_number(h: &mut Harness<'static, ViewerApp>, label: &str, text: &str) {
    h.get_by_role_and_label(Role::SpinButton, label).click();
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.get_by_role_and_label(Role::SpinButton, label).type_text(text);
    h.run_steps(1);
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
}

#[test]
fn a_40_point_drag_moves_shininess_about_a_decade_and_typed_values_beyond_the_span_are_kept() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    choose(&mut h, "Materials", "Material", "floor");
    let material = |h: &Harness<'static, ViewerApp>| h.state().doc.desc.materials["floor"].shininess;
    type_number(&mut h, "Shininess n", "200");
    assert_eq!(material(&h), 200.0);
    // A 40-point drag from the handle, as the issue's (it took n from 200 to 3.0e-5).
    let rect = h.get_by_role_and_label(Role::Slider, "Shininess n").rect();
    let from = egui::pos2(rect.left() + rect.width() * (200f32.log10() / 3.0), rect.center().y);
    h.hover_at(from);
    h.step();
    h.drag_at(from);
    h.step();
    // The press itself moves the handle to the pointer: count the drag from there.
    let pressed = material(&h);
    for k in 1..=8 {
        h.hover_at(from - egui::vec2(5.0 * k as f32, 0.0));
        h.step();
    }
    h.drop_at(from - egui::vec2(40.0, 0.0));
    h.run_steps(2);
    let n = material(&h);
    let decades = (n / pressed).log10().abs();
    assert!(n > 0.0 && decades <= 1.3, "a 40-point drag took n from {pressed} to {n} ({decades:.2} decades)");
    assert!(decades >= 0.5, "the drag did not move the slider (n = {n})");
    // Typed values are free within validation's range, beyond the slider's span.
    for (typed, want) in [("1000000", 1e6), ("0", 0.0), ("0.25", 0.25)] {
        type_number(&mut h, "Shininess n", typed);
        assert_eq!(material(&h), want, "typed {typed}");
    }
    settle(&mut h);
    assert!(h.state().doc.issues.is_empty(), "{:?}", h.state().doc.issues);
}

#[test]
fn a_typed_nan_or_infinity_leaves_the_value_as_it_was() {
    // egui's own reading of "NaN" clamped it to the range's end: the field of view became 179°,
    // ε 1000, and a width 16384 (which the window's textures did not hold).
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let before = h.state().doc.desc.clone();
    for label in ["Field of view", "Epsilon", "Width", "Background R"] {
        for typed in ["NaN", "inf", "-inf", "nan"] {
            type_number(&mut h, label, typed);
        }
    }
    let doc = &h.state().doc.desc;
    assert_eq!(doc.camera.fov_y, before.camera.fov_y);
    assert_eq!(doc.render.epsilon, before.render.epsilon);
    assert_eq!(doc.render.width, before.render.width);
    assert_eq!(doc.world.background, before.world.background);
    // Each is named under its field, as a number outside the range is (they were left without
    // a word; a viewer tester).
    type_number(&mut h, "Field of view", "nan");
    assert!(h.query_by_label("Field of view: nan is not a finite number; the value was kept").is_some());
    type_number(&mut h, "Field of view", "abc");
    assert!(h.query_by_label("Field of view: `abc` is not a number; the value was kept").is_some());
    // A finite number typed the same way is taken, and the note goes.
    type_number(&mut h, "Field of view", "50");
    assert_eq!(h.state().doc.desc.camera.fov_y, 50.0);
    assert!(h.query_by_label_contains("Field of view: `abc`").is_none());
}

#[test]
fn a_typed_value_outside_its_range_is_named_and_the_value_kept() {
    // egui clamped typed values to the range's end without a word: I_d −1 became 0, n = 1e30
    // became 1e6, and an ior of −2 became the excluded 0, which validation then refused naming
    // 0 (a lecturer).
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    choose(&mut h, "Materials", "Material", "floor");
    let before = h.state().doc.desc.materials["floor"].clone();
    let notes = |h: &Harness<'static, ViewerApp>| -> Vec<String> {
        h.query_all_by_label_contains("the value was kept").filter_map(|n| n.accesskit_node().label()).collect()
    };
    type_number(&mut h, "Index of refraction", "-2");
    let note = "Index of refraction: -2 is outside (0, 1000]; the value was kept";
    assert!(h.query_by_label(note).is_some(), "no note {note:?} among {:?}", notes(&h));
    type_number(&mut h, "Shininess n", "1e30");
    assert!(h.query_by_label("Shininess n: 1e30 is outside [0, 1e6]; the value was kept").is_some(), "{:?}", notes(&h));
    let floor = &h.state().doc.desc.materials["floor"];
    assert_eq!((floor.ior, floor.shininess), (before.ior, before.shininess));
    // A valid value typed after it is taken, and the note goes.
    type_number(&mut h, "Index of refraction", "1.25");
    assert_eq!(h.state().doc.desc.materials["floor"].ior, 1.25);
    assert!(h.query_by_label(note).is_none(), "the note stayed after a valid edit");
    // Whole numbers too: a depth beyond 1024 and a fraction of one.
    h.get_by_label("Scene").click();
    h.run_steps(2);
    let depth = h.state().doc.desc.render.max_depth;
    type_number(&mut h, "Max depth", "99999");
    assert!(h.query_by_label("Max depth: 99999 is outside [0, 1024]; the value was kept").is_some(), "{:?}", notes(&h));
    type_number(&mut h, "Max depth", "2.5");
    assert!(
        h.query_by_label("Max depth: 2.5 is not a whole number in [0, 1024]; the value was kept").is_some(),
        "{:?}",
        notes(&h)
    );
    assert_eq!(h.state().doc.desc.render.max_depth, depth);
    settle(&mut h);
    assert!(h.state().doc.issues.is_empty(), "{:?}", h.state().doc.issues);
}

/// Types `text` into the field `label` one key at a time, a frame after each, as a person
/// types, then Return, and gives `value` after each key: `type_number` types it in one event,
/// which hid what each partial text did.
fn type_keys(
    h: &mut Harness<'static, ViewerApp>,
    label: &str,
    text: &str,
    value: impl Fn(&Harness<'static, ViewerApp>) -> f64,
) -> Vec<f64> {
    let role = Role::SpinButton;
    h.get_by_role_and_label(role, label).click();
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    let mut seen = Vec::new();
    for c in text.chars() {
        h.get_by_role_and_label(role, label).type_text(&c.to_string());
        h.run_steps(1);
        seen.push(value(h));
    }
    h.key_press(egui::Key::Enter);
    h.run_steps(2);
    seen
}

#[test]
fn a_value_typed_key_by_key_is_taken_on_return_and_a_refused_one_leaves_the_old() {
    // Each partial text was applied as it was typed: −0.5 set the ambient to 0 (from "-0")
    // before −0.5 was refused "and kept", and 2000000 left shininess at 200000 (a viewer tester).
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let ambient = |h: &Harness<'static, ViewerApp>| h.state().doc.desc.world.ambient.0[0];
    let before = ambient(&h);
    let while_typing = type_keys(&mut h, "Ambient I_a R", "-0.5", ambient);
    assert!(while_typing.iter().all(|v| *v == before), "applied while typing: {while_typing:?}");
    assert_eq!(ambient(&h), before, "a refused value leaves the old one");
    assert!(h.query_by_label("Ambient I_a R: -0.5 is outside [0, 1e9]; the value was kept").is_some());
    // A valid one is taken on Return, not before.
    let while_typing = type_keys(&mut h, "Ambient I_a R", "0.25", ambient);
    assert!(while_typing.iter().all(|v| *v == before), "applied while typing: {while_typing:?}");
    assert_eq!(ambient(&h), 0.25);
    // A slider's text too.
    choose(&mut h, "Materials", "Material", "floor");
    let floor = |h: &Harness<'static, ViewerApp>| h.state().doc.desc.materials["floor"].shininess;
    let shininess = floor(&h);
    let while_typing = type_keys(&mut h, "Shininess n", "2000000", floor);
    assert!(while_typing.iter().all(|v| *v == shininess), "applied while typing: {while_typing:?}");
    assert_eq!(floor(&h), shininess, "2000000 is refused whole");
}

#[test]
fn a_refusal_note_goes_with_the_scene_it_was_of() {
    // It stayed under the next scene's valid value (a viewer tester).
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    type_number(&mut h, "Ambient I_a G", "-1");
    let note = "Ambient I_a G: -1 is outside [0, 1e9]; the value was kept";
    assert!(h.query_by_label(note).is_some(), "no note to start with");
    h.state_mut().open("cornell");
    h.run_steps(3);
    assert!(h.query_by_label(note).is_none(), "the note outlived its scene");
}

#[test]
fn a_refused_channel_is_named_under_its_row_which_stays_whole() {
    // k_t R = −1 put its note inline after the R field, and G and B wrapped onto the next line
    // (a lecturer): the note goes under the row, as a single value's goes under its field.
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    choose(&mut h, "Materials", "Material", "glass");
    type_number(&mut h, "k_t R", "-1");
    let note = h.get_by_label("k_t R: -1 is outside [0, 1e9]; the value was kept").rect();
    let field = |ch: &str| h.get_by_role_and_label(Role::SpinButton, &format!("k_t {ch}")).rect();
    let (r, g, b) = (field("R"), field("G"), field("B"));
    assert!(
        (g.center().y - r.center().y).abs() < 1.0 && (b.center().y - r.center().y).abs() < 1.0,
        "R, G and B on one row: {r:?} {g:?} {b:?}"
    );
    assert!(note.top() >= r.bottom(), "the note under the row: {note:?}, the row {r:?}");
    assert!(note.left() < r.left(), "the note starts the line under the row: {note:?}, R at {r:?}");
}
