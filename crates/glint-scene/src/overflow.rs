//! What in a scene lets radiance leave the f32 range, for the error of a render that did
//! (docs/numerics.md, "Non-finite images"). Validation bounds every number by 1e9, so a scene
//! whose surfaces return no more light than they receive (their gain, `MaterialDesc::gain`:
//! k_r + k_t ≤ 1 under Whitted's tree, k_d + k_s + k_r + k_t ≤ 1 under paths) stays far below
//! f32's 3.4e38 at any depth; a surface of gain g > 1 multiplies radiance by up to g at every
//! bounce, g^depth in all. The message names such materials first, then the brightest sources.

use super::Integrator;
use super::desc::SceneDesc;
use super::number::format_number;
use super::ray_tree::largest_attenuation;

/// The largest value f32 holds; radiance beyond it is stored as +inf.
const F32_MAX: f64 = f32::MAX as f64;

/// The fields of `desc` that can make radiance overflow f32 at `max_depth` under `integrator`,
/// with the remedy; `all_nan`: no pixel overflowed, every bad one is NaN, which a scene without
/// gain cannot make (a defect to report, said so).
pub fn overflow_causes(desc: &SceneDesc, max_depth: u32, integrator: Integrator, all_nan: bool) -> String {
    let terms = match integrator {
        Integrator::Whitted => "k_r + k_t",
        Integrator::Path => "k_d + k_s + k_r + k_t",
    };
    // Both integrators weigh each bounce's light by the world's global attenuation, up to
    // 1 / (its least denominator): with c < 1 it lifts every material's gain.
    let global = largest_attenuation(&desc.world.global_attenuation);
    let mut gains: Vec<(f64, String)> = desc
        .materials
        .iter()
        .map(|(name, m)| (m.gain(integrator) * global, name.clone()))
        .filter(|(g, _)| *g > 1.0)
        .collect();
    gains.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut causes: Vec<String> = gains
        .iter()
        .take(3)
        .map(|(g, name)| {
            let m = &desc.materials[name];
            let growth = g.powf(f64::from(max_depth));
            // Two digits: the factor is a bound, not a measurement.
            let reach = match growth {
                g if !g.is_finite() => "more than f64 holds".to_string(),
                g if g > F32_MAX => format!("{g:.1e}, beyond f32's 3.4e38"),
                g => format!("{g:.1e}"),
            };
            let fields = match integrator {
                Integrator::Whitted => {
                    format!("kr = {}, kt = {}", format_number(m.kr.max_channel()), format_number(m.kt.max_channel()))
                }
                Integrator::Path => format!(
                    "kd = {}, ks = {}, kr = {}, kt = {}",
                    format_number(m.kd.max_channel()),
                    format_number(m.ks.max_channel()),
                    format_number(m.kr.max_channel()),
                    format_number(m.kt.max_channel())
                ),
            };
            let lifted = if global > 1.0 {
                format!(
                    ", and world.global_attenuation weighs it by up to {} (c = {} < 1)",
                    format_number(global),
                    format_number(desc.world.global_attenuation.c)
                )
            } else {
                String::new()
            };
            // A shadow ray is weighed by k_t at every surface it crosses, however many and
            // whatever the depth: at depth 0 "0 bounces multiply radiance by up to 1" had been
            // the whole explanation of four k_t = 1e9 panes (a tester).
            let kt = m.kt.max_channel();
            let crossings = if kt > 1.0 {
                format!(
                    "; shadow rays multiply a light's term by k_t = {} at every surface of it they cross, however \
                     many, whatever the depth",
                    format_number(kt)
                )
            } else {
                String::new()
            };
            let bounces = if max_depth > 0 {
                format!(": up to {max_depth} bounces (the render's max depth) multiply radiance by up to {reach}")
            } else {
                String::new()
            };
            format!(
                "materials.{name} returns {terms} = {} times the light it receives ({fields}){lifted}{bounces}{crossings}",
                format_number(m.gain(integrator)),
            )
        })
        .collect();
    let transmits_more = gains.iter().any(|(_, name)| desc.materials[name].kt.max_channel() > 1.0);
    let emission = desc
        .materials
        .iter()
        .map(|(name, m)| (m.emission.max_channel(), format!("materials.{name}.emission")))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let light = desc
        .sourced_lights()
        .flat_map(|(name, l)| {
            [("diffuse", l.diffuse), ("specular", l.specular), ("ambient", l.ambient)]
                .map(|(field, v)| (v.max_channel(), format!("{name}.{field}")))
        })
        .max_by(|a, b| a.0.total_cmp(&b.0));
    let sources: Vec<String> = [emission, light]
        .into_iter()
        .flatten()
        .filter(|(v, _)| *v > 1.0)
        .map(|(v, field)| format!("{field} = {}", format_number(v)))
        .collect();
    // Without gain nothing overflows (validation bounds every source by 1e9, far within f32):
    // NaN pixels there are no source's fault.
    if gains.is_empty() && all_nan {
        let sources = if sources.is_empty() {
            "no source is brighter than 1".to_string()
        } else {
            format!("the brightest sources ({}) are far within f32's range", sources.join(", "))
        };
        return format!(
            "no material amplifies light and {sources}, so the NaN is no overflow but a defect in glint: \
             please report it with the scene and the render's settings"
        );
    }
    if !sources.is_empty() {
        causes.push(format!("the brightest sources: {}", sources.join(", ")));
    }
    let remedy = if gains.is_empty() {
        "lower the brightest sources".to_string()
    } else if global > 1.0 {
        format!(
            "raise world.global_attenuation's c (and l, q) so that 1 / (c + l·d + q·d²) stays ≤ 1, keep {terms} ≤ 1, \
             or lower the max depth (render.max_depth, --depth) or the brightest sources"
        )
    } else if max_depth == 0 && transmits_more {
        "keep k_t ≤ 1 where shadow rays cross, or lower the brightest sources".to_string()
    } else {
        format!("keep {terms} ≤ 1, lower the max depth (render.max_depth, --depth) or the brightest sources")
    };
    if causes.is_empty() {
        causes.push("no material amplifies light and no source is brighter than 1".into());
    }
    format!("{}; {remedy}", causes.join("; "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> SceneDesc {
        let head = "[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n";
        toml::from_str(&format!("{head}{text}")).expect("scene parses")
    }

    #[test]
    fn names_the_amplifying_material_and_the_brightest_sources() {
        let desc = scene(
            "[materials.dull]\nkd = 0.5\n[materials.mirror]\nkr = 1e9\nemission = 1e9\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\ndiffuse = 2.0\n",
        );
        let text = overflow_causes(&desc, 4, Integrator::Whitted, false);
        assert!(text.starts_with("materials.mirror returns k_r + k_t = 1000000000 times"), "{text}");
        assert!(text.contains("kr = 1000000000, kt = 0"), "{text}");
        assert!(text.contains("up to 4 bounces (the render's max depth) multiply radiance by up to 1.0e36"), "{text}");
        assert!(text.contains("materials.mirror.emission = 1000000000, lights[0].diffuse = 2"), "{text}");
        assert!(
            text.ends_with(
                "keep k_r + k_t ≤ 1, lower the max depth (render.max_depth, --depth) or the brightest sources"
            ),
            "{text}"
        );
        assert!(!text.contains("dull"), "{text}");
        assert!(
            overflow_causes(&desc, 30, Integrator::Whitted, false).contains("by up to 1.0e270, beyond f32's 3.4e38")
        );
        assert!(overflow_causes(&desc, 40, Integrator::Whitted, false).contains("by up to more than f64 holds"));
    }

    #[test]
    fn shadow_rays_through_panes_of_gain_are_named_whatever_the_depth() {
        let desc = scene("[materials.filter]\nkt = 1e9\n[[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\n");
        let text = overflow_causes(&desc, 0, Integrator::Whitted, false);
        assert_eq!(
            text,
            "materials.filter returns k_r + k_t = 1000000000 times the light it receives (kr = 0, kt = 1000000000); \
             shadow rays multiply a light's term by k_t = 1000000000 at every surface of it they cross, however many, \
             whatever the depth; keep k_t ≤ 1 where shadow rays cross, or lower the brightest sources"
        );
        let deep = overflow_causes(&desc, 3, Integrator::Whitted, false);
        assert!(
            deep.contains("up to 3 bounces (the render's max depth) multiply radiance by up to 1.0e27; shadow rays"),
            "{deep}"
        );
    }

    #[test]
    fn a_scene_without_gain_says_so() {
        let desc = scene("[materials.dull]\nkd = 0.5\n");
        assert_eq!(
            overflow_causes(&desc, 4, Integrator::Whitted, false),
            "no material amplifies light and no source is brighter than 1; lower the brightest sources"
        );
        assert!(overflow_causes(&desc, 4, Integrator::Path, true).contains("the NaN is no overflow but a defect"));
        // A bright lamp without gain cannot overflow either: a NaN is still a defect.
        let lamp = scene("[materials.dull]\nkd = 0.5\n[materials.lamp]\nemission = 15.0\n");
        let text = overflow_causes(&lamp, 4, Integrator::Path, true);
        assert!(text.contains("the NaN is no overflow but a defect"), "{text}");
        // Named as the brightest source, not called one no brighter than 1.
        assert!(
            text.contains("the brightest sources (materials.lamp.emission = 15) are far within f32's range"),
            "{text}"
        );
    }

    #[test]
    fn a_global_attenuation_above_1_lifts_every_materials_gain() {
        // Mirrors that return less than they receive, weighed by up to 1e6 a bounce (c = 1e-6):
        // this overflowed and was called "no material amplifies light" (an extreme-scenes tester).
        let desc = scene(
            "[materials.mirror]\nkr = 0.999999\nemission = 0.001\n\
             [world]\nglobal_attenuation = { c = 1e-6 }\n",
        );
        let text = overflow_causes(&desc, 20, Integrator::Whitted, false);
        assert!(
            text.starts_with(
                "materials.mirror returns k_r + k_t = 0.999999 times the light it receives (kr = 0.999999, kt = 0), \
                 and world.global_attenuation weighs it by up to 1000000 (c = 1e-6 < 1): up to 20 bounces"
            ),
            "{text}"
        );
        assert!(text.contains("raise world.global_attenuation's c"), "{text}");
        // Under paths too: each bounce's weight is attenuated there as well.
        assert!(overflow_causes(&desc, 20, Integrator::Path, false).starts_with("materials.mirror returns"));
    }

    #[test]
    fn under_paths_k_d_and_k_s_count_too() {
        // Whitted adds k_d once per light; a path multiplies by it at every bounce.
        let desc = scene("[materials.bright]\nkd = 1e9\nemission = 1.0\n");
        assert!(overflow_causes(&desc, 6, Integrator::Whitted, false).starts_with("no material amplifies light"));
        let text = overflow_causes(&desc, 6, Integrator::Path, false);
        assert!(
            text.starts_with("materials.bright returns k_d + k_s + k_r + k_t = 1000000000 times the light it receives (kd = 1000000000, ks = 0, kr = 0, kt = 0)"),
            "{text}"
        );
        assert!(
            text.ends_with("keep k_d + k_s + k_r + k_t ≤ 1, lower the max depth (render.max_depth, --depth) or the brightest sources"),
            "{text}"
        );
    }
}
