//! An offset ε as large as the scene itself: every mode moves a ray about ε off the surface it
//! leaves (`tmin` skips hits nearer than ε), so in a scene a few ε across rays pass through the
//! geometry they should meet: a furnace box 2e-6 wide at the default ε = 1e-6 returned 1.46 of
//! its 2.00, and a model scaled to 8e-3 wide (ε 1.25e-4 of it) lost a mirror's reflection of a
//! sphere in 12 pixels. And one too small for the classic modes, which have nothing but ε to
//! keep a ray off the surface it leaves: below f32's step at the scene's size the GPU's hit
//! points lie on either side of their surface, and at 0 the CPU's too (a fuzzed scene at
//! `nudge_ray`, ε = 0: acne on both, 102 of 1,728 pixels 10 % apart). Warnings, not errors: both
//! are also experiments (numerics.md case 2 is the acne a small ε lets through).

use crate::desc::{RenderSettings, SceneDesc};
use crate::number::{format_number, format_rounded};
use glint_types::EpsilonMode;

/// f32's step at the scene's size, as a share of it (2^-23): hit points stored and computed in
/// f32 are that far off their surfaces.
const F32_STEP_SHARE: f64 = 1.0 / 8_388_608.0;

/// The share of the scene's size beyond which ε is warned about: ten times what the default
/// ε is of a scene 1 wide.
pub const EPSILON_WARN_SHARE: f64 = 1e-5;

/// The ε to suggest, as a share of the scene's size: the default ε's of a scene 1 wide.
pub const EPSILON_SHARE: f64 = 1e-6;

/// The warning for an ε beyond `EPSILON_WARN_SHARE` of the scene's bounded geometry's largest
/// side, or, in a mode that only ε keeps off the surface a ray leaves (`tmin`, `nudge_ray`,
/// `nudge_normal`), below f32's step at that size (`F32_STEP_SHARE`; without bounded geometry, 0).
pub fn epsilon_warning(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    let extent = crate::storage::scene_extent(desc).filter(|e| *e > 0.0 && e.is_finite());
    too_small(settings, extent)
        .or_else(|| extent.and_then(|e| too_large(settings, e)))
        .or_else(|| too_large_for_a_sphere(desc, settings))
}

/// The share of a sphere's diameter beyond which ε is warned about: a sphere fewer than 100 ε
/// across. The scene's size hid a small one beside a large one (a sphere of radius 1e-7 under
/// ε = 1e-6 beside one of 1e7 lost its contact shadow without a word).
pub const EPSILON_SPHERE_SHARE: f64 = 1e-2;

