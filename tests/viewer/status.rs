//! A GPU image whose shader raised a status flag (work is missing) is marked in red over the
//! GPU view, never shown as if it were a result; a long GPU render says it is under way.

use std::time::{Duration, Instant};

use egui_kittest::kittest::Queryable;
use glint_test_support::scene::stack_overflow_slab;

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
fn a_long_gpu_render_says_how_long_it_has_been_rendering() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.query_by_label_contains("GPU rendering").is_none(), "nothing is rendering");
    // 16 samples at 640×480 take seconds on lavapipe.
    let render = &mut h.state_mut().doc.desc.render;
    (render.spp, render.width, render.height) = (16, 640, 480);
    h.state_mut().doc.edited();
    let deadline = Instant::now() + Duration::from_secs(60);
    let mut shown = None;
    while shown.is_none() && Instant::now() < deadline && !h.state().is_settled() {
        h.step();
        shown = h.query_by_label_contains("GPU rendering… ").and_then(|n| n.value());
        std::thread::sleep(Duration::from_millis(5));
    }
    let shown = shown.expect("the status bar never said the GPU was rendering");
    assert!(shown.ends_with(" s"), "{shown:?}");
    settle(&mut h);
    assert!(h.query_by_label_contains("GPU rendering").is_none(), "the label stays after the render");
}
