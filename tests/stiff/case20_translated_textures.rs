//! Case 20: textures far from the world origin — the GPU tests' textured scene (a checker floor,
//! an image texture with a UV transform on a quad with vertex UVs, a clamped image and an
//! emission texture on a sphere in planar coordinates) with a glass sphere refracting the
//! checker and a mirror reflecting it, translated by T·(1, 1/2, −1) for T = 1e2 … 1e6.
//!
//! Expected: the GPU's image as close to its CPU reference at every T as at the origin (mean
//! FLIP within 2×, and 4 pixels' worth). Planar coordinates are taken relative to the GPU's
//! frame and each texture's coordinates of the frame's origin are computed once in f64 and
//! folded into its period (`texture_table::planar_origins`): a checker edge 1e6 units out is
//! where it is at the origin. Before, the GPU took planar coordinates at the f32 world
//! position (1/16 apart at 1e6): checker edges moved, seen directly and through the glass
//! (FLIP 0.08 at 1e6 on the scene; this one's figures are in docs/numerics.md).

use glint_core::compare::flip_mean;
use glint_test_support::TempDir;
use glint_test_support::render::render_cpu_checked;
use glint_test_support::texture::textured_scene_moved;

use crate::TRANSLATED_TEXTURES;
use crate::gpu::render_both;
use crate::scene::SceneText;

const W: u32 = 96;
const H: u32 = 72;

/// The textured scene of the GPU tests with a glass sphere and a mirror, moved by `o`.
fn scene(dir: &std::path::Path, o: [f64; 3]) -> SceneText {
    let p = |v: [f64; 3]| [v[0] + o[0], v[1] + o[1], v[2] + o[2]];
    let mirror = [p([-3.0, -0.2, -1.0]), p([-2.0, -0.2, 1.5]), p([-2.0, 2.0, 1.5]), p([-3.0, 2.0, -1.0])];
    textured_scene_moved(dir, W, H, 4, o)
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.25\nshininess = 128.0\nkr = 0.125\nkt = 0.875\nior = 1.5")
        .material("mirror", "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.875")
        .sphere(p([-0.6, 0.3, -0.8]), 0.5, "glass")
        .mesh(&mirror, &[[0, 1, 2], [0, 2, 3]], None, "mirror")
}

#[test]
fn textures_far_from_the_origin_are_as_accurate_on_the_gpu_as_at_the_origin() {
    let dir = TempDir::new("case20");
    let mut out = String::new();
    say!(
        out,
        "case 20: checker, image textures, glass and a mirror translated by T·(1, 1/2, −1); GPU FLIP against its CPU"
    );
    let flip_at = |t: f64| {
        let flat = scene(&dir, [t, t / 2.0, -t]).flat_in(&dir);
        let both = render_both("stiff/case20", &format!("T{t:e}"), &flat);
        both.gpu.as_ref().map(|g| flip_mean(&both.cpu.image, &g.image))
    };
    let Some(base) = flip_at(0.0) else {
        eprintln!("case 20: no GPU, nothing to compare");
        return;
    };
    say!(out, "  {:>8}  {:>9}", "T", "FLIP");
    say!(out, "  {:>8}  {:>9.2e}", 0, base);
    // 4 pixels' worth of FLIP: one pixel decided the other way at a texel edge is no drift.
    let allowed = 2.0 * base + 4.0 / f64::from(W * H);
    let mut failures = Vec::new();
    for t in TRANSLATED_TEXTURES {
        let flip = flip_at(t).expect("the GPU rendered the origin");
        say!(out, "  {:>8.0e}  {:>9.2e}", t, flip);
        if flip > allowed {
            failures
                .push(format!("T = {t:e}: FLIP {flip:.2e} > {allowed:.2e} (2× the origin's {base:.2e} + 4 pixels)"));
        }
    }
    eprint!("{out}");
    crate::generated::section("case20-textures", &out);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A checker floor of size 0.3 (its scale 1/0.6 is not an f32) and a sphere, moved by `o`.
fn checker_scene(o: [f64; 3]) -> SceneText {
    let p = |v: [f64; 3]| [v[0] + o[0], v[1] + o[1], v[2] + o[2]];
    SceneText::new(96, 72, "max_depth = 0", p([0.3, 1.5, -5.0]), p([0.2, 0.5, 0.0]), crate::Y, 40.0)
        .world([0.0; 3], [0.0; 3])
        .material("f", "ka = 0.0\nkd = 0.8\nchecker = { kd = 0.2, size = 0.3 }")
        .light("directional", "direction = [0.3, -1.0, 0.5]")
        .plane(p([0.0; 3]), crate::Y, "f")
        .sphere(p([0.0, 0.8, 0.0]), 0.8, "f")
}

#[test]
fn a_checker_moved_by_whole_periods_is_where_it_was_on_the_cpu() {
    // (750000, 0, −9019794) periods of 0.6: every square lands where it was. Before, each
    // texture's planar origin was placed with its f32 scale (1/0.6 rounded by 3e-8), whose
    // error times 9e6 periods is half a period: 2053 of 6912 pixels took the other colour, on
    // both tracers alike.
    let at = |o: [f64; 3]| render_cpu_checked(&checker_scene(o).flat(), 2, true).image;
    let (origin, moved) = (at([0.0; 3]), at([450_000.0, 0.0, -5_411_876.4]));
    let differing = origin.pixels.iter().zip(&moved.pixels).filter(|(a, b)| (0..3).any(|c| (a[c] - b[c]).abs() > 1e-3));
    assert_eq!(differing.count(), 0, "pixels of the moved checker unlike the origin's");
}
