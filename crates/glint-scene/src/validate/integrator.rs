//! What a scene sets that its integrator does not use, or lacks that it needs: warnings for the
//! path tracer, which has no ambient term and draws its light from lights, emitters and the
//! background alone.

use crate::desc::{RenderSettings, SceneDesc};
use crate::error::FieldIssue;
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
    use crate::rgb::Rgb;

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
        assert_eq!(fields(&settings), ["world.ambient", "render.bailout", "render.integrator"]);
        settings.integrator = Integrator::Whitted;
        assert!(fields(&settings).is_empty(), "Whitted's render uses all of it");
    }
}
