//! χ² tests of every sampling routine of `glint_core::cpu::sample` and of the lobes of
//! `glint_core::cpu::bsdf` against the density it claims (Nori's warp tests): 10⁶ samples each into a grid over the unit square. The family of
//! the module's χ² runs rejects a correct routine with probability 0.01 (Šidák's correction, as
//! Nori's warp test: each run passes at p > 1 − 0.99^(1/RUNS)). A test of the test: a routine
//! held against a slightly wrong density fails by far.

use glam::{DVec2, DVec3};
use glint_core::cpu::bsdf::{
    blinn_pdf, cook_torrance_pdf, phong_pdf, sample_blinn, sample_cook_torrance, sample_phong,
};
use glint_core::cpu::sample::*;
use glint_test_support::chi2::{Chi2, chi2_test, ln_gamma, sphere_to_square, square_density, upper_gamma_regularized};

const SAMPLES: u32 = 1_000_000;
/// Cells in cos θ and in φ: 0.1 by π/20.
const CELLS: (usize, usize) = (20, 40);

fn directions(seed: u32, sample: impl Fn(DVec2) -> DVec3, pdf: impl Fn(DVec3) -> f64) -> Chi2 {
    chi2_test(CELLS, SAMPLES, seed, |u| sphere_to_square(sample(u)), square_density(pdf))
}

/// The χ² runs of this module that must pass: cosine, three power cosines, Phong, Blinn–Phong,
/// two Cook–Torrance, the cone, the sphere and the triangle.
const RUNS: i32 = 11;

fn assert_passes(name: &str, r: Chi2) {
    let level = 1.0 - 0.99_f64.powf(1.0 / f64::from(RUNS));
    assert!(
        r.p_value > level,
        "{name}: χ² = {:.1} on {} degrees of freedom, p = {:.2e} (the level: {level:.2e})",
        r.statistic,
        r.dof,
        r.p_value
    );
}

/// The viewing direction of the reflection lobes: 35° from the normal.
fn outgoing() -> DVec3 {
    let a = 35f64.to_radians();
    DVec3::new(a.sin(), 0.0, a.cos())
}

#[test]
fn the_chi2_tail_is_the_published_one() {
    assert!((ln_gamma(5.0) - 24f64.ln()).abs() < 1e-13);
    assert!((ln_gamma(0.5) - std::f64::consts::PI.sqrt().ln()).abs() < 1e-13);
    // Q(1, x) = e^−x; the 5 % points of χ² at 10 and 100 degrees of freedom (tables).
    assert!((upper_gamma_regularized(1.0, 2.5) - (-2.5f64).exp()).abs() < 1e-14);
    assert!((upper_gamma_regularized(5.0, 18.307 / 2.0) - 0.05).abs() < 1e-4);
    assert!((upper_gamma_regularized(50.0, 124.342 / 2.0) - 0.05).abs() < 1e-4);
}

#[test]
fn cosine_hemisphere_follows_cos_over_pi() {
    assert_passes("cosine hemisphere", directions(1, cosine_hemisphere, |d| cosine_hemisphere_pdf(d.z)));
}

#[test]
fn a_wrong_density_is_caught() {
    // The cosine lobe against cos^1.2 (normalised): 3 % off at most anywhere.
    let r = directions(1, cosine_hemisphere, |d| power_cosine_pdf(d.z, 1.2));
    assert!(r.p_value < 1e-6, "χ² = {:.1}, p = {:.2e}", r.statistic, r.p_value);
}

#[test]
fn power_cosine_follows_its_density() {
    for (seed, n) in [(2, 1.0), (3, 12.0), (4, 80.0)] {
        assert_passes(
            &format!("power cosine n = {n}"),
            directions(seed, |u| power_cosine(u, n), |d| power_cosine_pdf(d.z, n)),
        );
    }
}

#[test]
fn phong_lobe_follows_its_density() {
    let o = outgoing();
    // n = 0 is Lambert's lobe, drawn as Lambert's.
    for (seed, n) in [(5, 20.0), (12, 0.0)] {
        let r = directions(seed, |u| sample_phong(o, u, n), |d| phong_pdf(o, d, n));
        assert_passes(&format!("Phong lobe n = {n}"), r);
    }
}

#[test]
fn blinn_phong_lobe_follows_its_density() {
    let o = outgoing();
    for (seed, n) in [(6, 20.0), (13, 0.0)] {
        let r = directions(seed, |u| sample_blinn(o, u, n), |d| blinn_pdf(o, d, n));
        assert_passes(&format!("Blinn–Phong lobe n = {n}"), r);
    }
}

#[test]
fn cook_torrance_lobe_follows_its_density() {
    let o = outgoing();
    for (seed, m) in [(7, 0.15), (8, 0.3)] {
        let r = directions(seed, |u| sample_cook_torrance(o, u, m), |d| cook_torrance_pdf(o, d, m));
        assert_passes(&format!("Cook–Torrance lobe m = {m}"), r);
    }
}

#[test]
fn a_sphere_lights_cone_is_uniform() {
    // 1 − cos θ_max = 0.3 puts the cone's rim on a cell boundary (cos θ = 0.7).
    let versin = 0.3;
    let result =
        directions(9, |u| uniform_cone(u, versin), |d| if 1.0 - d.z < versin { uniform_cone_pdf(versin) } else { 0.0 });
    assert_passes("sphere light cone", result);
}

#[test]
fn uniform_sphere_is_uniform() {
    assert_passes("uniform sphere", directions(10, uniform_sphere, |_| uniform_sphere_pdf()));
}

#[test]
fn triangle_samples_are_uniform_in_area() {
    // Barycentrics (b, c) as (s, t) = (b + c, c / (b + c)): the area element is s ds dt, so a
    // uniform point has density 2s on the square, with no edge inside it.
    let result = chi2_test(
        (32, 32),
        SAMPLES,
        11,
        |u| {
            let b = uniform_triangle(u);
            let s = b.x + b.y;
            if s > 0.0 { DVec2::new(s, b.y / s) } else { DVec2::ZERO }
        },
        |p| 2.0 * p.x,
    );
    assert_passes("uniform triangle", result);
}
