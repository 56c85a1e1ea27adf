//! CPU twin of `shaders/bsdf.wgsl`: the seed's glossy terms as BRDFs, for the path tracer, each
//! with the sampling routine that draws its lobe and that routine's density.
//!
//! Directions are local (z along the shading normal) and both point away from the surface: `wo`
//! towards the viewer, `wi` towards the light. Each BRDF is per unit k (the caller multiplies by
//! k_d or k_s) and 0 unless both directions are above the surface.
//!
//! The units are the seed's: a point light of intensity I gives the irradiance π·I·(N·L), so
//! that k_d/π reflects exactly Whitted's I·k_d·(N·L). The seed's specular terms are not BRDFs
//! (`spec_j` has no 1/(N·L)); these are their normalised forms (docs/scene-format.md gives each
//! factor between the two).

use std::f64::consts::FRAC_1_PI;

use glam::{DVec2, DVec3};

use super::sample::{
    beckmann_normal, beckmann_normal_pdf, cosine_hemisphere, cosine_hemisphere_pdf, power_cosine, power_cosine_pdf,
    reflect_about, reflected_pdf, to_world,
};
use super::shade::{beckmann_distribution, fresnel_exact, fresnel_schlick, safe_pow};
use glint_scene::{Fresnel, SpecularModel};
use glint_types::MaterialTags;
use glint_types::layout::GpuMaterial;

/// The half vector of `wo` and `wi`, if they are not opposite.
fn half_vector(wo: DVec3, wi: DVec3) -> Option<DVec3> {
    let h = wo + wi;
    let len = h.length();
    (len > 1e-12).then(|| h / len)
}

/// Lambert's BRDF per unit k_d: 1/π above the surface.
pub fn lambert_brdf(wo: DVec3, wi: DVec3) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 { 0.0 } else { FRAC_1_PI }
}

/// The factor that gives Blinn–Phong's lobe (N·H)^n a directional albedo of exactly 1 at normal
/// incidence (where it is largest): 1 / (2π ∫₀¹ ((1 + c)/2)^(n/2) c dc), in closed form with
/// k = n/2: the integral is 4(1 − 2^−(k+2))/(k + 2) − 2(1 − 2^−(k+1))/(k + 1). At n = 0 it is 1/π,
/// Lambert's. (The common (n + 8)/(8π) overshoots by up to 7.5 %, at n = 8.)
pub fn blinn_normalisation(exponent: f64) -> f64 {
    let k = 0.5 * exponent;
    let integral = 4.0 * (1.0 - (-(k + 2.0)).exp2()) / (k + 2.0) - 2.0 * (1.0 - (-(k + 1.0)).exp2()) / (k + 1.0);
    0.5 * FRAC_1_PI / integral
}

/// Blinn–Phong normalised per unit k_s: `blinn_normalisation(n)` · (N·H)^n.
pub fn blinn_brdf(wo: DVec3, wi: DVec3, exponent: f64) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    match half_vector(wo, wi) {
        Some(h) => blinn_normalisation(exponent) * safe_pow(h.z, exponent),
        None => 0.0,
    }
}

/// Lafortune and Willems' normalised Phong per unit k_s: (n + 2)/(2π) (R·wo)^n, R the mirror
/// image of `wi` (albedo exactly 1 at normal incidence).
pub fn phong_brdf(wo: DVec3, wi: DVec3, exponent: f64) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let r = reflect_about(wi, DVec3::Z);
    (exponent + 2.0) * 0.5 * FRAC_1_PI * safe_pow(r.dot(wo), exponent)
}

