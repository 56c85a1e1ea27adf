//! Edits made through the widgets, found by their labels, change the document, the GPU image
//! and the statistics the way the model says they should.

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use glint_scene::{LightKind, RenderSettings};

use crate::support::{choose, gpu_image, mean_abs_diff, settle, viewer};

#[test]
fn depth_and_epsilon_set_through_the_ui_change_the_gpu_image_and_the_statistics() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let before = gpu_image(&h);
    let counts_before =
        h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.counts).expect("counts");
    assert!(counts_before.reflection > 0 && counts_before.refraction > 0, "whitted has mirror and glass rays");

    h.get_by_role_and_label(Role::Slider, "Max depth").set_value_accesskit(0.0);
    settle(&mut h);
    assert_eq!(h.state().doc.desc.render.max_depth, 0);
    let depth0 = gpu_image(&h);
    let counts = h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.counts).expect("counts");
    // Depth 0 is local shading only: no secondary rays, so the mirror and glass go dull.
    assert_eq!((counts.reflection, counts.refraction), (0, 0), "{counts:?}");
    assert!(mean_abs_diff(&before, &depth0) > 1e-3, "depth 0 must change the image");
    // The statistics are of the new revision and still show agreement of GPU and CPU.
    let errors = h.state().renders.comparison.latest.as_ref().map(|c| (c.revision, c.errors)).expect("comparison");
    assert_eq!(errors.0, h.state().doc.revision);
    assert!(errors.1.psnr > 40.0, "GPU and CPU disagree at depth 0: {:?}", errors.1);

    // A huge ε with t-min offsets lets shadow rays escape through nearby geometry.
    h.get_by_role_and_label(Role::Slider, "Epsilon").set_value_accesskit(0.5);
    settle(&mut h);
    let RenderSettings { epsilon, .. } = h.state().doc.desc.render;
    assert!((epsilon - 0.5).abs() < 1e-12, "epsilon {epsilon}");
    assert!(mean_abs_diff(&depth0, &gpu_image(&h)) > 1e-4, "ε = 0.5 must change the image");
    // The statistics follow: they are of the new revision, and both tracers offset alike.
    assert_current_agreement(&h);
}

#[test]
fn material_ks_and_light_type_set_through_the_ui_change_the_gpu_image_and_the_statistics() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let before = gpu_image(&h);

    dull_the_mirror(&mut h);
    assert_eq!(h.state().doc.desc.materials["mirror"].ks.0, [0.0; 3]);
    let dull = gpu_image(&h);
    // The mirror sphere loses its specular highlight (k_s·I_s·spec).
    assert!(mean_abs_diff(&before, &dull) > 1e-6, "k_s = 0 must remove the mirror's highlight");
    let dull_counts = latest_counts(&h);
    assert_current_agreement(&h);

    choose(&mut h, "Lights", "Type", "spot");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].kind, LightKind::Spot);
    // A 30° cone aimed at the look-at point leaves most of the floor unlit.
    assert!(mean_abs_diff(&dull, &gpu_image(&h)) > 1e-3, "a spot light must change the image");
    // Outside the cone S = 0, and a light that cannot contribute casts no shadow ray.
    let spot_counts = latest_counts(&h);
    assert!(spot_counts.shadow < dull_counts.shadow, "spot {spot_counts:?} vs point {dull_counts:?}");
    assert_eq!(spot_counts.camera, dull_counts.camera);
    assert_current_agreement(&h);
}

/// Sets the mirror's k_s to 0 through its three fields, a frame apart, and lets it render.
fn dull_the_mirror(h: &mut egui_kittest::Harness<'static, glint_viewer::ViewerApp>) {
    choose(h, "Materials", "Material", "mirror");
    for channel in ["k_s R", "k_s G", "k_s B"] {
        h.get_by_label(channel).set_value_accesskit(0.0);
        h.run_steps(1);
    }
    settle(h);
}

fn latest_counts(h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>) -> glint_core::cpu::RayCounts {
    h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.counts).expect("GPU ray counts")
}

/// The error statistics shown are those of the current revision, and GPU and CPU agree.
pub fn assert_current_agreement(h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>) {
    let (revision, errors) =
        h.state().renders.comparison.latest.as_ref().map(|c| (c.revision, c.errors)).expect("comparison");
    assert_eq!(revision, h.state().doc.revision, "the statistics are of an older revision");
    assert!(errors.psnr > 40.0, "GPU and CPU disagree: {errors:?}");
}

