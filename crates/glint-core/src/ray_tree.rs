//! The Whitted ray tree of one camera sample, as the tracer walked it: every ray (camera,
//! reflection, refraction, shadow) with its path weight and own factor, its hit and the local
//! terms there, and the children the bailout or the depth limit cut. The CPU tracer records it
//! through `TreeRecorder` (`probe_tree`); the GPU probe variant writes the same nodes in the
//! same depth-first order (`shaders/probe.wgsl`, this module's twin, into `layout::ProbeTree`),
//! so the two line up by index.

use glam::DVec3;

use crate::cpu::shade::{Breakdown, light_sample};
use crate::cpu::{Ray, TraceContext};
use glint_types::RayKind;

/// Why a child ray was not traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cut {
    /// Its path weight fell below the bailout.
    Bailout,
    /// Its parent was at the maximum depth.
    MaxDepth,
    /// The sample's tree reached `TraceContext::max_rays_per_sample` (CPU only).
    RayCap,
}

impl Cut {
    pub fn name(self) -> &'static str {
        match self {
            Self::Bailout => "cut by the bailout",
            Self::MaxDepth => "cut at max depth",
            Self::RayCap => "cut by the ray cap",
        }
    }
}

/// One ray of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct RayNode {
    pub kind: RayKind,
    /// Index of the ray whose hit spawned this one (`None` for the camera ray).
    pub parent: Option<usize>,
    pub depth: u32,
    pub origin: DVec3,
    pub dir: DVec3,
    /// Distance to the hit (to the light for a shadow ray); `None` for a miss or a cut ray.
    pub t: Option<f64>,
    /// This ray's own factor: k_r, k_t, k_r + k_t under total internal reflection, V_j for a
    /// shadow ray, 1 for the camera ray.
    pub factor: DVec3,
    /// The product of the factors along the path to this ray, its own included: what the
    /// bailout judges and what scales the radiance it brings back into the pixel.
    pub weight: DVec3,
    /// The world's global attenuation f_att(t) at the hit (1 without it).
    pub attenuation: f64,
    /// A mirror ray that also carries the k_t share (total internal reflection).
    pub tir: bool,
    pub cut: Option<Cut>,
    /// The light a shadow ray goes to.
    pub light: Option<u32>,
    /// The local terms at the hit (the probe's breakdown; `total`, `reflected` and
    /// `transmitted` are this node's own on the CPU, zero on the GPU).
    pub terms: Option<Breakdown>,
    /// The radiance the ray brings back (CPU only: the GPU sums weighted terms instead).
    pub radiance: Option<DVec3>,
}

impl RayNode {
    /// A ray about to be traced (or cut), before its hit is known.
    pub fn new(kind: RayKind, parent: Option<usize>, depth: u32, ray: &Ray, factor: DVec3, weight: DVec3) -> Self {
        Self {
            kind,
            parent,
            depth,
            origin: ray.origin,
            dir: ray.dir,
            t: None,
            factor,
            weight,
            attenuation: 1.0,
            tir: false,
            cut: None,
            light: None,
            terms: None,
            radiance: None,
        }
    }

    /// Whether the ray was traced and hit a surface (for a shadow ray: reached its light's
    /// distance, whatever the visibility).
    pub fn hit(&self) -> bool {
        self.t.is_some()
    }
}

/// The tree of one camera sample, nodes in depth-first order: a ray, its shadow rays (in light
/// order), then its mirror child's subtree, then its refracted child's.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RayTree {
    pub nodes: Vec<RayNode>,
    /// More nodes were met than recorded (the GPU's fixed capacity).
    pub overflow: bool,
    /// The scene has more lights than the GPU records terms of.
    pub lights_truncated: bool,
}

/// What the tracer tells a tree as it walks it. The ordinary render passes `NoTree`, whose
/// `RECORDS` is false: the tracer then skips every recording step at compile time.
pub trait TreeRecorder {
    const RECORDS: bool;
    /// Adds a node; returns its index.
    fn open(&mut self, node: RayNode) -> usize;
    /// The hit (or miss) of node `index`, its local terms and the radiance it brings back.
    fn close(&mut self, index: usize, t: Option<f64>, attenuation: f64, terms: Option<Breakdown>, radiance: DVec3);
}

/// The recorder of the ordinary render: records nothing.
#[derive(Debug)]
pub struct NoTree;

impl TreeRecorder for NoTree {
    const RECORDS: bool = false;
    #[inline(always)]
    fn open(&mut self, _: RayNode) -> usize {
        0
    }
    #[inline(always)]
    fn close(&mut self, _: usize, _: Option<f64>, _: f64, _: Option<Breakdown>, _: DVec3) {}
}

