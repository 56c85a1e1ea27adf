//! The world's global attenuation of reflected and transmitted terms, edited in the Scene
//! panel's World section: off by default, switched on with a starting polynomial, edited, checked
//! by validation as a light's attenuation (a polynomial that reaches 0 is reported in the UI and
//! the last valid image stays), and switched off again.

use egui_kittest::kittest::Queryable;
use glint_scene::GlobalAttenuation;

use crate::edits::assert_current_agreement;
use crate::support::{gpu_image, mean_abs_diff, settle, viewer};

const CHECKBOX: &str = "Global attenuation of k_r·I_r, k_t·I_t";

#[test]
fn global_attenuation_is_switched_on_edited_validated_and_off_in_the_scene_panel() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    assert!(h.state().doc.desc.world.global_attenuation.is_none(), "off by default");
    assert!(h.query_by_label("c_g").is_none(), "no coefficients while it is off");
    let off = gpu_image(&h);

    h.get_by_label(CHECKBOX).click();
    settle(&mut h);
    assert_eq!(h.state().doc.desc.world.global_attenuation, GlobalAttenuation { c: 1.0, l: 0.1, q: 0.0 });
    let on = gpu_image(&h);
    // whitted's mirror and glass spheres bring back less from farther away.
    assert!(mean_abs_diff(&off, &on) > 1e-4, "global attenuation must dim the mirror and the glass");
    assert_current_agreement(&h);

    h.get_by_label("q_g").set_value_accesskit(0.05);
    settle(&mut h);
    assert_eq!(h.state().doc.desc.world.global_attenuation, GlobalAttenuation { c: 1.0, l: 0.1, q: 0.05 });
    let quadratic = gpu_image(&h);
    assert!(mean_abs_diff(&on, &quadratic) > 1e-5, "q_g must change the image");
    assert_current_agreement(&h);

    // 1/(c + l·d + q·d²) with c = l = q = 0 divides by zero: refused and shown, as for a light.
    let revision = h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.revision);
    for field in ["c_g", "l_g", "q_g"] {
        h.get_by_label(field).set_value_accesskit(0.0);
        h.run_steps(1);
    }
    h.run_steps(3);
    assert!(!h.state().doc.issues.is_empty(), "c = l = q = 0 must be reported");
    assert!(h.query_all_by_label_contains("world.global_attenuation").count() > 0, "the problem is shown in the UI");
    assert_eq!(h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.revision), revision);

    // Off again: back to (1, 0, 0), valid, and the image of the scene without it.
    h.get_by_label(CHECKBOX).click();
    settle(&mut h);
    assert!(h.state().doc.desc.world.global_attenuation.is_none());
    assert!(h.state().doc.issues.is_empty(), "{:?}", h.state().doc.issues);
    assert_eq!(mean_abs_diff(&off, &gpu_image(&h)), 0.0, "off gives the image without it");
}
