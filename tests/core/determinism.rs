//! Same bits for any thread count, and with or without feature specialisation.

use std::path::Path;

use glint_core::{CpuRender, FlatScene};
use glint_io::{BUILTIN_SCENES, parse_scene};

use crate::support::render_with;

fn identical(a: &CpuRender, b: &CpuRender, what: &str) {
    assert_eq!(a.image.pixels.len(), b.image.pixels.len(), "{what}");
    for (i, (p, q)) in a.image.pixels.iter().zip(&b.image.pixels).enumerate() {
        let (pb, qb) = (p.to_array().map(f64::to_bits), q.to_array().map(f64::to_bits));
        assert_eq!(pb, qb, "{what}: pixel {i} differs: {p} vs {q}");
    }
    assert_eq!(a.image.first_hit, b.image.first_hit, "{what}: first-hit ids");
    assert_eq!(a.counts, b.counts, "{what}: ray counts");
}

#[test]
fn builtin_scenes_are_bit_identical_across_threads_and_specialisation() {
    // The scene files; the generated scenes are tested by their generator and `glint bench rays`.
    let files: Vec<_> = BUILTIN_SCENES.iter().filter_map(|b| Some((b, b.toml()?))).collect();
    assert_eq!(files.len(), 5);
    for (scene, text) in files {
        let (desc, _) = parse_scene(text, Path::new(scene.name)).expect("built-in scene loads");
        for spp in [1, 4] {
            let mut settings = desc.render.clone();
            // 96×72: six by five tiles of 16×16, the last row and column partial.
            settings.width = 96;
            settings.height = 72;
            settings.spp = spp;
            let flat = FlatScene::build(&desc, &settings);
            let what = |s: &str| format!("{} at spp {spp}: {s}", scene.name);
            let one = render_with(&flat, 1, true);
            assert_eq!(one.threads, 1);
            assert!(one.counts.camera == 96 * 72 * u64::from(spp), "{}", what("camera rays"));
            // Not a constant image: the comparison below would be vacuous.
            let first = one.image.pixels[0];
            assert!(one.image.pixels.iter().any(|p| *p != first), "{}", what("constant image"));
            for threads in [2, 3] {
                identical(&one, &render_with(&flat, threads, true), &what(&format!("1 vs {threads} threads")));
            }
            identical(&one, &render_with(&flat, 2, false), &what("specialised vs unspecialised"));
            // The same render twice.
            identical(&one, &render_with(&flat, 1, true), &what("repeat"));
        }
    }
}

#[test]
fn jitter_really_moves_samples() {
    // spp 4 must differ from spp 1 (otherwise the spp 4 runs above test nothing new), and a
    // different seed must give a different image.
    let scene = &BUILTIN_SCENES[0];
    let (desc, _) = scene.load(None).unwrap();
    let mut settings = desc.render.clone();
    settings.width = 48;
    settings.height = 36;
    let one = render_with(&FlatScene::build(&desc, &settings), 1, true);
    settings.spp = 4;
    let four = render_with(&FlatScene::build(&desc, &settings), 1, true);
    settings.seed = 12345;
    let reseeded = render_with(&FlatScene::build(&desc, &settings), 1, true);
    assert_ne!(one.image.pixels, four.image.pixels);
    assert_ne!(four.image.pixels, reseeded.image.pixels);
}
