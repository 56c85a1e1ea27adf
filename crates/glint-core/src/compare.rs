//! Errors of one image against a reference, and the difference heat map.
//!
//! Differences are taken on linear radiance, per channel. PSNR uses a peak of 1 (display
//! white); FLIP (Andersson et al. 2020, the nv-flip crate) compares the sRGB-encoded images as
//! a viewer would see them.

use glam::DVec3;

use crate::HdrImage;

/// Lower end of the heat map's log scale: |difference| ≤ 10^-7 is dark, 1 is bright.
pub const HEATMAP_LOG10_MIN: f64 = -7.0;
pub const HEATMAP_LOG10_MAX: f64 = 0.0;

/// The ε of relMSE = mean((x − r)² / (r² + ε)), as in pbrt's and Mitsuba's reports.
pub const REL_MSE_EPSILON: f64 = 1e-2;

#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
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

/// The root mean square of every channel of `pixels`: an image's RMS, or a difference's.
pub fn rms(pixels: &[DVec3]) -> f64 {
    let sum: f64 = pixels.iter().map(|p| p.length_squared()).sum();
    (sum / (3 * pixels.len().max(1)) as f64).sqrt()
}

/// The RMS of `a − b` (same length), the RMSE of `compare_images`, without a difference image.
pub fn rms_difference(a: &[DVec3], b: &[DVec3]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(p, q)| (*p - *q).length_squared()).sum();
    (sum / (3 * a.len().max(1)) as f64).sqrt()
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

/// Where |difference| `d` falls on the heat map's scale, in [0, 1]: log10 d from
/// `HEATMAP_LOG10_MIN` (0) to `HEATMAP_LOG10_MAX` (1), clamped; a non-finite `d` is 1.
pub fn heatmap_position(d: f64) -> f64 {
    if d.is_finite() {
        ((d.log10() - HEATMAP_LOG10_MIN) / (HEATMAP_LOG10_MAX - HEATMAP_LOG10_MIN)).clamp(0.0, 1.0)
    } else {
        1.0
    }
}

/// The heat map's colour at position `x` in [0, 1]: the magma colour map, starting a little
/// above its black so that "tiny but not zero" stays visible against identical pixels.
pub fn heatmap_colour(x: f64) -> [u8; 3] {
    static LUT: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    let lut = LUT.get_or_init(|| nv_flip::magma_lut().to_vec());
    let k = (24.0 + x.clamp(0.0, 1.0) * 231.0).round() as usize;
    [lut[3 * k], lut[3 * k + 1], lut[3 * k + 2]]
}

/// A diverging colour at `t` in [−1, 1] (ColorBrewer's RdBu, reversed): blue below 0, near
/// white at 0, red above; for signed differences such as Whitted − GI.
pub fn diverging_colour(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 5] =
        [[5.0, 48.0, 97.0], [67.0, 147.0, 195.0], [247.0, 247.0, 247.0], [214.0, 96.0, 77.0], [103.0, 0.0, 31.0]];
    let x = (t.clamp(-1.0, 1.0) + 1.0) * 2.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    [0, 1, 2].map(|c| (a[c] + (b[c] - a[c]) * f).round() as u8)
}

/// A signed difference of two images (`a − b`, per pixel the mean of the channels) on a
/// symmetric scale: what a diverging colour map shows.
#[derive(Clone, Debug, PartialEq)]
pub struct SignedDifference {
    pub width: u32,
    pub height: u32,
    /// `a − b` per pixel and channel.
    pub pixels: Vec<DVec3>,
    /// The colour map's ends are ±scale: the 99th percentile of |mean difference|, rounded up
    /// to 1, 2 or 5 times a power of ten, so that a few fireflies do not wash the rest out.
    pub scale: f64,
    /// 8-bit RGB of `diverging_colour(mean / scale)`.
    pub rgb: Vec<u8>,
}

impl SignedDifference {
    pub fn new(a: &HdrImage, b: &HdrImage) -> Self {
        assert_eq!((a.width, a.height), (b.width, b.height), "images of different sizes");
        let pixels: Vec<DVec3> = a.pixels.iter().zip(&b.pixels).map(|(x, y)| *x - *y).collect();
        let mean = |d: &DVec3| d.element_sum() / 3.0;
        let mut magnitudes: Vec<f64> = pixels.iter().map(|d| mean(d).abs()).filter(|m| m.is_finite()).collect();
        magnitudes.sort_by(f64::total_cmp);
        let p99 =
            magnitudes.get((magnitudes.len().saturating_sub(1) as f64 * 0.99).ceil() as usize).copied().unwrap_or(0.0);
        let scale = nice_ceiling(p99.max(1e-6));
        let rgb = pixels.iter().flat_map(|d| diverging_colour(mean(d) / scale)).collect();
        Self { width: a.width, height: a.height, pixels, scale, rgb }
    }

