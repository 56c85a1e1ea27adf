//! How large a ray tree can grow (issue 13, point 8): a hit on a material with both k_r and k_t
//! spawns two rays, so a tree can double at every level up to `max_depth`, unless the bailout
//! stops it first. The path weight of a child is its parent's times k_r or k_t (k_r + k_t under
//! total internal reflection), so after k levels it is at most g^k with g the largest
//! max-channel k_r + k_t of any material: with g < 1 and a bailout b > 0 no ray deeper than
//! ln b / ln g levels is traced. A scene whose worst case passes `WARN_RAYS_PER_SAMPLE` is
//! warned about at load, with the bound and the remedy.

use super::desc::{RenderSettings, SceneDesc};
use super::material::MaterialDesc;
use super::number::format_number;

/// Rays of one camera sample's tree beyond which a scene is warned about: the GPU's walk bound
/// is about as many (65,000 nodes), and on the CPU a 640×480 image of such pixels is 2e10 rays.
pub const WARN_RAYS_PER_SAMPLE: f64 = 65_536.0;

/// The levels of the deepest ray a tree can reach: `max_depth`, or fewer where the bailout
/// stops every path first.
pub fn reachable_depth(desc: &SceneDesc, settings: &RenderSettings) -> u32 {
    let gain = largest_gain(desc);
    if settings.bailout > 0.0 && gain < 1.0 {
        if gain <= 0.0 {
            return 0;
        }
        // The largest k with gain^k ≥ bailout.
        let levels = (settings.bailout.ln() / gain.ln()).floor();
        return settings.max_depth.min(levels as u32);
    }
    settings.max_depth
}

/// g: the largest max-channel k_r + k_t of any material an object uses, the most a level
/// multiplies a path's weight by.
fn largest_gain(desc: &SceneDesc) -> f64 {
    used_materials(desc).map(|(_, m)| m.gain(glint_types::Integrator::Whitted)).fold(0.0, f64::max)
}

/// The materials some object uses, in the scene's order: a material no ray can hit shapes no
/// tree (a scene file may define materials it does not use).
fn used_materials(desc: &SceneDesc) -> impl Iterator<Item = (&String, &MaterialDesc)> {
    let used: std::collections::HashSet<&str> = desc.objects.iter().flat_map(|o| o.materials()).collect();
    desc.materials.iter().filter(move |(name, _)| used.contains(name.as_str()))
}

/// The levels of the largest tree not warned about: 2^(k+1) − 1 ≤ `WARN_RAYS_PER_SAMPLE`.
const UNWARNED_LEVELS: i32 = 15;