/// Cook and Torrance's microfacet BRDF normalised as Walter et al. (EGSR 2007) do, per unit k_s:
/// F·D·G / (4π (N·L)(N·V)) with the paper's D (shade.rs's `beckmann_distribution`, which
/// integrates to π over the projected hemisphere). The paper's own reflectance, F·D·G /
/// (π (N·L)(N·V)), is 4× this and returns up to 4× the light it receives, which a path meets
/// bounce after bounce; 4π·(N·L) times this is the seed's Cook–Torrance `spec_j`.
pub fn cook_torrance_brdf(wo: DVec3, wi: DVec3, m: f64, eta: f64, fresnel: Fresnel) -> f64 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let Some(h) = half_vector(wo, wi) else { return 0.0 };
    let o_dot_h = wo.dot(h);
    if h.z <= 0.0 || o_dot_h <= 0.0 {
        return 0.0;
    }
    let d = beckmann_distribution(m, h.z, h.x * h.x + h.y * h.y);
    let f = match fresnel {
        Fresnel::Exact => fresnel_exact(eta, o_dot_h),
        Fresnel::Schlick => fresnel_schlick(eta, o_dot_h),
    };
    let g = (2.0 * h.z * wo.z / o_dot_h).min(2.0 * h.z * wi.z / o_dot_h).min(1.0);
    f * d * g * 0.25 * FRAC_1_PI / (wi.z * wo.z)
}

/// A direction from Blinn–Phong's lobe: `wo` mirrored about a half vector drawn ∝ cos^n θ_h.
/// At n = 0 the lobe is C(0) = 1/π, Lambert's, drawn as Lambert's: mirrored about uniform half
/// vectors its weights spread (a white sphere under a white sky: pixels 0.85–1.13 at 2048
/// paths, where Lambert's are all exactly 1).
pub fn sample_blinn(wo: DVec3, u: DVec2, exponent: f64) -> DVec3 {
    if exponent == 0.0 {
        return cosine_hemisphere(u);
    }
    reflect_about(wo, power_cosine(u, exponent))
}

/// The density of `sample_blinn` at `wi`.
pub fn blinn_pdf(wo: DVec3, wi: DVec3, exponent: f64) -> f64 {
    if exponent == 0.0 {
        return cosine_hemisphere_pdf(wi.z);
    }
    match half_vector(wo, wi) {
        Some(h) => reflected_pdf(power_cosine_pdf(h.z, exponent), wo.dot(h)),
        None => 0.0,
    }
}

/// A direction from Phong's lobe: ∝ cos^n about the mirror image of `wo`. At n = 0 the lobe is
/// (R·wo)⁰ = 1 wherever both directions are above the surface (x⁰ = 1, as Whitted's term has
/// it): Lambert's lobe, drawn as Lambert's, since a cone about R would miss the directions
/// with R·wi < 0 (a furnace lost 12–29 % of its light).
pub fn sample_phong(wo: DVec3, u: DVec2, exponent: f64) -> DVec3 {
    if exponent == 0.0 {
        return cosine_hemisphere(u);
    }
    to_world(reflect_about(wo, DVec3::Z), power_cosine(u, exponent))
}

/// The density of `sample_phong` at `wi`.
pub fn phong_pdf(wo: DVec3, wi: DVec3, exponent: f64) -> f64 {
    if exponent == 0.0 {
        return cosine_hemisphere_pdf(wi.z);
    }
    power_cosine_pdf(reflect_about(wo, DVec3::Z).dot(wi), exponent)
}

/// A direction from the Cook–Torrance lobe: `wo` mirrored about a Beckmann microfacet normal.
pub fn sample_cook_torrance(wo: DVec3, u: DVec2, m: f64) -> DVec3 {
    reflect_about(wo, beckmann_normal(u, m))
}

/// The density of `sample_cook_torrance` at `wi`.
pub fn cook_torrance_pdf(wo: DVec3, wi: DVec3, m: f64) -> f64 {
    match half_vector(wo, wi) {
        Some(h) => reflected_pdf(beckmann_normal_pdf(h.z, m), wo.dot(h)),
        None => 0.0,
    }
}

/// The glossy lobe's BRDF per unit k_s, for the material's specular model.
pub fn glossy_brdf(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, wi: DVec3) -> f64 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => blinn_brdf(wo, wi, n),
        SpecularModel::Phong => phong_brdf(wo, wi, n),
        SpecularModel::CookTorrance => {
            cook_torrance_brdf(wo, wi, f64::from(mat.roughness), f64::from(mat.ior), tags.fresnel)
        }
    }
}

