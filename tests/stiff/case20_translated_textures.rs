//! Case 20: textures far from the world origin — a checker floor, an image texture with a UV
//! transform on a quad with vertex UVs, a clamped image and an emission texture on a sphere in
//! planar coordinates, a glass sphere refracting the checker and a mirror reflecting it, all
//! translated by T·(1, 1/2, −1) for T = 1e2 … 1e6.
//!
//! Expected: the GPU's image as close to its CPU reference at every T as at the origin (mean
//! FLIP within 2×, and 4 pixels' worth). Planar coordinates are taken relative to the GPU's
//! frame and each texture's coordinates of the frame's origin are computed once in f64 and
//! folded into its period (`rebase::place_texture_origins`): a checker edge 1e6 units out is
//! where it is at the origin. Before, the GPU took planar coordinates at the f32 world
//! position (1/16 apart at 1e6): checker edges moved, seen directly and through the glass
//! (FLIP 0.08 at 1e6 on the scene; this one's figures are in docs/numerics.md).

use glint_core::compare::flip_mean;
use glint_test_support::TempDir;
use glint_test_support::texture::write_fixture_textures;

use crate::gpu::render_both;
use crate::scene::{SceneText, arr};
use crate::{TRANSLATED_TEXTURES, Y};

const W: u32 = 96;
const H: u32 = 72;

/// The scene moved by `o`.
fn scene(o: [f64; 3]) -> SceneText {
    let p = |v: [f64; 3]| [v[0] + o[0], v[1] + o[1], v[2] + o[2]];
    let quad = [p([-1.5, -0.2, 1.0]), p([1.5, -0.2, 1.0]), p([1.5, 2.2, 1.0]), p([-1.5, 2.2, 1.0])];
    let uvs = [[0.0, 2.0], [3.0, 2.0], [3.0, -0.5], [0.0, -0.5]];
    let mirror = [p([-3.0, -0.2, -1.0]), p([-2.0, -0.2, 1.5]), p([-2.0, 2.0, 1.5]), p([-3.0, 2.0, -1.0])];
    SceneText::new(W, H, "max_depth = 4", p([0.3, 1.2, -3.5]), p([0.0, 0.6, 0.0]), Y, 60.0)
        .world([0.2; 3], [0.1, 0.1, 0.15])
        .material(
            "poster",
            "ka = 0.5\nkd = [0.9, 0.8, 0.7]\nks = 0.2\nshininess = 16.0\n\
             texture = { path = \"tex.png\", wrap_s = \"repeat\", wrap_t = \"mirrored_repeat\", \
             filter = \"bilinear\", transform = { offset = [0.1, 0.2], rotation = 0.3, scale = [1.25, 0.75] } }",
        )
        .material(
            "ball",
            "ka = 0.3\nkd = 0.7\nks = 0.3\nemission = 0.5\n\
             texture = { path = \"tex.png\", wrap_s = \"clamp_to_edge\", wrap_t = \"clamp_to_edge\", filter = \"nearest\", \
             transform = { offset = [0.5, 0.5], scale = [0.5, 0.5] } }\n\
             emission_texture = { path = \"glow.png\", filter = \"nearest\" }",
        )
        .material("floor", "ka = 0.3\nkd = [0.7, 0.6, 0.5]\nchecker = { kd = [0.2, 0.25, 0.3], size = 0.25 }")
        .material("glass", "ka = 0.0\nkd = 0.0\nks = 0.25\nshininess = 128.0\nkr = 0.125\nkt = 0.875\nior = 1.5")
        .material("mirror", "ka = 0.0\nkd = 0.0\nks = 0.0\nkr = 0.875")
        .light("point", &format!("position = {}\ndiffuse = 0.8\nspecular = 0.6", arr(p([-2.0, 4.0, -3.0]))))
        .plane(p([0.0, -0.2, 0.0]), Y, "floor")
        .sphere(p([0.9, 0.35, 0.2]), 0.55, "ball")
        .sphere(p([-0.6, 0.3, -0.8]), 0.5, "glass")
        .textured_mesh(&quad, &[[0, 1, 2], [0, 2, 3]], &uvs, "poster")
        .mesh(&mirror, &[[0, 1, 2], [0, 2, 3]], None, "mirror")
}

#[test]
fn textures_far_from_the_origin_are_as_accurate_on_the_gpu_as_at_the_origin() {
    let dir = TempDir::new("case20");
    write_fixture_textures(&dir);
    let mut out = String::new();
    say!(
        out,
        "case 20: checker, image textures, glass and a mirror translated by T·(1, 1/2, −1); GPU FLIP against its CPU"
    );
    let flip_at = |t: f64| {
        let flat = scene([t, t / 2.0, -t]).flat_in(&dir);
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