    /// `a − b` at pixel (x, y).
    pub fn at(&self, x: u32, y: u32) -> Option<DVec3> {
        (x < self.width && y < self.height).then(|| self.pixels[(y * self.width + x) as usize])
    }
}

/// The least of 1, 2 and 5 times a power of ten that is at least `v` (> 0): the difference
/// view's scale, and the viewer's plot ticks.
pub fn nice_ceiling(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0].into_iter().map(|m| m * p).find(|c| *c >= v * (1.0 - 1e-12)).unwrap_or(10.0 * p)
}

/// |test − reference| per channel as a linear image (the EXR form of the difference view).
pub fn abs_difference(reference: &HdrImage, test: &HdrImage) -> HdrImage {
    let mut out = reference.clone();
    for (o, t) in out.pixels.iter_mut().zip(&test.pixels) {
        *o = (*t - *o).abs();
    }
    out
}

/// The per-pixel max-channel |test − reference| as an 8-bit RGB heat map: black where the
/// images are identical, else `heatmap_colour(heatmap_position(d))`.
pub fn diff_heatmap(reference: &HdrImage, test: &HdrImage) -> Vec<u8> {
    let mut out = Vec::with_capacity(reference.pixels.len() * 3);
    for (r, t) in reference.pixels.iter().zip(&test.pixels) {
        let d = (*t - *r).abs().max_element();
        if d == 0.0 {
            out.extend_from_slice(&[0, 0, 0]);
            continue;
        }
        out.extend_from_slice(&heatmap_colour(heatmap_position(d)));
    }
    out
}

/// The per-pixel differences of a test image against its reference: what the difference view
/// reads under the cursor, bins into its histogram and searches for the worst pixel.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PixelDiffs {
    pub width: u32,
    pub height: u32,
    /// Max-channel |test − reference| per pixel (NaN where either is NaN), row by row.
    pub abs: Vec<f64>,
    /// Whether the first sample hit a different object (or one of them hit nothing).
    pub hit_differs: Vec<bool>,
}

/// One bin of `PixelDiffs::histogram`: |difference| in [lo, hi) (`lo` = `hi` = 0 for identical
/// pixels; `hi` infinite for the last bin, which also holds non-finite ones).
#[derive(Clone, Debug, PartialEq)]
pub struct DiffBin {
    pub lo: f64,
    pub hi: f64,
    /// Pixels whose first hit agrees (shading differences).
    pub same_hit: usize,
    /// Pixels whose first hit differs (silhouettes, acne, missed objects).
    pub hit_differs: usize,
}

impl DiffBin {
    pub fn label(&self) -> String {
        if self.hi == 0.0 {
            "0".into()
        } else if self.lo == 0.0 {
            format!("< {:.0e}", self.hi)
        } else if self.hi.is_infinite() {
            format!("≥ {:.0e}", self.lo)
        } else {
            format!("{:.0e}", self.lo)
        }
    }
}

impl PixelDiffs {
    /// `test` against `reference` (same size).
    pub fn new(reference: &HdrImage, test: &HdrImage) -> Self {
        let abs = reference
            .pixels
            .iter()
            .zip(&test.pixels)
            .map(|(r, t)| {
                let d = (*t - *r).abs();
                if d.is_nan() { f64::NAN } else { d.max_element() }
            })
            .collect();
        let hit_differs = reference.first_hit.iter().zip(&test.first_hit).map(|(a, b)| a != b).collect();
        Self { width: reference.width, height: reference.height, abs, hit_differs }
    }

