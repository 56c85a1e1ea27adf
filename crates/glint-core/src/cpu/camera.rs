//! CPU twin of `shaders/camera.wgsl`: primary ray generation.

use glam::DVec3;

use super::rng::{hash_to_unit, sample_hash};
use super::{Ray, v3};
use glint_types::layout::GpuCamera;

/// Rows of the stratification grid: the largest divisor of spp not above √spp, so that the
/// nx × ny = spp cells tile the pixel and are as square as spp allows (2 → 2×1, 8 → 4×2,
/// 16 → 4×4, a prime p → p×1). spp ≤ 4096 bounds the search at 64 steps.
pub fn strata_rows(spp: u32) -> u32 {
    let mut rows = 1;
    for d in (1..=64).take_while(|d| d * d <= spp) {
        if spp.is_multiple_of(d) {
            rows = d;
        }
    }
    rows
}

/// Position of a sample inside its pixel, in [0, 1)², spp ≥ 1. Without jitter (the JITTER
/// feature off, or Whitted's one sample: the callers decide) the pixel centre; with it, jittered inside the
/// cells of the stratification grid (one cell, the whole pixel, for a path's single sample).
pub fn sample_offset(pixel: u32, sample: u32, spp: u32, seed: u32, jitter: bool) -> (f64, f64) {
    if !jitter {
        return (0.5, 0.5);
    }
    let rows = strata_rows(spp);
    let cols = spp / rows;
    let jx = hash_to_unit(sample_hash(pixel, sample, 0, seed));
    let jy = hash_to_unit(sample_hash(pixel, sample, 1, seed));
    // Samples past spp (a caller drawing more than the header's) go round the grid again.
    // spp ≥ 1 (validated).
    let cell = sample % spp;
    ((f64::from(cell % cols) + jx) / f64::from(cols), (f64::from(cell / cols) + jy) / f64::from(rows))
}

/// A camera ray: it starts on the anchor's plane and is traced from `t_min` < 0, the eye
/// (`GpuCamera` says why).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraRay {
    pub ray: Ray,
    pub t_min: f64,
}

/// Where the ray leaves the eye, and its distance from there to the ray's point at t: what a
/// probe and a ray tree report of a camera ray.
pub fn eye(c: &CameraRay) -> DVec3 {
    c.ray.origin + c.t_min * c.ray.dir
}

pub fn from_eye(c: &CameraRay, t: f64) -> f64 {
    t - c.t_min
}

/// The camera ray through image position (x + ox, y + oy), y downwards.
pub fn camera_ray(cam: &GpuCamera, width: u32, height: u32, x: u32, y: u32, ox: f64, oy: f64) -> CameraRay {
    let ndc_x = 2.0 * (f64::from(x) + ox) / f64::from(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * (f64::from(y) + oy) / f64::from(height);
    if cam.is_orthographic() {
        let forward = v3(cam.forward);
        let across = ndc_x * v3(cam.right) + ndc_y * v3(cam.up);
        let w = f64::from(cam.anchor[3]);
        return CameraRay {
            ray: Ray { origin: v3(cam.anchor) + across, dir: forward.normalize() },
            t_min: -w * forward.length(),
        };
    }
    // Summed in this order, not as forward + across: an eye that is its own anchor (w = 0)
    // traces bit for bit as the eye-stored camera did.
    let dir: DVec3 = v3(cam.forward) + ndc_x * v3(cam.right) + ndc_y * v3(cam.up);
    let across = ndc_x * v3(cam.right) + ndc_y * v3(cam.up);
    let w = f64::from(cam.anchor[3]);
    CameraRay { ray: Ray { origin: v3(cam.anchor) + w * across, dir: dir.normalize() }, t_min: -w * dir.length() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_types::layout::CAMERA_ORTHOGRAPHIC;

    #[test]
    fn strata_tile_the_pixel() {
        for (spp, rows) in [(1, 1), (2, 1), (4, 2), (6, 2), (7, 1), (8, 2), (16, 4), (4096, 64)] {
            assert_eq!(strata_rows(spp), rows, "spp {spp}");
        }
        // Every cell of a 4×2 grid gets exactly one of 8 samples.
        let mut cells = [0; 8];
        for s in 0..8 {
            let (x, y) = sample_offset(17, s, 8, 3, true);
            cells[(y * 2.0) as usize * 4 + (x * 4.0) as usize] += 1;
        }
        assert_eq!(cells, [1; 8]);
        // A path's one sample is jittered over the whole pixel, and samples past spp (tests draw
        // thousands from a scene of spp 1) stay inside it.
        for s in 0..100 {
            for spp in [1, 8] {
                let (x, y) = sample_offset(17, s, spp, 3, true);
                assert!((0.0..1.0).contains(&x) && (0.0..1.0).contains(&y), "spp {spp}, sample {s}: ({x}, {y})");
            }
        }
        assert_eq!(sample_offset(17, 5, 1, 3, false), (0.5, 0.5));
    }

    #[test]
    fn orthographic_rays_are_parallel_and_leave_the_eyes_plane() {
        // Eye at (0, 0, −10), anchored 8 along +z; the view 2 × 4 (half-sides 1 and 2).
        let cam = GpuCamera {
            anchor: [0.0, 0.0, -2.0, 8.0],
            forward: [0.0, 0.0, 1.0, CAMERA_ORTHOGRAPHIC],
            right: [-2.0, 0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0, 0.0],
        };
        for (x, y) in [(0, 0), (3, 1), (1, 0)] {
            let c = camera_ray(&cam, 4, 2, x, y, 0.5, 0.5);
            assert_eq!(c.ray.dir, DVec3::Z);
            let ndc = (2.0 * (f64::from(x) + 0.5) / 4.0 - 1.0, 1.0 - 2.0 * (f64::from(y) + 0.5) / 2.0);
            assert_eq!(eye(&c), DVec3::new(-2.0 * ndc.0, ndc.1, -10.0), "pixel ({x}, {y})");
            assert_eq!(from_eye(&c, 0.0), 8.0);
        }
    }
}
