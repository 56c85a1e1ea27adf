//! Textures on both tracers: a scene with every texture path (vertex UVs with a bilinear,
//! mirrored, transformed texture; planar UVs with a nearest, clamped one and an emission
//! texture on a sphere; the checker floor) against the CPU reference, with the parity
//! thresholds of `parity.rs`, and the probe's textured k_a and k_d term by term.

use glint_core::probe_pixel;
use glint_test_support::TempDir;
use glint_test_support::texture::textured_scene;
use glint_types::layout::feature;

use super::support::{compare_and_keep, cpu, gpu_or_skip, gpu_render, log_errors, within_parity, write_failure_images};

#[test]
fn textured_scene_matches_the_cpu_reference() {
    let tracer = gpu_or_skip!();
    let dir = TempDir::new("gpu-textures");
    let flat = textured_scene(&dir, 160, 120).flat_in(&dir);
    assert!(flat.header.features & feature::TEXTURES != 0);
    assert_eq!((flat.textures.len(), flat.uvs.len()), (4, 4), "poster, ball, glow, checker; the quad's UVs");
    let c = cpu(&flat);
    for specialise in [true, false] {
        let g = gpu_render(tracer, &flat, specialise);
        let name = format!("textured-specialised-{specialise}");
        let (e, base) = compare_and_keep("textures", &name, &c, &g);
        log_errors(&name, &e, g.status);
        let ok = within_parity(&e, g.status);
        if !ok {
            write_failure_images(&base, &c, &g);
        }
        assert!(ok, "{name}: GPU/CPU parity failed (images in target/tmp/gpu-tests/textures)");
    }
}

#[test]
fn probe_shows_the_textured_colours_on_both_tracers() {
    let tracer = gpu_or_skip!();
    let dir = TempDir::new("gpu-texture-probe");
    let flat = textured_scene(&dir, 160, 120).flat_in(&dir);
    let poster = flat.materials[flat.material_names.iter().position(|n| n == "poster").expect("poster")];
    let mut textured = 0;
    // The poster, the ball, the checker floor (both colours) and the background.
    for (x, y) in [(60, 40), (90, 50), (120, 58), (20, 110), (70, 112), (5, 5)] {
        let c = probe_pixel(&flat, x, y, 0).expect("valid tags");
        let (g, status) = tracer.probe_pixel(&flat, x, y).expect("GPU probe");
        assert_eq!(status, 0);
        assert_eq!(c.object_id, g.object_id, "({x}, {y}): first hit differs");
        for (term, a, b) in [("k_a", c.ka, g.ka), ("k_d", c.kd, g.kd), ("E_m", c.emission, g.emission)] {
            assert!((a - b).abs().max_element() <= 1e-5, "({x}, {y}) {term}: CPU {a} GPU {b}");
        }
        // Where a texture coloured the hit, k_a / k_d is the texel colour: the same ratio.
        if c.material as usize == flat.material_names.iter().position(|n| n == "poster").unwrap() {
            let (ka, kd) = (f64::from(poster.ka[0]), f64::from(poster.kd[0]));
            assert!((c.ka.x / ka - c.kd.x / kd).abs() < 1e-12, "({x}, {y}): k_a and k_d not modulated alike");
            textured += 1;
        }
    }
    assert!(textured >= 1, "no probe hit the textured poster");
}

#[test]
fn a_huge_checker_seen_near_its_origin_shows_its_four_squares_on_both_tracers() {
    // Squares of 1e7 and 1e9 (the largest allowed) meeting in view: u = x / (2·size) is within
    // 2^-25 of 0 there. Looking down at the origin (the GPU's frame origin there too), a point's
    // u < 0 folded to 1 − |u|, which f32 rounds onto 1, the first texel's edge. Looking at
    // x, z < 0, the frame origin's coordinates folded to 1 − 1e-9, 1 in f32, and 1 + a point's
    // own tiny u is 1 again. Either way half the floor took the other colour (PSNR 14.8 dB).
    let tracer = gpu_or_skip!();
    let views = [
        ("above", [0.3, 4.0, 0.2], [0.0; 3], [0.0, 0.0, 1.0]),
        ("aside", [0.3, 4.0, -3.0], [-0.5, 0.0, -0.7], [0.0, 1.0, 0.0]),
    ];
    for (view, eye, look_at, up) in views {
        for size in [1e7, 1e9] {
            let flat = glint_test_support::scene::SceneText::new(64, 48, "max_depth = 0", eye, look_at, up, 60.0)
                .world([0.2; 3], [0.0; 3])
                .material(
                    "floor",
                    &format!("kd = [0.9, 0.1, 0.1]\nchecker = {{ kd = [0.1, 0.1, 0.9], size = {size:?} }}"),
                )
                .light("directional", "direction = [0.0, -1.0, 0.0]")
                .plane([0.0; 3], [0.0, 1.0, 0.0], "floor")
                .flat();
            let c = cpu(&flat);
            let reds = c.image.pixels.iter().filter(|p| p.x > p.z).count();
            let name = format!("checker-{view}-{size:e}");
            assert!(
                reds * 4 > c.image.pixels.len() && reds * 4 < 3 * c.image.pixels.len(),
                "{name}: the CPU shows {reds} red pixels"
            );
            let g = gpu_render(tracer, &flat, true);
            let (e, base) = compare_and_keep("textures", &name, &c, &g);
            log_errors(&name, &e, g.status);
            if e.max_abs > 1e-5 {
                write_failure_images(&base, &c, &g);
            }
            assert!(
                e.max_abs <= 1e-5,
                "{name}: GPU off by {:.3e} (images in target/tmp/gpu-tests/textures)",
                e.max_abs
            );
        }
    }
}
