//! The ray-cast kernel of `glint bench rays` (shaders/raycast.wgsl, bvh.wgsl's closest_hit)
//! against the CPU's (cpu/raycast.rs) on a small bumpy scene, for both ray sets; and its
//! status check, which turns lavapipe's silent loop cut-off into an error.
//!
//! Thresholds, with what was measured on lavapipe (LLVM 15) at N = 30 (3,602 triangles):
//! - the same primitive (or the same miss) for ≥ 99.9 % of the rays: measured 100 % for both.
//!   Only exact ties and silhouettes that f32 rounding moves may differ.
//! - t within 1e-4 relative where the primitive is the same, for hits at t ≥ T_NEAR: measured
//!   5.2e-6 (primary) and 6.9e-6 (incoherent), the f32 rounding of a few dozen operations.
//!   Nearer hits (incoherent rays start anywhere, some a hair from a surface; at N = 20 one
//!   differed by 9.5e-4 relative) are held to 1e-4·T_NEAR absolute instead, measured 1.1e-7:
//!   there the f32 rounding of the origin (~2e-7 at |origin| ≈ 2) is most of t.

use glint_core::FlatScene;
use glint_core::cpu::TraceContext;
use glint_core::cpu::raycast::HitRecord;
use glint_core::cpu::raycast::cast_rays;
use glint_core::rays::{RaySet, compare_hits, hit_fraction, primary_rays};
use glint_gpu::GpuError;
use glint_gpu::raycast::RayCaster;
use glint_io::{LoadOptions, load_scene_with};
use glint_scene::{MeshDesc, ObjectDesc};
use glint_types::layout::STATUS_DRIVER_LOOP_CUTOFF;

use super::support::gpu_or_skip;

const SAME_PRIMITIVE_MIN: f64 = 0.999;
const T_REL_MAX: f64 = 1e-4;
const T_NEAR: f32 = 1e-2;

fn bumpy(n: u32) -> FlatScene {
    let loaded =
        load_scene_with("bumpy", &LoadOptions { resolution: Some(n), ..LoadOptions::default() }).expect("bumpy loads");
    FlatScene::build(&loaded.desc, &loaded.desc.render)
}

#[test]
fn gpu_hits_equal_the_cpu_hits_on_both_ray_sets() {
    let tracer = gpu_or_skip!();
    let ctx = tracer.context();
    let flat = bumpy(30);
    let caster = RayCaster::new(ctx, &flat).expect("the kernel compiles and the scene uploads");
    let cpu_ctx = TraceContext::new(&flat).expect("valid scene");
    for set in RaySet::ALL {
        let rays = set.rays();
        let cpu: Vec<HitRecord> = cast_rays(&cpu_ctx, &rays);
        let batch = caster.upload(ctx, &rays).expect("rays upload");
        caster.cast(ctx, &batch).expect("no status bit raised");
        let gpu = caster.hits(ctx, &batch).expect("hits read back");
        assert_eq!(gpu.len(), rays.len());
        let a = compare_hits(&gpu, &cpu);
        let (mut far_worst, mut near_worst) = (0.0f64, 0.0f64);
        for (g, c) in gpu.iter().zip(&cpu) {
            if (g.prim, g.index) == (c.prim, c.index) && c.is_hit() {
                let diff = (f64::from(g.t) - f64::from(c.t)).abs();
                if c.t >= T_NEAR {
                    far_worst = far_worst.max(diff / f64::from(c.t));
                } else {
                    near_worst = near_worst.max(diff);
                }
            }
        }
        let (fraction_cpu, fraction_gpu) = (hit_fraction(&cpu), hit_fraction(&gpu));
        eprintln!(
            "{}: {} of {} rays differ, hit fraction CPU {fraction_cpu:.4} GPU {fraction_gpu:.4}, \
             max rel t {far_worst:.2e} (t ≥ {T_NEAR}), max abs t {near_worst:.2e} (nearer)",
            set.name(),
            a.differing,
            a.rays
        );
        assert!(fraction_cpu > 0.05 && fraction_cpu < 0.95, "{}: a ray set that hits {fraction_cpu}", set.name());
        assert!(1.0 - a.differing_fraction() >= SAME_PRIMITIVE_MIN, "{}: {a:?}", set.name());
        assert!(far_worst <= T_REL_MAX, "{}: relative t difference {far_worst:e}", set.name());
        assert!(near_worst <= T_REL_MAX * f64::from(T_NEAR), "{}: near t difference {near_worst:e}", set.name());
    }
}

