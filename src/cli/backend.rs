//! Running one render on either backend, with the timings the table reports.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use anyhow::Context;
use glint_core::cpu::RayCounts;
use glint_core::render::{Tile, tile_count};
use glint_core::{Backend, CpuOptions, FlatScene, HdrImage, RenderControl, render_cpu};
use glint_gpu::{AdapterRequest, GpuContext, GpuOptions, GpuTracer};
use indicatif::{ProgressBar, ProgressStyle};

use super::units::{count, mrays_per_s};

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

pub fn run_cpu(flat: &FlatScene, options: &CpuOptions, quiet: bool) -> anyhow::Result<Run> {
    let start = Instant::now();
    let tiles = tile_count(flat.header.width, flat.header.height) as u64;
    let bar = if quiet || !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::new(tiles);
        bar.set_style(
            ProgressStyle::with_template("{spinner} cpu [{bar:40}] {percent:>3}% {msg} {elapsed_precise} eta {eta}")
                .context("progress bar template")?
                .progress_chars("=> "),
        );
        bar
    };
    let on_tile = |_: &Tile| bar.inc(1);
    // SIGINT/SIGTERM stop the render at the next tile (see `interrupt`).
    let cancel = glint_core::interrupt::flag();
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

/// Opens the GPU named by `--adapter` (or `WGPU_ADAPTER_NAME`).
pub fn open_gpu(adapter: Option<&str>) -> anyhow::Result<GpuTracer> {
    let request = AdapterRequest { name: adapter.map(str::to_string), prefer_cpu: false };
    let ctx = GpuContext::new(&request).context("cannot start the GPU tracer")?;
    Ok(GpuTracer::new(ctx))
}

pub fn run_gpu(tracer: &GpuTracer, flat: &FlatScene, options: &GpuOptions) -> anyhow::Result<Run> {
    let start = Instant::now();
    let r = tracer.render(flat, options).context("GPU render failed")?;
    // A dispatched render cannot be stopped: a signal that came during it stops here.
    super::interrupt::check()?;
    Ok(Run {
        backend: Backend::Gpu,
        image: r.image,
        counts: r.counts,
        render: r.render_time,
        total: start.elapsed(),
        device: tracer.context().adapter.to_string(),
        gpu_status: r.status,
        incomplete: glint_gpu::status::messages(r.status, r.key.stack_size),
    })
}
