//! The Lights panel: a light switched through every type stays valid, and what a type lacks
//! comes back when the light switches back.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_core::glam::DVec3;
use glint_core::scene::{Attenuation, LightKind};
use glint_viewer::ViewerApp;

use crate::support::{choose, settle, viewer};

#[test]
fn switching_a_light_through_every_type_keeps_it_valid_and_restores_what_was_set_aside() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    // A point light with an attenuation of its own, which a directional light cannot have.
    h.state_mut().doc.desc.lights[0].attenuation = Attenuation::Polynomial { c: 1.0, l: 0.05, q: 0.0 };
    h.state_mut().doc.edited();
    let original = h.state().doc.desc.lights[0].clone();
    let position = DVec3::from(original.position.expect("a point light"));
    let centre = DVec3::from(h.state().doc.desc.camera.look_at);

    check(&mut h, "directional");
    let light = &h.state().doc.desc.lights[0];
    let direction = DVec3::from(light.direction.expect("a direction"));
    assert!((direction - (centre - position).normalize()).length() < 1e-12, "aimed at the look-at point");
    check(&mut h, "spot");
    let light = &h.state().doc.desc.lights[0];
    assert_eq!(light.position, original.position, "the position came back");
    assert_eq!(light.attenuation, original.attenuation, "the attenuation came back");
    assert_eq!(light.cutoff, 30.0, "a spot gets a cone");
    h.get_by_role_and_label(Role::Slider, "Cutoff").set_value_accesskit(20.0);
    h.run_steps(2);
    check(&mut h, "point");
    assert_eq!(h.state().doc.desc.lights[0], original, "a point light again, as it was");
    check(&mut h, "spot");
    assert_eq!(h.state().doc.desc.lights[0].cutoff, 20.0, "the spot's own cone came back");
    check(&mut h, "directional");
    check(&mut h, "point");
    assert_eq!(h.state().doc.desc.lights[0], original);
    // And every revision on the way rendered on both tracers.
    check(&mut h, "directional");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].kind, LightKind::Directional);
    assert!(h.state().renders.gpu.as_ref().is_some_and(|g| g.error.is_none()));
}

/// Switches light 0 to `kind` in the panel; the light must be valid and no problem shown.
fn check(h: &mut Harness<'static, ViewerApp>, kind: &str) {
    choose(h, "Lights", "Type", kind);
    let doc = &h.state().doc;
    assert_eq!(doc.desc.lights[0].kind.name(), kind);
    assert!(doc.issues.is_empty(), "after switching to {kind}: {:?}", doc.issues);
    assert!(h.query_by_label_contains("Invalid values").is_none(), "after switching to {kind}");
}
