//! Case 26: a far object out of sight — an eye 0.01 over a checkered floor, looking down at it
//! 40° below the horizon, with a sphere of radius 1 behind the eye at D = 1e3, 1e5 and 1e7 (the
//! sun of a scene made in real units, or a model left far away), 96×72.
//!
//! Expected: the sphere is not in the picture, so the CPU's image is its image without the
//! sphere, bit for bit, and the GPU's matches the CPU's (no first hit that differs, largest
//! difference ≤ 1e-6).
//!
//! Why it was stiff: a scene is stored relative to its bounded geometry (spheres and meshes),
//! and an eye far from that box is anchored by it. With the sphere at 3e5 behind the eye the
//! scene was stored around the sphere, where f32's step is 0.03: the stored eye came to lie on
//! the floor, and both tracers showed the background where the floor was (a user's 1 cm camera
//! under a sun at 1e6 rendered black). A far box the camera cannot see now leaves the storage
//! origin to the eye's neighbourhood out to its nearest plane (`glint_scene::storage_origin`),
//! and the camera is not anchored by it.

use glint_core::compare::compare_images;

use crate::gpu::render_both;
use crate::scene::SceneText;

const DISTANCES: [f64; 3] = [1e3, 1e5, 1e7];

fn scene(sphere_at: Option<f64>) -> SceneText {
    let (sin, cos) = 40f64.to_radians().sin_cos();
    let eye = [0.3, 0.01, 0.2];
    let look_at = [eye[0], eye[1] - sin, eye[2] + cos];
    let text = SceneText::new(96, 72, "max_depth = 1", eye, look_at, [0.0, 1.0, 0.0], 60.0)
        .world([0.1; 3], [0.3; 3])
        .material("floor", "kd = 0.8\nchecker = { kd = 0.1, size = 0.005 }")
        .light("directional", "direction = [-0.3, -1.0, 0.2]")
        .plane([0.0; 3], [0.0, 1.0, 0.0], "floor");
    match sphere_at {
        Some(d) => text.sphere([eye[0], 1.0 + d * 0.1, eye[2] - d], 1.0, "floor"),
        None => text,
    }
}

#[test]
fn a_far_object_out_of_sight_leaves_the_eye_and_its_floor_their_digits() {
    let mut out = String::new();
    say!(out, "case 26: an eye 0.01 over a checkered floor, a sphere D behind it (96×72)");
    say!(
        out,
        "  {:>7}  {:>30}  {:>10}  {:>10}  {:>11}",
        "D",
        "CPU pixels unlike no sphere's",
        "max |diff|",
        "PSNR (dB)",
        "hits differ"
    );
    let alone = render_both("stiff/case26", "no-sphere", &scene(None).flat());
    for distance in DISTANCES {
        let both = render_both("stiff/case26", &format!("sphere-{distance:e}"), &scene(Some(distance)).flat());
        let cpu = &both.cpu.image;
        let unlike = cpu.pixels.iter().zip(&alone.cpu.image.pixels).filter(|(a, b)| a != b).count();
        let Some(gpu) = &both.gpu else {
            both.ensure(unlike == 0, || {
                format!("D = {distance:e}: {unlike} CPU pixels unlike the image without the sphere")
            });
            continue;
        };
        let e = compare_images(cpu, &gpu.image);
        let hits = both.first_hit_mismatches().len();
        say!(out, "  {distance:>7.0e}  {unlike:>30}  {:>10.2e}  {:>10.1}  {hits:>11}", e.max_abs, e.psnr);
        both.ensure(unlike == 0 && hits == 0 && e.max_abs <= 1e-6, || {
            format!(
                "D = {distance:e}: {unlike} CPU pixels unlike the image without the sphere, GPU off by {:.2e}, {hits} hits differ",
                e.max_abs
            )
        });
    }
    eprint!("{out}");
    crate::generated::section("case26-far-object-out-of-sight", &out);
}
