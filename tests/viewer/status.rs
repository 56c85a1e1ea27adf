//! A GPU image whose shader raised a status flag (work is missing) is marked in red over the
//! GPU view, never shown as if it were a result.

use egui_kittest::kittest::Queryable;
use glint_test_support::scene::stack_overflow_slab;

use super::support::{temp_dir, viewer};

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
