//! What a scene sets that its integrator does not use, or lacks that it needs: warnings for the
//! path tracer, which has no ambient term and draws its light from lights, emitters and the
//! background alone, and that may return more light than they receive under it.

use crate::desc::{RenderSettings, SceneDesc};
use crate::error::FieldIssue;
use crate::rgb::Rgb;
use glint_types::Integrator;

/// The warnings `settings.integrator` gives `desc`; none for Whitted's.
pub fn integrator_warnings(desc: &SceneDesc, settings: &RenderSettings) -> Vec<FieldIssue> {
    let mut out = Vec::new();
    match settings.integrator {
        Integrator::Whitted => return out,
        Integrator::Path => {}
    }
    let unused = "is not used by the path tracer: the indirect light it stands in for is computed";
    if !desc.world.ambient.is_zero() {
        out.push(FieldIssue { field: "world.ambient".into(), problem: unused.into() });
    }
    for (i, light) in desc.lights.iter().enumerate() {
        if !light.ambient.is_zero() {
            out.push(FieldIssue {
                field: format!("lights[{i}].ambient"),
                problem: format!("({}) {unused}", light.name),
            });
        }
    }
    if settings.bailout != RenderSettings::default().bailout {
        out.push(FieldIssue {
            field: "render.bailout".into(),
            problem: "is not used by the path tracer: Russian roulette ends its paths, without bias".into(),
        });
    }
    // The path tracer follows k_d, k_s, k_r and k_t as one BSDF (each lobe's albedo at most its
    // k), so where they sum above 1 a surface returns more light than it receives and radiance
    // grows with every bounce; Whitted's tree sums k_d and k_s once per light instead.
    for (name, m) in &desc.materials {
        let kd = m.checker.as_ref().map_or(m.kd, |c| Rgb(std::array::from_fn(|k| m.kd.0[k].max(c.kd.0[k]))));
        let sums: [f64; 3] = std::array::from_fn(|k| kd.0[k] + m.ks.0[k] + m.kr.0[k] + m.kt.0[k]);
        let (k, sum) =
            sums.iter().enumerate().fold((0, sums[0]), |best, (k, &v)| if v > best.1 { (k, v) } else { best });
        if sum > 1.0 {
            let channel = if sums.iter().all(|&v| v == sum) {
                String::new()
            } else {
                format!(" (channel {})", ["r", "g", "b"][k])
            };
            out.push(FieldIssue {
                field: format!("materials.{name}"),
                problem: format!(
                    "k_d + k_s + k_r + k_t = {sum:.4} > 1{channel}: under the path tracer the surface returns more \
                     light than it receives, so radiance grows with --depth"
                ),
            });
        }
    }
    let emits = desc.materials.values().any(|m| !m.emission.is_zero());
    if desc.lights.is_empty() && !emits && desc.world.background.is_zero() {
        out.push(FieldIssue {
            field: "render.integrator".into(),
            problem: "no light, no emitting material and a black background: the path-traced image will be black"
                .into(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_render_is_warned_of_what_it_leaves_out_and_of_a_black_image() {
        // A bumpy scene without its light, under an ambient sky.
        let mut desc = crate::bumpy::bumpy(2);
        desc.lights.clear();
        desc.world.ambient = Rgb([0.1; 3]);
        desc.world.background = Rgb([0.0; 3]);
        let mut settings = RenderSettings { integrator: Integrator::Path, bailout: 0.01, ..RenderSettings::default() };
        let fields =
            |s: &RenderSettings| integrator_warnings(&desc, s).into_iter().map(|w| w.field).collect::<Vec<_>>();
        assert_eq!(fields(&settings), ["world.ambient", "render.bailout", "materials.clay", "render.integrator"]);
        settings.integrator = Integrator::Whitted;
        assert!(fields(&settings).is_empty(), "Whitted's render uses all of it");
    }

    #[test]
    fn a_path_render_is_warned_of_a_material_that_returns_more_light_than_it_receives() {
        let mut desc = crate::bumpy::bumpy(2);
        let settings = RenderSettings { integrator: Integrator::Path, ..RenderSettings::default() };
        let gain = |desc: &SceneDesc| {
            integrator_warnings(desc, &settings)
                .into_iter()
                .filter(|w| w.field.starts_with("materials."))
                .collect::<Vec<_>>()
        };
        let name = desc.materials.keys().next().expect("a material").clone();
        let m = desc.materials.get_mut(&name).expect("it");
        (m.kd, m.ks, m.kr, m.kt) = (Rgb([0.5, 0.2, 0.2]), Rgb([0.3; 3]), Rgb([0.1; 3]), Rgb([0.1; 3]));
        assert!(gain(&desc).is_empty(), "a sum of 1 at most is fine");
        desc.materials.get_mut(&name).expect("it").kt = Rgb([0.2, 0.1, 0.1]);
        let warned = gain(&desc);
        assert_eq!(warned.len(), 1, "{warned:?}");
        assert!(
            warned[0].problem.starts_with("k_d + k_s + k_r + k_t = 1.1000 > 1 (channel r)"),
            "{}",
            warned[0].problem
        );
    }
}
