//! The GPU tracer keeps the geometry it uploaded last and reuses it for a scene that shares it
//! (`FlatScene::rebuild`, the viewer's scene after a camera or light edit), never for another.

use std::sync::Arc;

use glint_core::FlatScene;
use glint_gpu::{GpuOptions, GpuTracer};
use glint_io::builtin;

use super::support::gpu_or_skip;
use crate::gpu::gpu_render_with;

/// Moves the camera the fraction `f` of the way to what it looks at: the centre ray meets the
/// same point, so the frame stays (`rebase::camera_frame`).
fn dolly(camera: &mut glint_scene::CameraDesc, f: f64) {
    for k in 0..3 {
        camera.position[k] += f * (camera.look_at[k] - camera.position[k]);
    }
}

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
    dolly(&mut moved.camera, 0.05);
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

#[test]
fn a_scene_far_from_the_origin_reuses_its_rebased_geometry_while_the_camera_moves() {
    // Whitted moved 1e5 along x: the GPU traces it in a frame where the camera looks (rebased
    // positions). A camera move that keeps the centre ray on the same surface point keeps that
    // frame: the rebased geometry is reused and not uploaded again; a pan across the scene
    // changes the frame and uploads once more.
    let tracer = GpuTracer::new(gpu_or_skip!().context().clone());
    let options = GpuOptions::default();
    let (mut desc, _) = builtin("whitted").expect("built-in").load(None).expect("loads");
    glint_test_support::scene::translate(&mut desc, [1e5, 0.0, 0.0]);
    let first = FlatScene::build(&desc, &desc.render);
    let frame = glint_core::rebase::camera_frame(&first);
    assert_ne!(frame, glint_types::layout::WORLD_FRAME);
    gpu_render_with(&tracer, &first, &options);
    assert_eq!(tracer.geometry_uploads(), 1);

    let mut moved = desc.clone();
    dolly(&mut moved.camera, 0.05);
    let rebuilt = first.rebuild(&moved, &moved.render);
    assert_eq!(glint_core::rebase::camera_frame(&rebuilt), frame, "a dolly keeps the frame");
    let reused = gpu_render_with(&tracer, &rebuilt, &options);
    assert_eq!(tracer.geometry_uploads(), 1, "the rebased geometry was uploaded again");
    // The same image as a fresh tracer rebasing from scratch.
    let fresh = gpu_render_with(&GpuTracer::new(tracer.context().clone()), &rebuilt, &options);
    assert!(reused.image.pixels == fresh.image.pixels, "reused rebased geometry renders another image");

    let mut far = desc.clone();
    far.camera.position[0] += 400.0;
    far.camera.look_at[0] += 400.0;
    let rebuilt_far = first.rebuild(&far, &far.render);
    assert_ne!(glint_core::rebase::camera_frame(&rebuilt_far), frame);
    gpu_render_with(&tracer, &rebuilt_far, &options);
    assert_eq!(tracer.geometry_uploads(), 2);
}
