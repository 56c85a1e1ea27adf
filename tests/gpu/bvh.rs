//! The GPU BVH (`Accel::Bvh`, the default) against GPU brute force (`Accel::None`) on
//! generated meshes small enough for brute force to stay within lavapipe's loop budget, and
//! against the CPU reference on meshes brute force cannot walk on lavapipe (10k triangles).
//! The built-in scenes run through the BVH in parity.rs. Thresholds are parity.rs's.

use std::f64::consts::PI;

use glint_core::compare::compare_images;
use glint_core::{Accel, CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_gpu::GpuOptions;
use glint_test_support::scene::SceneText;

use super::support::gpu_or_skip;
use crate::gpu::gpu_render_with;

const Y: [f64; 3] = [0.0, 1.0, 0.0];
const FLIP_MEAN_MAX: f64 = 0.005;
const P99_MAX: f64 = 1.0 / 255.0;
const MISMATCH_MAX: f64 = 0.005;

/// A UV sphere of 4·n² triangles (rings θ = π·i/n, segments φ = 2π·k/(2n)), radius `r` around
/// `c`, with a small bump so that not every triangle is a plain facet.
fn uv_sphere(n: u32, c: [f64; 3], r: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let m = 2 * n;
    let mut v = Vec::new();
    for i in 0..=n {
        let th = PI * f64::from(i) / f64::from(n);
        for k in 0..=m {
            let ph = 2.0 * PI * f64::from(k) / f64::from(m);
            let rr = r * (1.0 + 0.05 * (7.0 * th).sin() * (5.0 * ph).sin());
            v.push([c[0] + rr * th.sin() * ph.cos(), c[1] + rr * th.cos(), c[2] + rr * th.sin() * ph.sin()]);
        }
    }
    let mut t = Vec::new();
    for i in 0..n {
        for k in 0..m {
            let a = i * (m + 1) + k;
            let (b, cc) = (a + 1, a + m + 1);
            t.push([a, cc, b]);
            t.push([b, cc, cc + 1]);
        }
    }
    (v, t)
}

/// A lit scene with a ground plane, a mirror sphere and one mesh.
fn mesh_scene(w: u32, h: u32, mesh: (Vec<[f64; 3]>, Vec<[u32; 3]>)) -> SceneText {
    SceneText::new(w, h, "max_depth = 2", [0.3, 1.1, -3.2], [0.0, 0.2, 0.0], Y, 45.0)
        .world([0.1; 3], [0.2, 0.3, 0.4])
        .material("ground", "ka = 0.2\nkd = 0.6\nks = 0.2\nchecker = { kd = [0.2, 0.2, 0.2], size = 0.5 }")
        .material("clay", "ka = 0.2\nkd = [0.7, 0.5, 0.3]\nks = 0.4\nshininess = 20.0")
        .material("mirror", "ka = 0.0\nkd = 0.1\nks = 0.3\nkr = 0.6")
        .light("point", "position = [-2.0, 4.0, -3.0]\ndiffuse = 0.8\nspecular = 0.6")
        .light("directional", "direction = [0.3, -1.0, 0.2]\ndiffuse = 0.3\nspecular = 0.2")
        .plane([0.0, -1.2, 0.0], Y, "ground")
        .sphere([1.3, -0.6, 0.6], 0.6, "mirror")
        .mesh(&mesh.0, &mesh.1, None, "clay")
}

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
