//! The GPU BVH (`Accel::Bvh`, the default) against GPU brute force (`Accel::None`) on
//! generated meshes small enough for brute force to stay within lavapipe's loop budget, and
//! against the CPU reference on meshes brute force cannot walk on lavapipe (10k triangles).
//! The built-in scenes run through the BVH in parity.rs. Thresholds are parity.rs's.

use glint_core::compare::compare_images;
use glint_core::{Accel, CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_gpu::GpuOptions;
use glint_test_support::scene::{mesh_scene, uv_sphere};

use super::support::{FLIP_MEAN_MAX, MISMATCH_MAX, P99_MAX, gpu_or_skip};
use crate::gpu::gpu_render_with;

fn render(tracer: &glint_gpu::GpuTracer, flat: &FlatScene, accel: Accel) -> glint_gpu::GpuRender {
    gpu_render_with(tracer, flat, &GpuOptions { accel, ..GpuOptions::default() })
}

#[test]
fn bvh_matches_brute_force_on_the_gpu_for_small_meshes() {
    let tracer = gpu_or_skip!();
    for n in [6, 10, 14] {
        let flat = mesh_scene(64, 48, uv_sphere(n, [0.0, 0.1, 0.0], 1.0)).flat();
        let (bvh, none) = (render(tracer, &flat, Accel::Bvh), render(tracer, &flat, Accel::None));
        assert!(bvh.key.bvh && !none.key.bvh, "the accel option selects the variant");
        assert_eq!(none.status, 0, "n = {n}: brute force must stay within the loop budget to be a reference");
        assert_eq!(bvh.status, 0, "n = {n}: BVH status");
        let e = compare_images(&none.image, &bvh.image);
        eprintln!(
            "{} triangles: BVH vs brute force FLIP {:.5} p99 {:.2e} max {:.2e} mismatch {:.3} %",
            flat.triangles.len(),
            e.flip_mean,
            e.p99_abs_same_hit,
            e.max_abs,
            100.0 * e.first_hit_mismatch
        );
        assert_eq!(bvh.image.first_hit, none.image.first_hit, "n = {n}: first hits differ");
        assert!(e.flip_mean <= FLIP_MEAN_MAX && e.p99_abs_same_hit <= P99_MAX, "n = {n}: {e:?}");
        assert_eq!(bvh.counts, none.counts, "n = {n}: ray counts");
    }
}

#[test]
fn bvh_matches_the_cpu_on_a_10k_triangle_mesh() {
    let tracer = gpu_or_skip!();
    let flat = mesh_scene(64, 48, uv_sphere(50, [0.0, 0.1, 0.0], 1.0)).flat();
    assert!(flat.triangles.len() > 9_800);
    // Directly, not through the golden-hash hook: this scene is tests/core/bvh.rs's, whose CPU
    // images (BVH = brute force, bit for bit) are checked there.
    let c = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render");
    glint_test_support::render::assert_all_finite(&c.image, "CPU render");
    let g = render(tracer, &flat, Accel::Bvh);
    let e = compare_images(&c.image, &g.image);
    eprintln!(
        "10k sphere: GPU BVH vs CPU FLIP {:.5} p99 {:.2e} mismatch {:.3} % status {:#x}",
        e.flip_mean,
        e.p99_abs_same_hit,
        100.0 * e.first_hit_mismatch,
        g.status
    );
    assert_eq!(g.status, 0, "status word");
    assert!(
        e.flip_mean <= FLIP_MEAN_MAX && e.p99_abs_same_hit <= P99_MAX && e.first_hit_mismatch <= MISMATCH_MAX,
        "{e:?}"
    );
}

#[test]
fn beyond_the_brute_force_limit_only_the_bvh_renders() {
    let tracer = gpu_or_skip!();
    let flat = mesh_scene(32, 24, uv_sphere(130, [0.0, 0.1, 0.0], 1.0)).flat();
    assert!(flat.triangles.len() > 65_535, "{} triangles", flat.triangles.len());
    let brute = tracer.render(&flat, &GpuOptions { accel: Accel::None, ..GpuOptions::default() });
    let message = brute.expect_err("brute force is limited to 65,535 triangles").to_string();
    assert!(message.contains("GPU_PRIMITIVE_LIMIT") && message.contains("--accel bvh"), "{message}");
    let g = render(tracer, &flat, Accel::Bvh);
    assert_eq!(g.status, 0, "status word");
    let c = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render");
    let e = compare_images(&c.image, &g.image);
    eprintln!("{} triangles through the BVH: {e:?}", flat.triangles.len());
    assert!(
        e.flip_mean <= FLIP_MEAN_MAX && e.p99_abs_same_hit <= P99_MAX && e.first_hit_mismatch <= MISMATCH_MAX,
        "{e:?}"
    );
}

/// wgpu's own limit on one storage binding, which lavapipe and typical GPUs also report.
const BINDING_LIMIT: u64 = 128 << 20;

#[test]
fn four_million_triangles_fit_the_128_mib_binding_and_render() {
    let tracer = gpu_or_skip!();
    let desc = glint_test_support::scene::large_mesh_desc(16, 12, uv_sphere(1000, [0.0, 0.1, 0.0], 1.0));
    let flat = FlatScene::build(&desc, &desc.render);
    assert!(flat.triangles.len() >= 3_990_000, "{} triangles", flat.triangles.len());
    // Every buffer the upload checks against the device's limits: lavapipe's may be larger.
    let sizes = glint_gpu::buffers::storage_sizes(&flat);
    let per_triangle = sizes.iter().map(|(_, b)| b).sum::<u64>() / flat.triangles.len() as u64;
    eprintln!("{} triangles: {sizes:?} bytes, {per_triangle} bytes per triangle", flat.triangles.len());
    for (what, bytes) in sizes {
        assert!(bytes < BINDING_LIMIT, "{what}: {bytes} bytes do not fit one 128 MiB binding");
    }
    let g = render(tracer, &flat, Accel::Bvh);
    assert_eq!(g.status, 0, "status word");
    let c = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render");
    let e = compare_images(&c.image, &g.image);
    eprintln!("4M triangles, GPU against CPU: {e:?}");
    assert!(e.first_hit_mismatch <= 0.05 && e.flip_mean <= 0.02, "{e:?}");
}

#[test]
fn a_buffer_beyond_the_binding_limit_is_an_error_naming_it() {
    gpu_or_skip!();
    // A device that binds at most 1 MiB per storage buffer, and 60,000 triangles (1.2 MB).
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(
        instance.request_adapter(&wgpu::RequestAdapterOptions { force_fallback_adapter: false, ..Default::default() }),
    )
    .expect("an adapter (the shared GPU tracer found one)");
    let limits = wgpu::Limits { max_storage_buffer_binding_size: 1 << 20, ..adapter.limits() };
    let (device, queue) = pollster::block_on(
        adapter.request_device(&wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() }),
    )
    .expect("a device with lower limits");
    let tracer = glint_gpu::GpuTracer::new(glint_gpu::GpuContext::from_device(device, queue, &adapter.get_info()));
    let flat = mesh_scene(8, 6, uv_sphere(123, [0.0, 0.1, 0.0], 1.0)).flat();
    assert!(size_of_val(&flat.triangles[..]) > 1 << 20);
    let message = tracer.render(&flat, &GpuOptions::default()).expect_err("does not fit").to_string();
    assert!(
        message.contains("the triangle buffer") && message.contains("max_storage_buffer_binding_size"),
        "{message}"
    );
}

