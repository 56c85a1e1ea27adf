//! The pixel probe: one pixel's radiance split into the terms of the model, on the CPU
//! (instant: one camera ray tree) and on the GPU (its probe shader variant, on a thread so
//! that compiling the variant never stalls the UI).

use std::sync::Arc;

use glint_core::cpu::shade::Breakdown;
use glint_core::glam::DVec3;
use glint_core::{FlatScene, probe_pixel};
use glint_gpu::GpuTracer;

use crate::worker::Worker;

#[derive(Debug)]
pub enum GpuProbe {
    Pending(Worker<Result<Breakdown, String>>),
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
}

impl ProbeState {
    /// Probes pixel (x, y) of the full-resolution scene on both tracers. The UI of `repaint`
    /// is woken when the GPU result arrives (it may be idle by then).
    pub fn start(
        scene: &FlatScene,
        x: u32,
        y: u32,
        revision: u64,
        gpu: Option<&Arc<GpuTracer>>,
        repaint: &egui::Context,
    ) -> Self {
        let cpu = probe_pixel(scene, x, y, 0);
        let gpu = match gpu {
            None => GpuProbe::Unavailable("no GPU".into()),
            Some(tracer) => {
                let mut worker = Worker::new("glint-probe", "probe", Some(repaint.clone()));
                let (tracer, scene) = (tracer.clone(), scene.clone());
                let started = worker.start(revision, move |_| {
                    tracer
                        .probe_pixel(&scene, x, y)
                        .map(|(record, _status)| glint_gpu::probe::breakdown(&record))
                        .map_err(|e| e.to_string())
                });
                match started {
                    Ok(()) => GpuProbe::Pending(worker),
                    Err(e) => GpuProbe::Unavailable(e.to_string()),
                }
            }
        };
        Self { x, y, revision, cpu, gpu }
    }

    /// Collects the GPU result when it has arrived; true when it did.
    pub fn poll(&mut self) -> bool {
        let GpuProbe::Pending(worker) = &mut self.gpu else { return false };
        let Some((_, result)) = worker.poll() else { return false };
        self.gpu = GpuProbe::Done(result.unwrap_or_else(|e| Err(e.to_string())));
        true
    }

    pub fn gpu_breakdown(&self) -> Option<&Breakdown> {
        match &self.gpu {
            GpuProbe::Done(Ok(b)) => Some(b),
            _ => None,
        }
    }
}

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
    let scale = a.abs().max(b.abs()).max_element();
    (a - b).abs().max_element() > ABS_TOLERANCE + REL_TOLERANCE * scale
}

/// The terms of both breakdowns in the order of the model.
pub fn terms(cpu: &Breakdown, gpu: Option<&Breakdown>) -> Vec<Term> {
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
    push("k_r·I_r".into(), cpu.reflected, gpu.map(|g| g.reflected));
    push("k_t·I_t".into(), cpu.transmitted, gpu.map(|g| g.transmitted));
    push("t".into(), s(cpu.t), gpu.map(|g| s(g.t)));
    push("N".into(), cpu.normal, gpu.map(|g| g.normal));
    push("I (pixel)".into(), cpu.total, gpu.map(|g| g.total));
    out
}

/// Index of the first term where the two tracers differ beyond the tolerance.
pub fn first_difference(terms: &[Term]) -> Option<usize> {
    terms.iter().position(|t| t.gpu.is_some_and(|g| differs(t.cpu, g)))
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
