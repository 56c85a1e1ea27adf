//! Running one render on either backend, with the timings the table reports.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use anyhow::Context;
use glint_core::cpu::RayCounts;
use glint_core::render::{Tile, tile_count};
use glint_core::{Backend, CpuOptions, FlatScene, HdrImage, RenderControl, render_cpu};
use glint_gpu::status::StatusContext;
use glint_gpu::{AdapterRequest, DispatchControl, GpuContext, GpuError, GpuOptions, GpuTracer, SampleProgress};
use indicatif::{ProgressBar, ProgressStyle};

use super::units::{count, mrays_per_s};
use crate::cli::usage::usage;

/// One finished render.
#[derive(Debug)]
pub struct Run {
    pub backend: Backend,
    pub image: HdrImage,
    pub counts: RayCounts,
    /// The render itself.
    pub render: Duration,
    /// Including set-up (thread pool or device, pipeline, upload, readback).
    pub total: Duration,
    /// Worker threads (CPU) or the adapter (GPU).
    pub device: String,
    pub gpu_status: u32,
    /// What the raised status bits mean (`glint_gpu::status`); empty for a complete render.
    pub incomplete: Vec<String>,
}

impl Run {
    pub fn mrays(&self) -> f64 {
        mrays_per_s(self.counts.total(), self.render)
    }
}

/// The progress bar of a render on stderr, hidden when quiet or when stderr is no terminal;
/// `unit` follows the position (the CPU's tiles are shown as a percentage).
fn progress_bar(quiet: bool, len: u64, backend: &str, unit: &str) -> anyhow::Result<ProgressBar> {
    if quiet || !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        return Ok(ProgressBar::hidden());
    }
    let done = if unit.is_empty() { "{percent:>3}%".to_string() } else { format!("{{pos}}/{{len}} {unit}") };
    let template = format!("{{spinner}} {backend} [{{bar:40}}] {done} {{msg}} {{elapsed_precise}} eta {{eta}}");
    let bar = ProgressBar::new(len);
    bar.set_style(ProgressStyle::with_template(&template).context("progress bar template")?.progress_chars("=> "));
    Ok(bar)
}

pub fn run_cpu(flat: &FlatScene, options: &CpuOptions, quiet: bool) -> anyhow::Result<Run> {
    let start = Instant::now();
    let (w, h) = options.region.map_or((flat.header.width, flat.header.height), |r| (r.width, r.height));
    let tiles = tile_count(w, h) as u64;
    let bar = progress_bar(quiet, tiles, "cpu", "")?;
    let on_tile = |_: &Tile| bar.inc(1);
    // SIGINT/SIGTERM stop the render at the next pixel (see `interrupt`).
    let cancel = glint_io::interrupt::flag();
    let rays = AtomicU64::new(0);
    let done = AtomicBool::new(false);
    let control = RenderControl { cancel: Some(&cancel), on_tile: Some(&on_tile), rays: Some(&rays) };
    let r = std::thread::scope(|scope| {
        if !bar.is_hidden() {
            // Rays traced so far, also while one long tile holds the bar still.
            scope.spawn(|| {
                while !done.load(Ordering::Relaxed) {
                    bar.set_message(format!("{} rays", count(rays.load(Ordering::Relaxed))));
                    std::thread::sleep(Duration::from_millis(200));
                }
            });
        }
        let r = render_cpu(flat, options, control);
        done.store(true, Ordering::Relaxed);
        r
    })?;
    bar.finish_and_clear();
    Ok(Run {
        backend: Backend::Cpu,
        image: r.image,
        counts: r.counts,
        render: r.elapsed,
        total: start.elapsed(),
        device: format!("{} threads", r.threads),
        gpu_status: 0,
        incomplete: Vec::new(),
    })
}

/// `--adapter` where it can choose something: with a GPU backend (`uses_gpu`), and not empty.
pub fn check_adapter(adapter: Option<&str>, uses_gpu: bool) -> anyhow::Result<()> {
    match adapter {
        Some(_) if !uses_gpu => usage!(
            "--adapter chooses the GPU, and --backend cpu uses none: give --backend gpu or both, or leave --adapter out"
        ),
        Some(a) if a.trim().is_empty() => usage!(
            "--adapter is empty: give a part of an adapter's name (`glint adapters` lists them), or leave it out"
        ),
        _ => Ok(()),
    }
}

/// Opens the GPU named by `--adapter` (or `WGPU_ADAPTER_NAME`).
pub fn open_gpu(adapter: Option<&str>) -> anyhow::Result<GpuTracer> {
    let request = AdapterRequest { name: adapter.map(str::to_string), prefer_cpu: false };
    let ctx = GpuContext::new(&request).context("cannot start the GPU tracer")?;
    Ok(GpuTracer::new(ctx))
}

pub fn run_gpu(tracer: &GpuTracer, flat: &FlatScene, options: &GpuOptions, quiet: bool) -> anyhow::Result<Run> {
    let start = Instant::now();
    let progress = Arc::new(SampleProgress::new(flat.header.spp.max(1)));
    let bar = progress_bar(quiet, u64::from(flat.header.spp.max(1)), "gpu", "samples")?;
    // SIGINT/SIGTERM stop the render between two submissions.
    let cancel = glint_io::interrupt::flag();
    let control = DispatchControl { cancel: Some(&cancel), progress: Some(&progress) };
    let done = AtomicBool::new(false);
    let r = std::thread::scope(|scope| {
        if !bar.is_hidden() {
            scope.spawn(|| {
                while !done.load(Ordering::Relaxed) {
                    bar.set_position(u64::from(progress.get().0));
                    std::thread::sleep(Duration::from_millis(200));
                }
            });
        }
        let r = tracer.render_with(flat, options, control);
        done.store(true, Ordering::Relaxed);
        r
    });
    bar.finish_and_clear();
    if matches!(r, Err(GpuError::Cancelled)) {
        super::interrupt::check()?;
    }
    let r = r.context("GPU render failed")?;
    super::interrupt::check()?;
    Ok(Run {
        backend: Backend::Gpu,
        image: r.image,
        counts: r.counts,
        render: r.render_time,
        total: start.elapsed(),
        device: tracer.context().adapter.with_driver(),
        gpu_status: r.status,
        incomplete: glint_gpu::status::messages(r.status, &StatusContext::new(&flat.header, &r.key)),
    })
}
