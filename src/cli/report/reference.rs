//! A Monte Carlo reference that shares no random numbers with the rows held against it: the
//! mean of `REFERENCE_GROUPS` CPU renders at seeds no row uses (`reference_seed`), whose spread
//! estimates its own noise. The Whitted-against-GI section's path-traced reference and the main
//! sweep's reference of a path-traced scene are both made here.

use anyhow::Context;
use glint_core::glam::DVec3;
use glint_core::{CpuOptions, FlatScene, HdrImage};
use glint_scene::{RenderSettings, SceneDesc};
use serde::{Deserialize, Serialize};

/// The reference is this many CPU renders with consecutive seeds, averaged: their spread
/// estimates its noise. Two (one degree of freedom a pixel) let one firefly set the estimate:
/// the highlights scene's came out 0.249 where other seeds gave 0.063–0.071, above the error
/// of a 16-sample row.
pub const REFERENCE_GROUPS: u32 = 8;

/// The seed of the reference's render `k`: the rows' seed plus 1 + k, so that none shares its
/// random numbers with the rows (rendered at the rows' seed). A row whose samples were the
/// reference's first would correlate with it (0.37 measured on cornell-gi at 16 spp), and its
/// squared error would hold the reference's noise with the wrong sign.
pub fn reference_seed(rows: u32, k: u32) -> u32 {
    rows.wrapping_add(1).wrapping_add(k)
}

/// The samples of the reference's render `k` of `total`: as equal as `total` allows (100 over
/// eight renders: 13 in the first four, 12 in the rest), each at least 1.
pub fn group_spp(total: u32, k: u32) -> u32 {
    (total / REFERENCE_GROUPS + u32::from(k < total % REFERENCE_GROUPS)).max(1)
}

/// What a reference of independent renders is: its image, and its own noise.
pub struct Averaged {
    pub image: HdrImage,
    pub stats: ReferenceStats,
}

/// A Monte Carlo reference's seeds and samples, and the noise its renders' spread estimates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceStats {
    /// Each render's seed and samples a pixel.
    pub seeds: Vec<u32>,
    pub spp: Vec<u32>,
    /// The RMS over pixels and channels of the reference's standard error: what an independent
    /// reference adds, squared, to each row's MSE on average.
    pub noise_rmse: f64,
    /// The reference image's mean over pixels and channels, and that mean's standard error.
    pub mean: f64,
    pub mean_se: f64,
}

/// The weighted mean of `groups` (images of equal size, `spp` samples each) and, from their
/// spread, the RMS over pixels and channels of that mean's standard error and the standard
/// error of its image mean. With `n_k` samples in group `k` and N in all, Σ n_k (x_k − x̄)² / (K − 1)
/// estimates one sample's variance without bias, and that over N the mean's.
pub fn mean_and_noise(groups: &[HdrImage], spp: &[u32]) -> (HdrImage, f64, f64) {
    let k = groups.len() as f64;
    let weights: Vec<f64> = spp.iter().map(|&n| f64::from(n)).collect();
    let total: f64 = weights.iter().sum();
    let mut mean = groups[0].clone();
    let mut variance = 0.0;
    for (i, p) in mean.pixels.iter_mut().enumerate() {
        *p = groups.iter().zip(&weights).map(|(g, w)| g.pixels[i] * *w).sum::<DVec3>() / total;
        variance +=
            groups.iter().zip(&weights).map(|(g, w)| w * (g.pixels[i] - *p).length_squared()).sum::<f64>() / (k - 1.0);
    }
    let per_value = variance / (3 * mean.pixels.len().max(1)) as f64;
    let image_mean = mean.mean();
    let mean_variance =
        groups.iter().zip(&weights).map(|(g, w)| w * (g.mean() - image_mean).powi(2)).sum::<f64>() / (k - 1.0);
    (mean, (per_value / total).sqrt(), (mean_variance / total).sqrt())
}

/// The reference of `desc` at `settings` (its `spp` in all, its `seed` the rows'): the mean of
/// `REFERENCE_GROUPS` CPU renders at `reference_seed`s, `done` called after each.
pub fn render_reference(
    desc: &SceneDesc,
    settings: &RenderSettings,
    options: &CpuOptions,
    mut done: impl FnMut(),
) -> anyhow::Result<Averaged> {
    let seeds: Vec<u32> = (0..REFERENCE_GROUPS).map(|k| reference_seed(settings.seed, k)).collect();
    let spp: Vec<u32> = (0..REFERENCE_GROUPS).map(|k| group_spp(settings.spp, k)).collect();
    let mut groups = Vec::with_capacity(seeds.len());
    for (&seed, &n) in seeds.iter().zip(&spp) {
        let s = RenderSettings { spp: n, seed, ..settings.clone() };
        let r = super::cpu_render::cpu_render(&FlatScene::build(desc, &s), options)
            .with_context(|| format!("the reference's render at seed {seed}"))?;
        groups.push(r.image);
        done();
    }
    let (image, noise_rmse, mean_se) = mean_and_noise(&groups, &spp);
    let mean = image.mean();
    Ok(Averaged { image, stats: ReferenceStats { seeds, spp, noise_rmse, mean, mean_se } })
}

