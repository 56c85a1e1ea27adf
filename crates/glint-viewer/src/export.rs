//! "Save image": the GPU view, the CPU view, the difference view or all three side by side,
//! and the Whitted vs GI view's Whitted image, paths, signed difference or all three, as PNG
//! with the render settings embedded (the same `glint:*` keys as `glint render`) or as linear
//! EXR (the signed difference signed: Whitted − GI).

use std::path::Path;

use glint_core::image::{RenderInfo, render_metadata};
use glint_io::image_file::{write_exr, write_png_rgb8};
use glint_scene::RenderSettings;

use crate::comparison::Compared;
use crate::cpu_worker::Finished;
use crate::error::ViewerError;
use crate::gpu_view::GpuImage;
use crate::images::{side_by_side, side_by_side_hdr};
use glint_core::HdrImage;
use glint_core::compare::{SignedDifference, abs_difference};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportView {
    Gpu,
    Cpu,
    Difference,
    All,
    /// Whitted vs GI: Whitted's image (rendered on the CPU).
    Whitted,
    /// Whitted vs GI: the paths shown beside it (the GPU's mean over its batches, else the CPU's).
    Paths,
    /// Whitted vs GI: Whitted − paths, signed.
    WhittedMinusGi,
    /// Whitted vs GI: the three side by side.
    WhittedVsGi,
}

impl ExportView {
    pub const ALL: [Self; 8] = [
        Self::Gpu,
        Self::Cpu,
        Self::Difference,
        Self::All,
        Self::Whitted,
        Self::Paths,
        Self::WhittedMinusGi,
        Self::WhittedVsGi,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Self::Gpu => "GPU view",
            Self::Cpu => "CPU view",
            Self::Difference => "Difference view",
            Self::All => "All three side by side",
            Self::Whitted => "Whitted vs GI: Whitted's image",
            Self::Paths => "Whitted vs GI: the paths (GI)",
            Self::WhittedMinusGi => "Whitted vs GI: Whitted − GI, signed",
            Self::WhittedVsGi => "Whitted vs GI: the three side by side",
        }
    }

    pub fn is_gi(self) -> bool {
        match self {
            Self::Gpu | Self::Cpu | Self::Difference | Self::All => false,
            Self::Whitted | Self::Paths | Self::WhittedMinusGi | Self::WhittedVsGi => true,
        }
    }

    fn backend(self) -> &'static str {
        match self {
            Self::Gpu => "gpu",
            Self::Cpu | Self::Whitted => "cpu",
            Self::Difference => "diff",
            Self::All => "cpu|gpu|diff",
            Self::Paths => "paths",
            Self::WhittedMinusGi | Self::WhittedVsGi => "whitted-gi",
        }
    }
}

/// What the Whitted vs GI view shows: Whitted's image (of `settings` with Whitted's
/// integrator) and the paths beside it.
#[derive(Clone, Copy, Debug)]
pub struct GiSources<'a> {
    pub whitted: &'a HdrImage,
    pub whitted_settings: &'a RenderSettings,
    pub paths: &'a HdrImage,
    pub samples: u32,
    pub paths_on_gpu: bool,
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
    /// The Whitted vs GI view's images, where both are there.
    pub gi: Option<GiSources<'a>>,
}

pub fn export(path: &Path, view: ExportView, s: &Sources) -> Result<(), ViewerError> {
    // By the name's extension, as `glint render -o` reads it: any other (cpu.jpg) was written
    // as a PNG under that name (a viewer tester).
    let is_exr = match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png") => false,
        Some("exr") => true,
        _ => return Err(ViewerError::ImageFormat(path.to_owned())),
    };
    if view.is_gi() {
        let gi = s.gi.ok_or(ViewerError::NotReady(
            "the Whitted vs GI view has no Whitted image and paths of this scene yet (open that view and let it render)",
        ))?;
        return export_gi(path, view, s, &gi, is_exr);
    }
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

/// The Whitted vs GI views: the difference taken again from the images as they are now (the
/// view's own follows the paths at each doubling of their samples).
fn export_gi(path: &Path, view: ExportView, s: &Sources, gi: &GiSources, is_exr: bool) -> Result<(), ViewerError> {
    // The paths are the scene's own render: under Whitted's integrator that is a second Whitted
    // image, which was saved as "the paths (GI)" with `glint:integrator` path (a lecturer).
    if view != ExportView::Whitted && s.settings.integrator.is_whitted() {
        return Err(ViewerError::NotReady(
            "the scene renders with Whitted's integrator, so there are no paths to save as GI (switch it to Paths)",
        ));
    }
    if (gi.whitted.width, gi.whitted.height) != (gi.paths.width, gi.paths.height) {
        return Err(ViewerError::NotReady("Whitted's image and the paths are of different sizes"));
    }
    let paths_device = if gi.paths_on_gpu { s.adapter.to_string() } else { "cpu".to_string() };
    let paths_settings = RenderSettings { spp: gi.samples, ..s.settings.clone() };
    let (settings, backend, device) = match view {
        ExportView::Whitted => (gi.whitted_settings, "cpu", "cpu".to_string()),
        ExportView::Paths => (&paths_settings, if gi.paths_on_gpu { "gpu" } else { "cpu" }, paths_device.clone()),
        _ => (gi.whitted_settings, view.backend(), paths_device.clone()),
    };
    let info = RenderInfo { scene: s.scene, backend, device: &device, specialised: true, time_ms: None, rays: None };
    let mut metadata = render_metadata(settings, &info);
    metadata.push(("glint:view".into(), view.label().into()));
    let diff = SignedDifference::new(gi.whitted, gi.paths);
    if matches!(view, ExportView::WhittedMinusGi | ExportView::WhittedVsGi) {
        metadata.push(("glint:gi_spp".into(), gi.samples.to_string()));
        metadata.push((
            "glint:diff_scale".into(),
            format!(
                "Whitted - GI, mean of R, G, B: blue below, white 0, red above, full at +-{:e}{}",
                diff.scale,
                if is_exr { "; the EXR holds the signed difference per channel" } else { "" }
            ),
        ));
    }
    if is_exr {
        let signed = || HdrImage { pixels: diff.pixels.clone(), ..gi.whitted.clone() };
        let image = match view {
            ExportView::Whitted => gi.whitted.clone(),
            ExportView::Paths => gi.paths.clone(),
            ExportView::WhittedMinusGi => signed(),
            _ => side_by_side_hdr(&[gi.whitted, gi.paths, &signed()]),
        };
        return Ok(write_exr(path, &image, &metadata)?);
    }
    let (w, h) = (gi.whitted.width, gi.whitted.height);
    let (width, height, rgb) = match view {
        ExportView::Whitted => (w, h, gi.whitted.to_srgb8()),
        ExportView::Paths => (w, h, gi.paths.to_srgb8()),
        ExportView::WhittedMinusGi => (w, h, diff.rgb.clone()),
        _ => {
            let (ws, ps) = (gi.whitted.to_srgb8(), gi.paths.to_srgb8());
            side_by_side(&[(w, h, &ws), (w, h, &ps), (w, h, &diff.rgb)])
        }
    };
    Ok(write_png_rgb8(path, width, height, &rgb, &metadata)?)
}