#[test]
fn an_invalid_value_is_reported_in_the_ui_and_the_last_valid_image_stays() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let revision = h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.revision);
    h.get_by_label("Lights").click();
    h.run_steps(2);
    // Attenuation with c = l = q = 0 divides by zero: validation must refuse it.
    h.get_by_label("c").set_value_accesskit(0.0);
    h.run_steps(3);
    assert!(!h.state().doc.issues.is_empty(), "c = 0 must be reported");
    assert!(h.query_all_by_label_contains("lights[0].attenuation").count() > 0, "the problem is shown in the UI");
    assert_eq!(h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.revision), revision);
    // The images say they are held, not "updating…" (nothing renders until the value is mended).
    for said in ["GPU: held while a value is invalid", "CPU: held while a value is invalid", "GPU vs CPU: held"] {
        assert!(h.query_all_by_label_contains(said).count() > 0, "{said:?} is not shown");
    }
    assert_eq!(h.query_all_by_label_contains("updating…").count(), 0);
}

#[test]
fn the_integrator_switch_renders_paths_on_both_tracers_and_back() {
    // A small window and image: paths cost more than Whitted's tree on lavapipe.
    let Some(mut h) = viewer("cornell-gi", (1000.0, 640.0)) else { return };
    assert_eq!(h.state().doc.desc.render.integrator, glint_scene::Integrator::Path, "cornell-gi asks for paths");
    let paths = gpu_image(&h);
    choose(&mut h, "Scene", "Integrator", "whitted");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.render.integrator, glint_scene::Integrator::Whitted);
    assert!(h.query_by_label("Indirect light").is_none(), "Whitted's tree has no indirect-light switch");
    let whitted = gpu_image(&h);
    // cornell-gi has no point light and no ambient term: Whitted sees the lamp (and its images in
    // the mirror and the glass) and little else; the paths light the whole box.
    let lit = |i: &glint_core::HdrImage| {
        i.pixels.iter().filter(|p| p.max_element() > 0.01).count() as f64 / i.pixels.len() as f64
    };
    assert!(lit(&whitted) < 0.1 && lit(&paths) > 0.7, "lit: Whitted {}, paths {}", lit(&whitted), lit(&paths));
    let mean = |i: &glint_core::HdrImage| i.pixels.iter().map(|p| p.x + p.y + p.z).sum::<f64>() / i.pixels.len() as f64;
    assert_current_agreement(&h);
    choose(&mut h, "Scene", "Integrator", "path");
    settle(&mut h);
    h.get_by_label("Indirect light").click();
    settle(&mut h);
    assert!(!h.state().doc.desc.render.indirect, "the switch sets render.indirect");
    let direct = gpu_image(&h);
    assert!(mean(&direct) < mean(&paths), "without indirect light the box is darker");
    assert_current_agreement(&h);

    // The toolbar's switch does the same, from any panel; render.indirect = false stays through
    // Whitted (warned of, changing nothing there) and is the paths' again on the way back (the
    // switch had reset it, losing a setting of the lesson's file).
    h.get_by_label("Whitted").click();
    settle(&mut h);
    let r = &h.state().doc.desc.render;
    assert_eq!((r.integrator, r.indirect), (glint_scene::Integrator::Whitted, false));
    assert!(h.state().doc.warnings.iter().any(|w| w.field == "render.indirect"), "{:?}", h.state().doc.warnings);
    h.get_by_label("Paths").click();
    settle(&mut h);
    let r = &h.state().doc.desc.render;
    assert_eq!((r.integrator, r.indirect), (glint_scene::Integrator::Path, false));
    assert_current_agreement(&h);
}

