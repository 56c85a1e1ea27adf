// Twin of crates/glint-core/src/cpu/camera.rs: primary ray generation.
#define_import_path glint::camera

#import glint::scene_data::GpuCamera
#import glint::rng::{sample_hash, hash_to_unit}
#import glint::ray::Ray

#ifdef JITTER
// Rows of the stratification grid: the largest divisor of spp not above √spp.
fn strata_rows(spp: u32) -> u32 {
    var rows = 1u;
    // Stops at √spp: every loop iteration counts against lavapipe's per-invocation budget.
    for (var d = 1u; d <= 64u && d * d <= spp; d++) {
        if spp % d == 0u {
            rows = d;
        }
    }
    return rows;
}
#endif

// Without JITTER (spp 1), the pixel centre; the CPU twin takes the feature as `jitter`.
fn sample_offset(pixel: u32, sample_index: u32, spp: u32, seed: u32) -> vec2<f32> {
#ifdef JITTER
    if spp <= 1u {
        return vec2<f32>(0.5, 0.5);
    }
    let rows = strata_rows(spp);
    let cols = spp / rows;
    let jx = hash_to_unit(sample_hash(pixel, sample_index, 0u, seed));
    let jy = hash_to_unit(sample_hash(pixel, sample_index, 1u, seed));
    return vec2<f32>((f32(sample_index % cols) + jx) / f32(cols), (f32(sample_index / cols) + jy) / f32(rows));
#else
    return vec2<f32>(0.5, 0.5);
#endif
}

fn camera_ray(cam: GpuCamera, width: u32, height: u32, x: u32, y: u32, offset: vec2<f32>) -> Ray {
    let ndc_x = 2.0 * (f32(x) + offset.x) / f32(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * (f32(y) + offset.y) / f32(height);
    let dir = cam.forward.xyz + ndc_x * cam.right.xyz + ndc_y * cam.up.xyz;
    return Ray(cam.position.xyz, normalize(dir));
}
