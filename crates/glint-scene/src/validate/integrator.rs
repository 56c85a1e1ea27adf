//! What a scene sets that its integrator does not use, or lacks that it needs: warnings for the
//! path tracer, which has no ambient term and draws its light from lights, emitters and the
//! background alone, and that may return more light than they receive under it.

use crate::desc::{RenderSettings, SceneDesc, WorldDesc};
use crate::error::FieldIssue;
use glint_types::Integrator;

/// The warnings `settings.integrator` gives `desc`: for Whitted's, a path-tracing setting the
/// file keeps (one file is rendered under both in the Whitted against GI lesson, so not an
/// error).
pub fn integrator_warnings(desc: &SceneDesc, settings: &RenderSettings) -> Vec<FieldIssue> {
    let mut out = Vec::new();
    match settings.integrator {
        Integrator::Whitted => {
            if !settings.indirect {
                out.push(FieldIssue {
                    field: "render.indirect".into(),
                    problem: "false is a path-tracing setting (paths that follow only k_r and k_t), and changes \
                              nothing under Whitted's model, whose ray tree follows nothing else"
                        .into(),
                });
            }
            return out;
        }
        Integrator::Path => {}
    }
    let unused = "is not used by the path tracer: the indirect light it stands in for is computed";
    // The default is not the scene's doing: a path scene without a [world] table is not warned.
    if !desc.world.ambient.is_zero() && desc.world.ambient != WorldDesc::default().ambient {
        out.push(FieldIssue { field: "world.ambient".into(), problem: unused.into() });
    }
    for (i, light) in desc.lights.iter().enumerate() {
        if !light.ambient.is_zero() {
            out.push(FieldIssue {
                field: format!("lights[{i}].ambient"),
                // Named where the light has a name: an unnamed one printed "()".
                problem: if light.name.is_empty() { unused.to_string() } else { format!("({}) {unused}", light.name) },
            });
        }
    }
    // Nor is a bailout of 0, which turns it off: paths have none to turn off.
    if settings.bailout != RenderSettings::default().bailout && settings.bailout != 0.0 {
        out.push(FieldIssue {
            field: "render.bailout".into(),
            problem: "is not used by the path tracer: Russian roulette ends its paths, without bias".into(),
        });
    }
    if let Some(problem) = path_gain_warning(desc) {
        out.push(FieldIssue { field: "materials".into(), problem });
    }
    let emits = desc.materials.values().any(|m| !m.emission.is_zero());
    // At the last bounce no path goes on, so an emitter's light there is a light sample alone,
    // unweighted: on a glossy lobe that is the noisiest estimate of it (a tester: RMS error 0.061
    // at depth 0 against 0.0087 at depth 1, 64 paths).
    if settings.max_depth == 0 && emits && desc.materials.values().any(|m| !m.ks.is_zero()) {
        out.push(FieldIssue {
            field: "render.max_depth".into(),
            problem: "0 with paths: an emitter's light on a glossy (k_s) surface is then estimated by light samples \
                      alone, unweighted, and is noisy where the lobe is sharp; at depth 1 the lobe's own samples are \
                      weighted against them (docs/path-tracing.md)"
                .into(),
        });
    }
    if desc.lights.is_empty() && !emits && desc.world.background.is_zero() {
        out.push(FieldIssue {
            field: "render.integrator".into(),
            problem: "no light, no emitting material and a black background: the path-traced image will be black"
                .into(),
        });
    }
    out
}

