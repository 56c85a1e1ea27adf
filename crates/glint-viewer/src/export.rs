//! "Save image": the GPU view, the CPU view, the difference view or all three side by side,
//! as PNG with the render settings embedded (the same `glint:*` keys as `glint render`) or as
//! linear EXR.

use std::path::Path;

use glint_core::image::{RenderInfo, render_metadata};
use glint_io::image_file::{write_exr, write_png_rgb8};
use glint_scene::RenderSettings;

use crate::comparison::Compared;
use crate::cpu_worker::Finished;
use crate::error::ViewerError;
use crate::gpu_view::GpuImage;
use crate::images::{side_by_side, side_by_side_hdr};
use glint_core::compare::abs_difference;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportView {
    Gpu,
    Cpu,
    Difference,
    All,
}

impl ExportView {
    pub const ALL: [Self; 4] = [Self::Gpu, Self::Cpu, Self::Difference, Self::All];

    pub fn label(self) -> &'static str {
        match self {
            Self::Gpu => "GPU view",
            Self::Cpu => "CPU view",
            Self::Difference => "Difference view",
            Self::All => "All three side by side",
        }
    }

    fn backend(self) -> &'static str {
        match self {
            Self::Gpu => "gpu",
            Self::Cpu => "cpu",
            Self::Difference => "diff",
            Self::All => "cpu|gpu|diff",
        }
    }
}

/// The finished renders of the current scene revision.
#[derive(Clone, Copy, Debug)]
pub struct Sources<'a> {
    pub scene: &'a str,
    pub settings: &'a RenderSettings,
    pub cpu: Option<&'a Finished>,
    pub gpu: Option<&'a GpuImage>,
    pub diff: Option<&'a Compared>,
    pub adapter: &'a str,
}

pub fn export(path: &Path, view: ExportView, s: &Sources) -> Result<(), ViewerError> {
    let is_exr = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let need_cpu = matches!(view, ExportView::Cpu | ExportView::Difference | ExportView::All);
    let need_gpu = matches!(view, ExportView::Gpu | ExportView::Difference | ExportView::All);
    let cpu = s.cpu.filter(|_| need_cpu);
    let gpu = s.gpu.filter(|_| need_gpu);
    if need_cpu && cpu.is_none() {
        return Err(ViewerError::NotReady("the CPU reference is still rendering"));
    }
    if need_gpu && gpu.is_none() {
        return Err(ViewerError::NotReady("there is no finished GPU render of this scene"));
    }
    let device = match view {
        ExportView::Cpu => cpu.map(|c| format!("{} threads", c.threads)).unwrap_or_default(),
        _ => s.adapter.to_string(),
    };
    let info = RenderInfo {
        scene: s.scene,
        backend: view.backend(),
        device: &device,
        specialised: true,
        time_ms: match view {
            ExportView::Cpu => cpu.map(|c| c.elapsed.as_secs_f64() * 1e3),
            ExportView::Gpu => gpu.map(|g| g.gpu_ms),
            _ => None,
        },
        rays: match view {
            ExportView::Cpu => cpu.map(|c| c.counts.total()),
            ExportView::Gpu => gpu.map(|g| g.counts.total()),
            _ => None,
        },
    };
    // In path mode the GPU's image is the mean of every batch so far: its samples, not the
    // scene's (a saved mean of 340 said 64).
    let gpu_samples = gpu.map(|g| g.samples).filter(|&n| n != s.settings.spp);
    let settings = match (view, gpu_samples) {
        (ExportView::Gpu, Some(spp)) => RenderSettings { spp, ..s.settings.clone() },
        _ => s.settings.clone(),
    };
    let mut metadata = render_metadata(&settings, &info);
    if let (ExportView::Difference | ExportView::All, Some(spp)) = (view, gpu_samples) {
        metadata.push(("glint:gpu_spp".into(), spp.to_string()));
    }
    metadata.push(("glint:view".into(), view.label().into()));
    if let Some(d) = s.diff.filter(|_| matches!(view, ExportView::Difference | ExportView::All)) {
        metadata.push(("glint:diff_scale".into(), "magma over log10 |gpu-cpu| from -7 to 0".into()));
        metadata.push(("glint:psnr_db".into(), format!("{:.2}", d.errors.psnr)));
    }
    if is_exr {
        let image = match (view, cpu, gpu) {
            (ExportView::Cpu, Some(c), _) => c.image.clone(),
            (ExportView::Gpu, _, Some(g)) => g.image.clone(),
            (ExportView::Difference, Some(c), Some(g)) => abs_difference(&c.image, &g.image),
            (ExportView::All, Some(c), Some(g)) => {
                side_by_side_hdr(&[&c.image, &g.image, &abs_difference(&c.image, &g.image)])
            }
            _ => return Err(ViewerError::NotReady("the renders are not ready")),
        };
        return Ok(write_exr(path, &image, &metadata)?);
    }
    let heatmap = || s.diff.ok_or(ViewerError::NotReady("the comparison of GPU and CPU is still running"));
    let (width, height, rgb) = match (view, cpu, gpu) {
        (ExportView::Cpu, Some(c), _) => (c.image.width, c.image.height, c.image.to_srgb8()),
        (ExportView::Gpu, _, Some(g)) => (g.image.width, g.image.height, g.image.to_srgb8()),
        (ExportView::Difference, _, _) => {
            let d = heatmap()?;
            (d.width, d.height, d.heatmap.clone())
        }
        (ExportView::All, Some(c), Some(g)) => {
            let d = heatmap()?;
            let (cs, gs) = (c.image.to_srgb8(), g.image.to_srgb8());
            side_by_side(&[
                (c.image.width, c.image.height, &cs),
                (g.image.width, g.image.height, &gs),
                (d.width, d.height, &d.heatmap),
            ])
        }
        _ => return Err(ViewerError::NotReady("the renders are not ready")),
    };
    Ok(write_png_rgb8(path, width, height, &rgb, &metadata)?)
}
