//! Small things of the view: the wipe's labels inside the image, the probed pixel marked and
//! its tab shown on Ctrl+click, the frame rate in the status bar from the first frame.

use egui::Modifiers;
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_viewer::{Tab, ViewerApp};

use crate::support::{click, settle, viewer};

/// Where the image labels `text` are drawn.
fn label_rects(h: &Harness<'static, ViewerApp>, text: &str) -> Vec<egui::Rect> {
    h.query_all_by_role_and_label(Role::Label, text).map(|n| n.rect()).collect()
}

#[test]
fn the_wipe_labels_stay_inside_the_image_at_either_end() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.get_by_label("Split wipe").click();
    h.run_steps(2);
    for (wipe, shown) in [(0.0, vec!["CPU"]), (1.0, vec!["GPU"]), (0.5, vec!["GPU", "CPU"])] {
        h.state_mut().layout.wipe = wipe;
        h.run_steps(2);
        let image = *h.state().layout.view_rects.first().expect("the view is drawn");
        for text in ["GPU", "CPU"] {
            let rects = label_rects(&h, text);
            assert_eq!(rects.len(), usize::from(shown.contains(&text)), "{text} at wipe {wipe}: {rects:?}");
            for r in rects {
                assert!(image.contains_rect(r), "{text} at wipe {wipe}: {r:?} outside the image {image:?}");
            }
        }
    }
}

#[test]
fn ctrl_click_shows_the_probe_tab_and_marks_the_probed_pixel_in_every_image() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.get_by_label("Materials").click();
    h.run_steps(2);
    let (x, y) = (100, 70);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    assert_eq!(h.state().layout.tab, Tab::Probe, "the probe's tab is shown");
    let marks: Vec<egui::Rect> = h.query_all_by_label(&format!("Probed pixel ({x}, {y})")).map(|n| n.rect()).collect();
    // Side by side: one mark on the GPU image, one on the CPU image, each on the pixel.
    let images = h.state().layout.view_rects.clone();
    assert_eq!(marks.len(), images.len(), "{marks:?}");
    for (mark, image) in marks.iter().zip(&images) {
        let at = image.min + (pos - images[0].min);
        assert!(mark.contains(at) && image.contains(mark.center()), "{mark:?} is not on the pixel at {at:?}");
    }
}

#[test]
fn the_gpu_time_shows_from_the_first_render_and_a_shader_compile_is_no_render_rate() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    // One render since the start, no edit: its time is there already. It compiled its shader,
    // which on lavapipe read "GPU 14539.8 ms/frame 0.1 fps" for a 40 ms render (a lecturer).
    assert_eq!(h.state().renders.gpu_renders(), 1);
    assert!(h.query_by_label_contains(" ms/render, its shader's compile included").is_some(), "no compile said");
    assert!(h.query_by_label_contains("renders/s").is_none(), "a compile's time given as a rate");
    // A render of the same shader: its own time, and the rate of GPU renders (not "fps").
    h.state_mut().doc.desc.lights[0].diffuse.0[0] *= 0.5;
    h.state_mut().doc.edited();
    settle(&mut h);
    assert!(h.query_by_label_contains("compile included").is_none(), "the compile's time persists");
    assert!(h.query_by_label_contains(" ms/render").is_some(), "no GPU time in the status bar");
    assert!(h.query_by_label_contains(" renders/s").is_some(), "no render rate in the status bar");
    assert!(h.query_by_label_contains(" fps").is_none(), "renders called frames");
}

#[test]
fn at_1024_by_768_the_side_panel_leaves_the_images_room_and_f9_hides_it() {
    let Some(mut h) = viewer("whitted", (1024.0, 768.0)) else { return };
    let view = h.state().layout.view_rects[0];
    // The panel's default width is 300 of 1024 points (29 %; it was 380, 37 %): the image,
    // as wide as the rest allows, starts right after it.
    assert!(view.left() < 350.0, "the view starts at {}", view.left());
    h.key_press(egui::Key::F9);
    h.run_steps(3);
    assert!(h.query_by_label("Scene").is_none(), "the side panel is hidden");
    let wide = h.state().layout.view_rects[0];
    assert!(wide.left() < 20.0 || wide.width() > view.width(), "{wide:?} against {view:?}");
    // A probe brings the panel back with its result.
    let pos = h.state().screen_pos_of_pixel(40, 30).expect("drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    h.run_steps(3);
    assert!(h.state().layout.show_side_panel && h.query_by_label("Probe").is_some());
}

#[test]
fn an_image_of_an_earlier_edit_is_marked_updating_and_keeps_its_aspect() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.query_by_label_contains("updating…").is_none(), "settled images are current");
    // A wider image: the CPU pane keeps the old image, dimmed and marked, until the new one
    // is done, and draws it at its own aspect, not stretched to the new frame.
    let (w, h0) = (h.state().doc.desc.render.width, h.state().doc.desc.render.height);
    h.state_mut().doc.desc.render.width = 2 * w;
    h.state_mut().doc.edited();
    h.step();
    assert!(h.query_by_label("CPU: updating…").is_some(), "the CPU pane shows an older image unmarked");
    let old = glint_viewer::view_placement(
        egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(400.0, 100.0)),
        (2 * w, h0),
        (w, h0),
    );
    assert!((old.width() / old.height() - w as f32 / h0 as f32).abs() < 1e-3, "stretched: {old:?}");
    settle(&mut h);
    assert!(h.query_by_label_contains("updating…").is_none(), "marked after the new images arrived");
}
