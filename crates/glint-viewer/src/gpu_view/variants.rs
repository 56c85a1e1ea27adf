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

/// What `key` compiles in that `last` did not, in words ("spot lights, phong"), or what else
/// makes it new.
pub(super) fn new_in(key: ShaderKey, last: Option<ShaderKey>) -> String {
    let before = last.map_or(0, |l| l.features);
    let added: Vec<String> = glint_types::layout::feature::NAMES
        .iter()
        .enumerate()
        .filter(|(bit, _)| key.features & !before & (1 << bit) != 0)
        .map(|(_, n)| n.to_lowercase().replace('_', " "))
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
    }
}
