//! The terms of the model at a probed hit as rows of CPU (f64) beside GPU (f32) values, and
//! where the two first differ beyond what f32 rounding explains: the pixel probe's table and
//! the ray tree's node comparison share it.

use glam::DVec3;

use crate::cpu::shade::Breakdown;

/// One row of the probe table.
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    pub name: String,
    pub cpu: DVec3,
    pub gpu: Option<DVec3>,
}

/// Relative tolerance between the f64 CPU and f32 GPU value of a term. f32 rounds at 6e-8;
/// a term is a product of a few factors and a dot product or a power, so honest rounding
/// stays well below 1e-4 of its size, while a real divergence (another branch, another hit)
/// is far larger.
pub const REL_TOLERANCE: f64 = 1e-4;
/// Absolute floor of the tolerance for terms near zero.
pub const ABS_TOLERANCE: f64 = 1e-6;

pub fn differs(a: DVec3, b: DVec3) -> bool {
    differs_within(a, b, 1.0)
}

/// `differs` with both tolerances times `widen` (the ray tree's deeper nodes, whose f32
/// inputs carry the rounding of every bounce before them).
pub fn differs_within(a: DVec3, b: DVec3, widen: f64) -> bool {
    let scale = a.abs().max(b.abs()).max_element();
    (a - b).abs().max_element() > widen * (ABS_TOLERANCE + REL_TOLERANCE * scale)
}

/// The terms of both breakdowns in the order of the model.
pub fn terms(cpu: &Breakdown, gpu: Option<&Breakdown>) -> Vec<Term> {
    let mut out = local_terms(cpu, gpu);
    let s = |v: f64| DVec3::splat(v);
    let mut push = |name: &str, c: DVec3, g: Option<DVec3>| out.push(Term { name: name.into(), cpu: c, gpu: g });
    push("k_r·I_r", cpu.reflected, gpu.map(|g| g.reflected));
    push("k_t·I_t", cpu.transmitted, gpu.map(|g| g.transmitted));
    push("t", s(cpu.t), gpu.map(|g| s(g.t)));
    push("N", cpu.normal, gpu.map(|g| g.normal));
    push("I (pixel)", cpu.total, gpu.map(|g| g.total));
    out
}

/// The terms of the local model alone (what a node of the ray tree holds on both tracers).
pub fn local_terms(cpu: &Breakdown, gpu: Option<&Breakdown>) -> Vec<Term> {
    let s = |v: f64| DVec3::splat(v);
    let mut out = Vec::new();
    let mut push = |name: String, c: DVec3, g: Option<DVec3>| out.push(Term { name, cpu: c, gpu: g });
    // The colours after the textures first: where a texture is sampled differently, the terms
    // it feeds differ too, and the first difference should name the cause.
    push("k_a (textured)".into(), cpu.ka, gpu.map(|g| g.ka));
    push("k_d (textured)".into(), cpu.kd, gpu.map(|g| g.kd));
    push("E_m".into(), cpu.emission, gpu.map(|g| g.emission));
    push("I_a·k_a".into(), cpu.ambient, gpu.map(|g| g.ambient));
    for (j, l) in cpu.lights.iter().enumerate() {
        let gl = gpu.and_then(|g| g.lights.get(j));
        push(format!("light {j}: f_att"), s(l.f_att), gl.map(|g| s(g.f_att)));
        push(format!("light {j}: S"), s(l.spot), gl.map(|g| s(g.spot)));
        push(format!("light {j}: V"), l.visibility, gl.map(|g| g.visibility));
        push(format!("light {j}: I_a,j·k_a"), l.ambient, gl.map(|g| g.ambient));
        push(format!("light {j}: diffuse"), l.diffuse, gl.map(|g| g.diffuse));
        push(format!("light {j}: specular"), l.specular, gl.map(|g| g.specular));
        push(format!("light {j}: total"), l.contribution, gl.map(|g| g.contribution));
    }
    out
}

/// Index of the first term where the two tracers differ beyond the tolerance.
pub fn first_difference(terms: &[Term]) -> Option<usize> {
    first_difference_within(terms, 1.0)
}

/// `first_difference` with the tolerances times `widen`.
pub fn first_difference_within(terms: &[Term], widen: f64) -> Option<usize> {
    terms.iter().position(|t| t.gpu.is_some_and(|g| differs_within(t.cpu, g, widen)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_term_beyond_tolerance_is_found() {
        let mut cpu = Breakdown { emission: DVec3::splat(0.5), ambient: DVec3::splat(0.2), ..Breakdown::default() };
        cpu.total = cpu.sum_of_terms();
        let mut gpu = cpu.clone();
        gpu.emission += DVec3::splat(1e-9); // rounding: within tolerance
        assert_eq!(first_difference(&terms(&cpu, Some(&gpu))), None);
        gpu.ambient += DVec3::new(0.0, 0.01, 0.0);
        assert_eq!(first_difference(&terms(&cpu, Some(&gpu))), Some(3));
        gpu.kd += DVec3::new(0.0, 0.01, 0.0);
        assert_eq!(first_difference(&terms(&cpu, Some(&gpu))), Some(1));
    }
}
