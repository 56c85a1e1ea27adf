//! Case 8: the camera inside a sphere, exactly on its surface, and outside looking at its
//! silhouette (tangent rays). A wall behind makes every miss of the sphere visible.
//!
//! Expected, on both backends: inside, every ray finds the far side of the sphere (both roots
//! are taken from the stable quadratic; the near one is negative); on the surface (c = |o − C|²
//! − r² = 0 exactly in f32) rays into the sphere find its far side, rays out of it see the wall,
//! and the rays of the tangent plane find nothing at t > 0; outside, pixels inside the
//! silhouette see the sphere. Where the two backends disagree on the first hit, the ray is
//! tangent to within the ring measured below: |cos| of its angle with the tangent plane (on the
//! surface) or the discriminant over r² (outside) below the ring width.

use glam::DVec3;
use glint_core::FlatScene;

use crate::gpu::{Both, render_both};
use crate::reference::primary_ray;
use crate::scene::SceneText;
use crate::{Y, Z};

const N: u32 = 41;

/// Measured (lavapipe): in all three views the GPU's first hits equal the CPU's on every pixel
/// (the tangent-plane rays of the on-surface view included: c = 0 and b = 0 exactly in f32 too).
/// Allowed: disagreements within 1e-5 of tangency, ≈ 100 times the f32 rounding of a ray
/// direction, where either answer is right.
const RING: f64 = 1e-5;

fn scene(position: [f64; 3], look_at: [f64; 3], up: [f64; 3], fov: f64) -> FlatScene {
    SceneText::new(N, N, "max_depth = 0", position, look_at, up, fov)
        .world([0.25; 3], [0.0; 3])
        .material("ball", "ka = 1.0\nkd = 0.5\nks = 0.5\nshininess = 10.0")
        .material("wall", "ka = 0.5\nkd = 0.5\nks = 0.0")
        .light("point", "position = [0.2, 0.3, -0.4]")
        .sphere([0.0; 3], 1.0, "ball") // object 0
        .plane([0.0, 0.0, -5.0], Z, "wall") // object 1, behind the camera on the surface
        .plane([0.0, 0.0, 6.0], [0.0, 0.0, -1.0], "wall") // object 2, behind the sphere
        .flat()
}

/// Checks that the first hit is `want(x, y)` where that is decided (Some), and that the
/// backends disagree only where `ring(x, y)` (a measure of tangency) is below RING. Returns the
/// number of mismatches and the largest ring value among them.
fn check(
    both: &Both,
    flat: &FlatScene,
    want: impl Fn(DVec3, DVec3) -> Option<u32>,
    ring: impl Fn(DVec3, DVec3) -> f64,
) -> (usize, f64) {
    for (backend, img) in both.images() {
        for y in 0..N {
            for x in 0..N {
                let (o, d) = primary_ray(flat, x, y);
                let got = img.first_hit[(y * N + x) as usize];
                if let Some(w) = want(o, d).filter(|_| ring(o, d) >= RING) {
                    both.ensure(got == w, || format!("{} ({x}, {y}): first hit {got}, expected {w}", backend.name()));
                }
            }
        }
    }
    let mismatches = both.first_hit_mismatches();
    let mut worst = 0.0_f64;
    for &i in &mismatches {
        let (x, y) = (i as u32 % N, i as u32 / N);
        let (o, d) = primary_ray(flat, x, y);
        let r = ring(o, d);
        worst = worst.max(r);
        both.ensure(r < RING, || format!("({x}, {y}): the backends disagree on a ray {r:e} from tangency"));
    }
    (mismatches.len(), worst)
}

#[test]
fn camera_inside_on_and_outside_a_sphere() {
    let mut out = String::new();
    say!(out, "case 8: first-hit mismatches GPU vs CPU, and how far from tangency the worst one is");
    // Inside: every ray hits the sphere (object 0), far from any tangency.
    let flat = scene([0.3, 0.2, -0.1], [0.3, 0.2, 1.0], Y, 90.0);
    let both = render_both("stiff/case08", "inside", &flat);
    let (n, worst) = check(&both, &flat, |_, _| Some(0), |_, _| 1.0);
    say!(out, "  inside the sphere:      {n} mismatches (worst {worst:.1e})");
    both.ensure(n == 0, || format!("{n} mismatches inside the sphere"));

    // On the surface at (0, 0, −1), looking along the tangent +x: the image's columns run
    // along z, the centre column is the tangent plane z = −1 itself (d.z = 0 exactly).
    let flat = scene([0.0, 0.0, -1.0], [1.0, 0.0, -1.0], Y, 90.0);
    let both = render_both("stiff/case08", "on-surface", &flat);
    let (n, worst) = check(
        &both,
        &flat,
        |_, d| Some(if d.z > 0.0 { 0 } else { 1 }),
        |_, d| d.z.abs(), // cos of the angle with the tangent plane
    );
    say!(out, "  on the surface:         {n} mismatches (worst |d·n| {worst:.1e})");
    let centre: Vec<u32> =
        both.cpu.image.first_hit.iter().skip((N / 2) as usize).step_by(N as usize).copied().collect();
    assert!(centre.iter().all(|&h| h != 0), "a tangent-plane ray hit the sphere at t > 0 on the CPU: {centre:?}");

    // Outside, the silhouette filling most of the view.
    let flat = scene([0.0, 0.0, -3.0], [0.0; 3], Y, 45.0);
    let both = render_both("stiff/case08", "outside", &flat);
    let disc = |o: DVec3, d: DVec3| {
        let b = o.dot(d);
        (b * b - (o.dot(o) - 1.0)).abs()
    };
    let (n, worst) =
        check(&both, &flat, |o, d| Some(if o.dot(d).powi(2) - (o.dot(o) - 1.0) > 0.0 { 0 } else { 2 }), disc);
    say!(out, "  outside (tangent rays): {n} mismatches (worst |disc|/r² {worst:.1e})");
    eprint!("{out}");
}
