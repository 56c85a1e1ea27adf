// Twin of crates/glint-core/src/cpu/camera.rs: primary ray generation.
#define_import_path glint::camera

#import glint::scene_data::{GpuCamera, CAMERA_ORTHOGRAPHIC}
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

// Without jitter (the JITTER feature off, or Whitted's one sample: the callers decide, as
// the CPU twin's), the pixel centre. spp ≥ 1 (validated).
fn sample_offset(pixel: u32, sample_index: u32, spp: u32, seed: u32, jitter: bool) -> vec2<f32> {
#ifdef JITTER
    if !jitter {
        return vec2<f32>(0.5, 0.5);
    }
    let rows = strata_rows(spp);
    let cols = spp / rows;
    let jx = hash_to_unit(sample_hash(pixel, sample_index, 0u, seed));
    let jy = hash_to_unit(sample_hash(pixel, sample_index, 1u, seed));
    // Samples past spp go round the grid again (the CPU twin says when).
    let cell = sample_index % spp;
    return vec2<f32>((f32(cell % cols) + jx) / f32(cols), (f32(cell / cols) + jy) / f32(rows));
#else
    return vec2<f32>(0.5, 0.5);
#endif
}

// A camera ray: it starts on the anchor's plane and is traced from t_min < 0, the eye
// (GpuCamera in layout.rs says why).
struct CameraRay {
    ray: Ray,
    t_min: f32,
}

// Where the ray leaves the eye, and its distance from there to the ray's point at t: what a
// probe and a ray tree report of a camera ray.
fn eye(c: CameraRay) -> vec3<f32> {
    return c.ray.origin + c.t_min * c.ray.dir;
}

fn from_eye(c: CameraRay, t: f32) -> f32 {
    return t - c.t_min;
}

fn camera_ray(cam: GpuCamera, width: u32, height: u32, x: u32, y: u32, offset: vec2<f32>) -> CameraRay {
    let ndc_x = 2.0 * (f32(x) + offset.x) / f32(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * (f32(y) + offset.y) / f32(height);
    if cam.forward.w == CAMERA_ORTHOGRAPHIC {
        let across = ndc_x * cam.right.xyz + ndc_y * cam.up.xyz;
        return CameraRay(Ray(cam.anchor.xyz + across, normalize(cam.forward.xyz)), -cam.anchor.w * length(cam.forward.xyz));
    }
    // Summed in this order (the CPU twin says why).
    let dir = cam.forward.xyz + ndc_x * cam.right.xyz + ndc_y * cam.up.xyz;
    let across = ndc_x * cam.right.xyz + ndc_y * cam.up.xyz;
    let w = cam.anchor.w;
    return CameraRay(Ray(cam.anchor.xyz + w * across, normalize(dir)), -w * length(dir));
}
