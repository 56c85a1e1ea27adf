//! Specialisation never changes pixels: the shader compiled for exactly a scene's features and
//! the full shader give the same image. (The CPU side of this is in tests/core/determinism.rs;
//! what the specialised module lacks is checked in glint-gpu's shader tests.)

use glint_io::BUILTIN_SCENES;

use super::support::{builtin, gpu_or_skip, gpu_render};

#[test]
fn specialised_and_full_shaders_agree() {
    let tracer = gpu_or_skip!();
    let mut worst: f64 = 0.0;
    for scene in BUILTIN_SCENES.iter().filter(|b| !b.is_generated()) {
        for spp in [1, 4] {
            let flat = builtin(scene.name, 96, 72, spp, 5);
            let special = gpu_render(tracer, &flat, true);
            let full = gpu_render(tracer, &flat, false);
            assert!(special.key.features != full.key.features, "{}: no specialisation happened", scene.name);
            let max = special
                .image
                .pixels
                .iter()
                .zip(&full.image.pixels)
                .map(|(a, b)| (*a - *b).abs().max_element())
                .fold(0.0, f64::max);
            let same_hits = special.image.first_hit == full.image.first_hit;
            eprintln!("{} spp {spp}: max |specialised − full| = {max:e}, first hits equal: {same_hits}", scene.name);
            assert!(same_hits, "{}: specialisation changed which object a pixel sees", scene.name);
            assert_eq!(special.counts, full.counts, "{}: specialisation changed the rays traced", scene.name);
            worst = worst.max(max);
        }
    }
    assert_eq!(worst, 0.0, "specialised and full shaders differ by up to {worst:e}");
}

/// A scene without child rays renders one image at every depth (`glint report` leaves out its
/// deeper rows on that ground, `SceneNeeds`): the GPU's shader variant for depth 8 has a ray
/// stack the depth-0 one lacks, and neither may change a pixel.
#[test]
fn a_scene_without_child_rays_renders_one_image_at_every_depth() {
    let tracer = gpu_or_skip!();
    let flat_scenes: Vec<&str> = BUILTIN_SCENES
        .iter()
        .filter(|b| !b.is_generated())
        .map(|b| b.name)
        .filter(|&name| !glint_types::layout::feature::recurses(builtin(name, 8, 6, 1, 16).header.features))
        .collect();
    assert!(flat_scenes.contains(&"lights"), "{flat_scenes:?}");
    for name in flat_scenes {
        let shallow = gpu_render(tracer, &builtin(name, 64, 48, 2, 0), true);
        for depth in [1, 8] {
            let deep = gpu_render(tracer, &builtin(name, 64, 48, 2, depth), true);
            assert!(deep.image == shallow.image, "{name}: depth {depth} differs from depth 0 on the GPU");
            assert_eq!(deep.counts, shallow.counts, "{name}: depth {depth}");
        }
    }
}