/// The warning for a scene whose ray tree can grow past `WARN_RAYS_PER_SAMPLE` rays a camera
/// sample, naming a branching material, the bound and the remedy; `None` for the others.
pub fn unbounded_ray_tree(desc: &SceneDesc, settings: &RenderSettings) -> Option<String> {
    // A path follows one lobe a bounce: it never branches.
    if settings.integrator == glint_types::Integrator::Path {
        return None;
    }
    let (name, m) = used_materials(desc).find(|(_, m)| m.kr.max_channel() > 0.0 && m.kt.max_channel() > 0.0)?;
    let depth = reachable_depth(desc, settings);
    // A full binary tree of `depth` levels below the camera ray.
    let rays = 2f64.powf(f64::from(depth) + 1.0) - 1.0;
    if rays <= WARN_RAYS_PER_SAMPLE {
        return None;
    }
    let stop = if depth < settings.max_depth {
        format!("the bailout ({}) stops it only after {depth} levels", format_number(settings.bailout))
    } else {
        format!(
            "the bailout ({}) cannot stop it before max_depth = {}",
            format_number(settings.bailout),
            settings.max_depth
        )
    };
    // A bailout that a gain below 1 lets work is already set: what stops the tree in time is
    // a larger one (g^15 stops it after 15 levels) or a lower depth.
    let gain = largest_gain(desc);
    let remedy = if settings.bailout > 0.0 && gain < 1.0 {
        format!(
            "raise render.bailout to {} or more (k_r + k_t = {} then stops it after {UNWARNED_LEVELS} levels) or lower \
             render.max_depth to {UNWARNED_LEVELS}",
            // Rounded up to three decimals: at least g^15.
            format_number((gain.powi(UNWARNED_LEVELS) * 1e3).ceil() / 1e3),
            format_number(gain)
        )
    } else if settings.bailout > 0.0 {
        // The bailout is set: asking for one (as before) read as if it were not (a glTF glass,
        // k_r + k_t = 0.04 + 0.96, under the default 1/255).
        format!(
            "k_r + k_t = {} keeps a path's weight from level to level, so no bailout stops it: lower render.max_depth (--depth) to {UNWARNED_LEVELS}, or make k_r + k_t < 1",
            format_number(gain)
        )
    } else {
        "set render.bailout (--bailout; e.g. 1/255, with k_r + k_t < 1) or lower render.max_depth (--depth)".to_string()
    };
    Some(format!(
        "materials.{name} reflects and refracts (k_r = {}, k_t = {}), so a ray tree can double at every level, and \
         {stop}: up to 2^{} − 1{} rays per camera sample; {remedy}",
        format_number(m.kr.max_channel()),
        format_number(m.kt.max_channel()),
        // Widened: max_depth = u32::MAX (refused, but warned of in the same pass) overflowed.
        u64::from(depth) + 1,
        if rays.is_finite() { format!(" ≈ {rays:.1e}") } else { String::new() }
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPHERE: &str = "[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\n";

    /// A sphere of `material` (named glass).
    fn scene(material: &str) -> SceneDesc {
        let head = "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
        toml::from_str(&format!("{head}[materials.glass]\n{material}\n{SPHERE}material = \"glass\"\n"))
            .expect("scene parses")
    }

    fn settings(max_depth: u32, bailout: f64) -> RenderSettings {
        RenderSettings { max_depth, bailout, ..RenderSettings::default() }
    }

    #[test]
    fn a_bailout_already_set_is_not_asked_for_again() {
        // glTF's clear glass: k_r + k_t = 1 keeps the weight, so the default bailout cannot stop it.
        let glass = scene("kr = 0.04\nkt = 0.96");
        let text = unbounded_ray_tree(&glass, &settings(40, 1.0 / 255.0)).expect("a warning");
        assert!(text.contains("k_r + k_t = 1 keeps a path's weight"), "{text}");
        assert!(
            text.contains("lower render.max_depth (--depth) to 15") && !text.contains("set render.bailout"),
            "{text}"
        );
    }

    #[test]
    fn glass_between_mirrors_without_a_bailout_is_warned_about_with_its_bound() {
        let glass = scene("kr = 0.5\nkt = 0.4");
        let text = unbounded_ray_tree(&glass, &settings(1024, 0.0)).expect("a warning");
        assert!(text.starts_with("materials.glass reflects and refracts (k_r = 0.5, k_t = 0.4)"), "{text}");
        assert!(
            text.contains("cannot stop it before max_depth = 1024: up to 2^1025 − 1 rays per camera sample"),
            "{text}"
        );
        assert!(unbounded_ray_tree(&glass, &settings(20, 0.0)).unwrap().contains("up to 2^21 − 1 ≈ 2.1e6 rays"));
        assert!(text.ends_with("or lower render.max_depth (--depth)"), "{text}");
        // 0.9^k ≥ 1/255 up to k = 52 levels: the bailout bounds it, but not below the threshold.
        assert_eq!(reachable_depth(&glass, &settings(1024, 1.0 / 255.0)), 52);
        let bounded = unbounded_ray_tree(&glass, &settings(1024, 1.0 / 255.0)).unwrap();
        assert!(bounded.contains("only after 52 levels"), "{bounded}");
        // Its bailout already works; a larger one is the remedy (0.9^15 = 0.2059), not "set" one.
        assert!(
            bounded.ends_with(
                "raise render.bailout to 0.206 or more (k_r + k_t = 0.9 then stops it after 15 levels) or lower \
                 render.max_depth to 15"
            ),
            "{bounded}"
        );
        // 0.9^k ≥ 1/32 up to 32 levels; 15 levels (65,535 rays) is the largest tree not warned about.
        assert!(unbounded_ray_tree(&glass, &settings(15, 0.0)).is_none());
        assert!(unbounded_ray_tree(&glass, &settings(16, 0.0)).is_some());
    }

    #[test]
    fn a_gain_of_one_or_more_defeats_the_bailout_and_a_tree_without_branches_is_not_warned_about() {
        let gain = scene("kr = 0.6\nkt = 0.6");
        assert_eq!(reachable_depth(&gain, &settings(40, 0.5)), 40);
        assert!(unbounded_ray_tree(&gain, &settings(40, 0.5)).is_some());
        let mirror = scene("kr = 1.0");
        assert!(unbounded_ray_tree(&mirror, &settings(1024, 0.0)).is_none(), "a chain, not a tree");
    }

    #[test]
    fn a_branching_material_no_object_uses_is_not_warned_about() {
        let head = "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
        let text = format!(
            "{head}[materials.glass]\nkr = 0.3\nkt = 0.9\n[materials.mirror]\nkr = 0.5\n{SPHERE}material = \"mirror\"\n"
        );
        let mirrors: SceneDesc = toml::from_str(&text).expect("scene parses");
        assert!(unbounded_ray_tree(&mirrors, &settings(1024, 0.0)).is_none(), "glass is on nothing");
        // 0.5^3 ≥ 0.1 > 0.5^4; counting glass's gain of 1.2, the bailout could stop nothing.
        assert_eq!(reachable_depth(&mirrors, &settings(1024, 0.1)), 3);
    }
}
