//! Pearson's χ² test of a sampling routine against the density it claims, as Nori's warp tests
//! do: draw many samples into a grid of cells over the unit square, integrate the density over
//! each cell for the expected counts, pool the cells expecting fewer than five, and ask how
//! likely a statistic this large is if the samples do follow the density.
//!
//! Directions are tested on the square through (cos θ, φ) → ((1 + cos θ)/2, φ/2π), which is
//! area-preserving up to the constant 4π: a density per unit solid angle times 4π is the density
//! on the square (`sphere_to_square`, `square_density`).

use std::f64::consts::PI;

use glam::{DVec2, DVec3};
use glint_core::cpu::rng::{hash_to_unit, sample_hash};

/// The outcome of one test: the statistic, its degrees of freedom and the p-value.
#[derive(Clone, Copy, Debug)]
pub struct Chi2 {
    pub statistic: f64,
    pub dof: usize,
    pub p_value: f64,
}

/// The point of the unit square a unit direction maps to.
pub fn sphere_to_square(d: DVec3) -> DVec2 {
    let phi = d.y.atan2(d.x).rem_euclid(2.0 * PI);
    DVec2::new((0.5 * (1.0 + d.z)).clamp(0.0, 1.0), (phi / (2.0 * PI)).clamp(0.0, 1.0))
}

/// The unit direction at a point of the unit square (the inverse of `sphere_to_square`).
pub fn square_to_sphere(p: DVec2) -> DVec3 {
    let z = 2.0 * p.x - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * p.y;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A density per unit solid angle as a density on the unit square.
pub fn square_density(pdf: impl Fn(DVec3) -> f64) -> impl Fn(DVec2) -> f64 {
    move |p| 4.0 * PI * pdf(square_to_sphere(p))
}

/// The i-th of a fixed stream of points in [0, 1)², from Glint's own counter-based generator.
pub fn uniform_pair(i: u32, seed: u32) -> DVec2 {
    DVec2::new(hash_to_unit(sample_hash(i, 0, 0, seed)), hash_to_unit(sample_hash(i, 0, 1, seed)))
}

/// Tests `samples` draws of `sample` (a point of the unit square) against `density` over a
/// `cells.0` × `cells.1` grid.
pub fn chi2_test(
    cells: (usize, usize),
    samples: u32,
    seed: u32,
    sample: impl Fn(DVec2) -> DVec2,
    density: impl Fn(DVec2) -> f64,
) -> Chi2 {
    let (nx, ny) = cells;
    let mut observed = vec![0.0; nx * ny];
    for i in 0..samples {
        let p = sample(uniform_pair(i, seed));
        let x = ((p.x * nx as f64) as usize).min(nx - 1);
        let y = ((p.y * ny as f64) as usize).min(ny - 1);
        observed[y * nx + x] += 1.0;
    }
    // Each cell's share of the density: the midpoint rule on a 40 × 40 grid inside the cell,
    // fine enough for a cos^80 lobe (its error there is 0.1 % of a cell's count).
    const SUB: usize = 40;
    let mut expected = vec![0.0; nx * ny];
    let cell_area = 1.0 / (nx * ny) as f64;
    for y in 0..ny {
        for x in 0..nx {
            let mut sum = 0.0;
            for sy in 0..SUB {
                for sx in 0..SUB {
                    let p = DVec2::new(
                        (x as f64 + (sx as f64 + 0.5) / SUB as f64) / nx as f64,
                        (y as f64 + (sy as f64 + 0.5) / SUB as f64) / ny as f64,
                    );
                    sum += density(p);
                }
            }
            expected[y * nx + x] = sum / (SUB * SUB) as f64 * cell_area * f64::from(samples);
        }
    }
    pearson(&observed, &expected)
}

/// Pearson's statistic over cells expecting at least five samples, the rest pooled into one cell
/// (and left out if even the pool expects fewer than five).
pub fn pearson(observed: &[f64], expected: &[f64]) -> Chi2 {
    let (mut statistic, mut cells) = (0.0, 0usize);
    let (mut pooled_observed, mut pooled_expected) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e < 5.0 {
            pooled_observed += o;
            pooled_expected += e;
        } else {
            statistic += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pooled_expected >= 5.0 {
        statistic += (pooled_observed - pooled_expected).powi(2) / pooled_expected;
        cells += 1;
    } else if pooled_observed > 10.0 {
        // Samples where the density says there are (almost) none: no statistic needed.
        return Chi2 { statistic: f64::INFINITY, dof: cells.max(1), p_value: 0.0 };
    }
    let dof = cells.saturating_sub(1).max(1);
    Chi2 { statistic, dof, p_value: upper_gamma_regularized(dof as f64 / 2.0, statistic / 2.0) }
}

/// Q(a, x) = Γ(a, x)/Γ(a), the χ² survival function at 2x for 2a degrees of freedom: the
/// series of P below a + 1, Legendre's continued fraction (modified Lentz) above.
pub fn upper_gamma_regularized(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    if !x.is_finite() {
        return 0.0;
    }
    let log_prefix = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut term, mut sum, mut n) = (1.0 / a, 1.0 / a, a);
        for _ in 0..10_000 {
            n += 1.0;
            term *= x / n;
            sum += term;
            if term.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        (1.0 - sum * log_prefix.exp()).clamp(0.0, 1.0)
    } else {
        const TINY: f64 = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / TINY;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -f64::from(i) * (f64::from(i) - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < TINY {
                d = TINY;
            }
            c = b + an / c;
            if c.abs() < TINY {
                c = TINY;
            }
            d = 1.0 / d;
            let step = d * c;
            h *= step;
            if (step - 1.0).abs() < 1e-15 {
                break;
            }
        }
        (log_prefix.exp() * h).clamp(0.0, 1.0)
    }
}

/// ln Γ(x) for x > 0 (Lanczos, g = 7, nine coefficients: about 15 digits).
pub fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // The reflection formula.
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let mut a = C[0];
    let t = x + G + 0.5;
    for (i, c) in C.iter().enumerate().skip(1) {
        a += c / (x + i as f64);
    }
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}
