//! The Lights panel: a light switched through every type stays valid, and what a type lacks
//! comes back when the light switches back.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_core::glam::DVec3;
use glint_scene::{Attenuation, LightKind, SpotFalloff};
use glint_viewer::ViewerApp;

use crate::edits::assert_current_agreement;
use crate::support::{choose, gpu_image, mean_abs_diff, settle, viewer};

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

/// The glTF light options edited in the Lights panel: the inverse-square model with its range
/// window and the smooth spot cone reach the document, change the GPU image, keep GPU and CPU
/// in agreement, and a bad cone order is reported in the UI.
#[test]
fn inverse_square_range_and_smooth_cone_edited_in_the_lights_panel() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let before = gpu_image(&h);

    // 1/d² at ~9.5 units from the light: much darker than f_att = 1.
    choose(&mut h, "Lights", "Attenuation", "inverse_square");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].attenuation, Attenuation::InverseSquare { range: None });
    let plain = gpu_image(&h);
    assert!(mean_abs_diff(&before, &plain) > 1e-3, "inverse-square attenuation must change the image");
    assert_current_agreement(&h);

    // A range window that ends inside the scene: the far floor goes to ambient only.
    h.get_by_label("Range window").click();
    h.run_steps(2);
    h.get_by_role_and_label(Role::Slider, "Range").set_value_accesskit(10.0);
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].attenuation, Attenuation::InverseSquare { range: Some(10.0) });
    let windowed = gpu_image(&h);
    assert!(mean_abs_diff(&plain, &windowed) > 1e-5, "the range window must change the image");
    assert_current_agreement(&h);

    // A smooth spot with glTF's cones, under the polynomial f_att = 1 again: at ~9.5 units the
    // inverse-square light is too dim (1/d² ≈ 0.01) for its cone to show in the mean.
    choose(&mut h, "Lights", "Attenuation", "polynomial");
    settle(&mut h);
    let point_light = gpu_image(&h);
    choose(&mut h, "Lights", "Type", "spot");
    choose(&mut h, "Lights", "Falloff", "smooth");
    h.get_by_role_and_label(Role::Slider, "Outer cone").set_value_accesskit(25.0);
    h.run_steps(2);
    h.get_by_role_and_label(Role::Slider, "Inner cone").set_value_accesskit(10.0);
    settle(&mut h);
    let light = &h.state().doc.desc.lights[0];
    assert_eq!((light.kind, light.falloff), (LightKind::Spot, SpotFalloff::Smooth));
    assert_eq!((light.inner_cone, light.outer_cone), (Some(10.0), Some(25.0)));
    assert_eq!((light.exponent, light.cutoff), (0.0, glint_scene::NO_CONE_CUTOFF), "power fields cleared");
    assert!(h.state().doc.issues.is_empty(), "{:?}", h.state().doc.issues);
    assert!(mean_abs_diff(&point_light, &gpu_image(&h)) > 1e-3, "a smooth spot must change the image");
    assert_current_agreement(&h);

    // An inner cone wider than the outer one is refused, and said so in the UI.
    h.get_by_role_and_label(Role::Slider, "Inner cone").set_value_accesskit(40.0);
    h.run_steps(3);
    assert!(!h.state().doc.issues.is_empty(), "inner > outer must be reported");
    assert!(h.query_all_by_label_contains("lights[0].inner_cone").count() > 0, "the problem is shown in the UI");
}
