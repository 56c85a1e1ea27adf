//! Case 20: textures far from the world origin — the GPU tests' textured scene (a checker floor,
//! an image texture with a UV transform on a quad with vertex UVs, a clamped image and an
//! emission texture on a sphere in planar coordinates) with a glass sphere refracting the
//! checker and a mirror reflecting it, translated by T·(1, 1/2, −1) for T = 1e2 … 1e6.
//!
//! Expected: the GPU's image as close to its CPU reference at every T as at the origin (mean
//! FLIP within 2×, and 4 pixels' worth). Planar coordinates are taken relative to the GPU's
//! frame and each texture's coordinates of the frame's origin are computed once in f64 and
//! folded into its period (`flat::place_texture_origins`): a checker edge 1e6 units out is
//! where it is at the origin. Before, the GPU took planar coordinates at the f32 world
//! position (1/16 apart at 1e6): checker edges moved, seen directly and through the glass
//! (FLIP 0.08 at 1e6 on the scene; this one's figures are in docs/numerics.md).

use glint_core::compare::flip_mean;
use glint_test_support::TempDir;
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
