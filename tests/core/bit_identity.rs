//! Every built-in scene rendered on the CPU, specialised and not, each image compared bit for
//! bit with the one recorded before a refactor (`glint_test_support::image_hash`; the stiff,
//! closed-form and GPU suites' CPU renders are checked the same way).

use std::path::Path;

use glint_core::FlatScene;
use glint_io::{BUILTIN_SCENES, parse_scene};
use glint_scene::{EpsilonMode, Integrator};

use crate::render::render_cpu_checked;

#[test]
fn builtin_scenes_render_bit_identically() {
    // What was added after the first recording is rendered after it, so that the recorded
    // renders keep their index (the key of their hash): the later ε strategies after every
    // scene, then the later scenes with all of theirs, then every scene with the path tracer.
    let later = [EpsilonMode::SkipConvex];
    let later_scenes = ["cornell-gi"];
    // The scene files; the generated scenes are tested by their generator and `glint bench rays`.
    let files: Vec<_> = BUILTIN_SCENES
        .iter()
        .filter_map(|b| Some((b.name, parse_scene(b.toml()?, Path::new(b.name)).expect("built-in scene parses").0)))
        .collect();
    let (first, rest): (Vec<_>, Vec<_>) = files.iter().partition(|(name, _)| !later_scenes.contains(name));
    for scenes in [first, rest] {
        let mut deferred = Vec::new();
        for (_, desc) in scenes {
            // Small, with the scene's own spp, depth and bailout, plus every ε strategy.
            let mut settings = desc.render.clone();
            settings.width = 96;
            settings.height = 72;
            for specialise in [true, false] {
                render_cpu_checked(&FlatScene::build(desc, &settings), 2, specialise);
            }
            for mode in EpsilonMode::ALL {
                settings.epsilon_mode = mode;
                let flat = FlatScene::build(desc, &settings);
                if later.contains(&mode) {
                    deferred.push(flat);
                } else {
                    render_cpu_checked(&flat, 2, true);
                }
            }
        }
        for flat in &deferred {
            render_cpu_checked(flat, 2, true);
        }
    }
    // Every scene with the paths, at 4 paths a pixel and depth 6: specialised and not.
    for (_, desc) in &files {
        let mut settings = desc.render.clone();
        (settings.width, settings.height, settings.spp, settings.max_depth) = (96, 72, 4, 6);
        settings.integrator = Integrator::Path;
        for specialise in [true, false] {
            render_cpu_checked(&FlatScene::build(desc, &settings), 2, specialise);
        }
    }
}
