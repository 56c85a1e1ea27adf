//! Same bits for any thread count, and with or without feature specialisation.

use std::path::Path;

use glint_core::{CpuRender, FlatScene};
use glint_io::{BUILTIN_SCENES, parse_scene};
use glint_scene::{Integrator, SceneDesc};

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

/// One scene at `spp` under `integrator` (paths at depth 6 at most): the same bits for 1, 2
/// and 3 threads, specialised or not, and twice.
fn check_scene(name: &str, desc: &SceneDesc, spp: u32, integrator: Integrator) {
    let mut settings = desc.render.clone();
    // 96×72: six by five tiles of 16×16, the last row and column partial.
    settings.width = 96;
    settings.height = 72;
    settings.spp = spp;
    settings.integrator = integrator;
    if integrator == Integrator::Path {
        settings.max_depth = settings.max_depth.min(6);
    }
    let flat = FlatScene::build(desc, &settings);
    let what = |s: &str| format!("{name} ({}) at spp {spp}: {s}", integrator.name());
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

#[test]
fn builtin_scenes_are_bit_identical_across_threads_and_specialisation() {
    // The scene files; the generated scenes are tested by their generator and `glint bench rays`.
    let files: Vec<_> = BUILTIN_SCENES
        .iter()
        .filter_map(|b| Some((b.name, parse_scene(b.toml()?, Path::new(b.name)).expect("built-in scene loads").0)))
        .collect();
    assert_eq!(files.len(), 6);
    // Whitted's renders first, in the order first recorded (their index keys their hash), then
    // every scene with the path tracer.
    for (name, desc) in &files {
        for spp in [1, 4] {
            check_scene(name, desc, spp, Integrator::Whitted);
        }
    }
    for (name, desc) in &files {
        for spp in [1, 4] {
            check_scene(name, desc, spp, Integrator::Path);
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

/// A scene without child rays renders one image at every depth, bit for bit (`glint report`
/// leaves out its deeper rows on that ground, `SceneNeeds`).
#[test]
fn a_scene_without_child_rays_renders_one_image_at_every_depth() {
    let at = |name: &str, depth: u32| {
        let loaded = glint_io::load_scene(name).expect("built-in scene");
        let mut s = loaded.desc.render.clone();
        (s.width, s.height, s.spp, s.max_depth) = (64, 48, 2, depth);
        FlatScene::build(&loaded.desc, &s)
    };
    let flat_scenes: Vec<&str> = BUILTIN_SCENES
        .iter()
        .filter(|b| !b.is_generated())
        .map(|b| b.name)
        .filter(|&name| !glint_types::layout::feature::recurses(at(name, 16).header.features))
        .collect();
    assert!(flat_scenes.contains(&"lights"), "{flat_scenes:?}");
    for name in flat_scenes {
        let shallow = crate::render::render_cpu_checked(&at(name, 0), 2, true);
        for depth in [1, 8] {
            let deep = crate::render::render_cpu_checked(&at(name, depth), 2, true);
            assert!(deep.image == shallow.image, "{name}: depth {depth} differs from depth 0");
            assert_eq!(deep.counts, shallow.counts, "{name}: depth {depth}");
        }
    }
}
