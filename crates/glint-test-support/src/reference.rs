//! An independent re-derivation of the geometry and the lobes (camera rays, sphere and plane
//! hits, Blinn, Phong and Cook–Torrance) in f64, so that expected values never come from the tracer itself;
//! and comparisons with a relative tolerance.

use glam::DVec3;
use glint_core::cpu::shade::Breakdown;
use glint_core::{FlatScene, camera_eye, probe_pixel};

use crate::scene::w3;

/// The per-term breakdown of the centre sample of pixel (x, y) on the CPU, checked finite.
pub fn probe(flat: &FlatScene, x: u32, y: u32) -> Breakdown {
    let b = probe_pixel(flat, x, y, 0).expect("a built scene has valid tags");
    assert!(b.total.is_finite(), "probe ({x}, {y}) total {}", b.total);
    b
}

/// The camera ray through the centre of pixel (x, y) (y downwards), re-derived from the stored
/// camera vectors: direction ∝ forward + ndc_x·right + ndc_y·up with pixel centres at
/// (x + 0.5, y + 0.5) (the documented camera model), or for an orthographic camera along forward
/// from eye + ndc_x·right + ndc_y·up. Its origin is in world space (the stored camera's eye plus
/// the scene's storage origin, `SceneHeader::frame`), where the tests' closed forms are written.
pub fn primary_ray(flat: &FlatScene, x: u32, y: u32) -> (DVec3, DVec3) {
    let (w, h) = (f64::from(flat.header.width), f64::from(flat.header.height));
    let c = &flat.camera;
    let ndc_x = 2.0 * (f64::from(x) + 0.5) / w - 1.0;
    let ndc_y = 1.0 - 2.0 * (f64::from(y) + 0.5) / h;
    let across = ndc_x * w3(c.right) + ndc_y * w3(c.up);
    let eye = camera_eye(c) + flat.frame_origin();
    if c.is_orthographic() {
        return (eye + across, w3(c.forward).normalize());
    }
    (eye, (w3(c.forward) + ndc_x * w3(c.right) + ndc_y * w3(c.up)).normalize())
}

/// Nearest ray/sphere hit with t > 0 and its discriminant relative to r² (how far from the
/// silhouette the ray is), by the textbook quadratic for a unit direction.
pub fn sphere_hit(o: DVec3, d: DVec3, center: DVec3, radius: f64) -> Option<(f64, f64)> {
    let oc = o - center;
    let b = oc.dot(d);
    let c = oc.dot(oc) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let t = if -b - s > 0.0 { -b - s } else { -b + s };
    (t > 0.0).then_some((t, disc / (radius * radius)))
}

/// Ray/plane hit for the plane n·x = k.
pub fn plane_hit(o: DVec3, d: DVec3, n: DVec3, k: f64) -> Option<f64> {
    let t = (k - n.dot(o)) / n.dot(d);
    (t.is_finite() && t > 0.0).then_some(t)
}

/// Blinn: max(N·H, 0)^n with H = (L̂ + V)/|L̂ + V| (L̂: L normalised), 0 where N·L ≤ 0;
/// x^0 = 1.
pub fn blinn(n: DVec3, l: DVec3, v: DVec3, shininess: f64) -> f64 {
    if n.dot(l) <= 0.0 {
        return 0.0;
    }
    let h = (l.normalize() + v).normalize();
    pow0(n.dot(h).max(0.0), shininess)
}

/// Phong: max(R·V, 0)^n with R = 2(N·L)N − L, 0 where N·L ≤ 0; x^0 = 1.
pub fn phong(n: DVec3, l: DVec3, v: DVec3, shininess: f64) -> f64 {
    let ndl = n.dot(l);
    if ndl <= 0.0 {
        return 0.0;
    }
    let r = 2.0 * ndl * n - l;
    pow0(r.dot(v).max(0.0), shininess)
}

/// Which Fresnel factor `cook_torrance` uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FresnelForm {
    Exact,
    Schlick,
}

/// Cook & Torrance (1982) in the seed's place of (N·H)^n: π·(N·L)·R_s with the paper's
/// R_s = F·D·G / (π (N·L)(N·V)), i.e. F·D·G/(N·V); the paper's D = exp(−(tan α / m)²) / (m² cos⁴ α)
/// with α = acos(N·H); G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)); F the paper's
/// unpolarised Fresnel equation or Schlick's, at c = V·H. 0 where N·L ≤ 0. Written from the
/// paper's formulas (angles through acos and tan), not from the tracer's.
pub fn cook_torrance(n: DVec3, l: DVec3, v: DVec3, m: f64, eta: f64, fresnel: FresnelForm) -> f64 {
    let ndl = n.dot(l);
    if ndl <= 0.0 {
        return 0.0;
    }
    let h = (l.normalize() + v).normalize();
    let (ndh, ndv, vdh) = (n.dot(h), n.dot(v), v.dot(h));
    let alpha = ndh.clamp(-1.0, 1.0).acos();
    let d = (-(alpha.tan() / m).powi(2)).exp() / (m * m * ndh.powi(4));
    let c = vdh;
    let f = match fresnel {
        FresnelForm::Exact => {
            let g = (eta * eta + c * c - 1.0).sqrt();
            0.5 * ((g - c) / (g + c)).powi(2) * (1.0 + ((c * (g + c) - 1.0) / (c * (g - c) + 1.0)).powi(2))
        }
        FresnelForm::Schlick => {
            let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
            f0 + (1.0 - f0) * (1.0 - c).powi(5)
        }
    };
    let g = 1.0_f64.min(2.0 * ndh * ndv / vdh).min(2.0 * ndh * ndl / vdh);
    f * d * g / ndv
}

/// x^n with x^0 = 1 (also 0^0).
pub fn pow0(x: f64, n: f64) -> f64 {
    if n == 0.0 { 1.0 } else { x.powf(n) }
}

/// Per channel |got − want| ≤ rel·max(|want|, 1e-6) (the floor keeps exact zeros meaningful
/// without demanding bit equality of sums of tiny terms).
pub fn assert_rel(got: DVec3, want: DVec3, rel: f64, what: &str) {
    for i in 0..3 {
        let (g, w) = (got[i], want[i]);
        let tol = rel * w.abs().max(1e-6);
        assert!(
            g.is_finite() && (g - w).abs() <= tol,
            "{what}: channel {i}: got {g:e}, expected {w:e} (diff {:e} > tol {tol:e}); got {got}, expected {want}",
            (g - w).abs()
        );
    }
}

/// DVec3 from an array (short form for expectations).
pub fn dv(a: [f64; 3]) -> DVec3 {
    DVec3::from(a)
}
