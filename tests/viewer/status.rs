//! A GPU image whose shader raised a status flag (work is missing) is marked in red over the
//! GPU view, never shown as if it were a result; a long GPU render says it is under way.

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_test_support::scene::stack_overflow_slab;
use glint_viewer::ViewerApp;

use super::support::{settle, temp_dir, viewer};

#[test]
fn an_incomplete_gpu_image_is_marked_over_the_gpu_view() {
    let dir = temp_dir("status");
    let path = dir.join("slab.toml");
    std::fs::write(&path, stack_overflow_slab()).unwrap();
    let Some(h) = viewer(path.to_str().expect("UTF-8 path"), (1000.0, 640.0)) else { return };
    // The banner says why (the messages panel below says it too, as "GPU: …").
    let banner = "GPU image incomplete: a ray tree branched deeper than the GPU stack";
    assert!(h.query_by_label_contains(banner).is_some(), "no banner over the GPU view");
    drop(h);
    let Some(h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.query_by_label_contains("GPU image incomplete").is_none(), "a complete image is not marked");
}

#[test]
fn a_long_gpu_render_says_how_far_it_is_and_how_long_it_has_been_rendering() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.query_by_label_contains("GPU rendering").is_none(), "nothing is rendering");
    // 16 samples at 640×480 take seconds on lavapipe.
    let render = &mut h.state_mut().doc.desc.render;
    (render.spp, render.width, render.height) = (16, 640, 480);
    h.state_mut().doc.edited();
    says_how_far(&mut h, 16);
}

#[test]
fn a_path_batch_says_how_far_it_is_as_its_tiles_finish() {
    // A lecturer's find: cornell-gi's 64 paths a pixel are one batch, and the status bar said
    // 0/64 for minutes, then all 64 at once. The batch's share now grows tile by tile.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let render = &mut h.state_mut().doc.desc.render;
    (render.integrator, render.spp, render.width, render.height) = (glint_scene::Integrator::Path, 64, 256, 192);
    h.state_mut().doc.edited();
    says_how_far(&mut h, 64);
}

/// Steps `h` until it settles, reading "GPU rendering n/`total` samples… t s" from the status
/// bar: n must be seen between 0 and `total`, rising, never past `total`.
fn says_how_far(h: &mut Harness<'static, ViewerApp>, total: u32) {
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut seen = Vec::new();
    while Instant::now() < deadline && !h.state().is_settled() {
        h.step();
        if let Some(shown) = h.query_by_label_contains("GPU rendering ").and_then(|n| n.value()) {
            let passes = shown.strip_prefix("GPU rendering ").and_then(|r| r.split_once(" samples… "));
            let (done, secs) = passes.unwrap_or_else(|| panic!("{shown:?}"));
            let (n, of) = done.split_once('/').unwrap_or_else(|| panic!("{shown:?}"));
            assert_eq!(of, total.to_string(), "{shown:?}");
            assert!(secs.ends_with(" s"), "{shown:?}");
            let n: u32 = n.parse().unwrap_or_else(|_| panic!("{shown:?}"));
            if seen.last() != Some(&n) {
                seen.push(n);
            }
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(seen.iter().any(|n| *n > 0 && *n < total), "the status bar never showed the render advance: {seen:?}");
    // The last pass may show while it is read back; never more, never going down.
    assert!(seen.windows(2).all(|w| w[0] < w[1]) && seen.iter().all(|n| *n <= total), "{seen:?}");
    settle(h);
    assert!(h.query_by_label_contains("GPU rendering").is_none(), "the label stays after the render");
}

#[test]
fn a_software_adapter_is_named_where_the_user_looks() {
    let Some(h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let software = h.state().renders.gpu.as_ref().is_some_and(|g| g.is_software());
    let said = h.query_by_label_contains(glint_viewer::SOFTWARE_ADAPTER).is_some();
    assert!(software, "the viewer tests run on lavapipe, a software adapter");
    assert!(said, "the status bar does not say that the GPU tracer runs on the CPU");
}

#[test]
fn the_variants_an_edit_is_likely_to_need_are_compiled_ahead_while_idle() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    settle(&mut h);
    let deadline = Instant::now() + Duration::from_secs(120);
    while h.state().renders.gpu.as_ref().is_some_and(|g| g.to_prewarm() > 0) {
        assert!(Instant::now() < deadline, "the likely variants were never compiled ahead");
        h.step();
        std::thread::sleep(Duration::from_millis(20));
    }
    // Four samples and one Phong material: both compiled ahead, so no render says it compiles.
    h.state_mut().doc.desc.render.spp = 4;
    if let Some(m) = h.state_mut().doc.desc.materials.values_mut().next() {
        m.specular_model = glint_scene::SpecularModel::Phong;
    }
    h.state_mut().doc.edited();
    let deadline = Instant::now() + Duration::from_secs(120);
    while !h.state().is_settled() {
        assert!(Instant::now() < deadline, "the edit never settled");
        h.step();
        let compiling = h.state().renders.gpu.as_ref().and_then(|g| g.compiling().map(|(_, w)| w.to_string()));
        assert_eq!(compiling, None, "a prewarmed variant was compiled again");
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn an_edit_made_while_a_variant_compiles_ahead_wakes_the_window_when_it_is_done() {
    // An edit arriving during a prewarm waits for it; the prewarm's end must wake the window
    // to submit the edit. It did not: the image said "updating…" until the mouse moved.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    settle(&mut h);
    let prewarming = |h: &Harness<'static, ViewerApp>| {
        h.state().renders.gpu.as_ref().and_then(|g| g.in_flight()).is_some_and(|(revision, _)| revision == 0)
    };
    let deadline = Instant::now() + Duration::from_secs(120);
    while !prewarming(&h) {
        assert!(Instant::now() < deadline, "no variant was compiled ahead");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.state_mut().doc.desc.world.ambient.0[0] = 0.3;
    h.state_mut().doc.edited();
    // Frames until the window has nothing more to ask of itself: the edit's CPU render done
    // (its worker wakes the window), its GPU render waiting behind the prewarm, which is not
    // the document's render.
    let revision = h.state().doc.revision;
    loop {
        h.step();
        let cpu_done = h.state().renders.cpu_of(revision).is_some();
        if cpu_done && !h.ctx.has_requested_repaint() {
            break;
        }
        assert!(Instant::now() < deadline, "the CPU render of the edit never finished");
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(prewarming(&h), "the prewarm ended before the test could wait on it: make it longer");
    let deadline = Instant::now() + Duration::from_secs(120);
    while !h.ctx.has_requested_repaint() {
        assert!(Instant::now() < deadline, "the window was not woken when the prewarm ended");
        std::thread::sleep(Duration::from_millis(20));
    }
    settle(&mut h);
    assert_eq!(h.state().renders.gpu.as_ref().and_then(|g| g.shown_revision()), Some(h.state().doc.revision));
}

#[test]
fn a_scene_opened_shows_none_of_the_last_scenes_figures() {
    // A lecturer's find: after whitted (160×120 here) the status bar went on saying its
    // 19,200 camera rays and its frame time for minutes while cornell-gi rendered.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let whitted = format!("Rays (GPU): {} camera", 160 * 120);
    assert!(h.query_by_label_contains(&whitted).is_some(), "whitted's rays are shown once rendered");
    h.state_mut().open("spotlights");
    h.run_steps(2);
    assert!(h.query_by_label_contains(&whitted).is_none(), "the last scene's rays are shown for the new one");
    settle(&mut h);
    assert!(h.query_by_label_contains("Rays (GPU): ").is_some(), "the new scene's rays once rendered");
}