#[test]
fn whitted_bumpy_at_depth_5_raises_no_status_flag() {
    let tracer = gpu_or_skip!();
    // The full million triangles: the loop budget is per group of invocations, so a small
    // image exercises it (neighbouring pixels of a smaller image are farther apart, and their
    // lanes' walks share less).
    for name in ["bumpy", "bumpy-glass"] {
        let loaded = glint_io::load_scene(name).expect("built-in scene");
        let mut settings = loaded.desc.render.clone();
        (settings.width, settings.height, settings.max_depth, settings.bailout) = (96, 54, 5, 0.0);
        let flat = FlatScene::build(&loaded.desc, &settings);
        assert!(flat.triangles.len() > 990_000, "{name}: {} triangles", flat.triangles.len());
        let g = render(tracer, &flat, Accel::Bvh);
        assert_eq!(g.status, 0, "{name}: status word");
        let c = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render");
        let e = compare_images(&c.image, &g.image);
        eprintln!("{name}, depth 5: {e:?}");
        assert!(e.flip_mean <= FLIP_MEAN_MAX && e.first_hit_mismatch <= MISMATCH_MAX, "{name}: {e:?}");
    }
}

/// `bumpy-glass` with its own depth (6) and bailout: refraction rays inside the glass walk
/// the sphere's tree at every level. Before each end of the slab test's interval had its own
/// margin, such a ray (t_max = FAR until its first hit) entered every box behind its origin
/// too, and at 320×180 lavapipe cut the loops (status 0x5).
#[test]
fn bumpy_glass_at_its_own_depth_stays_within_the_loop_budget() {
    let tracer = gpu_or_skip!();
    let loaded = glint_io::load_scene("bumpy-glass").expect("built-in scene");
    let mut settings = loaded.desc.render.clone();
    assert_eq!(settings.max_depth, 6, "the scene's own depth");
    (settings.width, settings.height) = (320, 180);
    let flat = FlatScene::build(&loaded.desc, &settings);
    let g = render(tracer, &flat, Accel::Bvh);
    assert_eq!(g.status, 0, "status word");
    assert!(g.image.pixels.iter().all(|p| p.is_finite()), "a non-finite pixel");
}

#[test]
fn a_far_small_triangle_does_not_pad_every_box_of_a_detailed_mesh() {
    // The GPU padded every box by 1e-5 of the whole scene's reach: one triangle 1e5 away padded
    // the boxes of a sphere 2 wide by 1, the walk culled nothing, and lavapipe's loop budget
    // ran out (status 0x4; a tester's engine 0.3 wide beside a triangle 3e3 away did the same).
    let tracer = gpu_or_skip!();
    let far = [[1e5, 0.0, 0.0], [1e5 + 0.01, 0.0, 0.0], [1e5, 0.01, 0.0]];
    let flat = mesh_scene(64, 48, uv_sphere(50, [0.0, 0.1, 0.0], 1.0)).mesh(&far, &[[0, 1, 2]], None, "clay").flat();
    let g = render(tracer, &flat, Accel::Bvh);
    assert_eq!(g.status, 0, "status word");
    let c = render_cpu(&flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render");
    let e = compare_images(&c.image, &g.image);
    assert!(
        e.flip_mean <= FLIP_MEAN_MAX && e.p99_abs_same_hit <= P99_MAX && e.first_hit_mismatch <= MISMATCH_MAX,
        "{e:?}"
    );
}
