//! The GPU tracer keeps the geometry it uploaded last and reuses it for a scene that shares it
//! (`FlatScene::rebuild`, the viewer's scene after a camera or light edit), never for another.

use std::sync::Arc;

use glint_core::FlatScene;
use glint_core::scene::builtin;
use glint_gpu::{GpuOptions, GpuTracer};

use super::support::gpu_or_skip;
use crate::gpu::gpu_render_with;

#[test]
fn a_rebuilt_scene_reuses_the_uploaded_geometry_and_renders_as_a_fresh_build() {
    // A tracer of its own on the shared device, so other tests' uploads do not count.
    let tracer = GpuTracer::new(gpu_or_skip!().context().clone());
    let options = GpuOptions::default();
    let (desc, _) = builtin("whitted").expect("built-in").load(None).expect("loads");
    let first = FlatScene::build(&desc, &desc.render);
    gpu_render_with(&tracer, &first, &options);
    assert_eq!(tracer.geometry_uploads(), 1);

    let mut moved = desc.clone();
    moved.camera.position[0] += 0.7;
    if let Some(p) = &mut moved.lights[0].position {
        p[1] += 1.0;
    }
    let rebuilt = first.rebuild(&moved, &moved.render);
    let reused = gpu_render_with(&tracer, &rebuilt, &options);
    assert_eq!(tracer.geometry_uploads(), 1, "the rebuilt scene's geometry was uploaded again");
    // A fresh build has its own geometry (equal values): uploaded, and the same image.
    let fresh = gpu_render_with(&tracer, &FlatScene::build(&moved, &moved.render), &options);
    assert_eq!(tracer.geometry_uploads(), 2);
    assert!(reused.image.pixels == fresh.image.pixels, "reused buffers render another image");

    // Changed geometry is never served from the cache.
    let mut changed = rebuilt.clone();
    Arc::make_mut(&mut changed.spheres)[0].center_radius[0] += 0.5;
    let other = gpu_render_with(&tracer, &changed, &options);
    assert_eq!(tracer.geometry_uploads(), 3);
    assert!(other.image.pixels != reused.image.pixels, "the moved sphere is not in the image");
}
