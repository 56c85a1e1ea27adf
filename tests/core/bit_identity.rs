//! Every built-in scene rendered on the CPU, specialised and not, each image compared bit for
//! bit with the one recorded before a refactor (`glint_test_support::image_hash`; the stiff,
//! closed-form and GPU suites' CPU renders are checked the same way).

use std::path::Path;

use glint_core::FlatScene;
use glint_io::{BUILTIN_SCENES, parse_scene};
use glint_scene::EpsilonMode;

use crate::render::render_cpu_checked;

#[test]
fn builtin_scenes_render_bit_identically() {
    // The strategies added after the first recording are rendered after every scene, so that
    // the recorded renders keep their index (the key of their hash).
    let later = [EpsilonMode::SkipConvex];
    let mut deferred = Vec::new();
    // The scene files; the generated scenes are tested by their generator and `glint bench rays`.
    for (b, text) in BUILTIN_SCENES.iter().filter_map(|b| Some((b, b.toml()?))) {
        let (desc, _) = parse_scene(text, Path::new(b.name)).expect("built-in scene parses");
        // Small, with the scene's own spp, depth and bailout, plus every ε strategy.
        let mut settings = desc.render.clone();
        settings.width = 96;
        settings.height = 72;
        for specialise in [true, false] {
            render_cpu_checked(&FlatScene::build(&desc, &settings), 2, specialise);
        }
        for mode in EpsilonMode::ALL {
            settings.epsilon_mode = mode;
            let flat = FlatScene::build(&desc, &settings);
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
