//! CPU twin of `shaders/sample.wgsl`: the warps the path tracer draws directions and points
//! with, each beside its density, so that an estimator divides by exactly the density it drew
//! from (the χ² tests in tests/core/sampling.rs hold each pair together).
//!
//! Directions are in a local frame whose z is the axis of the lobe (the normal, a mirror
//! direction, the direction to a sphere's centre); `frame_x`/`frame_y` and `to_world` take them
//! out of it. Densities are per unit solid angle, and defined on the whole sphere: a lobe that
//! reaches below a surface keeps those directions, and the integrator gives them no weight.

use std::f64::consts::{FRAC_1_PI, FRAC_PI_4, PI};

use glam::{DVec2, DVec3};

/// The x axis of an orthonormal frame around the unit vector `n` (Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 2017): continuous everywhere but across n.z = 0, with no
/// division by a small number. (The sign of n.z as WGSL's `select` takes it: −0 counts as +.)
pub fn frame_x(n: DVec3) -> DVec3 {
    let sign = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x)
}

/// The y axis of the frame of `frame_x`: n × x.
pub fn frame_y(n: DVec3) -> DVec3 {
    n.cross(frame_x(n))
}

/// `local` (z along `n`) in world coordinates.
pub fn to_world(n: DVec3, local: DVec3) -> DVec3 {
    frame_x(n) * local.x + frame_y(n) * local.y + n * local.z
}

/// The direction at polar angle θ (given as sin θ and cos θ) from z and azimuth φ from x.
pub fn spherical_direction(sin_theta: f64, cos_theta: f64, phi: f64) -> DVec3 {
    DVec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), cos_theta)
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disk: area-preserving,
/// and it keeps neighbouring points neighbours.
pub fn concentric_disk(u: DVec2) -> DVec2 {
    let a = 2.0 * u - DVec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return DVec2::ZERO;
    }
    if a.x.abs() > a.y.abs() {
        let phi = FRAC_PI_4 * (a.y / a.x);
        a.x * DVec2::new(phi.cos(), phi.sin())
    } else {
        let phi = 2.0 * FRAC_PI_4 - FRAC_PI_4 * (a.x / a.y);
        a.y * DVec2::new(phi.cos(), phi.sin())
    }
}

/// A direction about z with density cos θ / π (Malley's method: the concentric disk lifted onto
/// the hemisphere). The Lambertian lobe's importance sample.
pub fn cosine_hemisphere(u: DVec2) -> DVec3 {
    let d = concentric_disk(u);
    let z = (1.0 - d.length_squared()).max(0.0).sqrt();
    DVec3::new(d.x, d.y, z)
}

/// The density of `cosine_hemisphere` at a direction of cos θ = `cos_theta`.
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// A direction about z with density (n + 1)/(2π) cos^n θ: the normalised Phong lobe about the
/// mirror direction, and the normalised Blinn–Phong lobe's half vector about the normal.
pub fn power_cosine(u: DVec2, exponent: f64) -> DVec3 {
    let cos_theta = (1.0 - u.x).powf(1.0 / (exponent + 1.0));
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y)
}

/// The density of `power_cosine` at cos θ = `cos_theta` (0 below the horizon).
pub fn power_cosine_pdf(cos_theta: f64, exponent: f64) -> f64 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    (exponent + 1.0) * 0.5 * FRAC_1_PI * cos_theta.powf(exponent)
}

/// A microfacet normal about z drawn from Beckmann's distribution of roughness `m` weighted by
/// cos θ_h: tan² θ_h = −m² ln(1 − u), the density `beckmann_normal_pdf`.
pub fn beckmann_normal(u: DVec2, m: f64) -> DVec3 {
    let tan2 = -m * m * (1.0 - u.x).ln();
    let cos_theta = 1.0 / (1.0 + tan2).sqrt();
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y)
}

/// D(h)·cos θ_h with the normalised Beckmann D = exp(−tan²θ/m²) / (π m² cos⁴θ): the density of
/// `beckmann_normal` (0 below the horizon).
pub fn beckmann_normal_pdf(cos_theta: f64, m: f64) -> f64 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    let cos2 = cos_theta * cos_theta;
    let tan2 = (1.0 - cos2).max(0.0) / cos2;
    (-tan2 / (m * m)).exp() * FRAC_1_PI / (m * m * cos2 * cos_theta)
}

/// The mirror image of `v` about the unit `h`: the incident direction whose half vector with `v`
/// is `h`.
pub fn reflect_about(v: DVec3, h: DVec3) -> DVec3 {
    2.0 * v.dot(h) * h - v
}

/// The density of a direction reflected about a half vector drawn with density `half_pdf`: the
/// Jacobian of the reflection, 1 / (4 |v·h|) (Walter et al. 2007). 0 where v·h is 0.
pub fn reflected_pdf(half_pdf: f64, v_dot_h: f64) -> f64 {
    if v_dot_h == 0.0 {
        return 0.0;
    }
    half_pdf / (4.0 * v_dot_h.abs())
}

/// 1 − cos θ_max of the cone a sphere of sin² θ_max = `sin2_max` (its radius² over its distance²)
/// fills, without the cancellation of 1 − √(1 − s) for a small, far sphere.
pub fn cone_versin(sin2_max: f64) -> f64 {
    sin2_max / (1.0 + (1.0 - sin2_max).max(0.0).sqrt())
}

/// A direction about z, uniform in the cone of 1 − cos θ_max = `versin_max`.
pub fn uniform_cone(u: DVec2, versin_max: f64) -> DVec3 {
    let versin = u.x * versin_max;
    let cos_theta = 1.0 - versin;
    // sin² = (1 − cos)(1 + cos), exact for small angles where 1 − cos² is not.
    let sin_theta = (versin * (2.0 - versin)).max(0.0).sqrt();
    spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y)
}

