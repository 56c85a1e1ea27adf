//! The terms of the model at a probed hit as rows of CPU (f64) beside GPU (f32) values, and
//! where the two first differ beyond what f32 rounding explains: the pixel probe's table and
//! the ray tree's node comparison share it.

use glam::DVec3;
use glint_scene::SpecularModel;

use crate::cpu::ray_tree::RayTree;
use crate::cpu::shade::Breakdown;

/// One row of the probe table.
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    pub name: String,
    pub cpu: DVec3,
    pub gpu: Option<DVec3>,
    /// What the three components are: how the table labels them.
    pub channels: Channels,
    /// How its CPU and GPU values are held against each other.
    pub compared: Compared,
}

/// How a term's CPU and GPU values are held against each other (`differs_within`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compared {
    /// Relative to the values' size.
    Relative,
    /// A cosine of unit vectors: relative to 1, not to its own size. Its f32 error is that of
    /// the directions, whatever the cosine; near 0 (a grazing light, N·L = −0.028 two bounces
    /// into whitted) its own size made f32's 2e-5 a difference.
    Cosine,
    /// Shown, not held against: the lobe c^n magnifies its cosine's rounding n times (n up to
    /// 1e6), and where it counts, k_s > 0, the specular term that holds it is compared.
    Shown,
}

/// What a term's three components are (a table printed `t` three times, and N's x, y, z
/// under R, G, B).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channels {
    /// A colour: R, G, B.
    Rgb,
    /// One number (`t`, f_att, S), held in all three.
    Scalar,
    /// A direction: x, y, z.
    Xyz,
}

impl Term {
    pub fn rgb(name: impl Into<String>, cpu: DVec3, gpu: Option<DVec3>) -> Self {
        Self { name: name.into(), cpu, gpu, channels: Channels::Rgb, compared: Compared::Relative }
    }

    pub fn scalar(name: impl Into<String>, cpu: f64, gpu: Option<f64>) -> Self {
        let (cpu, gpu) = (DVec3::splat(cpu), gpu.map(DVec3::splat));
        Self { name: name.into(), cpu, gpu, channels: Channels::Scalar, compared: Compared::Relative }
    }

    pub fn xyz(name: impl Into<String>, cpu: DVec3, gpu: Option<DVec3>) -> Self {
        Self { name: name.into(), cpu, gpu, channels: Channels::Xyz, compared: Compared::Relative }
    }

    /// The same term held against its GPU value as `compared` says.
    pub fn compared(self, compared: Compared) -> Self {
        Self { compared, ..self }
    }

    /// Whether its GPU value differs from its CPU value beyond the tolerance times `widen`.
    pub fn differs_within(&self, widen: f64) -> bool {
        let Some(g) = self.gpu else { return false };
        match self.compared {
            Compared::Relative => differs_within(self.cpu, g, widen),
            Compared::Cosine => differs_beyond(self.cpu, g, widen, 1.0),
            Compared::Shown => false,
        }
    }
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
    differs_beyond(a, b, widen, 0.0)
}

/// `differs_within` with the relative tolerance of a size no less than `least` (1 for a cosine
/// of unit vectors).
fn differs_beyond(a: DVec3, b: DVec3, widen: f64, least: f64) -> bool {
    let scale = a.abs().max(b.abs()).max_element().max(least);
    (a - b).abs().max_element() > widen * (ABS_TOLERANCE + REL_TOLERANCE * scale)
}

/// The terms of both breakdowns in the order of the model.
pub fn terms(cpu: &Breakdown, gpu: Option<&Breakdown>) -> Vec<Term> {
    let mut out = local_terms(cpu, gpu);
    out.push(Term::rgb("k_r·I_r", cpu.reflected, gpu.map(|g| g.reflected)));
    out.push(Term::rgb("k_t·I_t", cpu.transmitted, gpu.map(|g| g.transmitted)));
    out.push(Term::scalar("t", cpu.t, gpu.map(|g| g.t)));
    out.push(Term::xyz("N", cpu.normal, gpu.map(|g| g.normal)));
    out.push(Term::rgb("I (pixel)", cpu.total, gpu.map(|g| g.total)));
    out
}

