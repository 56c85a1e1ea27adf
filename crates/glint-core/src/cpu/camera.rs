//! CPU twin of `shaders/camera.wgsl`: primary ray generation.

use glam::DVec3;

use super::rng::{hash_to_unit, sample_hash};
use super::{Ray, v3};
use crate::layout::GpuCamera;

/// Integer square root rounded up, the side of the stratification grid.
pub fn strata_side(spp: u32) -> u32 {
    let mut m = 1;
    while m * m < spp {
        m += 1;
    }
    m
}

/// Position of a sample inside its pixel, in [0, 1)². One sample sits at the pixel centre;
/// more samples are jittered inside the cells of an m×m grid (m = ⌈√spp⌉).
pub fn sample_offset(pixel: u32, sample: u32, spp: u32, seed: u32, jitter: bool) -> (f64, f64) {
    if !jitter || spp <= 1 {
        return (0.5, 0.5);
    }
    let m = strata_side(spp);
    let jx = hash_to_unit(sample_hash(pixel, sample, 0, seed));
    let jy = hash_to_unit(sample_hash(pixel, sample, 1, seed));
    let inv = 1.0 / f64::from(m);
    ((f64::from(sample % m) + jx) * inv, (f64::from(sample / m) + jy) * inv)
}

/// The camera ray through image position (x + ox, y + oy), y downwards.
pub fn camera_ray(cam: &GpuCamera, width: u32, height: u32, x: u32, y: u32, ox: f64, oy: f64) -> Ray {
    let ndc_x = 2.0 * (f64::from(x) + ox) / f64::from(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * (f64::from(y) + oy) / f64::from(height);
    let dir: DVec3 = v3(cam.forward) + ndc_x * v3(cam.right) + ndc_y * v3(cam.up);
    Ray { origin: v3(cam.position), dir: dir.normalize() }
}
