//! Whitted against global illumination in the viewer (issue 33): the GPU adds path samples
//! progressively (pause, continue, restart on an edit), the Whitted vs GI view (beside, wipe,
//! the signed difference with its readout), each kind of light alone, and the probe's split by
//! bounce and kind.

use std::time::{Duration, Instant};

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use glint_core::glam::DVec3;
use glint_viewer::ViewerApp;

use crate::support::{choose, settle, viewer, viewer_with};

/// The GPU's path samples a pixel of the current revision (0 before its first render is in).
fn gpu_samples(h: &Harness<'static, ViewerApp>) -> u32 {
    let rev = h.state().doc.render_revision;
    let a = h.state().renders.gpu.as_ref().and_then(|g| g.accumulation.as_ref());
    a.filter(|a| a.revision == rev).map_or(0, |a| a.samples)
}

fn spp_of_scene(h: &Harness<'static, ViewerApp>) -> u32 {
    h.state().doc.desc.render.spp
}

/// Steps the UI until `done` holds, failing after `secs` with `what`.
fn step_until(
    h: &mut Harness<'static, ViewerApp>,
    secs: u64,
    what: &str,
    done: impl Fn(&Harness<'static, ViewerApp>) -> bool,
) {
    let deadline = Instant::now() + Duration::from_secs(secs);
    while !done(h) {
        assert!(Instant::now() < deadline, "{what} within {secs} s");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn the_gpu_adds_path_samples_until_paused_and_starts_over_on_an_edit() {
    let Some(mut h) = viewer("cornell-gi", (1000.0, 640.0)) else { return };
    let spp = h.state().doc.desc.render.spp;
    assert!(gpu_samples(&h) >= spp, "the first render has the scene's {spp} samples");
    step_until(&mut h, 120, "the GPU adds samples", |h| gpu_samples(h) > spp);
    assert!(h.query_by_label_contains("samples (").is_some(), "the status bar gives the samples and their rate");

    h.get_by_label("Pause").click();
    // The batch in flight when paused still lands; then nothing more.
    step_until(&mut h, 120, "the last batch lands", |h| {
        !h.state().renders.gpu.as_ref().is_some_and(|g| g.is_accumulating())
    });
    let paused = gpu_samples(&h);
    for _ in 0..40 {
        h.step();
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(gpu_samples(&h), paused, "no samples are added while paused");
    assert!(h.query_by_label_contains(", paused").is_some(), "the status bar says it is paused");

    h.get_by_label("Continue").click();
    step_until(&mut h, 120, "the GPU adds samples again", |h| gpu_samples(h) > paused);

    // An ambient edit (applying a fitted I_a) changes no path: the samples go on from where
    // they were, and the CPU's paths are not rendered again.
    let cpu_of = |h: &Harness<'static, ViewerApp>| {
        let cpu = &h.state().renders.cpu;
        cpu.running_revision().or(cpu.finished.as_ref().map(|(r, _)| *r))
    };
    let (before, cpu_started) = (gpu_samples(&h), cpu_of(&h));
    h.state_mut().doc.desc.world.ambient.0[0] += 0.25;
    h.state_mut().doc.edited();
    step_until(&mut h, 120, "the GPU adds samples across an ambient edit", |h| gpu_samples(h) > before);
    assert!(h.state().doc.render_revision < h.state().doc.revision);
    assert_eq!(cpu_of(&h), cpu_started, "the CPU's paths go on");

    // A saved GPU image is the mean of every batch so far, and says so (it said the scene's
    // 64 samples of a mean of 340; a lecturer).
    let dir = crate::support::temp_dir("gi-export");
    let path = dir.join("gpu.png");
    h.state_mut().save_image(&path, glint_viewer::ExportView::Gpu).expect("the GPU view saves");
    let saved = h.state().renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).map(|l| l.samples);
    let text = glint_io::image_file::read_png_text(&path).expect("tEXt chunks");
    let written = text.iter().find(|(k, _)| k == "glint:spp").map(|(_, v)| v.clone());
    assert!(saved.is_some_and(|n| n > spp_of_scene(&h)), "{saved:?}");
    assert_eq!(written, saved.map(|n| n.to_string()), "the saved mean's samples");
    let _ = std::fs::remove_dir_all(dir);

    // An edit starts over from the new revision's first render.
    h.get_by_label("Pause").click();
    h.state_mut().doc.desc.camera.fov_y += 5.0;
    h.state_mut().doc.edited();
    settle(&mut h);
    assert_eq!(gpu_samples(&h), spp, "an edit starts the samples over");
}

#[test]
fn whitted_against_gi_shows_beside_wiped_and_as_a_signed_difference() {
    let Some(mut h) = viewer_with("cornell-gi", (800.0, 500.0), |o| o.paused = true) else { return };
    h.get_by_label("Whitted vs GI").click();
    h.run_steps(2);
    settle(&mut h);
    let rev = h.state().doc.revision;
    let gi = &h.state().renders.gi;
    let whitted = gi.whitted_of(rev).expect("Whitted's image of the revision").clone();
    let d = gi.difference_of(rev).expect("the difference").diff.clone();
    let paths = crate::support::gpu_image(&h);
    // Beside Whitted: the paths the difference was taken from (here the GPU's).
    let difference = gi.difference_of(rev).expect("the difference");
    assert!(difference.from_gpu, "a GPU's paths are the difference's");
    let textures = h.state().renders.textures(&h.state().doc);
    assert_eq!(textures.gi.map(|s| s.id), textures.gpu.map(|s| s.id), "the GPU's image is shown beside Whitted");
    // The signed difference is Whitted's image less the paths', pixel for pixel.
    for (i, v) in d.pixels.iter().enumerate() {
        assert_eq!(*v, whitted.pixels[i] - paths.pixels[i], "pixel {i}");
    }
    // cornell-gi has no point light: Whitted is darker nearly everywhere but on the lamp.
    let darker = d.pixels.iter().filter(|v| v.element_sum() < 0.0).count() as f64 / d.pixels.len() as f64;
    assert!(darker > 0.8, "Whitted darker on {:.0} % of the pixels", 100.0 * darker);
    crate::snapshots::snapshot(&mut h, "viewer_whitted_vs_gi");

    h.get_by_label("Whitted wipe GI").click();
    h.run_steps(3);
    assert!(h.query_by_label("Wipe").is_some(), "the wipe has its slider");
    crate::snapshots::snapshot(&mut h, "viewer_whitted_wipe_gi");

    h.get_by_label("Whitted − GI").click();
    h.run_steps(3);
    assert!(h.query_by_label_contains("Whitted too dark").is_some(), "the colour bar has its legend");
    // The value under the cursor, at a pixel of the floor.
    let (x, y) = (80, 100);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    h.hover_at(pos);
    h.run_steps(2);
    let v = d.at(x, y).expect("a pixel of the image");
    // Four digits, as a class reads them aloud (−0.2916, not −2.916e-1), the minus as U+2212.
    let mean = v.element_sum() / 3.0;
    let shown = glint_scene::format_rounded(mean, 4);
    let shown = if mean > 0.0 { format!("+{shown}") } else { shown.replace('-', "−") };
    let verdict = if mean < 0.0 { "too dark" } else { "too bright" };
    let text = format!("({x}, {y}): Whitted − GI (paths) = {shown}: {verdict} (R ");
    assert!(h.query_by_label_contains(&text).is_some(), "the readout says {text}");
    h.hover_at(egui::pos2(1.0, 1.0));
    h.run_steps(2);
    crate::snapshots::snapshot(&mut h, "viewer_whitted_minus_gi");
    // One kind of light shown: the GI side says which, not "GI (paths)" over the caustics alone
    // (whose lamp then read "too bright" against all of Whitted's light; a lecturer).
    // (As Scene → Light shown sets it; the panel's combo lies below this small window's fold.)
    let show = |h: &mut Harness<'static, ViewerApp>, omit: u32| {
        h.state_mut().doc.omit_kinds = omit;
        h.state_mut().doc.view_changed();
        settle(h);
    };
    show(&mut h, glint_scene::PathKind::Caustic.alone());
    assert!(h.query_by_label_contains("Whitted − GI: caustics alone, mean of R, G, B").is_some(), "no kind named");
    assert!(h.query_by_label_contains("Whitted − GI (paths)").is_none());
    show(&mut h, 0);
    assert!(h.query_by_label_contains("Whitted − GI (paths), mean of R, G, B").is_some(), "the whole light again");

    // A Whitted scene opened in this view is switched to paths as the view's choice switched
    // the first (it was shown on both sides, the copy labelled "GI (paths)": a lecturer).
    h.state_mut().open("whitted");
    h.run_steps(2);
    assert_eq!(h.state().doc.desc.render.integrator, glint_scene::Integrator::Path, "opened in Whitted vs GI");
    assert!(!h.state().doc.dirty, "switched for the view, not edited");
}

#[test]
fn each_kind_of_light_alone_adds_up_to_the_path_image_and_the_probe_splits_a_pixel() {
    let Some(mut h) = viewer_with("cornell-gi", (1000.0, 640.0), |o| o.paused = true) else { return };
    let whole = crate::support::gpu_image(&h);
    let mut sum = vec![DVec3::ZERO; whole.pixels.len()];
    for kind in ["Direct light", "Indirect diffuse", "Caustics", "The rest"] {
        choose(&mut h, "Scene", "Light shown", kind);
        settle(&mut h);
        assert!(!h.state().doc.dirty, "showing a kind of light is not an edit of the scene");
        for (s, p) in sum.iter_mut().zip(&crate::support::gpu_image(&h).pixels) {
            *s += *p;
        }
    }
    let worst = sum
        .iter()
        .zip(&whole.pixels)
        .map(|(s, w)| ((*s - *w).abs() / (w.abs() + DVec3::splat(1e-3))).max_element())
        .fold(0.0, f64::max);
    assert!(worst < 1e-5, "the four kinds add up to the path image to {worst:.1e}, not f32's precision");
    choose(&mut h, "Scene", "Light shown", "All light");
    settle(&mut h);

    // The probe: the paths' pixel by bounce and kind is the CPU image's pixel.
    let (x, y) = (80, 100);
    h.state_mut().probe_at(x, y);
    settle(&mut h);
    let rev = h.state().doc.revision;
    let cpu = h.state().renders.cpu_of(rev).expect("the CPU image").image.get(x, y);
    let probe = h.state().renders.probe.as_ref().and_then(|p| p.paths.clone()).expect("the paths' split");
    assert!((probe.total() - cpu).abs().max_element() < 1e-9, "{} against {cpu}", probe.total());
    assert!(probe.by_kind()[1].max_element() > 0.0, "the floor has indirect light");
    assert!(h.query_by_label_contains("by bounce and kind").is_some(), "the probe panel shows the split");
    h.run_steps(2);
    crate::snapshots::snapshot(&mut h, "viewer_probe_paths");
}

/// The toolbar's integrator switch "Whitted", not the image's caption.
fn whitted_switch<'a>(h: &'a Harness<'static, ViewerApp>) -> egui_kittest::Node<'a> {
    let mut found = h.query_all_by_label("Whitted").filter(|n| n.accesskit_node().role() != Role::Label);
    found.next().expect("the integrator switch's Whitted")
}

#[test]
fn whitted_vs_gi_holds_the_paths_and_never_saves_whitted_as_them() {
    // In Whitted vs GI the toolbar's "Whitted" made the GI side a second Whitted image, Whitted − GI
    // all white at ±1e-6, "paths of 1 samples", and Save image → the paths wrote that Whitted
    // image as glint:integrator path (a lecturer).
    let Some(mut h) = viewer_with("whitted", (1000.0, 640.0), |o| o.paused = true) else { return };
    h.get_by_label("Whitted vs GI").click();
    h.run_steps(2);
    settle(&mut h);
    let integrator = |h: &Harness<'static, ViewerApp>| h.state().doc.desc.render.integrator;
    assert_eq!(integrator(&h), glint_scene::Integrator::Path, "the view switches a Whitted scene to paths");
    assert!(whitted_switch(&h).accesskit_node().is_disabled(), "the switch's Whitted is disabled in the view");
    whitted_switch(&h).click();
    h.run_steps(3);
    assert_eq!(integrator(&h), glint_scene::Integrator::Path, "the GI side stays the paths");

    // Chosen from the View menu (which sets the mode alone) the view switches to paths too.
    h.get_by_label("GPU").click();
    h.run_steps(2);
    assert!(!whitted_switch(&h).accesskit_node().is_disabled(), "outside Whitted vs GI the switch is enabled");
    whitted_switch(&h).click();
    h.run_steps(2);
    assert_eq!(integrator(&h), glint_scene::Integrator::Whitted, "outside the view the switch works");
    h.state_mut().layout.mode = glint_viewer::ViewMode::WhittedVsGi;
    h.run_steps(2);
    assert_eq!(integrator(&h), glint_scene::Integrator::Path, "the View menu's Whitted vs GI renders paths");
    settle(&mut h);

    // A saved "paths" image is the path render, and says so.
    let dir = crate::support::temp_dir("gi-paths");
    let path = dir.join("paths.png");
    h.state_mut().save_image(&path, glint_viewer::ExportView::Paths).expect("the paths save");
    let text = glint_io::image_file::read_png_text(&path).expect("tEXt chunks");
    let get = |k: &str| text.iter().find(|(key, _)| key == k).map(|(_, v)| v.clone()).unwrap_or_default();
    let samples = h.state().renders.gi_paths(&h.state().doc).map(|p| p.1).expect("the paths shown");
    assert_eq!((get("glint:integrator"), get("glint:spp")), ("path".to_string(), samples.to_string()));
    // Whitted's images held as the paths (the scene switched with no render since) are refused
    // by name, not written as "the paths".
    h.state_mut().doc.desc.render.integrator = glint_scene::Integrator::Whitted;
    for view in [glint_viewer::ExportView::Paths, glint_viewer::ExportView::WhittedVsGi] {
        let refused = dir.join("refused.png");
        let e = h.state_mut().save_image(&refused, view).expect_err("no paths to save").to_string();
        assert!(e.contains("no paths to save"), "{e}");
        assert!(!refused.exists());
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn applying_the_fitted_ambient_in_whitted_vs_gi_keeps_the_paths_going_and_the_fit_current() {
    // Apply dropped the GPU's 160 path samples back to 1, rendered the CPU's 64 paths again,
    // and the fit then read "(fitted to an earlier edit of the scene)" over "I_a is the fitted
    // value." (a lecturer).
    // Opened in the view, as from File → Open (that scene had had no edit: Apply was its first).
    let Some(mut h) = viewer_with("whitted", (1000.0, 900.0), |o| o.view = Some(glint_viewer::ViewMode::WhittedVsGi))
    else {
        return;
    };
    let dir = crate::support::temp_dir("fit-apply");
    let scene = dir.join("cornell-gi.toml");
    let text = include_str!("../../assets/scenes/cornell-gi.toml")
        .replace("width = 256\nheight = 256", "width = 160\nheight = 120");
    assert!(text.contains("width = 160"), "the scene's size is where the test looks for it");
    std::fs::write(&scene, text).expect("writes the scene");
    h.state_mut().open(scene.to_str().expect("UTF-8 path"));
    settle(&mut h);
    let spp = spp_of_scene(&h);
    step_until(&mut h, 120, "the GPU adds samples", |h| gpu_samples(h) > spp);
    h.get_by_label("Fit ambient to paths").click();
    h.run_steps(2);
    step_until(&mut h, 240, "the fit", |h| h.state().fitter.result.is_some() && !h.state().fitter.is_running());
    h.run_steps(2);
    let cpu_of = |h: &Harness<'static, ViewerApp>| {
        let cpu = &h.state().renders.cpu;
        cpu.running_revision().or(cpu.finished.as_ref().map(|(r, _)| *r))
    };
    let (render, cpu_started, before) = (h.state().doc.render_revision, cpu_of(&h), gpu_samples(&h));
    h.get_by_label("Apply the fitted I_a").click();
    h.run_steps(3);
    assert_eq!(h.state().doc.render_revision, render, "an ambient edit is none of the paths'");
    assert!(h.state().doc.revision > render, "it is an edit of the scene");
    step_until(&mut h, 120, "the GPU adds samples after Apply", |h| gpu_samples(h) > before);
    assert_eq!(cpu_of(&h), cpu_started, "the CPU's paths are not rendered again");
    assert!(h.query_by_label("I_a is the fitted value.").is_some(), "the applied value is named");
    assert!(h.query_by_label("(fitted to an earlier edit of the scene)").is_none(), "the fit stays current");
    // Whitted's side reads I_a: it is rendered again.
    settle(&mut h);
    assert!(h.state().renders.gi.whitted_of(h.state().doc.revision).is_some());
    let _ = std::fs::remove_dir_all(dir);
}
