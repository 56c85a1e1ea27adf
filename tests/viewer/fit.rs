//! Every tab of the side panel fits its width, at the default and at the minimum: no widget
//! reaches past the panel's right edge (a clipped label, a button cut in half), for each light
//! type, each specular model, the probe and the errors.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable, by};
use glint_viewer::{Tab, ViewerApp};

use crate::support::{choose, settle, viewer};

/// The widgets of the side panel that reach past its right edge, with where they end.
fn clipped(h: &Harness<'static, ViewerApp>, what: &str) -> Vec<String> {
    let side = h.state().layout.side_rect;
    assert!(side.width() > 0.0, "the side panel is shown");
    let mut out = Vec::new();
    for node in h.query_all(by().predicate(|n| n.label().is_some() || n.value().is_some())) {
        let role = node.accesskit_node().role();
        if matches!(role, Role::ScrollView | Role::Window | Role::Pane | Role::GenericContainer | Role::Splitter) {
            continue;
        }
        let r = node.rect();
        let inside = r.left() >= side.left() - 0.5 && r.left() < side.right();
        // What is scrolled out of view vertically is checked when it is in view.
        let shown = r.bottom() > side.top() && r.top() < side.bottom();
        if inside && shown && r.right() > side.right() + 0.5 {
            let name = node.accesskit_node().label().or_else(|| node.accesskit_node().value()).unwrap_or_default();
            out.push(format!("{what}: {role:?} {name:?} ends at {:.0}, the panel at {:.0}", r.right(), side.right()));
        }
    }
    out
}

fn every_tab(window: (f32, f32)) -> Vec<String> {
    let Some(mut h) = viewer("whitted", window) else { return Vec::new() };
    settle(&mut h);
    let mut found = clipped(&h, "Scene");
    h.get_by_label("Global attenuation of k_r·I_r, k_t·I_t").click();
    h.run_steps(2);
    found.extend(clipped(&h, "Scene, global attenuation"));
    for kind in ["point", "directional", "spot"] {
        choose(&mut h, "Lights", "Type", kind);
        found.extend(clipped(&h, &format!("Lights, {kind}")));
    }
    choose(&mut h, "Lights", "Falloff", "smooth");
    found.extend(clipped(&h, "Lights, smooth falloff"));
    choose(&mut h, "Materials", "Material", "floor");
    found.extend(clipped(&h, "Materials"));
    for model in ["Phong (R·V)^n", "Cook–Torrance F·D·G/(N·V)"] {
        choose(&mut h, "Materials", "Specular model", model);
        found.extend(clipped(&h, &format!("Materials, {model}")));
    }
    let (w, h0) = (h.state().doc.desc.render.width, h.state().doc.desc.render.height);
    h.state_mut().probe_at(w / 2, h0 / 2);
    settle(&mut h);
    h.state_mut().layout.tab = Tab::Probe;
    h.run_steps(2);
    found.extend(clipped(&h, "Probe"));
    h.state_mut().layout.tab = Tab::Errors;
    h.run_steps(2);
    found.extend(clipped(&h, "Errors"));
    found
}

#[test]
fn every_tab_fits_the_default_width_of_the_side_panel() {
    let found = every_tab((1200.0, 900.0));
    assert!(found.is_empty(), "clipped at the default width:\n{}", found.join("\n"));
}

#[test]
fn every_tab_fits_the_minimum_width_of_the_side_panel() {
    // 700 points leave the images their 480 and the panel its minimum, 220.
    let found = every_tab((700.0, 900.0));
    assert!(found.is_empty(), "clipped at the minimum width:\n{}", found.join("\n"));
}

#[test]
fn the_side_panel_gets_its_width_back_when_the_window_widens_again() {
    // A tester's find: narrowed by a smaller window, the panel stayed at that width afterwards.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.run_steps(2);
    let first = h.state().layout.side_rect.width();
    assert!((first - 300.0).abs() < 2.0, "the default width: {first}");
    h.set_size(egui::vec2(740.0, 640.0));
    h.run_steps(3);
    let narrowed = h.state().layout.side_rect.width();
    assert!(narrowed < first - 20.0, "a narrower window narrows the panel: {first} → {narrowed}");
    h.set_size(egui::vec2(1000.0, 640.0));
    h.run_steps(3);
    let back = h.state().layout.side_rect.width();
    assert!((back - first).abs() < 1.0, "the panel came back to {back}, not {first}");
}