/// The density of `uniform_cone` inside its cone.
pub fn uniform_cone_pdf(versin_max: f64) -> f64 {
    1.0 / (2.0 * PI * versin_max)
}

/// A direction uniform on the whole sphere (a uniform environment's light sample).
pub fn uniform_sphere(u: DVec2) -> DVec3 {
    let z = 1.0 - 2.0 * u.x;
    spherical_direction((1.0 - z * z).max(0.0).sqrt(), z, 2.0 * PI * u.y)
}

/// The density of `uniform_sphere`.
pub fn uniform_sphere_pdf() -> f64 {
    0.25 * FRAC_1_PI
}

/// The barycentric weights (of vertices b and c) of a point uniform on a triangle's area
/// (Heitz, "A Low-Distortion Map Between Triangle and Square", 2019): the density 1/area.
pub fn uniform_triangle(u: DVec2) -> DVec2 {
    if u.y > u.x {
        let b0 = 0.5 * u.x;
        let b1 = u.y - b0;
        DVec2::new(b0, b1)
    } else {
        let b1 = 0.5 * u.y;
        let b0 = u.x - b1;
        DVec2::new(b0, b1)
    }
}

/// A density per unit area at a point at `distance` whose surface makes cos = `cos_at_light`
/// with the direction to it, as a density per unit solid angle there: d² / |cos|. 0 for a
/// surface seen edge on.
pub fn area_to_solid_angle(pdf_area: f64, distance: f64, cos_at_light: f64) -> f64 {
    if cos_at_light == 0.0 {
        return 0.0;
    }
    pdf_area * distance * distance / cos_at_light.abs()
}

/// The largest density whose square the power heuristic forms (twin of sample.wgsl's): f32's
/// square overflows at 1.8e19, which a small emitter's density reaches from far away (a sphere
/// 1e-4 across, 2e7 away along an infinite floor: 1e22 per steradian), and ∞/∞ is NaN.
pub const MAX_SQUARED_PDF: f64 = 1e18;

/// The power heuristic (β = 2) weight of a sample drawn with density `pdf` against one other
/// technique of density `other` (Veach 1997): the weights of the two add to 1. Beyond
/// `MAX_SQUARED_PDF`, from the ratio of the smaller density to the larger.
pub fn power_heuristic(pdf: f64, other: f64) -> f64 {
    if pdf.max(other) > MAX_SQUARED_PDF {
        let r = pdf.min(other) / pdf.max(other);
        let r2 = r * r;
        return if pdf >= other { 1.0 / (1.0 + r2) } else { r2 / (1.0 + r2) };
    }
    let (a, b) = (pdf * pdf, other * other);
    if a + b == 0.0 { 0.0 } else { a / (a + b) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_orthonormal_and_right_handed() {
        for n in [DVec3::Z, -DVec3::Z, DVec3::X, DVec3::new(0.3, -0.4, 0.5).normalize(), DVec3::new(1e-9, 0.0, -1.0)] {
            let n = n.normalize();
            let (x, y) = (frame_x(n), frame_y(n));
            assert!((x.length() - 1.0).abs() < 1e-12 && (y.length() - 1.0).abs() < 1e-12, "{n}");
            assert!(x.dot(n).abs() < 1e-12 && y.dot(n).abs() < 1e-12 && x.dot(y).abs() < 1e-12, "{n}");
            assert!((x.cross(y) - n).length() < 1e-12, "{n}");
            assert!((to_world(n, DVec3::Z) - n).length() < 1e-12);
        }
    }

    #[test]
    fn warps_give_unit_directions_on_the_right_side() {
        for i in 0..64 {
            let u = DVec2::new(f64::from(i % 8) / 8.0 + 0.01, f64::from(i / 8) / 8.0 + 0.02);
            for d in [cosine_hemisphere(u), power_cosine(u, 20.0), beckmann_normal(u, 0.3), uniform_cone(u, 0.1)] {
                assert!((d.length() - 1.0).abs() < 1e-12 && d.z >= 0.0, "{d}");
            }
            assert!((uniform_sphere(u).length() - 1.0).abs() < 1e-12);
            let b = uniform_triangle(u);
            assert!(b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0, "{b}");
        }
    }

    #[test]
    fn a_small_far_sphere_keeps_its_cone() {
        // A sphere of radius 1 at 1e5: sin² = 1e-10, where 1 − √(1 − s) in f64 keeps 6 digits.
        let v = cone_versin(1e-10);
        assert!((v - 5e-11).abs() < 1e-20, "{v}");
        assert!(uniform_cone(DVec2::new(1.0, 0.0), v).x > 0.0, "the cone's rim has its width");
    }

    #[test]
    fn power_heuristic_weights_add_to_one() {
        for (a, b) in [(1.0, 2.0), (0.3, 0.0), (5e-3, 7e2)] {
            assert!((power_heuristic(a, b) + power_heuristic(b, a) - 1.0).abs() < 1e-15);
        }
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        // Beyond f32's squares: from the ratio, still adding to 1.
        for (a, b) in [(1e22, 3.0), (9.5e21, 4e21), (2e30, 2e30), (1e19, 0.0)] {
            let (w, v) = (power_heuristic(a, b), power_heuristic(b, a));
            assert!(w.is_finite() && (w + v - 1.0).abs() < 1e-15, "{a}, {b}: {w} + {v}");
        }
        assert_eq!(power_heuristic(1e22, 0.0), 1.0);
        assert!((power_heuristic(1e22, 1e21) - 100.0 / 101.0).abs() < 1e-15);
        // The two forms agree where both hold: the squares' form just below the bound.
        assert!((power_heuristic(9e17, 3e17) - 9.0 / 10.0).abs() < 1e-15);
    }
}
