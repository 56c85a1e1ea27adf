//! An offset ε as large as the scene itself: every mode moves a ray about ε off the surface it
//! leaves (`tmin` skips hits nearer than ε), so in a scene a few ε across rays pass through the
//! geometry they should meet: a furnace box 2e-6 wide at the default ε = 1e-6 returned 1.46 of
//! its 2.00. A warning, not an error: a large ε is also an experiment (the acne it hides).

use crate::desc::{RenderSettings, SceneDesc};
use crate::number::format_number;

/// The share of the scene's size beyond which ε is warned about.
const WARN_SHARE: f64 = 0.01;

/// The warning for an ε beyond `WARN_SHARE` of the scene's bounded geometry's largest side.
pub fn epsilon_warning(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    let extent = crate::storage::scene_extent(desc).filter(|e| *e > 0.0 && e.is_finite())?;
    (settings.epsilon > WARN_SHARE * extent).then(|| {
        format!(
            "{} is {:.0} % of the scene's size ({}, the largest side of its spheres' and meshes' box): rays move \
             about ε off each surface they leave, so they can pass through geometry; lower it to {} or less",
            format_number(settings.epsilon),
            100.0 * settings.epsilon / extent,
            format_number(extent),
            format_number(1e-6 * extent)
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
        assert!(text.starts_with("1e-6 is 50 % of the scene's size (2e-6"), "{text}");
        assert!(text.ends_with("lower it to 2e-12 or less"), "{text}");
        let unit = scene(1.0);
        assert_eq!(epsilon_warning(&unit, &unit.render), None);
    }
}
