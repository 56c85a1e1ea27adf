//! The ambient term judged (issue 33): the global ambient I_a, per channel, that brings a
//! Whitted image closest to a path-traced one of the same scene and view.
//!
//! Whitted's image is affine in I_a, channel by channel: I_a enters as I_a·k_a at every node of
//! the tree, weighed by the path weights k_r, k_t and f_att, none of which depends on I_a (nor
//! do the bailout's decisions). So with W₀ the image at I_a = 0 and A the image at I_a = 1
//! less W₀, the image at I_a is W₀ + I_a·A, and the I_a that minimises the squared error
//! against a reference P is, per channel c, Σ A_c (P_c − W₀_c) / Σ A_c², at least 0. Two
//! renders give it exactly; no search.

use glam::DVec3;
use glint_scene::{RenderSettings, Rgb, SceneDesc};

use crate::compare::rms_difference;
use crate::flat::FlatScene;
use crate::image::HdrImage;
use crate::render::{CpuOptions, CpuRenderError, RenderControl, render_cpu};

/// What fitting I_a gives: the fitted value and the RMSE against the reference of Whitted's
/// image with I_a as the scene writes it, without it, and fitted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientFit {
    pub ambient: [f64; 3],
    /// Whether I_a changes the image at all in some channel: without k_a anywhere (or without
    /// a pixel that sees it) no value fits better than another, and `ambient` is 0 for want of
    /// one.
    pub determined: bool,
    pub rmse_as_written: f64,
    pub rmse_without: f64,
    pub rmse_fitted: f64,
    /// What I_a·k_a adds to the image's mean (over pixels and channels), as written and fitted:
    /// to be held against the indirect light it stands in for.
    pub adds_as_written: f64,
    pub adds_fitted: f64,
    /// How far Whitted's image without an ambient falls below the reference's mean: all the
    /// ambient can make up for. More than the paths' indirect light where Whitted misses direct
    /// light too (an area emitter's, which its point lights do not compute: cornell-gi's lamp),
    /// so a fitted ambient may add more than the indirect light (a lecturer asked why).
    pub below_reference: f64,
    /// Per channel, Σ(w₀−r)², Σ(w₀−r)·Δ, ΣΔ² and ΣΔ over the pixels (w₀ Whitted's image
    /// without an ambient, Δ its response to I_a = 1, r the reference): the image is affine in
    /// I_a, so these give its error and mean at any I_a written (`at`) without rendering again.
    pub moments: [[f64; 4]; 3],
    pub pixels: usize,
}

impl AmbientFit {
    /// Whitted's RMSE against the reference, and what I_a·k_a adds to its mean, with `ambient`
    /// written: `rmse_as_written` and `adds_as_written` of another I_a.
    pub fn at(&self, ambient: [f64; 3]) -> (f64, f64) {
        let n = (3 * self.pixels.max(1)) as f64;
        let (mut squares, mut adds) = (0.0, 0.0);
        for (&[e0, e1, e2, m], a) in self.moments.iter().zip(ambient) {
            squares += e0 + 2.0 * a * e1 + a * a * e2;
            adds += a * m;
        }
        (squares.max(0.0).sqrt() / n.sqrt(), adds / n)
    }
}

/// The mean of `a − b` over the pixels and channels.
fn mean_difference(a: &[DVec3], b: &[DVec3]) -> f64 {
    a.iter().zip(b).map(|(p, q)| (*p - *q).element_sum()).sum::<f64>() / (3 * a.len().max(1)) as f64
}

/// Fits the global ambient of `desc` rendered by Whitted's tree with `settings` (its integrator
/// set to Whitted's) to `reference`, an image of the same size (a converged path-traced render).
pub fn fit_ambient(
    desc: &SceneDesc,
    settings: &RenderSettings,
    reference: &HdrImage,
    options: &CpuOptions,
) -> Result<AmbientFit, CpuRenderError> {
    let settings = RenderSettings { integrator: glint_scene::Integrator::Whitted, ..settings.clone() };
    let render = |ambient: Rgb| -> Result<Vec<DVec3>, CpuRenderError> {
        let mut d = desc.clone();
        d.world.ambient = ambient;
        Ok(render_cpu(&FlatScene::build(&d, &settings), options, RenderControl::default())?.image.pixels)
    };
    let without = render(Rgb([0.0; 3]))?;
    let unit = render(Rgb([1.0; 3]))?;
    let as_written = render(desc.world.ambient)?;
    let p = &reference.pixels;
    let mut ambient = [0.0; 3];
    let mut moments = [[0.0; 4]; 3];
    let mut determined = false;
    for (c, (a, m)) in ambient.iter_mut().zip(&mut moments).enumerate() {
        for ((w0, w1), r) in without.iter().zip(&unit).zip(p) {
            let (response, off) = (w1[c] - w0[c], w0[c] - r[c]);
            *m = [m[0] + off * off, m[1] + off * response, m[2] + response * response, m[3] + response];
        }
        // The least squares of w₀ + a·Δ against r: a = Σ(r−w₀)Δ / ΣΔ².
        let (num, den) = (-m[1], m[2]);
        determined |= den > 0.0;
        *a = if den > 0.0 { (num / den).max(0.0) } else { 0.0 };
    }
    let fitted: Vec<DVec3> =
        without.iter().zip(&unit).map(|(w0, w1)| *w0 + DVec3::from(ambient) * (*w1 - *w0)).collect();
    Ok(AmbientFit {
        ambient,
        determined,
        rmse_as_written: rms_difference(&as_written, p),
        rmse_without: rms_difference(&without, p),
        rmse_fitted: rms_difference(&fitted, p),
        adds_as_written: mean_difference(&as_written, &without),
        adds_fitted: mean_difference(&fitted, &without),
        below_reference: mean_difference(p, &without),
        moments,
        pixels: p.len(),
    })
}
