//! Errors of one image against a reference, and the difference heat map.
//!
//! Differences are taken on linear radiance, per channel. PSNR uses a peak of 1 (display
//! white); FLIP (Andersson et al. 2020, the nv-flip crate) compares the sRGB-encoded images as
//! a viewer would see them.

use crate::HdrImage;
use crate::image::linear_to_srgb8;

/// Lower end of the heat map's log scale: |difference| ≤ 10^-7 is dark, 1 is bright.
pub const HEATMAP_LOG10_MIN: f64 = -7.0;
pub const HEATMAP_LOG10_MAX: f64 = 0.0;

/// The ε of relMSE = mean((x − r)² / (r² + ε)), as in pbrt's and Mitsuba's reports.
pub const REL_MSE_EPSILON: f64 = 1e-2;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ImageErrors {
    pub max_abs: f64,
    pub mean_abs: f64,
    pub rmse: f64,
    pub rel_mse: f64,
    /// 10·log10(1 / MSE); infinite for identical images.
    pub psnr: f64,
    pub flip_mean: f64,
    /// Fraction of pixels whose first sample hit a different object (or one hit nothing).
    pub first_hit_mismatch: f64,
    /// 99th percentile of the per-pixel max-channel |difference| over pixels whose first hit
    /// agrees (silhouettes excluded).
    pub p99_abs_same_hit: f64,
    /// Pixels of the test image with a NaN or infinite channel.
    pub nonfinite: usize,
}

/// Compares `test` with `reference` (same size).
pub fn compare_images(reference: &HdrImage, test: &HdrImage) -> ImageErrors {
    assert_eq!((reference.width, reference.height), (test.width, test.height), "images of different sizes");
    let n = reference.pixels.len().max(1);
    let mut e = ImageErrors::default();
    let mut sum_abs = 0.0;
    let mut sum_sq = 0.0;
    let mut sum_rel = 0.0;
    let mut same_hit = Vec::with_capacity(n);
    let mut mismatches = 0usize;
    for i in 0..reference.pixels.len() {
        let (r, t) = (reference.pixels[i], test.pixels[i]);
        if !t.is_finite() {
            e.nonfinite += 1;
            continue;
        }
        let d = (t - r).abs();
        e.max_abs = e.max_abs.max(d.max_element());
        sum_abs += d.x + d.y + d.z;
        sum_sq += d.length_squared();
        sum_rel += (d * d / (r * r + REL_MSE_EPSILON)).element_sum();
        if reference.first_hit[i] == test.first_hit[i] {
            same_hit.push(d.max_element());
        } else {
            mismatches += 1;
        }
    }
    let samples = (3 * n) as f64;
    e.mean_abs = sum_abs / samples;
    let mse = sum_sq / samples;
    e.rmse = mse.sqrt();
    e.rel_mse = sum_rel / samples;
    e.psnr = if mse > 0.0 { -10.0 * mse.log10() } else { f64::INFINITY };
    e.first_hit_mismatch = mismatches as f64 / n as f64;
    e.p99_abs_same_hit = percentile(&mut same_hit, 0.99);
    e.flip_mean = flip_mean(reference, test);
    e
}

fn percentile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let idx = ((values.len() - 1) as f64 * q).round() as usize;
    values[idx]
}

/// Mean FLIP error of the sRGB-encoded images at the default 67 pixels per degree.
pub fn flip_mean(reference: &HdrImage, test: &HdrImage) -> f64 {
    let encode = |img: &HdrImage| nv_flip::FlipImageRgb8::with_data(img.width, img.height, &img.to_srgb8());
    let map = nv_flip::flip(encode(reference), encode(test), nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    f64::from(nv_flip::FlipPool::from_image(&map).mean())
}

/// The per-pixel max-channel |test − reference| as an 8-bit RGB heat map: black where the
/// images are identical, then the magma colour map over log10 |difference| from
/// `HEATMAP_LOG10_MIN` to `HEATMAP_LOG10_MAX`.
pub fn diff_heatmap(reference: &HdrImage, test: &HdrImage) -> Vec<u8> {
    let lut = nv_flip::magma_lut().to_vec();
    let mut out = Vec::with_capacity(reference.pixels.len() * 3);
    for (r, t) in reference.pixels.iter().zip(&test.pixels) {
        let d = (*t - *r).abs().max_element();
        if d == 0.0 {
            out.extend_from_slice(&[0, 0, 0]);
            continue;
        }
        let x = if d.is_finite() {
            ((d.log10() - HEATMAP_LOG10_MIN) / (HEATMAP_LOG10_MAX - HEATMAP_LOG10_MIN)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        // Start a little above the LUT's black so "tiny but not zero" stays visible.
        let k = (24.0 + x * 231.0).round() as usize;
        out.extend_from_slice(&lut[3 * k..3 * k + 3]);
    }
    out
}

/// An 8-bit sRGB encoding of an image (for side-by-side composites).
pub fn srgb8(image: &HdrImage) -> Vec<u8> {
    image.pixels.iter().flat_map(|p| p.to_array().map(linear_to_srgb8)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn image(values: &[f64]) -> HdrImage {
        let mut img = HdrImage::new(values.len() as u32, 1);
        for (p, v) in img.pixels.iter_mut().zip(values) {
            *p = DVec3::splat(*v);
        }
        img
    }

    #[test]
    fn identical_images_have_zero_error_and_infinite_psnr() {
        let a = image(&[0.1, 0.5, 0.9, 0.2]);
        let e = compare_images(&a, &a);
        assert_eq!((e.max_abs, e.mean_abs, e.rmse, e.first_hit_mismatch, e.flip_mean), (0.0, 0.0, 0.0, 0.0, 0.0));
        assert!(e.psnr.is_infinite());
    }

    #[test]
    fn known_difference_gives_known_figures() {
        let a = image(&[0.5, 0.5, 0.5, 0.5]);
        let b = image(&[0.5, 0.6, 0.5, 0.5]);
        let e = compare_images(&a, &b);
        assert!((e.max_abs - 0.1).abs() < 1e-12);
        assert!((e.mean_abs - 0.1 / 4.0).abs() < 1e-12);
        assert!((e.rmse - (0.01f64 / 4.0).sqrt()).abs() < 1e-12);
        assert!((e.psnr - 10.0 * (4.0f64 / 0.01).log10()).abs() < 1e-9);
        assert!(e.flip_mean > 0.0);
    }

    #[test]
    fn heatmap_is_black_only_where_identical() {
        let a = image(&[0.5, 0.5]);
        let b = image(&[0.5, 0.5 + 1e-3]);
        let h = diff_heatmap(&a, &b);
        assert_eq!(&h[..3], &[0, 0, 0]);
        assert_ne!(&h[3..], &[0, 0, 0]);
    }
}
