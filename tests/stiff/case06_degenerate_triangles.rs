//! Case 6: degenerate triangles — three collinear vertices, a repeated vertex, all three
//! vertices equal — and a 1e6-aspect needle, with and without vertex normals, under a point
//! light with a specular term, in front of a wall.
//!
//! Most of the degenerate triangles lie on lines through the camera position, the stiffest
//! placement there is: every camera ray then sees the triangle edge-on, all three edge functions
//! of the watertight test are zero in exact arithmetic, and only rounding decides their signs.
//! (Before flat.rs left zero-area triangles out, the one on the view axis was "hit" on 638 of
//! 2304 pixels on the CPU and 713 on the GPU, with a 0/0 geometric normal; its NaN was only
//! hidden because every comparison with it is false.)
//!
//! Expected, on both backends: no pixel is ever NaN or infinite, and a triangle of zero area in
//! the stored data is never hit (validation promises as much: "they are never hit"). The needle
//! (area 5e-7) is a real triangle; it may be hit or not, but stays finite.

use crate::gpu::render_both;
use crate::scene::SceneText;
use crate::{Y, Z};

const W: u32 = 48;
const H: u32 = 48;

/// Points s·dir for the given s: on a line through the camera at the origin.
fn on_ray(dir: [f64; 3], s: [f64; 3]) -> [[f64; 3]; 3] {
    s.map(|s| dir.map(|c| c * s))
}

fn scene(normals: bool) -> (SceneText, Vec<[[f64; 3]; 3]>) {
    // Collinear on lines through the camera, with exactly representable (dyadic) components so
    // that they stay exactly collinear in f32 (the first is the one that was hit: on the axis).
    let degenerate: Vec<[[f64; 3]; 3]> = vec![
        on_ray([0.25, 0.125, 1.0], [2.0, 3.0, 4.0]),
        on_ray([-0.125, 0.25, 1.0], [4.0, 2.0, 3.0]),
        on_ray([0.0, 0.0, 1.0], [2.0, 3.0, 5.0]),
        // repeated vertex and all equal
        {
            let [a, _, c] = on_ray([0.0625, -0.25, 1.0], [2.0, 3.0, 4.0]);
            [a, a, c]
        },
        [[0.5, 0.5, 3.0]; 3],
        // collinear, but not on a line through the camera
        [[-0.5, -0.25, 3.0], [0.0, 0.0, 3.5], [0.5, 0.25, 4.0]],
    ];
    let mut s = SceneText::new(W, H, "max_depth = 0", [0.0; 3], Z, Y, 40.0)
        .world([0.125; 3], [0.0; 3])
        .material("m", "ka = 0.5\nkd = 0.5\nks = 0.5\nshininess = 20.0")
        .light("point", "position = [0.4, 0.8, -0.5]\ndiffuse = 1.0\nspecular = 1.0");
    let up = [[0.0, 1.0, 0.0]; 3];
    for t in &degenerate {
        // With normals: all three equal, so the shading normal is fine while the geometric
        // normal is the cross product of the zero-area triangle.
        s = s.triangles(&[*t], normals.then_some(&up[..]), "m");
    }
    assert!(!zero_area(&on_ray([0.3, 0.2, 1.0], [2.0, 3.0, 4.0])), "the sliver must not be degenerate in f32");
    // On a line through the camera too, but with inexact (non-dyadic) coordinates: collinear in
    // decimal, a sliver of nonzero area once rounded to f32 — a real triangle, seen edge-on.
    s = s.triangles(&[on_ray([0.3, 0.2, 1.0], [2.0, 3.0, 4.0])], None, "m");
    // Two needles (aspect 1e6) whose long axes lie, within rounding, on a row and on a column of
    // pixel rays: the rays of row 24 meet z = 3 at y = −3·tan 20°/48, those of column 24 meet
    // z = 2.5 at x = −2.5·tan 20°/48 (the camera's right vector is −x).
    let half = 20.0_f64.to_radians().tan();
    let (ye, xc) = (-3.0 * half / 48.0 - 2e-7, -2.5 * half / 48.0);
    s = s.triangles(&[[[-0.6, ye, 3.0], [0.6, ye, 3.0], [0.0, ye + 1e-6, 3.0]]], None, "m");
    s = s.triangles(&[[[xc, -0.6, 2.5], [xc + 1e-6, 0.6, 2.5], [xc - 1e-6, 0.6, 2.5]]], None, "m");
    (s.plane([0.0, 0.0, 6.0], [0.0, 0.0, -1.0], "m"), degenerate)
}

/// Whether the triangle has zero area once its vertices are rounded to f32 (as stored).
fn zero_area(t: &[[f64; 3]; 3]) -> bool {
    let [a, b, c] = t.map(|v| glam::DVec3::from_array(v.map(|x| f64::from(x as f32))));
    (b - a).cross(c - a) == glam::DVec3::ZERO
}

#[test]
fn degenerate_triangles_are_never_nan_and_never_hit() {
    let mut out = String::new();
    say!(out, "case 6: degenerate triangles on lines through the camera; pixels hitting each object, CPU / GPU");
    for normals in [false, true] {
        let (text, degenerate) = scene(normals);
        assert!(degenerate.iter().all(zero_area), "the degenerate triangles are not degenerate in f32");
        let flat = text.flat();
        let both = render_both("stiff/case06", &format!("degenerate-normals-{normals}"), &flat);
        let mut hits_per_object = vec![Vec::new(); flat.object_names.len()];
        for (backend, img) in both.images() {
            for (id, hits) in hits_per_object.iter_mut().enumerate() {
                let n = img.first_hit.iter().filter(|&&h| h == id as u32).count();
                hits.push(n.to_string());
                if id < degenerate.len() {
                    both.ensure(n == 0, || {
                        format!("{}: the zero-area triangle {id} was hit on {n} pixels", backend.name())
                    });
                }
            }
        }
        let row: Vec<String> =
            hits_per_object.iter().enumerate().map(|(i, h)| format!("#{i}: {}", h.join("/"))).collect();
        say!(out, "  vertex normals {normals:<5}  {}", row.join("  "));
    }
    eprint!("{out}");
}
