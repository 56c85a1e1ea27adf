//! The shader variants the viewer's renders use, and which ones an edit is likely to need next
//! (`GpuView::prewarm` compiles those while idle).

use glint_core::{Accel, FlatScene};
use glint_gpu::{GpuOptions, ShaderKey};

/// The variant the viewer's renders of `scene` use (`GpuOptions::default()`).
pub(super) fn variant_of(scene: &FlatScene) -> ShaderKey {
    ShaderKey::for_scene(scene, GpuOptions::default().specialise).with_accel(scene, Accel::default())
}

/// 1×1 copies of `scene` with what an edit is likely to add next: more samples, depth 0, a spot
/// light, a Phong or a Cook–Torrance material (the features the first use of which froze the
/// window before the tracer had a device of its own).
pub(super) fn likely_next(scene: &FlatScene) -> Vec<FlatScene> {
    use glint_types::layout::feature;
    let tiny = |change: &dyn Fn(&mut FlatScene)| {
        let mut s = scene.clone();
        (s.header.width, s.header.height) = (1, 1);
        change(&mut s);
        s
    };
    vec![
        tiny(&|s| {
            s.header.spp = s.header.spp.max(4);
            s.header.features |= feature::JITTER;
        }),
        tiny(&|s| s.header.max_depth = 0),
        tiny(&|s| s.header.features |= feature::SPOT_LIGHTS),
        // The only point light switched to a spot: no point light is left.
        tiny(&|s| s.header.features = (s.header.features & !feature::POINT_LIGHTS) | feature::SPOT_LIGHTS),
        tiny(&|s| s.header.features |= feature::PHONG),
        tiny(&|s| s.header.features |= feature::COOK_TORRANCE),
    ]
}

/// Each feature bit in plain words, in bit order (`feature::NAMES` are shader defs: the status
/// bar said "compiling the shader for skip left" to students, after `SKIP_LEFT`; a lecturer).
/// Each reads after "compiling the shader for".
const PHRASES: [&str; glint_types::layout::feature::NAMES.len()] = [
    "point lights",
    "directional lights",
    "spot lights",
    "distance falloff of light",
    "shadows",
    "shadows through transparent objects",
    "mirror reflection",
    "refraction",
    "spheres",
    "planes",
    "triangles",
    "textures",
    "Blinn highlights",
    "Phong highlights",
    "the lights' own ambient",
    "emitting materials",
    "specular highlights",
    "several samples a pixel",
    "inverse-square falloff",
    "soft spot edges",
    "rays ignoring the surface they leave",
    "global attenuation",
    "Cook–Torrance highlights",
    "vertex colours",
];

/// What `key` compiles in that `last` did not, in words ("spot lights, Phong highlights"), or
/// what else makes it new.
pub(super) fn new_in(key: ShaderKey, last: Option<ShaderKey>) -> String {
    let before = last.map_or(0, |l| l.features);
    let added: Vec<&str> = PHRASES
        .iter()
        .enumerate()
        .filter(|(bit, _)| key.features & !before & (1 << bit) != 0)
        .map(|(_, p)| *p)
        .collect();
    if added.is_empty() { "this scene's features".into() } else { added.join(", ") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_variant_is_named_by_what_it_adds() {
        use glint_types::layout::feature;
        let key = |features| ShaderKey { features, ..ShaderKey::full() };
        let before = key(feature::SPHERES | feature::POINT_LIGHTS);
        let after = key(feature::SPHERES | feature::POINT_LIGHTS | feature::SPOT_LIGHTS);
        assert_eq!(new_in(after, Some(before)), "spot lights");
        assert_eq!(new_in(before, Some(after)), "this scene's features");
        let more = key(feature::SPHERES | feature::PHONG | feature::SKIP_LEFT);
        assert_eq!(new_in(more, Some(before)), "Phong highlights, rays ignoring the surface they leave");
    }

    #[test]
    fn every_feature_is_named_in_plain_words_not_by_its_shader_def() {
        use glint_types::layout::feature;
        // Names whose shader def, lower-cased, is already the plain word.
        let plain = [
            "POINT_LIGHTS",
            "DIRECTIONAL_LIGHTS",
            "SPOT_LIGHTS",
            "SHADOWS",
            "REFLECTION",
            "SPHERES",
            "PLANES",
            "TRIANGLES",
            "TEXTURES",
            "BLINN",
            "PHONG",
            "SPECULAR",
            "GLOBAL_ATTENUATION",
            "VERTEX_COLOURS",
        ];
        for (bit, name) in feature::NAMES.iter().enumerate() {
            let key = ShaderKey { features: 1 << bit, ..ShaderKey::full() };
            let said = new_in(key, Some(ShaderKey { features: 0, ..ShaderKey::full() }));
            assert_eq!(said, PHRASES[bit], "bit {bit} ({name})");
            assert!(!said.is_empty() && !said.contains('_'), "bit {bit} ({name}): {said:?}");
            assert!(!said.contains(name), "bit {bit} is named by its shader def: {said:?}");
            if !plain.contains(name) {
                let raw = name.to_lowercase().replace('_', " ");
                assert!(!said.to_lowercase().contains(&raw), "bit {bit} ({name}) reads as its shader def: {said:?}");
            }
        }
    }
}