    /// The difference and first-hit disagreement at pixel (x, y).
    pub fn at(&self, x: u32, y: u32) -> Option<(f64, bool)> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y * self.width + x) as usize;
        Some((self.abs[i], self.hit_differs[i]))
    }

    /// The pixel of the largest difference (a NaN or infinite one first; ties to the first in
    /// row order), or `None` when the images are identical.
    pub fn worst(&self) -> Option<(u32, u32, f64)> {
        let rank = |d: f64| if d.is_finite() { d } else { f64::INFINITY };
        let (i, d) =
            self.abs.iter().copied().enumerate().fold(None, |best: Option<(usize, f64)>, (i, d)| match best {
                Some((_, b)) if rank(d) <= rank(b) => best,
                _ => Some((i, d)),
            })?;
        if d == 0.0 {
            return None;
        }
        let w = self.width.max(1) as usize;
        Some(((i % w) as u32, (i / w) as u32, d))
    }

    /// The pixels by |difference|: identical, below 10^HEATMAP_LOG10_MIN, one bin per decade up
    /// to 10^HEATMAP_LOG10_MAX, and at or above it (with the non-finite); each bin split into
    /// pixels whose first hit agrees and those where it differs.
    pub fn histogram(&self) -> Vec<DiffBin> {
        let (min, max) = (HEATMAP_LOG10_MIN as i32, HEATMAP_LOG10_MAX as i32);
        let mut bins = vec![DiffBin { lo: 0.0, hi: 0.0, same_hit: 0, hit_differs: 0 }];
        bins.push(DiffBin { lo: 0.0, hi: 10f64.powi(min), same_hit: 0, hit_differs: 0 });
        for e in min..max {
            bins.push(DiffBin { lo: 10f64.powi(e), hi: 10f64.powi(e + 1), same_hit: 0, hit_differs: 0 });
        }
        bins.push(DiffBin { lo: 10f64.powi(max), hi: f64::INFINITY, same_hit: 0, hit_differs: 0 });
        for (&d, &differs) in self.abs.iter().zip(&self.hit_differs) {
            let bin = if d == 0.0 {
                0
            } else if !d.is_finite() || d >= 10f64.powi(max) {
                bins.len() - 1
            } else if d < 10f64.powi(min) {
                1
            } else {
                // Decade e (bin 2 + e − min), by comparison rather than log10's rounding.
                2 + (min..max).take_while(|&e| d >= 10f64.powi(e + 1)).count()
            };
            if differs {
                bins[bin].hit_differs += 1;
            } else {
                bins[bin].same_hit += 1;
            }
        }
        bins
    }
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
    fn pixel_differences_bin_by_decade_split_by_first_hit_and_find_the_worst() {
        let a = image(&[0.5, 0.5, 0.5, 0.5, 0.5, 0.5]);
        let mut b = image(&[0.5, 0.5 + 3e-5, 0.5 + 1e-9, 0.75, 0.5 + 2e-5, f64::INFINITY]);
        b.first_hit[3] = 7;
        let d = PixelDiffs::new(&a, &b);
        assert_eq!(d.at(1, 0).map(|(v, h)| ((v - 3e-5).abs() < 1e-12, h)), Some((true, false)));
        assert_eq!(d.at(3, 0), Some((0.25, true)));
        assert_eq!(d.at(6, 0), None);
        assert_eq!(d.worst(), Some((5, 0, f64::INFINITY)), "a non-finite pixel is the worst");
        let bins = d.histogram();
        let labels: Vec<String> = bins.iter().map(DiffBin::label).collect();
        assert_eq!(labels, ["0", "< 1e-7", "1e-7", "1e-6", "1e-5", "1e-4", "1e-3", "1e-2", "1e-1", "≥ 1e0"]);
        let counts: Vec<(usize, usize)> = bins.iter().map(|b| (b.same_hit, b.hit_differs)).collect();
        // 0; 1e-9; 2e-5 and 3e-5 in [1e-5, 1e-4); 0.25 (its hit differs); infinity.
        assert_eq!(counts, [(1, 0), (1, 0), (0, 0), (0, 0), (2, 0), (0, 0), (0, 0), (0, 0), (0, 1), (1, 0)]);
        assert_eq!(PixelDiffs::new(&a, &a).worst(), None);
        // The heat map's colours are the scale's: its ends and a midpoint.
        assert_eq!(heatmap_position(1e-7), 0.0);
        assert_eq!(heatmap_position(1.0), 1.0);
        assert!((heatmap_position(10f64.powf(-3.5)) - 0.5).abs() < 1e-12);
        assert_eq!(&diff_heatmap(&a, &b)[3..6], &heatmap_colour(heatmap_position(3e-5)));
    }

    #[test]
    fn heatmap_is_black_only_where_identical() {
        let a = image(&[0.5, 0.5]);
        let b = image(&[0.5, 0.5 + 1e-3]);
        let h = diff_heatmap(&a, &b);
        assert_eq!(&h[..3], &[0, 0, 0]);
        assert_ne!(&h[3..], &[0, 0, 0]);
    }

    #[test]
    fn a_signed_difference_keeps_its_sign_and_a_round_scale() {
        let mut a = HdrImage::new(2, 1);
        let b = HdrImage::new(2, 1);
        a.pixels[0] = DVec3::splat(0.3);
        a.pixels[1] = DVec3::splat(-0.03);
        let d = SignedDifference::new(&a, &b);
        assert_eq!(d.scale, 0.5);
        assert_eq!(d.at(1, 0), Some(DVec3::splat(-0.03)));
        assert_eq!(d.at(2, 0), None);
        // Positive is red, negative blue, zero near white.
        assert!(d.rgb[0] > d.rgb[2] && d.rgb[5] > d.rgb[3], "{:?}", d.rgb);
        assert_eq!(diverging_colour(0.0), [247, 247, 247]);
        assert_eq!(diverging_colour(-2.0), [5, 48, 97]);
        assert_eq!(nice_ceiling(0.3), 0.5);
        assert_eq!(nice_ceiling(0.02), 0.02);
        assert_eq!(nice_ceiling(7.0), 10.0);
    }
}
