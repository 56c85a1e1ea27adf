//! Orbiting by dragging in the view: scaled by the view's size, never under the floor, and never
//! leaving another camera's image on screen.

use egui::{Event, PointerButton, Pos2, Vec2};
use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_core::glam::DVec3;
use glint_viewer::ViewerApp;

use crate::support::{settle, viewer};

/// A primary-button drag from `from` by `by`, in `steps` moves, one frame each.
fn drag(h: &mut Harness<'static, ViewerApp>, from: Pos2, by: Vec2, steps: usize) {
    h.event(Event::PointerMoved(from));
    h.step();
    let press = |pressed, pos| Event::PointerButton {
        pos,
        button: PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    h.event(press(true, from));
    h.step();
    for i in 1..=steps {
        h.event(Event::PointerMoved(from + by * (i as f32 / steps as f32)));
        h.step();
    }
    h.event(press(false, from + by));
    h.step();
}

/// The camera's offset from its look-at point.
fn offset(h: &Harness<'static, ViewerApp>) -> DVec3 {
    let c = &h.state().doc.desc.camera;
    DVec3::from(c.position) - DVec3::from(c.look_at)
}

#[test]
fn a_drag_across_the_image_turns_half_way_and_a_short_upward_drag_stays_above_the_floor() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let image = *h.state().layout.view_rects.first().expect("the view is drawn");
    let start = offset(&h);
    // The drag: 120×40 points up and sideways put the camera under the floor (y = 0).
    drag(&mut h, image.center(), Vec2::new(120.0, -40.0), 8);
    let camera = h.state().doc.desc.camera.position;
    assert!(camera[1] > 0.0, "the camera went under the floor: {camera:?}");
    assert!((offset(&h) - start).length() > 1.0, "the drag orbited");

    // Across the image's width: half a turn about the up axis, whatever the window size.
    let before = offset(&h);
    drag(&mut h, image.left_center(), Vec2::new(image.width(), 0.0), 10);
    let after = offset(&h);
    let turned = after.x.atan2(after.z) - before.x.atan2(before.z);
    let turned = turned.rem_euclid(std::f64::consts::TAU);
    assert!((turned - std::f64::consts::PI).abs() < 0.05, "turned {turned} rad");
    assert!((after.y - before.y).abs() < 1e-9, "a level drag keeps the height");
}

#[test]
fn a_drag_during_a_long_render_never_leaves_the_old_camera_on_screen() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let image = *h.state().layout.view_rects.first().expect("the view is drawn");
    // 16 samples at 640×480: seconds of GPU work on lavapipe, sample pass after sample pass.
    let render = &mut h.state_mut().doc.desc.render;
    (render.spp, render.width, render.height) = (16, 640, 480);
    h.state_mut().doc.edited();
    let before = h.state().doc.revision;
    let deadline = Instant::now() + Duration::from_secs(60);
    let gpu =
        |h: &Harness<'static, ViewerApp>| h.state().renders.gpu.as_ref().map(|g| (g.shown_revision(), g.in_flight()));
    while gpu(&h).and_then(|g| g.1) != Some((before, false)) {
        assert!(Instant::now() < deadline, "the full render never started");
        h.step();
    }
    drag(&mut h, image.center(), Vec2::new(80.0, 0.0), 4);
    let after = h.state().doc.revision;
    assert!(after > before, "the drag moved the camera");
    // From the release on: once an image of a later camera is on screen, the old camera's
    // never comes back (its full render was cancelled between passes, or is dropped when it
    // completes), and this camera's preview arrives while its full render has not finished (it
    // went first). Until the first later image arrives the old one may stay: on a loaded
    // machine no preview finishes during the four drag frames.
    let mut preview_while_rendering = false;
    let mut later_shown = false;
    loop {
        h.step();
        let (shown, in_flight) = gpu(&h).expect("a GPU");
        later_shown |= shown.is_some_and(|s| s > before);
        assert!(!(later_shown && shown == Some(before)), "the pre-drag camera's image came back after the drag");
        if shown == Some(after) && in_flight.is_none_or(|f| f == (after, false)) && !h.state().is_settled() {
            preview_while_rendering = true;
        }
        if h.state().is_settled() {
            break;
        }
        assert!(Instant::now() < deadline + Duration::from_secs(60), "the render never finished");
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(preview_while_rendering, "no image of the new camera until its full render was done");
    assert_eq!(gpu(&h).and_then(|g| g.0), Some(after));
}

#[test]
fn a_camera_typed_in_shows_its_preview_before_its_long_render() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let render = &mut h.state_mut().doc.desc.render;
    (render.spp, render.width, render.height) = (16, 640, 480);
    h.state_mut().doc.edited();
    settle(&mut h);
    // A new camera not by dragging (typed in a field, picked from a file's cameras): no preview
    // came during an interaction, so one must come before the 16 passes.
    h.state_mut().doc.desc.camera.position[0] += 1.0;
    h.state_mut().doc.edited();
    let moved = h.state().doc.revision;
    let gpu =
        |h: &Harness<'static, ViewerApp>| h.state().renders.gpu.as_ref().map(|g| (g.shown_revision(), g.in_flight()));
    let deadline = Instant::now() + Duration::from_secs(120);
    let mut preview_while_rendering = false;
    while !h.state().is_settled() {
        h.step();
        let (shown, in_flight) = gpu(&h).expect("a GPU");
        preview_while_rendering |= shown == Some(moved) && in_flight == Some((moved, false));
        assert!(Instant::now() < deadline, "the render never finished");
        std::thread::sleep(Duration::from_millis(5));
    }
    assert!(preview_while_rendering, "the old camera stayed on screen until the full render was done");
}

#[test]
fn the_projection_switch_keeps_the_framing_and_renders_parallel_rays_on_both_tracers() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let perspective = crate::support::gpu_image(&h);
    let framing = h.state().doc.desc.camera.view_height();
    crate::support::choose(&mut h, "Scene", "Projection", "orthographic");
    settle(&mut h);
    let c = h.state().doc.desc.camera.clone();
    assert_eq!((c.projection, c.view_height), (glint_scene::Projection::Orthographic, Some(framing)));
    assert!(
        h.query_all_by_label("Field of view").next().is_none() && h.query_all_by_label("View height").next().is_some()
    );
    let orthographic = crate::support::gpu_image(&h);
    assert!(crate::support::mean_abs_diff(&perspective, &orthographic) > 1e-3, "the image changed");
    crate::edits::assert_current_agreement(&h);
    crate::support::choose(&mut h, "Scene", "Projection", "perspective");
    settle(&mut h);
    let c = &h.state().doc.desc.camera;
    assert_eq!((c.projection, c.view_height), (glint_scene::Projection::Perspective, None));
    assert!(crate::support::mean_abs_diff(&perspective, &crate::support::gpu_image(&h)) < 1e-6, "back as it was");
}
