//! Case 19: coplanar overlapping surfaces — two quads in one oblique plane, overlapping on half
//! their area, triangulated along different diagonals (so the two t values of a ray are
//! computed from different vertices and round differently), and a model-style floor face
//! lying on a ground plane.
//!
//! Expected: no tracer can pick a consistent winner here. Case 4's tie rule (scene order)
//! decides only exact ties; where the two t values round differently, rounding decides, pixel
//! by pixel, and differently in f64 and in f32 ("z-fighting"). What Glint guarantees is that
//! the scene says so: validation warns at load, naming both objects and the overlap's area,
//! and both tracers stay deterministic. The pixels each surface wins are printed.

use glint_io::parse_scene;

use crate::Y;
use crate::gpu::render_both;
use crate::render::render_cpu_checked;
use crate::scene::SceneText;

const W: u32 = 64;
const H: u32 = 48;

/// A point of the plane z = 1.3 + 0.2·x − 0.1·y.
fn p(x: f64, y: f64) -> [f64; 3] {
    [x, y, 1.3 + 0.2 * x - 0.1 * y]
}

#[test]
fn coplanar_overlaps_are_named_at_load_and_deterministic_on_both_backends() {
    let mut out = String::new();
    say!(out, "case 19: coplanar overlapping surfaces; pixels won by the first / the second, CPU / GPU");
    // Quad A over x in [-0.9, 0.3], quad B over x in [-0.3, 0.9]: they share x in [-0.3, 0.3].
    let (a, b) = (
        [p(-0.9, -0.7), p(0.3, -0.7), p(0.3, 0.7), p(-0.9, 0.7)],
        [p(-0.3, -0.7), p(0.9, -0.7), p(0.9, 0.7), p(-0.3, 0.7)],
    );
    let scene = SceneText::new(W, H, "max_depth = 0", [0.31, 0.17, -1.0], [0.0, 0.0, 1.3], Y, 60.0)
        .world([0.25; 3], [0.0; 3])
        .material("first", "ka = [1.0, 0.0, 0.0]\nkd = 0.0")
        .material("second", "ka = [0.0, 1.0, 0.0]\nkd = 0.0")
        .mesh(&a, &[[0, 1, 2], [0, 2, 3]], None, "first")
        .mesh(&b, &[[1, 2, 3], [1, 3, 0]], None, "second");
    let (desc, warnings) = parse_scene(&scene.text, std::path::Path::new("case19.toml")).expect("loads");
    let named = warnings
        .iter()
        .find(|w| w.problem.contains("z-fighting"))
        .unwrap_or_else(|| panic!("no warning: {warnings:?}"));
    assert!(named.problem.contains("objects[0]") && named.problem.contains("objects[1]"), "{}", named.problem);
    // The shared part: 0.6 × 1.4 in x–y, stretched by the plane's slope: √(1 + 0.2² + 0.1²).
    let area = 0.6 * 1.4 * (1.0_f64 + 0.04 + 0.01).sqrt();
    let stated = format!("{area:.4e}");
    assert!(named.problem.contains(&stated), "area {stated} not in: {}", named.problem);
    say!(out, "  warning at load: {}", named.problem);

    let flat = glint_core::FlatScene::build(&desc, &desc.render);
    let both = render_both("stiff/case19", "overlapping-quads", &flat);
    let mut counts = Vec::new();
    for (_, img) in both.images() {
        let first = img.first_hit.iter().filter(|&&h| h == 0).count();
        let second = img.first_hit.iter().filter(|&&h| h == 1).count();
        counts.push(format!("{first} / {second}"));
    }
    for threads in [1, 2] {
        let again = render_cpu_checked(&flat, threads, true);
        assert_eq!(again.image.first_hit, both.cpu.image.first_hit, "the winner changed with {threads} threads");
    }
    say!(
        out,
        "  overlapping quads: {} ({} pixels differ between the backends)",
        counts.join("   "),
        both.first_hit_mismatches().len()
    );

    // A floor face on a ground plane, as a model's base on the old lab ground was.
    let floor = SceneText::new(W, H, "max_depth = 0", [0.0, 2.0, -3.0], [0.0; 3], Y, 60.0)
        .material("ground", "ka = 0.5")
        .material("floor", "ka = 0.9")
        .plane([0.0; 3], Y, "ground")
        .mesh(
            &[[-1.0, 0.0, -1.0], [1.0, 0.0, -1.0], [1.0, 0.0, 1.0], [-1.0, 0.0, 1.0]],
            &[[0, 2, 1], [0, 3, 2]],
            None,
            "floor",
        );
    let (_, warnings) = parse_scene(&floor.text, std::path::Path::new("floor.toml")).expect("loads");
    let named = warnings
        .iter()
        .find(|w| w.problem.contains("z-fighting"))
        .unwrap_or_else(|| panic!("no warning: {warnings:?}"));
    assert!(named.problem.contains("area of 4.0000e0"), "{}", named.problem);
    say!(out, "  floor face on a ground plane: warned, area 4 (2 × 2)");
    eprint!("{out}");
}
