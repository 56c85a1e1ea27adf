//! Case 27: a huge triangle near the eye — a unit cube on a ground quad of half-size H (two
//! triangles, as exporters write a ground: glTF has no infinite plane), seen from about 4.5 away
//! under a directional light, at H = 1e4, 1e6 and 1e8 (96×72).
//!
//! Expected: the quad is the plane y = 0 wherever the picture sees it, so the CPU's image is the
//! image of the same cube on a plane primitive (to 1e-12), and the GPU's matches the CPU's (no
//! first hit that differs, largest difference ≤ 1e-5).
//!
//! Why it was stiff: the watertight test's t sums the corners' depths weighted by the edge
//! functions, terms of the size of the corners' distance (H) that cancel to the hit's (≈ 5), and
//! the robust offset re-projected the hit point by interpolating the corners, which carries their
//! rounding (f32's step at 1e8 is 8). On the GPU, shadows speckled from H = 1e4 and the ground
//! vanished at 1e8; the eye 2 mm over a cube of 1 mm on a quad of 1e6 lost 80 % of its first
//! hits. Where its error bound is 16× smaller, both twins now take t from the plane,
//! n·(a − o)/n·d, with n from the corners in a fixed order, and move the hit point along n
//! (`primitive::plane_t`, `triangle_surface_point`): exact for an axis-aligned ground.

use glint_core::compare::compare_images;

use crate::gpu::render_both;
use crate::scene::SceneText;

const HALF_SIZES: [f64; 3] = [1e4, 1e6, 1e8];

fn scene(ground_half_size: Option<f64>) -> SceneText {
    let (lo, hi) = (-0.5, 0.5);
    let corner = |i: usize| [[lo, hi][i & 1], [1e-4, 1.0001][(i >> 1) & 1], [lo, hi][i >> 2]];
    let cube: Vec<[f64; 3]> = (0..8).map(corner).collect();
    let faces = [
        [0, 2, 6, 4], // x = lo
        [1, 5, 7, 3], // x = hi
        [0, 4, 5, 1], // y = lo
        [2, 3, 7, 6], // y = hi
        [0, 1, 3, 2], // z = lo
        [4, 6, 7, 5], // z = hi
    ];
    let tris: Vec<[u32; 3]> = faces.iter().flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]]).collect();
    let text = SceneText::new(96, 72, "max_depth = 1", [1.5, 2.0, 4.0], [0.0, 0.4, 0.0], [0.0, 1.0, 0.0], 40.0)
        .world([0.1; 3], [0.3; 3])
        .material("ground", "kd = 0.9")
        .material("cube", "kd = [0.8, 0.2, 0.2]")
        .light("directional", "direction = [-0.5, -1.0, -0.3]")
        .mesh(&cube, &tris, None, "cube");
    match ground_half_size {
        Some(h) => text.mesh(
            &[[-h, 0.0, -h], [h, 0.0, -h], [h, 0.0, h], [-h, 0.0, h]],
            &[[0, 2, 1], [0, 3, 2]],
            None,
            "ground",
        ),
        None => text.plane([0.0; 3], [0.0, 1.0, 0.0], "ground"),
    }
}

#[test]
fn a_huge_ground_quad_near_the_eye_is_its_plane() {
    let mut out = String::new();
    say!(out, "case 27: a unit cube on a ground quad of half-size H, eye 4.5 away (96×72)");
    say!(
        out,
        "  {:>7}  {:>20}  {:>10}  {:>10}  {:>11}",
        "H",
        "CPU off the plane's",
        "max |diff|",
        "PSNR (dB)",
        "hits differ"
    );
    let plane = render_both("stiff/case27", "plane", &scene(None).flat());
    for h in HALF_SIZES {
        let both = render_both("stiff/case27", &format!("quad-{h:e}"), &scene(Some(h)).flat());
        let cpu = &both.cpu.image;
        let off = compare_images(cpu, &plane.cpu.image).max_abs;
        let Some(gpu) = &both.gpu else {
            both.ensure(off <= 1e-12, || format!("H = {h:e}: the CPU is {off:.2e} off the plane's image"));
            continue;
        };
        let e = compare_images(cpu, &gpu.image);
        let hits = both.first_hit_mismatches().len();
        say!(out, "  {h:>7.0e}  {off:>20.2e}  {:>10.2e}  {:>10.1}  {hits:>11}", e.max_abs, e.psnr);
        both.ensure(off <= 1e-12 && hits == 0 && e.max_abs <= 1e-5, || {
            format!("H = {h:e}: CPU {off:.2e} off the plane's image, GPU off by {:.2e}, {hits} hits differ", e.max_abs)
        });
    }
    eprint!("{out}");
    crate::generated::section("case27-huge-triangle-near-the-eye", &out);
}
