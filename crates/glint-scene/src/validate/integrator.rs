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