/// The terms of the local model alone (what a node of the ray tree holds on both tracers).
pub fn local_terms(cpu: &Breakdown, gpu: Option<&Breakdown>) -> Vec<Term> {
    // The colours at the hit (after the texture and the vertex colour) first: where a texture
    // is sampled differently, the terms it feeds differ too, and the first difference should
    // name the cause.
    let mut out = vec![
        Term::rgb("k_a at the hit", cpu.ka, gpu.map(|g| g.ka)),
        Term::rgb("k_d at the hit", cpu.kd, gpu.map(|g| g.kd)),
        Term::rgb("E_m", cpu.emission, gpu.map(|g| g.emission)),
        Term::rgb("I_a·k_a", cpu.ambient, gpu.map(|g| g.ambient)),
    ];
    for (j, l) in cpu.lights.iter().enumerate() {
        let gl = gpu.and_then(|g| g.lights.get(j));
        let (ca, ga) = (&l.angles, gl.map(|g| &g.angles));
        let (cosine, lobe) = lobe_names(ca.lobe_model);
        // Each product after the cosines it is of: where a direction differs, the first
        // difference names the angle, not the term.
        out.extend([
            Term::scalar(format!("light {j}: f_att"), l.f_att, gl.map(|g| g.f_att)),
            Term::scalar(format!("light {j}: S"), l.spot, gl.map(|g| g.spot)),
            Term::rgb(format!("light {j}: V"), l.visibility, gl.map(|g| g.visibility)),
            Term::rgb(format!("light {j}: I_a,j·k_a"), l.ambient, gl.map(|g| g.ambient)),
            Term::scalar(format!("light {j}: N·L"), ca.n_dot_l, ga.map(|g| g.n_dot_l)).compared(Compared::Cosine),
            Term::rgb(format!("light {j}: diffuse"), l.diffuse, gl.map(|g| g.diffuse)),
            Term::scalar(format!("light {j}: {cosine}"), ca.lobe_cosine, ga.map(|g| g.lobe_cosine))
                .compared(Compared::Cosine),
            Term::scalar(format!("light {j}: {lobe}"), ca.lobe, ga.map(|g| g.lobe)).compared(Compared::Shown),
            Term::rgb(format!("light {j}: specular"), l.specular, gl.map(|g| g.specular)),
            Term::rgb(format!("light {j}: total"), l.contribution, gl.map(|g| g.contribution)),
        ]);
    }
    out
}

/// The lobe each light's specular term was evaluated with: the tracers dispatch it by the
/// material's model and the features compiled in, and a GPU that took another branch differs
/// there first (its cosine and lobe rows would name only the symptom).
pub fn lobes(b: &Breakdown) -> Vec<SpecularModel> {
    b.lights.iter().map(|l| l.angles.lobe_model).collect()
}

/// The first light whose lobe the GPU evaluated otherwise than the CPU, as the probe names it.
pub fn lobe_difference(cpu: &Breakdown, gpu: &Breakdown) -> Option<String> {
    let (c, g) = (lobes(cpu), lobes(gpu));
    let j = c.iter().zip(&g).position(|(a, b)| a != b)?;
    Some(format!("light {j}: the CPU evaluated {}, the GPU {}", lobe_names(c[j]).1, lobe_names(g[j]).1))
}

/// What the probe calls a lobe's cosine and the lobe spec_j, in the seed's notation.
pub fn lobe_names(model: SpecularModel) -> (&'static str, &'static str) {
    match model {
        SpecularModel::Blinn => ("N·H", "(N·H)^n"),
        SpecularModel::Phong => ("R·V", "(R·V)^n"),
        SpecularModel::CookTorrance => ("N·H", "F·D·G/(N·V)"),
    }
}

/// Index of the first term where the two tracers differ beyond the tolerance.
pub fn first_difference(terms: &[Term]) -> Option<usize> {
    first_difference_within(terms, 1.0)
}

/// `first_difference` with the tolerances times `widen`.
pub fn first_difference_within(terms: &[Term], widen: f64) -> Option<usize> {
    terms.iter().position(|t| t.differs_within(widen))
}

/// How much wider than at the first hit the f32-against-f64 tolerance is at `depth`: doubled
/// per level. Each bounce starts from an f32 point and direction that already carry the
/// rounding of the bounces before; through glass the direction error grows about twofold a
/// level (measured: 1e-4 relative at depth 4 through whitted's sphere, within 2^4 × 1e-4),
/// while a real divergence (another branch, another object) changes the tree's shape.
pub fn depth_widening(depth: u32) -> f64 {
    f64::from(1u32 << depth.min(20))
}

/// Where two trees of the same pixel (CPU f64, GPU f32) first part: the node and what differs.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeDifference {
    pub node: usize,
    pub what: String,
}

