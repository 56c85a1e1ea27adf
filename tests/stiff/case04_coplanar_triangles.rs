//! Case 4: coplanar duplicate triangles — the same triangle twice, as two objects with
//! different materials, seen obliquely so that the ray parameters are not round numbers.
//!
//! Expected: a deterministic winner, the same on both backends — the first object, on every
//! pixel: a tie goes to the primitive tested first (scene order) on both tracers, and the
//! duplicates tie exactly, also with the copy's vertices rotated (b, c, a) or its winding
//! reversed (a, c, b) — two one-sided faces back to back, as meshes for one-sided renderers
//! have them. The watertight test permutes its edge functions exactly with the vertices, and
//! sums them smallest magnitude first (`sum_by_magnitude`), so t is bit-identical. (Summed in
//! vertex order, the permuted copies won 67–84 of 501 pixels each, differently on the two
//! backends: z-fighting.) For
//! comparison, a triangle lying in a plane object is printed too: plane and triangle compute t
//! by different formulas, so which one wins is a matter of rounding ("z-fighting"); it is only
//! required to be deterministic.

use glint_types::layout::NO_HIT;

use crate::Y;
use crate::gpu::render_both;
use crate::render::render_cpu_checked;
use crate::scene::SceneText;

const W: u32 = 48;
const H: u32 = 40;

type Tri = [[f64; 3]; 3];

/// A triangle in the plane z = 1.3 + 0.2·x − 0.1·y, large in the view.
fn tri() -> Tri {
    let p = |x: f64, y: f64| [x, y, 1.3 + 0.2 * x - 0.1 * y];
    [p(-0.97, -0.81), p(0.89, -0.73), p(-0.03, 0.87)]
}

/// The second copy of `t` in each of the three forms.
fn copies(t: Tri) -> [(&'static str, Tri); 3] {
    let [a, b, c] = t;
    [("identical", [a, b, c]), ("rotated", [b, c, a]), ("reversed", [a, c, b])]
}

#[test]
fn coplanar_duplicates_have_a_deterministic_winner_on_both_backends() {
    let mut out = String::new();
    say!(out, "case 4: coplanar duplicate triangles; pixels won by the first / the second copy, CPU / GPU");
    let mut coverage = None;
    for (i, (form, second)) in copies(tri()).into_iter().enumerate() {
        let scene = SceneText::new(W, H, "max_depth = 0", [0.31, 0.17, -1.0], [0.0, 0.0, 1.3], Y, 50.0)
            .world([0.25; 3], [0.0; 3])
            .material("first", "ka = [1.0, 0.0, 0.0]\nkd = 0.0")
            .material("second", "ka = [0.0, 1.0, 0.0]\nkd = 0.0")
            .triangles(&[tri()], None, "first")
            .triangles(&[second], None, "second");
        let flat = scene.flat();
        let both = render_both("stiff/case04", &format!("coplanar-{form}"), &flat);
        let mut counts = Vec::new();
        for (backend, img) in both.images() {
            let first = img.first_hit.iter().filter(|&&h| h == 0).count();
            let second = img.first_hit.iter().filter(|&&h| h == 1).count();
            both.ensure(first > 300, || format!("{}: the triangle covers only {first} pixels", backend.name()));
            both.ensure(second == 0, || {
                format!("{}: the second of two {form} duplicates won {second} pixels", backend.name())
            });
            coverage.get_or_insert(first + second);
            counts.push(format!("{first} / {second}"));
        }
        // Deterministic: the same pixels on a repeat and with another thread count.
        for threads in [1, 2] {
            let again = render_cpu_checked(&flat, threads, true);
            assert_eq!(
                again.image.first_hit, both.cpu.image.first_hit,
                "{form}: the winner changed with {threads} threads"
            );
        }
        if let Some(g) = &both.gpu {
            let again = crate::gpu::gpu_render(crate::gpu::gpu().unwrap(), &flat, true);
            assert_eq!(again.image.first_hit, g.image.first_hit, "{form}: the GPU winner changed on a repeat");
        }
        let mismatches = both.first_hit_mismatches();
        both.ensure(mismatches.is_empty(), || format!("{form}: the backends disagree on {} pixels", mismatches.len()));
        say!(out, "  {i}: duplicate {form:<10} {}", counts.join("   "));
    }

    // A triangle in a plane object (the plane is tested first): z-fighting, reported.
    let t = tri();
    let (a, b, c) = (glam::DVec3::from(t[0]), glam::DVec3::from(t[1]), glam::DVec3::from(t[2]));
    let n = (b - a).cross(c - a).normalize();
    let scene = SceneText::new(W, H, "max_depth = 0", [0.31, 0.17, -1.0], [0.0, 0.0, 1.3], Y, 50.0)
        .world([0.25; 3], [0.0; 3])
        .material("first", "ka = [1.0, 0.0, 0.0]\nkd = 0.0")
        .material("second", "ka = [0.0, 1.0, 0.0]\nkd = 0.0")
        .plane(t[0], n.to_array(), "first")
        .triangles(&[t], None, "second");
    let flat = scene.flat();
    let both = render_both("stiff/case04", "plane-and-triangle", &flat);
    let covered = coverage.unwrap_or(0);
    let mut counts = Vec::new();
    for (_, img) in both.images() {
        assert!(img.first_hit.iter().all(|&h| h != NO_HIT), "the plane fills the view");
        let triangle = img.first_hit.iter().filter(|&&h| h == 1).count();
        counts.push(format!("{triangle} of {covered}"));
    }
    let again = render_cpu_checked(&flat, 2, true);
    assert_eq!(again.image.first_hit, both.cpu.image.first_hit, "plane/triangle: the winner changed with 2 threads");
    say!(
        out,
        "  triangle inside a plane object: pixels won by the triangle, CPU / GPU: {} (rounding decides; {} differ)",
        counts.join(" / "),
        both.first_hit_mismatches().len()
    );
    eprint!("{out}");
    crate::generated::section("case04-coplanar", &out);
}