#[test]
fn a_traversal_cut_short_by_the_driver_is_an_error_not_a_fast_miss() {
    let tracer = gpu_or_skip!();
    let ctx = tracer.context();
    if !ctx.adapter.to_string().contains("llvmpipe") {
        eprintln!("not lavapipe ({}): no loop budget to run out of", ctx.adapter);
        return;
    }
    // 100,000 copies of one triangle: one BVH of coincident boxes, every leaf of which a ray
    // through the triangle visits (equal t: the tie rule keeps looking), about 150,000 loop
    // iterations against lavapipe's 65,535 per group of invocations.
    let loaded =
        load_scene_with("bumpy", &LoadOptions { resolution: Some(2), ..LoadOptions::default() }).expect("bumpy loads");
    let mut desc = loaded.desc;
    desc.objects = vec![ObjectDesc::Mesh(MeshDesc::new(
        vec![[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]; 100_000],
        "clay",
        "stack",
    ))];
    let flat = FlatScene::build(&desc, &desc.render);
    let caster = RayCaster::new(ctx, &flat).expect("the kernel compiles and the scene uploads");
    // A few rays through the middle of the triangle.
    let rays: Vec<_> = primary_rays(8, 8);
    let batch = caster.upload(ctx, &rays).expect("rays upload");
    match caster.cast(ctx, &batch) {
        Err(GpuError::RaycastStatus { status, messages }) => {
            assert!(status & STATUS_DRIVER_LOOP_CUTOFF != 0, "{status:#x}: {messages}");
            assert!(messages.contains("cut"), "{messages}");
        }
        other => panic!("expected the loop cut-off to be an error, got {other:?}"),
    }
}

#[test]
fn the_ray_caster_works_in_world_space_away_from_the_origin() {
    // The tracer rebases a scene on a frame near its camera; the ray caster's rays are records
    // in the scene's stored coordinates, so it must not. The scene, its camera and the rays
    // moved by 4096 along x: the scene is stored relative to its geometry (`storage_origin`),
    // the rays are moved into that frame (exact in f32: the shift and the origin are integers),
    // the tracer's frame differs from it (checked), and the caster's hits must not.
    const SHIFT: f64 = 4096.0;
    let tracer = gpu_or_skip!();
    let ctx = tracer.context();
    let loaded =
        load_scene_with("bumpy", &LoadOptions { resolution: Some(8), ..LoadOptions::default() }).expect("bumpy loads");
    let mut desc = loaded.desc;
    assert!(desc.objects.iter().all(|o| matches!(o, ObjectDesc::Mesh(_))), "bumpy is meshes only");
    glint_test_support::scene::translate(&mut desc, [SHIFT, 0.0, 0.0]);
    let flat = FlatScene::build(&desc, &desc.render);
    assert_ne!(flat.header.frame, glint_types::layout::WORLD_FRAME);
    assert_ne!(glint_core::rebase::camera_frame(&flat), flat.header.frame);
    // World to stored: + the shift, − the storage origin.
    let by: Vec<f64> = [SHIFT, 0.0, 0.0].iter().zip(&flat.header.frame).map(|(s, o)| s - f64::from(*o)).collect();
    let caster = RayCaster::new(ctx, &flat).expect("the kernel compiles and the scene uploads");
    let rays: Vec<_> = RaySet::Primary
        .rays()
        .into_iter()
        .map(|mut r| {
            for (c, by) in r.origin_t_min.iter_mut().zip(&by) {
                *c = (f64::from(*c) + by) as f32;
            }
            r
        })
        .collect();
    let cpu: Vec<HitRecord> = cast_rays(&TraceContext::new(&flat).expect("valid scene"), &rays);
    let batch = caster.upload(ctx, &rays).expect("rays upload");
    caster.cast(ctx, &batch).expect("no status bit raised");
    let a = compare_hits(&caster.hits(ctx, &batch).expect("hits read back"), &cpu);
    assert!(hit_fraction(&cpu) > 0.05, "the primary rays must hit the scene");
    assert!(1.0 - a.differing_fraction() >= SAME_PRIMITIVE_MIN, "{a:?}");
}
