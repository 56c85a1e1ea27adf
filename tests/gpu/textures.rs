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
        let c = probe_pixel(&flat, x, y, 0);
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
