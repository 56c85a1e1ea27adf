//! A learner's help: every editor on every tab has a tooltip saying what it is in the seed's
//! equation, every ε strategy has one, and the Help menu opens the first five minutes and the
//! keyboard and mouse bindings.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use glint_viewer::ViewerApp;
use glint_viewer::help::{option_tooltip, tooltip};

use crate::support::{choose, menu, viewer};

/// The labels of the editors on screen that have no tooltip.
fn without_tooltip(h: &Harness<'static, ViewerApp>) -> Vec<String> {
    let mut missing = Vec::new();
    for role in [Role::Slider, Role::SpinButton, Role::ComboBox, Role::CheckBox] {
        for node in h.query_all_by_role(role) {
            let label = node.accesskit_node().label().unwrap_or_default();
            if tooltip(&label).is_none() {
                missing.push(format!("{role:?} {label:?}"));
            }
        }
    }
    missing
}

#[test]
fn every_editor_of_every_tab_says_what_it_is_in_the_equation() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let mut missing = without_tooltip(&h);
    h.get_by_label("Global attenuation of k_r·I_r, k_t·I_t").click();
    h.run_steps(2);
    missing.extend(without_tooltip(&h));
    for kind in ["point", "directional", "spot"] {
        choose(&mut h, "Lights", "Type", kind);
        missing.extend(without_tooltip(&h));
    }
    choose(&mut h, "Lights", "Attenuation", "inverse_square");
    choose(&mut h, "Lights", "Falloff", "smooth");
    missing.extend(without_tooltip(&h));
    choose(&mut h, "Materials", "Material", "floor");
    missing.extend(without_tooltip(&h));
    choose(&mut h, "Materials", "Specular model", "Cook–Torrance F·D·G/(N·V)");
    missing.extend(without_tooltip(&h));
    missing.sort();
    missing.dedup();
    assert!(missing.is_empty(), "editors without a tooltip: {missing:?}");
    // Each ε strategy, light kind, attenuation model and falloff says what it does.
    for option in ["tmin", "nudge_ray", "nudge_normal", "robust", "skip_convex"] {
        assert!(option_tooltip("Epsilon strategy", option).is_some(), "{option}");
    }
    for (control, option) in [("Type", "point"), ("Type", "directional"), ("Type", "spot"), ("Falloff", "smooth")] {
        assert!(option_tooltip(control, option).is_some(), "{control} {option}");
    }
}

#[test]
fn the_help_menu_opens_the_first_five_minutes_and_the_bindings() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    menu(&mut h, &["Help", "The first five minutes"]);
    assert!(h.query_by_label_contains("Ctrl+click a pixel").is_some(), "the walkthrough is shown");
    // The seed's last lesson is in it, and no scene's depth is called 5 (cornell-gi starts at 16;
    // a lecturer).
    assert!(
        h.query_by_label_contains("Whitted vs GI (open cornell-gi)").is_some(),
        "Whitted vs GI is in the walkthrough"
    );
    assert!(h.query_by_label_contains("Set it back to 5").is_none());
    menu(&mut h, &["Help", "Keyboard and mouse"]);
    assert!(h.query_by_label("Ctrl+click").is_some() && h.query_by_label("F9").is_some(), "the bindings are listed");
    h.get_by_label("Help").click();
    h.run_steps(2);
    assert!(h.query_by_label("The viewer (docs/viewer.md)").is_some(), "the docs are linked");
}

#[test]
fn escape_closes_save_image_and_the_help_windows_one_at_a_time() {
    // Help → Keyboard and mouse says "Escape: close a dialog"; only "unsaved changes" did.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    menu(&mut h, &["Help", "Keyboard and mouse"]);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(2);
    assert!(h.query_by_label("Browse…").is_some() && h.query_by_label("F9").is_some(), "both windows open");
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(h.query_by_label("Browse…").is_none(), "Save image closed first");
    assert!(h.query_by_label("F9").is_some(), "one window an Escape");
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(h.query_by_label("F9").is_none(), "the bindings closed");
}
