//! Vertex colours on both tracers: a quad with a red, green, blue and white corner beside an
//! uncoloured triangle, seen directly, in a mirror floor and through a glass sphere, against
//! the CPU reference with the parity thresholds of `parity.rs`; and the probe's k_a and k_d,
//! which the colour multiplies, term by term.

use glint_core::probe_pixel;
use glint_test_support::scene::vertex_colour_scene;
use glint_types::layout::feature;

use super::support::{compare_and_keep, cpu, gpu_or_skip, gpu_render, log_errors, within_parity, write_failure_images};

#[test]
fn vertex_coloured_scene_matches_the_cpu_reference() {
    let tracer = gpu_or_skip!();
    let flat = vertex_colour_scene(160, 120, true).flat();
    assert!(flat.header.features & feature::VERTEX_COLOURS != 0);
    let c = cpu(&flat);
    for specialise in [true, false] {
        let g = gpu_render(tracer, &flat, specialise);
        let name = format!("vertex-colours-specialised-{specialise}");
        let (e, base) = compare_and_keep("vertex-colours", &name, &c, &g);
        log_errors(&name, &e, g.status);
        let ok = within_parity(&e, g.status);
        if !ok {
            write_failure_images(&base, &c, &g);
        }
        assert!(ok, "{name}: GPU/CPU parity failed (images in target/tmp/gpu-tests/vertex-colours)");
    }
}

#[test]
fn probe_shows_the_vertex_coloured_k_a_and_k_d_on_both_tracers() {
    let tracer = gpu_or_skip!();
    let flat = vertex_colour_scene(160, 120, true).flat();
    let paint = flat.material_names.iter().position(|n| n == "paint").expect("paint") as u32;
    let kd = glam::DVec3::from_array([0, 1, 2].map(|k| f64::from(flat.materials[paint as usize].kd[k])));
    let (mut coloured, mut white) = (0, 0);
    // Across the quad (red bottom left, green bottom right, blue top right, white top left),
    // the uncoloured triangle, the floor's reflection and the sphere.
    for (x, y) in [(45, 75), (70, 70), (60, 40), (40, 45), (121, 58), (60, 105), (105, 85)] {
        let c = probe_pixel(&flat, x, y, 0).expect("valid tags");
        let (g, status) = tracer.probe_pixel(&flat, x, y).expect("GPU probe");
        assert_eq!(status, 0);
        assert_eq!(c.object_id, g.object_id, "({x}, {y}): first hit differs");
        for (term, a, b) in [("k_a", c.ka, g.ka), ("k_d", c.kd, g.kd)] {
            assert!((a - b).abs().max_element() <= 1e-5, "({x}, {y}) {term}: CPU {a} GPU {b}");
        }
        if c.material == paint {
            // k_a = 1 · colour and k_d = 0.8 · colour: one colour, k_d / k_a = 0.8 in every channel.
            let ratio = c.kd / c.ka.max(glam::DVec3::splat(1e-300));
            let coloured_here = (c.kd - kd).abs().max_element() > 1e-6;
            if coloured_here {
                assert!((ratio - glam::DVec3::splat(0.8)).abs().max_element() < 1e-6, "({x}, {y}): {ratio}");
                coloured += 1;
            } else {
                white += 1;
            }
        }
    }
    assert!(coloured >= 3 && white >= 1, "{coloured} coloured and {white} uncoloured paint hits");
}