/// The path tracer follows k_d, k_s, k_r and k_t as one BSDF (`MaterialDesc::gain`), so
/// where they sum above 1 a surface returns more light than it receives and radiance grows with
/// every bounce; Whitted's tree sums k_d and k_s once per light instead. One warning for all
/// (a model's smooth materials, which count F0 as k_s and k_r, are many).
pub fn path_gain_warning(desc: &SceneDesc) -> Option<String> {
    let gains: Vec<String> = desc
        .materials
        .iter()
        .filter_map(|(name, m)| {
            let sum = m.gain(Integrator::Path);
            (sum > 1.0).then(|| format!("{name} ({sum:.4})"))
        })
        .collect();
    if gains.is_empty() {
        return None;
    }
    const SHOWN: usize = 6;
    let more = gains.len().saturating_sub(SHOWN);
    let more = if more > 0 { format!(" and {more} more") } else { String::new() };
    Some(format!(
        "k_d + k_s + k_r + k_t > 1 in {}{more}: under the path tracer such a surface returns more light than it \
         receives, so radiance grows with --depth",
        gains[..gains.len().min(SHOWN)].join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rgb::Rgb;

    #[test]
    fn a_path_render_is_warned_of_what_it_leaves_out_and_of_a_black_image() {
        // A bumpy scene without its light, under an ambient sky.
        let mut desc = crate::bumpy::bumpy(2);
        desc.lights.clear();
        desc.world.ambient = Rgb([0.2; 3]);
        desc.world.background = Rgb([0.0; 3]);
        let mut settings = RenderSettings { integrator: Integrator::Path, bailout: 0.01, ..RenderSettings::default() };
        let fields = |desc: &SceneDesc, s: &RenderSettings| {
            integrator_warnings(desc, s).into_iter().map(|w| w.field).collect::<Vec<_>>()
        };
        assert_eq!(fields(&desc, &settings), ["world.ambient", "render.bailout", "materials", "render.integrator"]);
        // The default ambient (a scene without a [world] table) is not the scene's doing.
        let mut unset = desc.clone();
        unset.world.ambient = WorldDesc::default().ambient;
        assert_eq!(fields(&unset, &settings), ["render.bailout", "materials", "render.integrator"]);
        let off = RenderSettings { bailout: 0.0, ..settings.clone() };
        assert_eq!(fields(&unset, &off), ["materials", "render.integrator"], "a bailout of 0 is off");
        settings.integrator = Integrator::Whitted;
        assert!(fields(&desc, &settings).is_empty(), "Whitted's render uses all of it");
    }

    #[test]
    fn a_lights_ambient_is_warned_of_by_its_name_or_by_its_place_alone() {
        let mut desc = crate::bumpy::bumpy(2);
        let settings = RenderSettings { integrator: Integrator::Path, ..RenderSettings::default() };
        let said = |desc: &SceneDesc| {
            let warnings = integrator_warnings(desc, &settings);
            warnings.into_iter().find(|w| w.field == "lights[0].ambient").expect("warned").problem
        };
        desc.lights[0].ambient = Rgb([0.1; 3]);
        desc.lights[0].name = String::new();
        assert!(said(&desc).starts_with("is not used by the path tracer"), "{}", said(&desc));
        desc.lights[0].name = "key".into();
        assert!(said(&desc).starts_with("(key) is not used"), "{}", said(&desc));
    }

    #[test]
    fn a_path_render_is_warned_of_a_material_that_returns_more_light_than_it_receives() {
        let mut desc = crate::bumpy::bumpy(2);
        let settings = RenderSettings { integrator: Integrator::Path, ..RenderSettings::default() };
        let gain = |desc: &SceneDesc| {
            integrator_warnings(desc, &settings).into_iter().filter(|w| w.field == "materials").collect::<Vec<_>>()
        };
        let name = desc.materials.keys().next().expect("a material").clone();
        let m = desc.materials.get_mut(&name).expect("it");
        (m.kd, m.ks, m.kr, m.kt) = (Rgb([0.5, 0.2, 0.2]), Rgb([0.3; 3]), Rgb([0.1; 3]), Rgb([0.1; 3]));
        assert!(gain(&desc).is_empty(), "a sum of 1 at most is fine");
        desc.materials.get_mut(&name).expect("it").kt = Rgb([0.2, 0.1, 0.1]);
        let warned = gain(&desc);
        assert_eq!(warned.len(), 1, "{warned:?}");
        assert!(
            warned[0].problem.starts_with(&format!("k_d + k_s + k_r + k_t > 1 in {name} (1.1000):")),
            "{}",
            warned[0].problem
        );
    }

    #[test]
    fn a_path_render_at_depth_0_is_warned_where_an_emitter_lights_a_glossy_lobe_and_whitted_of_indirect() {
        let mut desc = crate::bumpy::bumpy(2);
        let name = desc.materials.keys().next().expect("a material").clone();
        let m = desc.materials.get_mut(&name).expect("it");
        (m.ks, m.emission) = (Rgb([0.5; 3]), Rgb([1.0; 3]));
        let depth_0 = RenderSettings { integrator: Integrator::Path, max_depth: 0, ..RenderSettings::default() };
        let said = |desc: &SceneDesc, s: &RenderSettings| {
            integrator_warnings(desc, s).into_iter().filter(|w| w.field == "render.max_depth").count()
        };
        assert_eq!(said(&desc, &depth_0), 1);
        assert_eq!(said(&desc, &RenderSettings { max_depth: 1, ..depth_0.clone() }), 0, "depth 1 weighs both");
        desc.materials.values_mut().for_each(|m| m.ks = Rgb([0.0; 3]));
        assert_eq!(said(&desc, &depth_0), 0, "no glossy lobe");
        // A path-tracing setting a file keeps under Whitted is said, not refused.
        let whitted = RenderSettings { indirect: false, ..RenderSettings::default() };
        let fields: Vec<String> = integrator_warnings(&desc, &whitted).into_iter().map(|w| w.field).collect();
        assert_eq!(fields, ["render.indirect"]);
    }
}
