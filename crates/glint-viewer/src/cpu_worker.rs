//! The CPU reference render on a background thread: progressive tiles, cancelled by the next
//! edit. The UI thread only copies finished pixels; it never waits for the tracer.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use glint_core::cpu::RayCounts;
use glint_core::image::linear_to_srgb8;
use glint_core::render::{Tile, tile_count};
use glint_core::{CpuOptions, FlatScene, HdrImage, RenderControl, render_cpu};

/// What the worker has produced so far.
#[derive(Debug)]
struct Progress {
    /// sRGB RGBA8 of the tiles finished so far (converted on the worker, not the UI thread).
    rgba: Vec<u8>,
    tiles_done: usize,
    changed: bool,
    outcome: Option<Result<Finished, String>>,
}

/// A complete CPU render.
#[derive(Clone, Debug)]
pub struct Finished {
    pub image: HdrImage,
    pub counts: RayCounts,
    pub elapsed: Duration,
    pub threads: usize,
}

#[derive(Debug)]
struct Job {
    revision: u64,
    width: u32,
    height: u32,
    tiles_total: usize,
    started: Instant,
    cancel: Arc<AtomicBool>,
    progress: Arc<Mutex<Progress>>,
}

/// One render at a time; starting another cancels the running one.
#[derive(Debug, Default)]
pub struct CpuWorker {
    job: Option<Job>,
    /// The last complete render and the revision it belongs to.
    pub finished: Option<(u64, Finished)>,
    pub error: Option<String>,
    /// Time the last complete render took, from start to the last tile.
    pub last_time: Option<Duration>,
    /// The last pixels shown: a new render of the same size paints its tiles over them
    /// instead of starting from black.
    shown: Option<(u32, u32, Vec<u8>)>,
}

fn lock(p: &Mutex<Progress>) -> MutexGuard<'_, Progress> {
    p.lock().unwrap_or_else(|e| e.into_inner())
}

/// Worker threads: one core is left to the UI and the GPU driver (lavapipe runs on the CPU).
fn worker_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get().saturating_sub(1).max(1))
}

impl CpuWorker {
    /// Cancels the running render (its thread stops at its next tile).
    pub fn cancel(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// The revision being rendered, if any.
    pub fn running_revision(&self) -> Option<u64> {
        self.job.as_ref().map(|j| j.revision)
    }

    /// Starts rendering `scene` for document revision `revision`; `repaint` is called after
    /// each tile so the UI shows it.
    pub fn start(&mut self, scene: FlatScene, revision: u64, repaint: impl Fn() + Send + Sync + 'static) {
        self.cancel();
        let (width, height) = (scene.header.width, scene.header.height);
        let rgba = match self.shown.take() {
            Some((w, h, pixels)) if (w, h) == (width, height) => pixels,
            _ => vec![0; width as usize * height as usize * 4],
        };
        let progress = Arc::new(Mutex::new(Progress { rgba, tiles_done: 0, changed: true, outcome: None }));
        let cancel = Arc::new(AtomicBool::new(false));
        let (p, c) = (progress.clone(), cancel.clone());
        let spawned = std::thread::Builder::new().name("glint-cpu-render".into()).spawn(move || {
            let on_tile = |tile: &Tile| {
                let mut g = lock(&p);
                for row in 0..tile.height {
                    for col in 0..tile.width {
                        let src = tile.radiance[(row * tile.width + col) as usize];
                        let dst = (((tile.y0 + row) * width + tile.x0 + col) * 4) as usize;
                        let px = src.to_array().map(linear_to_srgb8);
                        g.rgba[dst..dst + 4].copy_from_slice(&[px[0], px[1], px[2], 255]);
                    }
                }
                g.tiles_done += 1;
                g.changed = true;
                drop(g);
                repaint();
            };
            let options = CpuOptions { threads: worker_threads(), specialise: true };
            let result = render_cpu(&scene, &options, RenderControl { cancel: Some(&c), on_tile: Some(&on_tile) });
            let outcome = result
                .map(|r| Finished { image: r.image, counts: r.counts, elapsed: r.elapsed, threads: r.threads })
                .map_err(|e| e.to_string());
            lock(&p).outcome = Some(outcome);
            repaint();
        });
        match spawned {
            Ok(_) => {
                self.job = Some(Job {
                    revision,
                    width,
                    height,
                    tiles_total: tile_count(width, height),
                    started: Instant::now(),
                    cancel,
                    progress,
                });
            }
            Err(e) => self.error = Some(format!("cannot start the CPU render thread: {e}")),
        }
    }

    /// New pixels since the last call, as (width, height, sRGB RGBA8); and whether the render
    /// just finished. Cheap when nothing changed.
    pub fn poll(&mut self) -> Option<(u32, u32, Vec<u8>)> {
        let job = self.job.as_ref()?;
        let mut g = lock(&job.progress);
        let pixels = g.changed.then(|| g.rgba.clone());
        g.changed = false;
        let outcome = g.outcome.take();
        drop(g);
        let (w, h, revision, started) = (job.width, job.height, job.revision, job.started);
        match outcome {
            Some(Ok(f)) => {
                self.last_time = Some(started.elapsed());
                self.finished = Some((revision, f));
                self.error = None;
                self.job = None;
            }
            Some(Err(e)) => {
                // A cancelled job is replaced by the next one: not an error worth showing.
                if !e.contains("cancelled") {
                    self.error = Some(e);
                }
                self.job = None;
            }
            None => {}
        }
        if let Some(p) = &pixels {
            self.shown = Some((w, h, p.clone()));
        }
        pixels.map(|p| (w, h, p))
    }

    /// (tiles done, tiles in all, seconds so far) of the running render.
    pub fn progress(&self) -> Option<(usize, usize, f64)> {
        let job = self.job.as_ref()?;
        let done = lock(&job.progress).tiles_done;
        Some((done, job.tiles_total, job.started.elapsed().as_secs_f64()))
    }

    pub fn is_running(&self) -> bool {
        self.job.is_some()
    }
}

impl Drop for CpuWorker {
    fn drop(&mut self) {
        self.cancel();
    }
}