/// The first node, in depth-first order, where `gpu` differs from `cpu`: in its shape (kind,
/// parent, cut, total internal reflection, light, hit or miss, object hit) exactly, in its
/// values (weight, factor, t, origin, direction, then the local terms) beyond the probe's
/// f32-against-f64 tolerance (`differs`) widened by `depth_widening(depth)`. A
/// tree with fewer nodes differs at the first node it lacks; an overflowed GPU tree is
/// compared over the nodes it kept. Ray origins (world space, as both probes report them) are
/// compared relative to `origin`, the scene's storage origin (`SceneHeader::frame`): the
/// relative tolerance is then of the scene's size, as at the world origin, not of its distance
/// from it (at 5e6 it would let the trees part by 500 units).
pub fn first_tree_difference(cpu: &RayTree, gpu: &RayTree, origin: DVec3) -> Option<NodeDifference> {
    let s = DVec3::splat;
    let kept = if gpu.overflow { gpu.nodes.len().min(cpu.nodes.len()) } else { cpu.nodes.len().max(gpu.nodes.len()) };
    for i in 0..kept {
        let differ = |what: String| Some(NodeDifference { node: i, what });
        let (Some(c), Some(g)) = (cpu.nodes.get(i), gpu.nodes.get(i)) else {
            return differ(format!("{} nodes on the CPU, {} on the GPU", cpu.nodes.len(), gpu.nodes.len()));
        };
        let shape = [
            ("kind", c.kind != g.kind),
            ("parent", c.parent != g.parent),
            ("cut", c.cut != g.cut),
            ("total internal reflection", c.tir != g.tir),
            ("light", c.light != g.light),
            ("hit or miss", c.t.is_some() != g.t.is_some()),
            ("object hit", c.terms.as_ref().map(|t| t.object_id) != g.terms.as_ref().map(|t| t.object_id)),
            ("specular lobe", c.terms.as_ref().map(lobes) != g.terms.as_ref().map(lobes)),
        ];
        if let Some((what, _)) = shape.iter().find(|(_, d)| *d) {
            return differ(what.to_string());
        }
        let values = [
            ("weight", c.weight, g.weight),
            ("factor", c.factor, g.factor),
            ("t", s(c.t.unwrap_or(0.0)), s(g.t.unwrap_or(0.0))),
            ("attenuation", s(c.attenuation), s(g.attenuation)),
            ("origin", c.origin - origin, g.origin - origin),
            ("direction", c.dir, g.dir),
        ];
        let widen = depth_widening(c.depth);
        let differs = |a: DVec3, b: DVec3| differs_within(a, b, widen);
        if let Some((what, ..)) = values.iter().find(|(_, a, b)| differs(*a, *b)) {
            return differ(what.to_string());
        }
        if let (Some(ct), Some(gt)) = (&c.terms, &g.terms) {
            let rows = local_terms(ct, Some(gt));
            if let Some(r) = first_difference_within(&rows, widen) {
                return differ(rows[r].name.clone());
            }
            if differs(ct.normal, gt.normal) {
                return differ("N".into());
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cpu::shade::LightTerm;

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

    #[test]
    fn another_lobe_on_the_gpu_is_named() {
        let mut cpu = Breakdown::default();
        cpu.lights.push(LightTerm::default());
        let mut gpu = cpu.clone();
        assert_eq!(lobe_difference(&cpu, &gpu), None);
        gpu.lights[0].angles.lobe_model = SpecularModel::Phong;
        assert_eq!(lobe_difference(&cpu, &gpu).as_deref(), Some("light 0: the CPU evaluated (N·H)^n, the GPU (R·V)^n"));
    }

    #[test]
    fn a_cosine_is_held_to_f32_of_its_unit_vectors_and_a_lobe_only_shown() {
        // whitted's glass at depth 2: a grazing light, N·L −0.027754 on the CPU, −0.027777 on
        // the GPU (2.3e-5 apart: f32 directions two bounces deep, within 4 × 1e-4 of 1).
        let mut cpu = Breakdown::default();
        cpu.lights.push(LightTerm::default());
        let mut gpu = cpu.clone();
        cpu.lights[0].angles.n_dot_l = -0.027754272301748317;
        gpu.lights[0].angles.n_dot_l = -0.027777403593063354;
        assert_eq!(first_difference_within(&local_terms(&cpu, Some(&gpu)), 4.0), None);
        // A cosine off by 0.01 is a difference, whatever its size.
        gpu.lights[0].angles.n_dot_l = -0.037754;
        let rows = local_terms(&cpu, Some(&gpu));
        assert_eq!(first_difference(&rows).map(|i| rows[i].name.as_str()), Some("light 0: N·L"));
        // The lobe is shown, not held against: its specular term is.
        gpu.lights[0].angles.n_dot_l = cpu.lights[0].angles.n_dot_l;
        gpu.lights[0].angles.lobe = 0.5;
        assert_eq!(first_difference(&local_terms(&cpu, Some(&gpu))), None);
    }

    #[test]
    fn each_term_says_what_its_components_are() {
        let cpu = Breakdown { lights: vec![Default::default()], ..Breakdown::default() };
        let rows = terms(&cpu, None);
        let of = |name: &str| rows.iter().find(|t| t.name == name).map(|t| t.channels);
        assert_eq!(of("t"), Some(Channels::Scalar));
        assert_eq!(of("light 0: f_att"), Some(Channels::Scalar));
        assert_eq!(of("light 0: S"), Some(Channels::Scalar));
        assert_eq!(of("N"), Some(Channels::Xyz));
        assert_eq!(of("light 0: diffuse"), Some(Channels::Rgb));
        assert_eq!(of("I (pixel)"), Some(Channels::Rgb));
    }
}