impl ReferenceStats {
    /// The standard error of `row`'s image mean less the reference's, for a row of `spp`
    /// samples: the reference's mean_se scaled to the row's samples, and the reference's own,
    /// added in quadrature. A row shallower than the reference has less variance a sample, so
    /// this errs towards calling its bias noise.
    pub fn bias_se(&self, spp: u32) -> f64 {
        let total: f64 = self.spp.iter().map(|&n| f64::from(n)).sum();
        self.mean_se * (1.0 + total / f64::from(spp.max(1))).sqrt()
    }

    /// Whether a row of `spp` samples whose image mean is `mean` differs from the reference's
    /// by more than `BIAS_SIGMAS` standard errors of that difference: its bias shows above the
    /// noise.
    pub fn biased(&self, mean: f64, spp: u32) -> bool {
        (mean - self.mean).abs() > BIAS_SIGMAS * self.bias_se(spp)
    }
}

/// A row's mean is called biased when it lies more than this many standard errors from the
/// reference's: Student's t for the 7 degrees of freedom of `REFERENCE_GROUPS` = 8 groups'
/// standard error, at 0.27 % two-sided (the normal's 3σ). At 3 itself 2.0 % of unbiased rows
/// were flagged, about one a scene's sweep (a reviewer).
pub const BIAS_SIGMAS: f64 = 4.53;
const _: () = assert!(REFERENCE_GROUPS == 8, "BIAS_SIGMAS is t for 7 degrees of freedom");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_is_its_groups_mean_and_its_noise_their_standard_error() {
        // One pixel, four groups of 1, 2, 3, 4 in every channel: mean 2.5, sample variance
        // 5/3 (k − 1 in the divisor), standard error of the mean √(5/3 / 4).
        let groups: Vec<HdrImage> = (1..=4)
            .map(|v| {
                let mut image = HdrImage::new(1, 1);
                image.pixels[0] = DVec3::splat(f64::from(v));
                image
            })
            .collect();
        let (mean, noise, mean_se) = mean_and_noise(&groups, &[1, 1, 1, 1]);
        assert_eq!(mean.pixels[0], DVec3::splat(2.5));
        assert!((noise - (5.0f64 / 3.0 / 4.0).sqrt()).abs() < 1e-15, "{noise}");
        assert!((mean_se - noise).abs() < 1e-15, "one pixel: the image mean's error is the pixel's");
        // Groups of equal samples weigh alike whatever their count; unequal ones by samples.
        let (_, same, _) = mean_and_noise(&groups, &[3, 3, 3, 3]);
        assert!((same - noise).abs() < 1e-15, "{same}");
        let (weighted, _, _) = mean_and_noise(&groups, &[1, 1, 1, 5]);
        assert_eq!(weighted.pixels[0], DVec3::splat((1.0 + 2.0 + 3.0 + 20.0) / 8.0));
    }

    #[test]
    fn no_reference_render_shares_the_rows_seed() {
        for rows in [0, 7, u32::MAX] {
            let seeds: Vec<u32> = (0..REFERENCE_GROUPS).map(|k| reference_seed(rows, k)).collect();
            assert!(!seeds.contains(&rows), "{rows}: {seeds:?}");
            let mut distinct = seeds.clone();
            distinct.sort_unstable();
            distinct.dedup();
            assert_eq!(distinct.len(), seeds.len(), "{rows}: {seeds:?}");
        }
    }

    #[test]
    fn the_groups_samples_add_up_to_the_references() {
        for total in [64, 100, 1024, 4095] {
            let spp: Vec<u32> = (0..REFERENCE_GROUPS).map(|k| group_spp(total, k)).collect();
            assert_eq!(spp.iter().sum::<u32>(), total, "{spp:?}");
            assert!(spp.iter().max().unwrap() - spp.iter().min().unwrap() <= 1, "{spp:?}");
        }
    }

    #[test]
    fn a_rows_mean_is_biased_beyond_bias_sigmas_standard_errors_of_the_difference() {
        let stats = ReferenceStats { seeds: vec![1; 8], spp: vec![8; 8], noise_rmse: 0.05, mean: 1.0, mean_se: 0.001 };
        // A 64-sample row: the difference's error is √2 · 0.001.
        assert!((stats.bias_se(64) - 0.001 * 2f64.sqrt()).abs() < 1e-15);
        assert!(!stats.biased(1.006, 64) && stats.biased(0.993, 64), "4.53 · 0.0014 = 0.0064");
        // One sample: √65 · 0.001, so 5 % off is beyond it and 2 % is not.
        assert!(!stats.biased(0.98, 1) && stats.biased(0.95, 1));
    }
}
