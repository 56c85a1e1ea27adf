//! An offset ε as large as the scene itself: every mode moves a ray about ε off the surface it
//! leaves (`tmin` skips hits nearer than ε), so in a scene a few ε across rays pass through the
//! geometry they should meet: a furnace box 2e-6 wide at the default ε = 1e-6 returned 1.46 of
//! its 2.00, and a model scaled to 8e-3 wide (ε 1.25e-4 of it) lost a mirror's reflection of a
//! sphere in 12 pixels. A warning, not an error: a large ε is also an experiment (the acne it
//! hides).

use crate::desc::{RenderSettings, SceneDesc};
use crate::number::{format_number, format_rounded};

/// The share of the scene's size beyond which ε is warned about: ten times what the default
/// ε is of a scene 1 wide.
pub const EPSILON_WARN_SHARE: f64 = 1e-5;

/// The ε to suggest, as a share of the scene's size: the default ε's of a scene 1 wide.
pub const EPSILON_SHARE: f64 = 1e-6;

/// The warning for an ε beyond `EPSILON_WARN_SHARE` of the scene's bounded geometry's largest side.
pub fn epsilon_warning(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    let extent = crate::storage::scene_extent(desc).filter(|e| *e > 0.0 && e.is_finite())?;
    (settings.epsilon > EPSILON_WARN_SHARE * extent).then(|| {
        format!(
            "{} is {} of the scene's size ({}, the largest side of its spheres' and meshes' box): rays move \
             about ε off each surface they leave, so they can pass through geometry; lower it to {} or less",
            format_number(settings.epsilon),
            format_rounded(settings.epsilon / extent, 2),
            format_rounded(extent, 3),
            format_rounded(EPSILON_SHARE * extent, 2)
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(radius: f64) -> SceneDesc {
        let text = format!(
            "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n[materials.m]\nkd = 0.5\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = {radius:?}\nmaterial = \"m\"\n"
        );
        toml::from_str(&text).expect("scene")
    }

    #[test]
    fn an_epsilon_a_sizeable_part_of_the_scene_is_warned_about() {
        let tiny = scene(1e-6);
        let text = epsilon_warning(&tiny, &tiny.render).expect("ε = 1e-6 in a scene 2e-6 wide");
        assert!(text.starts_with("1e-6 is 0.5 of the scene's size (2e-6"), "{text}");
        assert!(text.ends_with("lower it to 2e-12 or less"), "{text}");
        let unit = scene(1.0);
        assert_eq!(epsilon_warning(&unit, &unit.render), None);
        // A sphere of radius 0.04 is 8e-2 wide: ε = 1e-6 is 1.25e-5 of it, written to 2 digits;
        // the side rounded to 3 digits, not written out to 16.
        let small = scene(0.04);
        let text = epsilon_warning(&small, &small.render).expect("ε = 1e-6 of a scene 8e-2 wide");
        assert!(text.starts_with("1e-6 is 1.2e-5 of the scene's size (0.08,"), "{text}");
        assert!(text.ends_with("lower it to 8e-8 or less"), "{text}");
        let tenth = scene(0.06);
        assert_eq!(epsilon_warning(&tenth, &tenth.render), None, "8.3e-6 of the scene's size");
    }
}