impl TreeRecorder for RayTree {
    const RECORDS: bool = true;
    fn open(&mut self, node: RayNode) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }
    fn close(&mut self, index: usize, t: Option<f64>, attenuation: f64, terms: Option<Breakdown>, radiance: DVec3) {
        let node = &mut self.nodes[index];
        node.t = t;
        node.attenuation = attenuation;
        node.terms = terms;
        node.radiance = Some(radiance);
    }
}

/// The shadow rays of node `parent`'s hit at `p`, from its local terms: one node per light a
/// shadow ray was traced to, from p towards the light (the light sample's L, the direction the
/// model used; the traced ray starts ε off the surface), its factor the visibility V_j.
pub fn record_shadow_rays(
    ctx: &TraceContext,
    rec: &mut impl TreeRecorder,
    parent: usize,
    depth: u32,
    weight: DVec3,
    p: DVec3,
    terms: &Breakdown,
) {
    for (j, term) in terms.lights.iter().enumerate() {
        if !term.shadow_ray {
            continue;
        }
        let ls = light_sample(ctx, &ctx.scene.lights[j], ctx.light_tags[j], p);
        let ray = Ray { origin: p, dir: ls.l };
        let mut node = RayNode::new(RayKind::Shadow, Some(parent), depth + 1, &ray, term.visibility, weight);
        node.light = Some(j as u32);
        node.t = Some(ls.dist);
        rec.open(node);
    }
}

impl RayTree {
    /// The children of node `index` (shadow rays first, then the mirror and the refracted ray).
    pub fn children(&self, index: usize) -> impl Iterator<Item = usize> + '_ {
        self.nodes.iter().enumerate().filter(move |(_, n)| n.parent == Some(index)).map(|(i, _)| i)
    }

    /// The radiance of node `index` recomputed from the recorded terms and factors alone, in the
    /// CPU tracer's order of operations: E_m + I_a·k_a + Σ_j light_j, plus factor·I of each
    /// traced child, times the global attenuation; the background for a miss. For the CPU tree
    /// it equals the rendered radiance bit for bit, which shows that the tree holds everything
    /// the render computed.
    pub fn radiance_of(&self, index: usize, background: DVec3) -> DVec3 {
        let node = &self.nodes[index];
        let Some(terms) = &node.terms else { return background };
        let mut sum = DVec3::ZERO;
        for l in &terms.lights {
            sum += l.contribution;
        }
        let mut radiance = terms.emission + terms.ambient + sum;
        for child in self.children(index) {
            let c = &self.nodes[child];
            if c.kind != RayKind::Shadow && c.cut.is_none() {
                radiance += c.factor * self.radiance_of(child, background);
            }
        }
        if node.kind == RayKind::Camera { radiance } else { node.attenuation * radiance }
    }

    /// The number of nodes of `kind`.
    pub fn count(&self, kind: RayKind) -> usize {
        self.nodes.iter().filter(|n| n.kind == kind).count()
    }
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
/// f32-against-f64 tolerance (`probe_terms::differs`) widened by `depth_widening(depth)`. A
/// tree with fewer nodes differs at the first node it lacks; an overflowed GPU tree is
/// compared over the nodes it kept.
pub fn first_difference(cpu: &RayTree, gpu: &RayTree) -> Option<NodeDifference> {
    use crate::probe_terms::{differs_within, first_difference_within as first_term, local_terms};
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
        ];
        if let Some((what, _)) = shape.iter().find(|(_, d)| *d) {
            return differ(what.to_string());
        }
        let values = [
            ("weight", c.weight, g.weight),
            ("factor", c.factor, g.factor),
            ("t", s(c.t.unwrap_or(0.0)), s(g.t.unwrap_or(0.0))),
            ("attenuation", s(c.attenuation), s(g.attenuation)),
            ("origin", c.origin, g.origin),
            ("direction", c.dir, g.dir),
        ];
        let widen = depth_widening(c.depth);
        let differs = |a: DVec3, b: DVec3| differs_within(a, b, widen);
        if let Some((what, ..)) = values.iter().find(|(_, a, b)| differs(*a, *b)) {
            return differ(what.to_string());
        }
        if let (Some(ct), Some(gt)) = (&c.terms, &g.terms) {
            let rows = local_terms(ct, Some(gt));
            if let Some(r) = first_term(&rows, widen) {
                return differ(rows[r].name.clone());
            }
            if differs(ct.normal, gt.normal) {
                return differ("N".into());
            }
        }
    }
    None
}
