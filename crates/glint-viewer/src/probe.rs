//! The pixel probe: one pixel's radiance split into the terms of the model, and its whole ray
//! tree, on the CPU (instant: one camera ray tree) and on the GPU (its probe shader variant,
//! on a thread so that compiling the variant never stalls the UI).

use std::sync::Arc;

use glint_core::cpu::ray_tree::RayTree;
use glint_core::cpu::shade::Breakdown;
use glint_core::path_kinds::{PathProbe, probe_paths};
use glint_core::probe_terms::{NodeDifference, first_tree_difference as first_node_difference};
use glint_core::{FlatScene, probe_pixel, probe_tree};
use glint_gpu::GpuTracer;
use glint_types::layout::UnknownTag;

use crate::worker::Worker;

#[derive(Debug)]
pub enum GpuProbe {
    /// The breakdown and the ray tree, from one dispatch.
    Pending(Worker<Result<(Breakdown, RayTree), String>>),
    Done(Result<Breakdown, String>),
    Unavailable(String),
}

#[derive(Debug)]
pub struct ProbeState {
    pub x: u32,
    pub y: u32,
    pub revision: u64,
    pub cpu: Breakdown,
    pub gpu: GpuProbe,
    /// The sample's whole ray tree on the CPU.
    pub cpu_tree: RayTree,
    /// The GPU's, once its probe has arrived.
    pub gpu_tree: Option<RayTree>,
    /// The scene's storage origin, which the trees' points are compared relative to.
    pub origin: glint_core::glam::DVec3,
    /// In path mode, the pixel's path-traced radiance by bounce and kind of light (CPU).
    pub paths: Option<PathProbe>,
}

impl ProbeState {
    /// Probes pixel (x, y) of the full-resolution scene on both tracers: Whitted's terms and ray
    /// tree of `scene` (the scene with Whitted's integrator), and where `paths` is given (the
    /// scene as path-traced) the paths' radiance by bounce and kind. The UI of `repaint` is
    /// woken when the GPU result arrives (it may be idle by then).
    pub fn start(
        scene: &FlatScene,
        paths: Option<&FlatScene>,
        x: u32,
        y: u32,
        revision: u64,
        gpu: Option<&Arc<GpuTracer>>,
        repaint: &egui::Context,
    ) -> Result<Self, UnknownTag> {
        let cpu = probe_pixel(scene, x, y, 0)?;
        let cpu_tree = probe_tree(scene, x, y, 0)?;
        let gpu = match gpu {
            None => GpuProbe::Unavailable("no GPU".into()),
            Some(tracer) => {
                let mut worker = Worker::new("glint-probe", "probe", Some(repaint.clone()));
                let (tracer, scene) = (tracer.clone(), scene.clone());
                let started = worker.start(revision, move |_| {
                    tracer.probe(&scene, x, y).map(|p| (p.breakdown, p.tree)).map_err(|e| e.to_string())
                });
                match started {
                    Ok(()) => GpuProbe::Pending(worker),
                    Err(e) => GpuProbe::Unavailable(e.to_string()),
                }
            }
        };
        let paths = paths.and_then(|p| {
            let ctx = glint_core::cpu::TraceContext::new(p).ok()?;
            Some(probe_paths(&ctx, x, y, p.header.spp))
        });
        let origin = scene.frame_origin();
        Ok(Self { x, y, revision, cpu, gpu, cpu_tree, gpu_tree: None, origin, paths })
    }

    /// Collects the GPU result when it has arrived; true when it did.
    pub fn poll(&mut self) -> bool {
        let GpuProbe::Pending(worker) = &mut self.gpu else { return false };
        let Some((_, result)) = worker.poll() else { return false };
        let result = result.unwrap_or_else(|e| Err(e.to_string()));
        self.gpu = GpuProbe::Done(result.map(|(breakdown, tree)| {
            self.gpu_tree = Some(tree);
            breakdown
        }));
        true
    }

    /// The first node where the GPU's ray tree differs from the CPU's (none before it arrives).
    pub fn tree_difference(&self) -> Option<NodeDifference> {
        first_node_difference(&self.cpu_tree, self.gpu_tree.as_ref()?, self.origin)
    }

    pub fn gpu_breakdown(&self) -> Option<&Breakdown> {
        match &self.gpu {
            GpuProbe::Done(Ok(b)) => Some(b),
            _ => None,
        }
    }
}

pub use glint_core::probe_terms::{Channels, Term, first_difference, terms};