fn too_large_for_a_sphere(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    let (k, radius) = desc
        .objects
        .iter()
        .enumerate()
        .filter_map(|(k, o)| match o {
            crate::desc::ObjectDesc::Sphere(s) if s.radius > 0.0 && s.radius.is_finite() => Some((k, s.radius)),
            crate::desc::ObjectDesc::Sphere(_)
            | crate::desc::ObjectDesc::Plane(_)
            | crate::desc::ObjectDesc::Mesh(_)
            | crate::desc::ObjectDesc::Model(_) => None,
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let diameter = 2.0 * radius;
    (settings.epsilon > EPSILON_SPHERE_SHARE * diameter).then(|| {
        format!(
            "{} is {} the diameter of objects[{k}] (a sphere of radius {}), more than {}: rays move about ε off \
             each surface they leave, so near it they can pass through geometry and its contact shadows are lost; \
             lower it to {} or less",
            format_number(settings.epsilon),
            share_of(format_rounded(settings.epsilon / diameter, 3)),
            format_number(radius),
            format_number(EPSILON_SPHERE_SHARE),
            format_rounded(EPSILON_SPHERE_SHARE * diameter / 10.0, 2)
        )
    })
}

fn too_small(settings: &RenderSettings, extent: Option<f64>) -> Option<String> {
    let mode = settings.epsilon_mode;
    match mode {
        EpsilonMode::Tmin | EpsilonMode::NudgeRay | EpsilonMode::NudgeNormal => {}
        EpsilonMode::Robust | EpsilonMode::SkipConvex => return None,
    }
    let step = extent.map_or(0.0, |e| F32_STEP_SHARE * e);
    let eps = settings.epsilon;
    let why = if eps == 0.0 {
        "keeps no ray off the surface it leaves".to_string()
    } else if eps < step {
        format!(
            "is below f32's step at the scene's size ({}, 2^-23 of its largest side {}), which the GPU's hit \
             points are off their surfaces by",
            format_rounded(step, 2),
            format_rounded(extent.unwrap_or(0.0), 3)
        )
    } else {
        return None;
    };
    let fits =
        extent.map_or_else(|| "one that fits the scene's size".to_string(), |e| format_rounded(EPSILON_SHARE * e, 2));
    Some(format!(
        "{} in `{}` mode {why}: rays can meet the surface they leave again and shade it with acne (numerics.md \
         case 2); raise it to {fits}, or use `robust`",
        format_number(eps),
        mode.name()
    ))
}

/// `share` of a size in words: "0.5 of", or from 1 on "5 times" (a share of 5 read as a fraction).
fn share_of(share: String) -> String {
    if share.parse::<f64>().is_ok_and(|v| v >= 1.0) { format!("{share} times") } else { format!("{share} of") }
}

/// `share`, above `EPSILON_WARN_SHARE`, with the digits that show it is above: three at least,
/// more where fewer round onto the limit (5e-5 of a scene 4.9 wide, 1.02e-5, read "1e-5" at two;
/// 1.0001e-5 reads so at three).
fn above_limit(share: f64) -> String {
    (3..=17)
        .map(|digits| format_rounded(share, digits))
        .find(|shown| shown.parse::<f64>().is_ok_and(|v| v > EPSILON_WARN_SHARE))
        .unwrap_or_else(|| format_rounded(share, 17))
}

fn too_large(settings: &RenderSettings, extent: f64) -> Option<String> {
    (settings.epsilon > EPSILON_WARN_SHARE * extent).then(|| {
        format!(
            "{} is {} the scene's size ({}, the largest side of its spheres' and meshes' box), more than {}: \
             rays move about ε off each surface they leave, so they can pass through geometry; lower it to {} or less",
            format_number(settings.epsilon),
            share_of(above_limit(settings.epsilon / extent)),
            format_rounded(extent, 3),
            format_number(EPSILON_WARN_SHARE),
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
        // A sphere of radius 0.04 is 8e-2 wide: ε = 1e-6 is 1.25e-5 of it, written to 3 digits;
        // the side rounded to 3 digits, not written out to 16.
        let small = scene(0.04);
        let text = epsilon_warning(&small, &small.render).expect("ε = 1e-6 of a scene 8e-2 wide");
        assert!(
            above_limit(1.0001e-5) == "1.0001e-5" && above_limit(1.02e-5) == "1.02e-5",
            "{}",
            above_limit(1.0001e-5)
        );
        assert!(text.starts_with("1e-6 is 1.25e-5 of the scene's size (0.08, the largest side of its spheres' and meshes' box), more than 1e-5:"), "{text}");
        assert!(text.ends_with("lower it to 8e-8 or less"), "{text}");
        let tenth = scene(0.06);
        assert_eq!(epsilon_warning(&tenth, &tenth.render), None, "8.3e-6 of the scene's size");
    }

    #[test]
    fn an_epsilon_large_beside_the_smallest_sphere_is_warned_about_though_the_scene_is_large() {
        let text = "[camera]\nposition = [0.0, 0.0, -5e-7]\nlook_at = [0.0, 0.0, 0.0]\n[materials.m]\nkd = 0.5\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 10000000.0000002]\nradius = 1e7\nmaterial = \"m\"\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1e-7\nmaterial = \"m\"\n";
        let desc: SceneDesc = toml::from_str(text).expect("scene");
        let said = epsilon_warning(&desc, &desc.render).expect("ε = 1e-6 beside a sphere of radius 1e-7");
        assert!(
            said.starts_with("1e-6 is 5 times the diameter of objects[1] (a sphere of radius 1e-7), more than 0.01:"),
            "{said}"
        );
        assert!(said.ends_with("lower it to 2e-10 or less"), "{said}");
        let fine = RenderSettings { epsilon: 2e-10, ..desc.render.clone() };
        assert_eq!(epsilon_warning(&desc, &fine), None);
        // A unit sphere keeps the default ε without a word (100 ε across is 1e-4).
        let unit = scene(1.0);
        assert_eq!(too_large_for_a_sphere(&unit, &unit.render), None);
    }

    #[test]
    fn an_epsilon_too_small_for_a_classic_mode_is_warned_about() {
        let unit = scene(1.0);
        let at = |mode: EpsilonMode, epsilon: f64| {
            epsilon_warning(&unit, &RenderSettings { epsilon_mode: mode, epsilon, ..unit.render.clone() })
        };
        let zero = at(EpsilonMode::NudgeRay, 0.0).expect("ε = 0 at nudge_ray");
        assert!(zero.starts_with("0 in `nudge_ray` mode keeps no ray off the surface it leaves: rays"), "{zero}");
        assert!(zero.ends_with("raise it to 2e-6, or use `robust`"), "{zero}");
        // The step at a scene 2 wide is 2.4e-7.
        let tiny = at(EpsilonMode::Tmin, 1e-7).expect("ε = 1e-7 at tmin, in a scene 2 wide");
        assert!(tiny.starts_with("1e-7 in `tmin` mode is below f32's step at the scene's size (2.4e-7"), "{tiny}");
        assert_eq!(at(EpsilonMode::NudgeNormal, 3e-7), None);
        for mode in [EpsilonMode::Robust, EpsilonMode::SkipConvex] {
            assert_eq!(at(mode, 0.0), None, "{mode:?} needs no ε on a sphere");
        }
    }
}
