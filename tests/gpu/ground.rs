//! Models with a face at their lowest y (a floor panel facing up, one facing down, a box's
//! base) opened in the lab scene: its ground is never coplanar with them, so the two tracers
//! agree on every first hit. A ground at the model's lowest y z-fought with such faces: each
//! tracer picked its own winner pixel by pixel (21 % first-hit mismatch, FLIP 0.12).

use glint_core::FlatScene;
use glint_io::ImportOptions;
use glint_io::model::Ground;
use glint_io::{LoadOptions, load_scene_with};
use glint_scene::ObjectDesc;
use glint_test_support::TempDir;

use super::support::{compare_and_keep, cpu, gpu_or_skip, gpu_render, log_errors, within_parity, write_failure_images};

/// An OBJ of n×n quads in the plane y = 0 over [−1, 1]², facing up or down.
fn grid_obj(n: usize, up: bool) -> String {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, z) = (-1.0 + 2.0 * i as f64 / n as f64, -1.0 + 2.0 * j as f64 / n as f64);
            text += &format!("v {x} 0 {z}\n");
        }
    }
    let index = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
            // Counter-clockwise seen from +y is a → d → c → b.
            text += &if up { format!("f {a} {d} {c} {b}\n") } else { format!("f {a} {b} {c} {d}\n") };
        }
    }
    text
}

/// An OBJ of the unit cube on y = 0, faces outward (its base faces down).
fn box_obj() -> String {
    let mut text = String::new();
    for k in 0..8 {
        text += &format!("v {} {} {}\n", k & 1, (k >> 1) & 1, (k >> 2) & 1);
    }
    // Each face counter-clockwise seen from outside.
    text + "f 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\nf 1 3 4 2\nf 5 6 8 7\n"
}

#[test]
fn flat_models_and_a_box_on_the_lab_ground_agree_on_both_tracers() {
    let tracer = gpu_or_skip!();
    let dir = TempDir::new("ground");
    let cases = [
        ("floor-up", grid_obj(16, true), Ground::Auto, false),
        ("floor-up-on", grid_obj(16, true), Ground::On, true),
        ("floor-down", grid_obj(16, false), Ground::Auto, true),
        ("box", box_obj(), Ground::Auto, true),
    ];
    let mut failures = Vec::new();
    for (name, obj, ground, expect_ground) in cases {
        let path = dir.join(format!("{name}.obj"));
        std::fs::write(&path, obj).unwrap();
        let options =
            LoadOptions { import: ImportOptions { ground, ..ImportOptions::default() }, ..LoadOptions::default() };
        let loaded = load_scene_with(path.to_str().unwrap(), &options).unwrap_or_else(|e| panic!("{name}: {e}"));
        let plane = loaded.desc.objects.iter().find_map(|o| match o {
            ObjectDesc::Plane(p) => Some(p.point[1]),
            _ => None,
        });
        assert_eq!(plane.is_some(), expect_ground, "{name}: ground {plane:?} ({:?})", loaded.warnings);
        if let Some(y) = plane {
            assert!((y as f32) < 0.0, "{name}: the ground at y = {y} is coplanar with the model's base (y = 0)");
        }
        let mut s = loaded.desc.render.clone();
        (s.width, s.height, s.max_depth) = (160, 120, 3);
        let flat = FlatScene::build(&loaded.desc, &s);
        let c = cpu(&flat);
        let g = gpu_render(tracer, &flat, true);
        let (e, base) = compare_and_keep("ground", name, &c, &g);
        log_errors(name, &e, g.status);
        if !within_parity(&e, g.status) {
            write_failure_images(&base, &c, &g);
            failures.push(format!("{name}: mismatch {:.2} %, FLIP {:.4}", 100.0 * e.first_hit_mismatch, e.flip_mean));
        }
    }
    assert!(failures.is_empty(), "GPU/CPU parity failed: {failures:?} (images in target/tmp/gpu-tests/ground)");
}
