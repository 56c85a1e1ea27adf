//! Snapshots of the main layouts (side by side, difference, errors, probe and lights panels), 800×500.
//!
//! Threshold: both images are rendered by lavapipe on the CPU, deterministically, so a
//! re-run on the same Mesa matches exactly; a different Mesa or LLVM version may round a few
//! texture-filtering and text-antialiasing pixels differently. The per-pixel threshold stays
//! at kittest's default (0.6, far below any visible change) and up to 0.5 % of the pixels
//! (2000 of 400 000) may differ: a broken layout, a missing image or a changed colour map
//! moves far more. The status bar (timings vary run to run) is masked.

use egui::Modifiers;
use egui::accesskit::Role;
use egui_kittest::SnapshotOptions;
use egui_kittest::kittest::Queryable;

use crate::support::{choose, click, settle, viewer};

fn options() -> SnapshotOptions {
    SnapshotOptions::new()
        .output_path(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/viewer/snapshots"))
        .max_failed_pixels(2000)
}

/// The window as it shows: kittest clears to transparent, the window to the background colour
/// the transparent panels let through (glint_viewer::background).
pub fn snapshot(h: &mut egui_kittest::Harness<'static, glint_viewer::ViewerApp>, name: &str) {
    let status = h.state().layout.status_rect;
    h.mask(status);
    let mut image = h.render().expect("the harness renders");
    glint_viewer::over_background(&mut image, glint_viewer::background(&h.ctx.global_style().visuals));
    egui_kittest::image_snapshot_options(&image, name, &options());
}

#[test]
fn main_layouts_match_their_snapshots() {
    let Some(mut h) = viewer("whitted", (800.0, 500.0)) else { return };
    snapshot(&mut h, "viewer_side_by_side");

    h.get_by_label("Difference").click();
    h.run_steps(3);
    snapshot(&mut h, "viewer_difference");

    h.get_by_label("Errors").click();
    h.run_steps(3);
    snapshot(&mut h, "viewer_errors");

    h.get_by_role_and_label(Role::Button, "GPU").click();
    h.run_steps(2);
    let pos = h.state().screen_pos_of_pixel(100, 70).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    snapshot(&mut h, "viewer_probe");
}

/// The ray tree of a glass sphere pixel over the GPU image (side panel hidden: the image gets
/// the window). Also the README's docs/images/ray-tree.png.
#[test]
fn the_ray_tree_over_a_glass_sphere_matches_its_snapshot() {
    let Some(mut h) = viewer("whitted", (800.0, 500.0)) else { return };
    h.get_by_role_and_label(Role::Button, "GPU").click();
    h.run_steps(2);
    let pos = h.state().screen_pos_of_pixel(100, 70).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    h.state_mut().layout.show_side_panel = false;
    h.run_steps(3);
    snapshot(&mut h, "viewer_ray_tree");
}

#[test]
fn the_lights_panel_and_a_spot_gizmo_match_their_snapshot() {
    let Some(mut h) = viewer("whitted", (800.0, 500.0)) else { return };
    h.get_by_role_and_label(Role::Button, "GPU").click();
    choose(&mut h, "Lights", "Type", "spot");
    // Bring the light in front of the camera so that its dot and cone are in view, pointing
    // straight down (a new spot aims at the look-at point from where the light was).
    let axes = [("Position x", -1.0), ("Position y", 2.5), ("Position z", 0.0)];
    let spot_axis = [("Spot axis x", 0.0), ("Spot axis y", -1.0), ("Spot axis z", 0.0)];
    for (axis, v) in axes.into_iter().chain(spot_axis) {
        h.get_by_label(axis).set_value_accesskit(v);
        h.run_steps(1);
    }
    settle(&mut h);
    assert_eq!(h.state().doc.desc.lights[0].position, Some([-1.0, 2.5, 0.0]));
    assert_eq!(h.state().doc.desc.lights[0].direction, Some([0.0, -1.0, 0.0]));
    snapshot(&mut h, "viewer_lights_spot");
}
