//! The difference view you can read and the Errors panel: the colour bar's scale, the value
//! under the cursor, the histogram, "go to worst pixel", and the live plot of error against
//! samples from the comparisons made so far.

use egui_kittest::kittest::Queryable;
use glint_viewer::ViewMode;

use crate::support::{settle, viewer};

#[test]
fn the_difference_view_reads_out_the_pixel_under_the_cursor_against_a_log_scale() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.state_mut().layout.mode = ViewMode::Difference;
    h.run_steps(3);
    for tick in ["0", "1e-7", "1e-3", "1e0"] {
        assert!(h.query_by_label(tick).is_some(), "the colour bar has no {tick:?} label");
    }
    let rev = h.state().doc.revision;
    let (x, y) = (20, 15);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the difference image is drawn");
    h.hover_at(pos);
    h.run_steps(3);
    let (d, differs) = h.state().renders.comparison_of(rev).expect("a comparison").diffs.at(x, y).expect("in range");
    let text = format!(
        "({x}, {y}): |GPU − CPU| = {d:.3e}{}",
        if differs { ", first hit differs" } else { ", same first hit" }
    );
    assert!(h.query_by_label(&text).is_some(), "no readout {text:?}");
}

#[test]
fn the_errors_panel_goes_to_the_worst_pixel_and_plots_error_against_samples() {
    let Some(mut h) = viewer("whitted", (1000.0, 800.0)) else { return };
    h.get_by_label("Errors").click();
    h.run_steps(3);
    assert!(h.query_by_label_contains("Pixels by |GPU − CPU|").is_some(), "the histogram");
    let rev = h.state().doc.revision;
    let (x, y, _) = h.state().renders.comparison_of(rev).unwrap().diffs.worst().expect("whitted differs somewhere");
    h.get_by_label_contains("Go to worst pixel").click();
    settle(&mut h);
    let probe = h.state().renders.probe.as_ref().expect("the worst pixel is probed");
    assert_eq!((probe.x, probe.y), (x, y));
    assert_eq!(h.state().layout.tab, glint_viewer::Tab::Probe);
    // Two more sample counts: three points of error against samples.
    for spp in [2, 4] {
        h.state_mut().doc.desc.render.spp = spp;
        h.state_mut().doc.edited();
        settle(&mut h);
    }
    h.get_by_label("Errors").click();
    h.run_steps(3);
    assert_eq!(h.state().history.len(), 3);
    assert!(h.query_by_label("3 comparisons of this scene; log10 of the error").is_some(), "the plot's caption");
    // A material edit is another scene: the plot starts over.
    h.state_mut().doc.desc.world.ambient = glint_scene::Rgb::splat(0.3);
    h.state_mut().doc.edited();
    settle(&mut h);
    assert_eq!(h.state().history.len(), 1);
}
