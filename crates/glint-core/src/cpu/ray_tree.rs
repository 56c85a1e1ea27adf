//! The Whitted ray tree of one camera sample, as the tracer walked it: every ray (camera,
//! reflection, refraction, shadow) with its path weight and own factor, its hit and the local
//! terms there, and the children the bailout or the depth limit cut. The CPU tracer records it
//! through `TreeRecorder` (`probe_tree`); the GPU probe variant writes the same nodes in the
//! same depth-first order (`shaders/probe.wgsl`, this module's twin, into `layout::ProbeTree`),
//! so the two line up by index.

use glam::DVec3;

use super::shade::{Breakdown, light_sample};
use super::{Ray, TraceContext};
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

    /// Moves every point of the tree by `offset`: its rays' origins and hit points, from the
    /// frame it was traced in to world space (both probes).
    pub fn translate(&mut self, offset: DVec3) {
        for node in &mut self.nodes {
            node.origin += offset;
            if let Some(terms) = &mut node.terms {
                terms.point += offset;
            }
        }
    }

    /// The number of nodes of `kind`.
    pub fn count(&self, kind: RayKind) -> usize {
        self.nodes.iter().filter(|n| n.kind == kind).count()
    }
}
