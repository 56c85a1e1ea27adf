//! Every built-in scene, GPU against the CPU f64 reference.
//!
//! Thresholds, with what was measured on lavapipe (LLVM 15, 256 bits) at 160×120, depth 5:
//! - FLIP mean ≤ 0.005: measured 0.00000–0.00027 (whitted). FLIP is perceptual; 0.005 is far
//!   below a visible difference yet catches a wrong term on a few percent of the pixels.
//! - 99th percentile |GPU − CPU| on pixels whose first hit agrees ≤ 1/255 (one 8-bit step):
//!   measured 5e-7 … 2.7e-5, the f32 rounding of a few dozen operations per ray tree.
//! - first-hit mismatch ≤ 0.5 % of the pixels: measured 0 %. Only silhouettes and exact ties
//!   may differ; a systematic error (a wrong intersection) shows as a whole region.
//! - the status word (loop bound, stack overflow) stays 0 on every built-in scene.

use glint_core::FlatScene;
use glint_io::{BUILTIN_SCENES, load_scene};
use glint_scene::{EpsilonMode, Fresnel, GlobalAttenuation, RenderSettings, SceneDesc, SpecularModel};

use super::support::{compare_and_keep, cpu, gpu_or_skip, gpu_render, log_errors, within_parity, write_failure_images};

/// Renders every built-in scene file (a generated scene's hits are held against the CPU's by
/// tests/gpu/raycast.rs) at 160×120, depth 5, with each of `spps`, on both tracers after `setup`
/// changed its description and settings, and returns those outside parity. The same ray tree
/// means the same rays, up to rare f32 decisions at a bailout or a silhouette: within 0.1 %.
fn parity_failures(
    tracer: &glint_gpu::GpuTracer,
    label: &str,
    spps: &[u32],
    setup: impl Fn(&mut SceneDesc, &mut RenderSettings),
) -> Vec<String> {
    let mut failures = Vec::new();
    for scene in BUILTIN_SCENES.iter().filter(|b| !b.is_generated()) {
        for &spp in spps {
            let mut desc = load_scene(scene.name).expect("built-in scene").desc;
            let mut s = desc.render.clone();
            (s.width, s.height, s.spp, s.max_depth) = (160, 120, spp, 5);
            setup(&mut desc, &mut s);
            let flat = FlatScene::build(&desc, &s);
            let c = cpu(&flat);
            let g = gpu_render(tracer, &flat, true);
            let name = format!("{}-{label}{spp}", scene.name);
            let (e, base) = compare_and_keep("parity", &name, &c, &g);
            log_errors(&name, &e, g.status);
            let (rc, rg) = (c.counts.total() as f64, g.counts.total() as f64);
            if !(within_parity(&e, g.status) && (rc - rg).abs() <= 1e-3 * rc) {
                write_failure_images(&base, &c, &g);
                failures.push(format!("{name} (rays: CPU {rc}, GPU {rg})"));
            }
        }
    }
    failures
}

#[test]
fn builtin_scenes_match_the_cpu_reference() {
    let tracer = gpu_or_skip!();
    let failures = parity_failures(tracer, "spp", &[1, 4], |_, _| {});
    assert!(failures.is_empty(), "GPU/CPU parity failed for {failures:?} (images in target/tmp/gpu-tests/parity)");
}

/// `skip_convex` on the GPU against the CPU, every built-in scene (spheres seen and refracted
/// through from both sides, planes, meshes): the same thresholds as the default strategy's.
#[test]
fn builtin_scenes_match_the_cpu_reference_under_skip_convex() {
    let tracer = gpu_or_skip!();
    let failures = parity_failures(tracer, "skip-convex-spp", &[1], |_, s| s.epsilon_mode = EpsilonMode::SkipConvex);
    assert!(failures.is_empty(), "GPU/CPU parity failed for {failures:?} (images in target/tmp/gpu-tests/parity)");
}

/// The world's global attenuation of reflected and transmitted terms, GPU against CPU on every
/// built-in scene (mirrors and glass at several distances), at the default thresholds.
#[test]
fn builtin_scenes_match_the_cpu_reference_with_global_attenuation() {
    let tracer = gpu_or_skip!();
    let failures = parity_failures(tracer, "global-attenuation-spp", &[1], |d, _| {
        d.world.global_attenuation = GlobalAttenuation { c: 0.5, l: 0.1, q: 0.02 };
    });
    assert!(failures.is_empty(), "GPU/CPU parity failed for {failures:?} (images in target/tmp/gpu-tests/parity)");
}

/// Every material of every built-in scene forced to Cook–Torrance (m = 0.2, the exact Fresnel
/// factor on every other material and Schlick's on the rest), at the default thresholds.
#[test]
fn builtin_scenes_match_the_cpu_reference_with_cook_torrance() {
    let tracer = gpu_or_skip!();
    let failures = parity_failures(tracer, "cook-torrance-spp", &[1], |d, _| {
        for (i, m) in d.materials.values_mut().enumerate() {
            m.specular_model = SpecularModel::CookTorrance;
            m.roughness = 0.2;
            m.fresnel = Fresnel::ALL[i % 2];
        }
    });
    assert!(failures.is_empty(), "GPU/CPU parity failed for {failures:?} (images in target/tmp/gpu-tests/parity)");
}

/// Coefficients written as 8-bit fractions at the default bailout (1/255): the path weight of
/// k_r = 51/255 and then 5/255 is 1/255 exactly; f64's product of the stored f32 values fell
/// just below f32's 1/255 and the GPU's f32 product rounded onto it, so the GPU traced a
/// generation the CPU cut (576 rays against 384, every pixel 3.9e-3 apart; a stiff-cases
/// tester). Both tracers now form the weight in f32 and cut alike, for each pair of such k.
#[test]
fn a_path_weight_at_the_bailout_is_cut_or_traced_alike() {
    let tracer = gpu_or_skip!();
    for (front, back) in [(51.0, 5.0), (3.0, 85.0), (15.0, 17.0)] {
        let text = format!(
            "[render]\nwidth = 16\nheight = 12\nmax_depth = 4\n[camera]\nposition = [0.0, 0.0, 0.0]\n\
             look_at = [0.0, 0.0, 1.0]\nfov_y = 20.0\n[world]\nambient = 0.0\n\
             [materials.a]\nka = 0.0\nkd = 0.0\nkr = {:?}\nemission = 1.0\n\
             [materials.b]\nka = 0.0\nkd = 0.0\nkr = {:?}\nemission = 1.0\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, -1.0]\nmaterial = \"a\"\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, -1.0]\nnormal = [0.0, 0.0, 1.0]\nmaterial = \"b\"\n",
            front / 255.0,
            back / 255.0
        );
        let flat = glint_test_support::scene::flat_from_toml(&text);
        let (c, g) = (cpu(&flat), gpu_render(tracer, &flat, true));
        assert_eq!(
            (c.counts.reflection, c.counts.bailout_saved),
            (g.counts.reflection, g.counts.bailout_saved),
            "k_r = {front}/255 then {back}/255"
        );
        let e = glint_core::compare::compare_images(&c.image, &g.image);
        assert!(e.max_abs < 1e-6, "k_r = {front}/255 then {back}/255: {e:?}");
    }
}
