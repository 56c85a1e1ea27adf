//! The CPU reference render on a background thread: progressive tiles, cancelled by the next
//! edit. The UI thread only copies finished pixels; it never waits for the tracer.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use glint_core::cpu::RayCounts;
use glint_core::image::srgb8_as_stored;
use glint_core::render::{Tile, tile_count};
use glint_core::{CpuOptions, FlatScene, HdrImage, RenderControl, render_cpu};

use crate::worker::Worker;

/// How often a running CPU render's finished tiles are shown (and uploaded) at most.
pub const PROGRESS_INTERVAL: Duration = Duration::from_millis(100);

/// The tiles finished so far, shared with the render thread.
#[derive(Debug)]
struct Progress {
    /// sRGB RGBA8 of the tiles finished so far (converted on the worker, not the UI thread).
    rgba: Vec<u8>,
    tiles_done: usize,
    changed: bool,
}

/// A complete CPU render.
#[derive(Clone, Debug)]
pub struct Finished {
    pub image: HdrImage,
    pub counts: RayCounts,
    pub elapsed: Duration,
    pub threads: usize,
}

/// The render in progress (while the worker runs it).
#[derive(Debug)]
struct Job {
    width: u32,
    height: u32,
    tiles_total: usize,
    started: Instant,
    progress: Arc<Mutex<Progress>>,
}

/// One render at a time; starting another cancels the running one.
#[derive(Debug)]
pub struct CpuWorker {
    worker: Worker<Result<Finished, String>>,
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
    /// A worker that wakes the UI of `repaint` after each tile, so that the UI shows it.
    pub fn new(repaint: egui::Context) -> Self {
        Self {
            worker: Worker::new("glint-cpu-render", "CPU render", Some(repaint)),
            job: None,
            finished: None,
            error: None,
            last_time: None,
            shown: None,
        }
    }

    /// Cancels the running render (its thread stops at its next pixel).
    pub fn cancel(&mut self) {
        self.worker.cancel();
        self.job = None;
    }

    /// The revision being rendered, if any.
    pub fn running_revision(&self) -> Option<u64> {
        self.worker.running_revision()
    }

    /// Starts rendering `scene` for document revision `revision`.
    pub fn start(&mut self, scene: FlatScene, revision: u64) {
        self.cancel();
        let (width, height) = (scene.header.width, scene.header.height);
        let rgba = match self.shown.take() {
            Some((w, h, pixels)) if (w, h) == (width, height) => pixels,
            _ => vec![0; width as usize * height as usize * 4],
        };
        let progress = Arc::new(Mutex::new(Progress { rgba, tiles_done: 0, changed: true }));
        let p = progress.clone();
        let started = self.worker.start(revision, move |job| {
            let on_tile = |tile: &Tile| {
                let mut g = lock(&p);
                for row in 0..tile.height {
                    for col in 0..tile.width {
                        let src = tile.radiance[(row * tile.width + col) as usize];
                        let dst = (((tile.y0 + row) * width + tile.x0 + col) * 4) as usize;
                        let px = srgb8_as_stored(src);
                        g.rgba[dst..dst + 4].copy_from_slice(&[px[0], px[1], px[2], 255]);
                    }
                }
                g.tiles_done += 1;
                g.changed = true;
                drop(g);
                // Within the upload interval: a frame per tile would paint hundreds of frames a
                // second, each one on a CPU adapter taking the cores the renders need.
                job.repaint_within(PROGRESS_INTERVAL);
            };
            let options = CpuOptions { threads: worker_threads(), ..CpuOptions::default() };
            let control = RenderControl { cancel: Some(job.cancel_flag()), on_tile: Some(&on_tile), rays: None };
            render_cpu(&scene, &options, control)
                .map(|r| Finished { image: r.image, counts: r.counts, elapsed: r.elapsed, threads: r.threads })
                .map_err(|e| e.to_string())
        });
        match started {
            Ok(()) => {
                let tiles_total = tile_count(width, height);
                self.job = Some(Job { width, height, tiles_total, started: Instant::now(), progress });
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// New pixels since the last call, as (width, height, sRGB RGBA8); and whether the render
    /// just finished. Cheap when nothing changed.
    pub fn poll(&mut self) -> Option<(u32, u32, Vec<u8>)> {
        let job = self.job.as_ref()?;
        // The result before the pixels: it is sent after the last tile, so a finished render's
        // pixels read below include every tile. (A cancelled render's result never arrives.)
        let outcome = self.worker.poll();
        let mut g = lock(&job.progress);
        let pixels = g.changed.then(|| g.rgba.clone());
        g.changed = false;
        drop(g);
        let (w, h, started) = (job.width, job.height, job.started);
        match outcome {
            Some((revision, Ok(Ok(f)))) => {
                self.last_time = Some(started.elapsed());
                self.finished = Some((revision, f));
                self.error = None;
                self.job = None;
            }
            Some((_, Ok(Err(e)))) => {
                self.error = Some(e);
                self.job = None;
            }
            Some((_, Err(e))) => {
                self.error = Some(e.to_string());
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
        self.worker.is_running()
    }
}