#[test]
fn fit_ambient_lowers_whitteds_error_against_the_paths_and_applies_on_click() {
    let Some(mut h) = viewer("cornell-gi", (1000.0, 640.0)) else { return };
    // A small image: the fit renders paths on the CPU.
    h.get_by_role_and_label(Role::Slider, "Width").set_value_accesskit(48.0);
    h.get_by_role_and_label(Role::Slider, "Height").set_value_accesskit(36.0);
    settle(&mut h);
    h.get_by_label("Fit ambient to paths").click();
    let start = std::time::Instant::now();
    while h.state().fitter.result.is_none() {
        assert!(h.state().fitter.error.is_none(), "{:?}", h.state().fitter.error);
        assert!(start.elapsed().as_secs() < 120, "no fit after two minutes");
        std::thread::sleep(std::time::Duration::from_millis(50));
        h.run_steps(1);
    }
    let (_, fit, indirect) = h.state().fitter.result.expect("a fit");
    assert!(fit.ambient.iter().all(|a| *a > 0.0), "{fit:?}");
    assert!(fit.rmse_fitted < fit.rmse_without, "{fit:?}");
    // cornell-gi writes no ambient; the box's walls light each other, and the fitted ambient
    // brings some of that light.
    assert_eq!(fit.adds_as_written, 0.0, "{fit:?}");
    assert!(indirect > 0.01 && fit.adds_fitted > 0.0, "indirect {indirect}, {fit:?}");
    h.run_steps(2);
    assert!(h.query_by_label_contains("Fitted I_a = (").is_some(), "the fit is shown");
    assert!(h.query_by_label_contains("below the paths', of which").is_some(), "and what it makes up for");
    // cornell-gi's lamp is a panel, whose direct light Whitted's point lights do not compute:
    // all the ambient can make up for is more than the indirect light (a lecturer asked why
    // the fit added twice the indirect light).
    assert!(fit.below_reference > indirect, "below the paths by {}, indirect {indirect}", fit.below_reference);
    h.get_by_label("Apply the fitted I_a").click();
    settle(&mut h);
    assert_eq!(h.state().doc.desc.world.ambient.0, fit.ambient, "Apply sets the world's ambient");
    // Applied, the fit is the scene's, not an earlier edit's, and is not offered again (a
    // tester's find: both stayed).
    assert!(h.query_by_label_contains("fitted to an earlier edit").is_none(), "the applied fit called stale");
    assert!(h.query_by_label("Apply the fitted I_a").is_none(), "Apply offered again");
    assert!(h.query_by_label_contains("the fitted value").is_some(), "says it is applied");
    let as_written = format!("RMSE against the paths: {:.4} as written", fit.rmse_fitted);
    assert!(h.query_by_label_contains(&as_written).is_some(), "'as written' is the applied ambient's now");
    // Another I_a typed leaves the fit the scene's, its "as written" that I_a's (a lecturer saw
    // "fitted to an earlier edit" and the old figures after typing one).
    h.state_mut().doc.desc.world.ambient = glint_scene::Rgb([0.0; 3]);
    h.state_mut().doc.edited();
    h.run_steps(2);
    assert!(h.query_by_label_contains("fitted to an earlier edit").is_none(), "an I_a edit called the fit stale");
    let without = format!("RMSE against the paths: {:.4} as written", fit.rmse_without);
    assert!(h.query_by_label_contains(&without).is_some(), "'as written' follows the I_a typed");
    // Light shown is a way of looking, not an edit: the fit stays the scene's (a lecturer saw
    // "fitted to an earlier edit" beside "I_a is the fitted value" on choosing Caustics).
    h.state_mut().doc.omit_kinds = glint_scene::PathKind::Caustic.alone();
    h.state_mut().doc.view_changed();
    h.run_steps(2);
    assert!(h.query_by_label_contains("fitted to an earlier edit").is_none(), "a view change called the fit stale");
    // An edit of the scene does leave it an earlier edit's: a k_a, as a camera.
    h.state_mut().doc.desc.materials.values_mut().for_each(|m| m.ka.0[0] *= 0.5);
    h.state_mut().doc.edited();
    h.run_steps(2);
    assert!(h.query_by_label_contains("fitted to an earlier edit").is_some(), "a k_a edit left the fit current");
    h.state_mut().doc.desc.camera.fov_y += 1.0;
    h.state_mut().doc.edited();
    h.run_steps(2);
    assert!(h.query_by_label_contains("fitted to an earlier edit").is_some(), "an edit left the fit current");
}

#[test]
fn ctrl_z_takes_back_each_edit_with_its_image_and_ctrl_shift_z_gives_it_back() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let before = gpu_image(&h);
    dull_the_mirror(&mut h);
    let dull = gpu_image(&h);
    choose(&mut h, "Lights", "Type", "spot");
    settle(&mut h);
    assert!(mean_abs_diff(&dull, &gpu_image(&h)) > 1e-3, "a spot light must change the image");

    // The spot light is the last step; the three channels, set a frame (0.25 s) apart, are one
    // step before it.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].kind, LightKind::Point);
    assert_eq!(h.state().doc.desc.materials["mirror"].ks.0, [0.0; 3], "the spot light's step alone");
    assert_eq!(mean_abs_diff(&dull, &gpu_image(&h)), 0.0, "the point light's image again");
    assert_current_agreement(&h);
    assert_eq!(h.state().edits.undo_label(&h.state().doc).as_deref(), Some("Materials › mirror"));
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().edits.undo_label(&h.state().doc), None, "the drag of three channels was one step");
    settle(&mut h);
    assert_eq!(
        h.state().doc.desc.materials["mirror"],
        glint_io::load_scene("whitted").unwrap().desc.materials["mirror"]
    );
    assert_eq!(mean_abs_diff(&before, &gpu_image(&h)), 0.0, "the scene's image as opened");
    assert!(!h.state().doc.dirty, "back as opened, nothing is unsaved");

    // The Edit menu names what a redo gives back; Ctrl+Shift+Z and the menu give it.
    h.get_by_label("Edit").click();
    h.run_steps(2);
    h.get_by_label_contains("Redo Materials › mirror").click();
    h.run_steps(2);
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    h.run_steps(2);
    settle(&mut h);
    assert_eq!((h.state().doc.desc.lights[0].kind, h.state().doc.dirty), (LightKind::Spot, true));
    assert_eq!(h.state().doc.desc.materials["mirror"].ks.0, [0.0; 3]);
}
