//! `epsilon_mode = "skip_convex"` on the CPU: a secondary ray does not test the primitive it
//! leaves, and a ray into a sphere finds its far side. Spheres and planes then need no ε: with
//! ε = 0 the image agrees with `nudge_normal`'s at ε = 1e-9 (origins moved off the surface, every
//! primitive tested: clean in f64, case 2's table) on every pixel whose rays both strategies trace
//! alike, with the same ray counts, while `tmin` at ε = 0 is covered in acne. `robust`, which
//! skips the primitive left too, is held against the same independent reference.

use glint_core::FlatScene;
use glint_scene::EpsilonMode;
use glint_types::layout::feature;

use crate::support::{SceneText, render};

const Y: [f64; 3] = [0.0, 1.0, 0.0];

/// A mirror-and-diffuse sphere, a glass sphere (refraction in and out, total internal
/// reflection inside) and a diffuse floor, all lit by a point light that casts shadows.
fn scene(mode: EpsilonMode, epsilon: f64) -> FlatScene {
    SceneText::new(
        48,
        36,
        &format!("max_depth = 4\nepsilon = {epsilon:?}\nepsilon_mode = \"{}\"\nbailout = 0.0", mode.name()),
        [0.3, 1.1, -4.0],
        [0.0, 0.3, 0.0],
        Y,
        40.0,
    )
    .world([0.1; 3], [0.2, 0.3, 0.5])
    .material("mirror", "ka = 0.1\nkd = 0.4\nks = 0.3\nkr = 0.5")
    .material("glass", "ka = 0.0\nkd = 0.05\nkt = 0.9\nkr = 0.05\nior = 1.5")
    .material("floor", "ka = 0.2\nkd = 0.7")
    .light("point", "position = [2.0, 4.0, -3.0]\ndiffuse = 1.0\nspecular = 1.0")
    .plane([0.0, -0.5, 0.0], Y, "floor")
    .sphere([-0.7, 0.3, 0.3], 0.8, "mirror")
    .sphere([0.8, 0.2, -0.4], 0.6, "glass")
    .flat()
}

/// Pixels whose values differ by more than `rel` relative.
fn differing(a: &FlatScene, b: &FlatScene, rel: f64) -> (usize, glint_core::CpuRender, glint_core::CpuRender) {
    let (ra, rb) = (render(a), render(b));
    let n = ra
        .image
        .pixels
        .iter()
        .zip(&rb.image.pixels)
        .filter(|(p, q)| (**p - **q).abs().max_element() > rel * p.abs().max_element().max(q.abs().max_element()))
        .count();
    (n, ra, rb)
}

#[test]
fn skip_convex_at_epsilon_zero_and_robust_match_a_strategy_that_skips_nothing() {
    let reference = scene(EpsilonMode::NudgeNormal, 1e-9);
    assert_eq!(reference.header.features & feature::SKIP_LEFT, 0, "the reference tests every primitive");
    for mode in [EpsilonMode::SkipConvex, EpsilonMode::Robust] {
        let skip = scene(mode, 0.0);
        assert_ne!(skip.header.features & feature::SKIP_LEFT, 0, "{}: the scene uses the skip", mode.name());
        let (n, s, r) = differing(&skip, &reference, 1e-6);
        let pixels = s.image.pixels.len();
        // Measured: 0 of 1728 differ by more than 1e-6 relative. A few may, where a ray passes a
        // silhouette or the critical angle within the strategies' origins.
        assert!(n * 200 <= pixels, "{}: {n} of {pixels} pixels differ by more than 1e-6 relative", mode.name());
        // The same rays: refraction rays inside the glass sphere find its far side (a ray that
        // skipped the sphere it entered would leave it without a second refraction).
        assert_eq!(s.counts, r.counts, "ray counts of {} and the reference", mode.name());
        assert!(s.counts.refraction > 100, "the glass sphere is refracted through: {:?}", s.counts);
    }
    // Otherwise the scene would not need any remedy: tmin at ε = 0 self-intersects.
    let (acne, _, _) = differing(&scene(EpsilonMode::Tmin, 0.0), &reference, 1e-3);
    let pixels = 48 * 36;
    assert!(acne * 10 > pixels, "tmin at ε = 0 differs from the reference on only {acne} of {pixels} pixels");
}
