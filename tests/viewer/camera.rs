//! Orbiting by dragging in the view: scaled by the view's size, never under the floor.

use egui::{Event, PointerButton, Pos2, Vec2};
use egui_kittest::Harness;
use glint_core::glam::DVec3;
use glint_viewer::ViewerApp;

use crate::support::viewer;

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