/// A direction from the glossy lobe.
pub fn sample_glossy(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, u: DVec2) -> DVec3 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => sample_blinn(wo, u, n),
        SpecularModel::Phong => sample_phong(wo, u, n),
        SpecularModel::CookTorrance => sample_cook_torrance(wo, u, f64::from(mat.roughness)),
    }
}

/// The density of `sample_glossy` at `wi`.
pub fn glossy_pdf(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, wi: DVec3) -> f64 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => blinn_pdf(wo, wi, n),
        SpecularModel::Phong => phong_pdf(wo, wi, n),
        SpecularModel::CookTorrance => cook_torrance_pdf(wo, wi, f64::from(mat.roughness)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
        let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
        DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
    }

    #[test]
    fn the_brdfs_are_reciprocal() {
        for (a, b) in [(dir(10.0, 0.0), dir(35.0, 170.0)), (dir(60.0, 20.0), dir(5.0, 250.0))] {
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(1.0);
            assert!(close(blinn_brdf(a, b, 20.0), blinn_brdf(b, a, 20.0)));
            assert!(close(phong_brdf(a, b, 20.0), phong_brdf(b, a, 20.0)));
            // F is evaluated at wo·h = wi·h, and G is symmetric.
            let (x, y) = (
                cook_torrance_brdf(a, b, 0.3, 1.5, Fresnel::Exact),
                cook_torrance_brdf(b, a, 0.3, 1.5, Fresnel::Exact),
            );
            assert!(close(x, y), "{x} {y}");
        }
    }

    /// ∫ f(wo, wi) cos θ_i dω_i by the midpoint rule on a 400 × 400 grid in (cos θ, φ).
    fn albedo(f: impl Fn(DVec3, DVec3) -> f64, wo: DVec3) -> f64 {
        const N: usize = 400;
        let mut sum = 0.0;
        for i in 0..N {
            let c = (i as f64 + 0.5) / N as f64;
            let s = (1.0 - c * c).sqrt();
            for j in 0..N {
                let phi = 2.0 * std::f64::consts::PI * (j as f64 + 0.5) / N as f64;
                sum += f(wo, DVec3::new(s * phi.cos(), s * phi.sin(), c)) * c;
            }
        }
        sum * 2.0 * std::f64::consts::PI / (N * N) as f64
    }

    #[test]
    fn the_normalised_lobes_reflect_all_at_normal_incidence_and_less_elsewhere() {
        let close = |a: f64, what: &str| assert!((a - 1.0).abs() < 2e-3, "{what}: albedo {a}");
        close(albedo(lambert_brdf, DVec3::Z), "Lambert");
        for n in [0.0, 1.0, 8.0, 40.0] {
            close(albedo(|o, i| blinn_brdf(o, i, n), DVec3::Z), &format!("Blinn n = {n}"));
            close(albedo(|o, i| phong_brdf(o, i, n), DVec3::Z), &format!("Phong n = {n}"));
            for theta in [30.0, 60.0, 80.0] {
                let wo = dir(theta, 0.0);
                for (name, a) in [
                    ("Blinn", albedo(|o, i| blinn_brdf(o, i, n), wo)),
                    ("Phong", albedo(|o, i| phong_brdf(o, i, n), wo)),
                ] {
                    assert!(a < 1.0 + 2e-3, "{name} n = {n} at {theta}°: albedo {a}");
                }
            }
        }
        assert!((blinn_normalisation(0.0) - FRAC_1_PI).abs() < 1e-15, "n = 0 is Lambert's lobe");
    }

    /// ∫ f cos θ_i dω_i estimated with the lobe's own samples (a 400 × 400 grid of u): where
    /// the sampler misses part of the lobe, this falls short of `albedo`.
    fn sampled_albedo(
        f: impl Fn(DVec3, DVec3) -> f64,
        sample: impl Fn(DVec3, DVec2) -> DVec3,
        pdf: impl Fn(DVec3, DVec3) -> f64,
        wo: DVec3,
    ) -> f64 {
        const N: usize = 400;
        let mut sum = 0.0;
        for i in 0..N {
            for j in 0..N {
                let u = DVec2::new((i as f64 + 0.5) / N as f64, (j as f64 + 0.5) / N as f64);
                let wi = sample(wo, u);
                let p = pdf(wo, wi);
                if wi.z > 0.0 && p > 0.0 {
                    sum += f(wo, wi) * wi.z / p;
                }
            }
        }
        sum / (N * N) as f64
    }

    #[test]
    fn each_sampler_reaches_all_of_its_lobe() {
        type Brdf = fn(DVec3, DVec3, f64) -> f64;
        type Sample = fn(DVec3, DVec2, f64) -> DVec3;
        let lobes: [(&str, Brdf, Sample, Brdf); 2] =
            [("Phong", phong_brdf, sample_phong, phong_pdf), ("Blinn", blinn_brdf, sample_blinn, blinn_pdf)];
        for (name, brdf, sample, pdf) in lobes {
            for n in [0.0, 1.0, 8.0] {
                for theta in [0.0, 45.0, 75.0] {
                    let wo = dir(theta, 30.0);
                    let exact = albedo(|o, i| brdf(o, i, n), wo);
                    let sampled = sampled_albedo(|o, i| brdf(o, i, n), |o, u| sample(o, u, n), |o, i| pdf(o, i, n), wo);
                    assert!(
                        (sampled - exact).abs() < 0.01 * exact,
                        "{name} n = {n} at {theta}°: {sampled} against {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn cook_torrance_reflects_at_most_what_it_receives() {
        // F = 1 everywhere (η → ∞): what is left is D·G, whose albedo is 1 less the V-grooves'
        // masking. The paper's normalisation gave about 4 here.
        for m in [0.1, 0.3, 0.6] {
            for theta in [0.0, 30.0, 60.0, 80.0] {
                let a = albedo(|o, i| cook_torrance_brdf(o, i, m, 1e9, Fresnel::Exact), dir(theta, 0.0));
                assert!(a < 1.0 + 2e-3, "m = {m} at {theta}°: albedo {a}");
                if theta == 0.0 {
                    assert!(a > 0.75, "m = {m} at normal incidence: albedo {a}");
                }
            }
        }
    }

    #[test]
    fn cook_torrance_times_four_pi_cos_is_the_seeds_term() {
        use glint_types::layout::GpuMaterial;
        let mut mat: GpuMaterial = bytemuck::Zeroable::zeroed();
        (mat.roughness, mat.ior) = (0.3, 1.5);
        for (wo, wi) in [(dir(10.0, 0.0), dir(35.0, 170.0)), (dir(60.0, 20.0), dir(25.0, 230.0))] {
            for fresnel in [Fresnel::Exact, Fresnel::Schlick] {
                // The material stores m in f32: the BRDF gets that value.
                let brdf = cook_torrance_brdf(wo, wi, f64::from(mat.roughness), 1.5, fresnel);
                let term = crate::cpu::shade::cook_torrance_term(&mat, fresnel, DVec3::Z, wi, wo, wi.z);
                let from_brdf = 4.0 * std::f64::consts::PI * wi.z * brdf;
                assert!((from_brdf - term).abs() < 1e-12 * term, "{from_brdf} against {term}");
            }
        }
    }

    #[test]
    fn nothing_is_reflected_from_below() {
        let (up, down) = (dir(20.0, 0.0), dir(120.0, 180.0));
        assert_eq!(lambert_brdf(up, down), 0.0);
        assert_eq!(blinn_brdf(down, up, 8.0), 0.0);
        assert_eq!(phong_brdf(up, down, 8.0), 0.0);
        assert_eq!(cook_torrance_brdf(up, down, 0.3, 1.5, Fresnel::Schlick), 0.0);
    }
}
