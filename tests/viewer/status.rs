//! A GPU image whose shader raised a status flag (work is missing) is marked in red over the
//! GPU view, never shown as if it were a result.

use egui_kittest::kittest::Queryable;
use glint_test_support::scene::SceneText;

use super::support::{temp_dir, viewer};

/// The camera inside a glass slab at depth 65: one deferred ray more than the GPU stack holds
/// (tests/stiff case 15), so the GPU raises `STATUS_STACK_OVERFLOW`.
fn slab() -> String {
    let a = 10.0_f64.to_radians();
    SceneText::pinhole("max_depth = 65\nbailout = 0.0", [0.0; 3], [a.sin(), a.cos(), 0.0], [0.0, 0.0, 1.0])
        .world([0.0; 3], [0.25; 3])
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.9\nkt = 0.5\nior = 1.5\nemission = 0.0625")
        .plane([0.0, 1.0, 0.0], [0.0, 1.0, 0.0], "glass")
        .plane([0.0, -1.0, 0.0], [0.0, -1.0, 0.0], "glass")
        .text
}

#[test]
fn an_incomplete_gpu_image_is_marked_over_the_gpu_view() {
    let dir = temp_dir("status");
    let path = dir.join("slab.toml");
    std::fs::write(&path, slab()).unwrap();
    let Some(h) = viewer(path.to_str().expect("UTF-8 path"), (1000.0, 640.0)) else { return };
    // The banner says why (the messages panel below says it too, as "GPU: …").
    let banner = "GPU image incomplete: a ray tree branched deeper than the GPU stack";
    assert!(h.query_by_label_contains(banner).is_some(), "no banner over the GPU view");
    drop(h);
    let Some(h) = viewer("whitted", (1000.0, 640.0)) else { return };
    assert!(h.query_by_label_contains("GPU image incomplete").is_none(), "a complete image is not marked");
}
