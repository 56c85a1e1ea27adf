//! The GPU tracer on a wgpu device of its own, on the window's adapter: each render is traced,
//! encoded as sRGB pixels by glint-gpu's `Presenter`, read back without blocking and drawn by
//! egui. Full-resolution renders are also read back whole for the comparison and export.
//!
//! Not eframe's device: the window's frames would queue behind the tracer's submissions on the
//! one queue. On lavapipe that queue also compiles a new shader variant at its first dispatch,
//! and the window froze for as long (10–15 s on a slow 2-core machine; 0.8–1.1 s a variant
//! here, `glint view --benchmark-features`).

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glint_core::FlatScene;
use glint_core::HdrImage;
use glint_core::cpu::RayCounts;
use glint_gpu::status::StatusContext;
use glint_gpu::{
    AdapterRequest, DispatchControl, GpuContext, GpuError, GpuJob, GpuOptions, GpuTracer, JobReadback, PendingPixels,
    Presenter, SampleProgress, ShaderKey,
};

use crate::accumulation::Accumulation;
use crate::worker::Worker;
use rate::renders_per_second;
use variants::{likely_next, new_in, variant_of};

mod rate;
mod variants;

/// Tile sides of the viewer's renders. On a CPU adapter (lavapipe) each submission holds the
/// cores the UI needs, so full-resolution renders go in short ones. Measured with whitted at
/// 960×540, 16 spp, while the CPU reference renders: mean frame interval 77 ms with 256-pixel
/// tiles, 42 ms with 64 (the GPU image takes about twice as long), 37 ms with 32 (but five
/// times as long: each submission costs about 2 ms on lavapipe). A preview is small and goes
/// in one submission, as fast as it can.
const FULL_TILE_CPU_ADAPTER: u32 = 64;
const PREVIEW_TILE: u32 = 512;

/// Where a render in flight is.
#[derive(Debug)]
enum Stage {
    /// Being uploaded and dispatched by the submitter: on lavapipe `submit` runs as long as
    /// the render itself, and the UI must not wait for it.
    Submitting,
    Running(Box<GpuJob>),
}

/// A render in flight.
#[derive(Debug)]
struct InFlight {
    stage: Stage,
    revision: u64,
    /// What its status word's remedies depend on (its scene and variant).
    status_context: StatusContext,
    preview: bool,
    size: (u32, u32),
    started: Instant,
    /// Sample passes done, of how many (full-resolution renders go pass by pass).
    progress: Arc<SampleProgress>,
    /// What the render's shader variant compiles in that no earlier render's did: its first
    /// dispatch waits for the compiler (seconds on lavapipe).
    new_variant: Option<String>,
    /// A 1×1 render of a variant an edit is likely to need next, only to compile it: not
    /// shown, not counted.
    prewarm: bool,
    /// Which batch of its revision's paths it is (`accumulation`): 0 for a first render,
    /// which is shown as it lands; later ones only through the mean.
    batch: u32,
    spp: u32,
}

/// A full-resolution GPU image on the host.
#[derive(Clone, Debug)]
pub struct GpuImage {
    pub revision: u64,
    pub image: HdrImage,
    pub counts: RayCounts,
    pub status: u32,
    pub gpu_ms: f64,
    /// Samples a pixel: the render's own, or in path mode those of every batch so far.
    pub samples: u32,
}

/// What a full render's readback is of.
#[derive(Clone, Copy, Debug)]
struct Finished {
    revision: u64,
    status_context: StatusContext,
    gpu_ms: f64,
    /// Its batch of the revision's paths (0 for a first render) and its samples a pixel.
    batch: u32,
    spp: u32,
}

/// A finished render's pixels on their way to the screen.
#[derive(Debug)]
struct Arriving {
    pixels: PendingPixels,
    revision: u64,
    preview: bool,
}

pub struct GpuView {
    pub tracer: Arc<GpuTracer>,
    /// The UI, to draw the pixels with.
    egui: egui::Context,
    /// One per image size (preview and full), at most two.
    presenters: Vec<Presenter>,
    /// The pixels of the render in flight, presented after its last dispatch.
    presenting: Option<PendingPixels>,
    /// The pixels of the latest finished render to show, landing.
    arriving: Option<Arriving>,
    texture: Option<egui::TextureHandle>,
    /// The shader variants rendered with so far, and the last one.
    variants: std::collections::HashSet<ShaderKey>,
    last_variant: Option<ShaderKey>,
    /// The last scene rendered in full, whose likely next variants `prewarm` compiles.
    last_scene: Option<FlatScene>,
    /// Those variants' 1×1 scenes still to compile, derived once per full render when the GPU
    /// is first idle after it (`None` until then).
    prewarm_queue: Option<Vec<FlatScene>>,
    submitter: Worker<Result<GpuJob, GpuError>>,
    in_flight: Option<InFlight>,
    /// The readback of a full render, and what it is of.
    readback: Option<(JobReadback, Finished)>,
    /// The path batches of the revision on screen, added up (path mode only).
    pub accumulation: Option<Accumulation>,
    /// What is on screen: (revision, preview, size, texture).
    pub shown: Option<(u64, bool, (u32, u32), egui::TextureId)>,
    pub latest: Option<GpuImage>,
    /// GPU time of the last render, and whether it compiled its shader variant (on lavapipe
    /// at its first dispatch: seconds, which the status bar called "14539.8 ms/frame" of a
    /// 40 ms render; a lecturer).
    pub last_ms: Option<(f64, bool)>,
    /// Completion times of recent renders, for renders per second.
    completions: VecDeque<Instant>,
    pub error: Option<String>,
    pub warning: Option<String>,
    /// Renders completed since the start.
    pub renders: usize,
    /// A wgpu error no error scope caught (wgpu's default would abort the process).
    uncaptured: Arc<Mutex<Option<String>>>,
    full_tile: u32,
    /// Full renders of revisions below this are of a camera or scene edited since: the one
    /// still in flight when an edit arrived after its last submission is neither shown nor read
    /// back when it completes.
    superseded_below: u64,
}

/// How long dropping the view waits for its GPU jobs: a cancelled full render stops between
/// sample passes, a prewarm's 1×1 render ends when its shader is compiled (seconds on a slow
/// machine with lavapipe).
const JOBS_END_WITHIN: Duration = Duration::from_secs(20);

impl Drop for GpuView {
    fn drop(&mut self) {
        // The device goes with the view, and the process may exit next: a submission thread
        // still in the driver then (a prewarm compiling) crashed the viewer tests' process at
        // its exit, once, after every test had passed.
        let deadline = Instant::now() + JOBS_END_WITHIN;
        if !self.submitter.cancel_and_wait(deadline) {
            log::warn!("a GPU job was still running {} s after the view closed", JOBS_END_WITHIN.as_secs());
        }
        // Probes run on threads of their own, each holding the tracer: a probe still compiling
        // its variant in lavapipe's LLVM when the process exited aborted it ("LLVM ERROR:
        // Invalid size request on a scalable vector", after all 71 viewer tests had passed).
        while Arc::strong_count(&self.tracer) > 1 && Instant::now() < deadline {
            std::thread::sleep(Duration::from_millis(5));
        }
        if Arc::strong_count(&self.tracer) > 1 {
            log::warn!("a GPU probe was still running {} s after the view closed", JOBS_END_WITHIN.as_secs());
        }
    }
}

impl std::fmt::Debug for GpuView {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuView")
            .field("adapter", &self.adapter_name())
            .field("shown", &self.shown)
            .finish_non_exhaustive()
    }
}

impl GpuView {
    /// A device of its own on the window's adapter (eframe's device where a second one cannot
    /// be had: then the window's frames may wait for the tracer's).
    pub fn new(state: &egui_wgpu::RenderState, egui: &egui::Context) -> Self {
        let info = state.adapter.get_info();
        let request =
            AdapterRequest { name: Some(info.name.clone()), prefer_cpu: info.device_type == wgpu::DeviceType::Cpu };
        let ctx = GpuContext::new(&request).unwrap_or_else(|e| {
            log::warn!("no second device on {} ({e}); the tracer shares the window's", info.name);
            GpuContext::from_device(state.device.clone(), state.queue.clone(), &info)
        });
        let uncaptured: Arc<Mutex<Option<String>>> = Arc::default();
        let slot = uncaptured.clone();
        // Shown in the UI instead of wgpu's default of panicking: no crash on a GPU error.
        ctx.device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            log::error!("GPU error: {e}");
            *slot.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.to_string());
        }));
        log::info!("viewer GPU: {}", ctx.adapter);
        Self {
            tracer: Arc::new(GpuTracer::new(ctx)),
            egui: egui.clone(),
            presenters: Vec::new(),
            presenting: None,
            arriving: None,
            texture: None,
            variants: std::collections::HashSet::new(),
            last_variant: None,
            last_scene: None,
            prewarm_queue: None,
            // Woken when a job ends (its thread waits for the GPU first): a prewarm is no render
            // of the document, so an edit that waits behind one is submitted only on this wake.
            submitter: Worker::new("glint-gpu-submit", "GPU submission", Some(egui.clone())),
            in_flight: None,
            readback: None,
            accumulation: None,
            shown: None,
            latest: None,
            last_ms: None,
            completions: VecDeque::new(),
            error: None,
            warning: None,
            renders: 0,
            uncaptured,
            superseded_below: 0,
            full_tile: if info.device_type == wgpu::DeviceType::Cpu {
                FULL_TILE_CPU_ADAPTER
            } else {
                GpuOptions::default().tile
            },
        }
    }

    /// The adapter and its driver, as `glint render` names the device in an image's metadata.
    pub fn adapter_name(&self) -> String {
        self.tracer.context().adapter.with_driver()
    }

    /// Whether a render of the document is under way (a prewarm is not).
    /// Later path batches refine an image already there and do not count.
    pub fn is_busy(&self) -> bool {
        self.in_flight.as_ref().is_some_and(|f| !f.prewarm && f.batch == 0)
            || self.readback.as_ref().is_some_and(|r| r.1.batch == 0)
            || self.arriving.is_some()
    }

    /// Whether a later path batch is being rendered or read back.
    pub fn is_accumulating(&self) -> bool {
        self.in_flight.as_ref().is_some_and(|f| f.batch > 0) || self.readback.as_ref().is_some_and(|r| r.1.batch > 0)
    }

    /// Whether the next step is found only by polling the device: a finished render's last
    /// step and its readbacks (all short). A render still running wakes the UI itself.
    pub fn needs_polling(&self) -> bool {
        self.readback.is_some()
            || self.arriving.is_some()
            || matches!(self.in_flight, Some(InFlight { stage: Stage::Running(_), .. }))
    }

    /// The revision of the image on screen.
    pub fn shown_revision(&self) -> Option<u64> {
        self.shown.map(|s| s.0)
    }

    pub fn in_flight(&self) -> Option<(u64, bool)> {
        self.in_flight.as_ref().map(|f| (f.revision, f.preview))
    }

    /// How many of the variants an edit of the last scene is likely to need next are still to
    /// be compiled (`prewarm`); one while they are not derived yet.
    pub fn to_prewarm(&self) -> usize {
        match (&self.prewarm_queue, &self.last_scene) {
            (Some(queue), _) => queue.iter().filter(|s| !self.variants.contains(&variant_of(s))).count(),
            (None, Some(_)) => 1,
            (None, None) => 0,
        }
    }

    /// What the shader of the render in flight compiles in for the first time, while its first
    /// dispatch may still wait for the compiler, and for how long it has run.
    pub fn compiling(&self) -> Option<(Duration, &str)> {
        let f = self.in_flight.as_ref()?;
        let what = f.new_variant.as_deref()?;
        matches!(f.stage, Stage::Submitting).then(|| (f.started.elapsed(), what))
    }

    /// How long the full-resolution render in flight has been running (none for a preview),
    /// and how many of its sample passes the GPU has finished, of how many.
    pub fn full_render_progress(&self) -> Option<(Duration, (u32, u32))> {
        self.in_flight.as_ref().filter(|f| !f.preview).map(|f| (f.started.elapsed(), f.progress.get()))
    }

    /// Stops the full-resolution render in flight if it is of another revision than `current`
    /// and still being dispatched: its remaining passes are not submitted, so a preview of the
    /// new camera can go next instead of waiting seconds behind an image nobody will see.
    pub fn cancel_full_render_unless(&mut self, current: u64) {
        self.superseded_below = self.superseded_below.max(current);
        if let Some(InFlight { stage: Stage::Submitting, preview: false, revision, .. }) = &self.in_flight
            && *revision != current
        {
            log::debug!("GPU render of revision {revision} cancelled for revision {current}");
            self.submitter.cancel();
            self.in_flight = None;
        }
    }

    /// Renders per second over the last two seconds, current during a long render.
    pub fn renders_per_second(&self) -> Option<f64> {
        let running = self.in_flight.as_ref().map(|f| f.started.elapsed());
        let last_ms = self.last_ms.filter(|(_, compiled)| !compiled).map(|(ms, _)| ms);
        renders_per_second(Instant::now(), self.completions.iter().copied(), last_ms, running)
    }

    /// Whether the adapter is a software one (lavapipe, WARP, SwiftShader): the "GPU" tracer
    /// then runs on the same CPU cores as the reference, and usually slower.
    pub fn is_software(&self) -> bool {
        self.tracer.context().adapter.is_software()
    }

    /// Submits a render unless one is still running (the next frame submits the newest edit,
    /// so renders never queue up behind each other).
    pub fn submit(&mut self, scene: &FlatScene, revision: u64, preview: bool) -> bool {
        if !preview {
            self.last_scene = Some(scene.clone());
            self.prewarm_queue = None;
        }
        self.start(scene, revision, preview, false, 0)
    }

    /// Submits batch `batch` (from 1) of the paths of `revision`, whose full render is on
    /// screen: `scene` with that batch's seed (`accumulation::batch_seed`).
    pub fn submit_batch(&mut self, scene: &FlatScene, revision: u64, batch: u32) -> bool {
        self.start(scene, revision, false, false, batch)
    }

    /// When idle, compiles the next shader variant an edit is likely to need (more samples,
    /// depth 0, a spot light, Phong, Cook–Torrance, added to what the scene uses) by a 1×1
    /// render nobody sees: lavapipe compiles a variant at its first dispatch, seconds on a slow
    /// machine, and the edit's own render then starts at once. One at a time; an edit that
    /// arrives meanwhile waits for it, never the window.
    pub fn prewarm(&mut self) {
        if self.in_flight.is_some() || self.arriving.is_some() || self.readback.is_some() {
            return;
        }
        let Some(scene) = &self.last_scene else { return };
        // Taken out while a render starts from it; the most likely first.
        let mut queue = self.prewarm_queue.take().unwrap_or_else(|| likely_next(scene).into_iter().rev().collect());
        while let Some(next) = queue.pop() {
            let key = variant_of(&next);
            if self.variants.insert(key) {
                log::debug!("prewarming the GPU variant {}", key.describe());
                self.start(&next, 0, true, true, 0);
                break;
            }
        }
        self.prewarm_queue = Some(queue);
    }

    fn start(&mut self, scene: &FlatScene, revision: u64, preview: bool, prewarm: bool, batch: u32) -> bool {
        if self.in_flight.is_some() {
            return false;
        }
        let ctx = self.tracer.context().clone();
        if ctx.is_lost() {
            self.error = Some(GpuError::DeviceLost.to_string());
            return false;
        }
        let size = (scene.header.width, scene.header.height);
        let max_side = ctx.limits.max_texture_dimension_2d;
        if size.0 > max_side || size.1 > max_side {
            self.error = Some(format!(
                "{}×{} is larger than this GPU's textures ({max_side} pixels a side); the CPU view still renders it",
                size.0, size.1
            ));
            return false;
        }
        let key = variant_of(scene);
        let status_context = StatusContext::new(&scene.header, &key);
        let new_variant = (self.variants.insert(key) && !prewarm).then(|| new_in(key, self.last_variant));
        if !prewarm {
            self.last_variant = Some(key);
        }
        let spp = scene.header.spp.max(1);
        let (tracer, scene, full_tile) = (self.tracer.clone(), scene.clone(), self.full_tile);
        let progress = Arc::new(SampleProgress::new(scene.header.spp.max(1)));
        let job_progress = progress.clone();
        let started = self.submitter.start(revision, move |handle| {
            let start = Instant::now();
            let options = GpuOptions { tile: if preview { PREVIEW_TILE } else { full_tile }, ..GpuOptions::default() };
            let control = DispatchControl { cancel: Some(handle.cancel_flag()), progress: Some(&job_progress) };
            let job = tracer.submit(&scene, &options, control);
            log::debug!("GPU submit took {:.1} ms", start.elapsed().as_secs_f64() * 1e3);
            // Waits here for the GPU to finish, so that the worker's wake-up after it sends the
            // job tells the UI, rather than frames painted every few milliseconds to poll: on a
            // CPU adapter each frame takes the cores the render needs.
            if job.is_ok()
                && let Err(e) = tracer.context().device.poll(wgpu::PollType::wait_indefinitely())
            {
                log::warn!("waiting for the GPU render: {e}");
            }
            job
        });
        match started {
            Ok(()) => {
                self.in_flight = Some(InFlight {
                    stage: Stage::Submitting,
                    revision,
                    status_context,
                    preview,
                    size,
                    started: Instant::now(),
                    progress,
                    new_variant,
                    prewarm,
                    batch,
                    spp,
                });
                true
            }
            Err(e) => {
                self.error = Some(e.to_string());
                false
            }
        }
    }

    fn presenter_for(&mut self, size: (u32, u32)) -> &Presenter {
        if let Some(i) = self.presenters.iter().position(|p| (p.width, p.height) == size) {
            return &self.presenters[i];
        }
        // Keep at most two sizes (preview and full).
        if self.presenters.len() >= 2 {
            self.presenters.remove(0);
        }
        self.presenters.push(Presenter::new(self.tracer.context(), size.0, size.1));
        self.presenters.last().expect("just pushed")
    }

    /// Advances the render in flight and the readback; returns true when something changed.
    pub fn poll(&mut self) -> bool {
        let ctx = self.tracer.context().clone();
        let mut changed = false;
        if let Some(e) = self.uncaptured.lock().unwrap_or_else(|p| p.into_inner()).take() {
            self.error = Some(e);
            changed = true;
        }
        // No poll of the tracer's device here: the submit worker waits for its render itself
        // (which runs the job's callbacks), and the readbacks below poll when they have
        // something to read. A poll every frame needs the device's submission lock, which a
        // probe or render thread holds for the whole of a `vkQueueSubmit`; lavapipe's returns
        // only once its queue thread has JIT-compiled a new variant, so the window stood still
        // for 40–115 s after a Max depth edit (a lecturer; gdb: the UI in `Device::maintain`
        // waiting for `command_indices`).
        if let Some(InFlight { stage: Stage::Submitting, size, prewarm, .. }) = &self.in_flight {
            let (size, prewarm) = (*size, *prewarm);
            match self.submitter.poll() {
                Some((_, Ok(Ok(_)))) if prewarm => {
                    log::debug!("GPU variant prewarmed");
                    self.in_flight = None;
                }
                Some((_, Ok(Ok(job)))) => {
                    // Queued after the tracer's dispatches, so it encodes the finished image.
                    self.presenting = Some(self.presenter_for(size).present(&ctx, &job.buffers.output));
                    if let Some(f) = &mut self.in_flight {
                        f.stage = Stage::Running(Box::new(job));
                    }
                    self.error = None;
                }
                Some((_, Ok(Err(e)))) => {
                    self.error = Some(e.to_string());
                    self.in_flight = None;
                    changed = true;
                }
                Some((_, Err(e))) => {
                    self.error = Some(e.to_string());
                    self.in_flight = None;
                }
                None => {}
            }
        }
        if let Some(InFlight { stage: Stage::Running(job), .. }) = &self.in_flight
            && let Some(time) = job.gpu_time()
        {
            let f = self.in_flight.take().expect("checked above");
            let Stage::Running(job) = f.stage else { return changed };
            let ms = time.as_secs_f64() * 1e3;
            log::debug!("GPU render {}x{} done in {ms:.1} ms", f.size.0, f.size.1);
            let compiled = f.new_variant.is_some();
            self.last_ms = Some((ms, compiled));
            // A compile is no render's rate.
            if !compiled {
                self.completions.push_back(Instant::now());
            }
            self.renders += 1;
            while self.completions.len() > 64 {
                self.completions.pop_front();
            }
            // Never an older camera over a newer one: a full render that finishes after a
            // preview of a later edit (a drag began while it ran) is not shown.
            // Nor a full render that finished after an edit it no longer shows (a drag began
            // after its last pass was submitted, so it could not be cancelled).
            let superseded = !f.preview && f.revision < self.superseded_below;
            let newer = self.shown.is_none_or(|s| s.0 <= f.revision) && !superseded;
            // A later batch is shown through the mean, once read back.
            if let Some(pixels) = self.presenting.take().filter(|_| newer && f.batch == 0) {
                self.arriving = Some(Arriving { pixels, revision: f.revision, preview: f.preview });
            }
            if !f.preview && !superseded {
                let finished = Finished {
                    revision: f.revision,
                    gpu_ms: ms,
                    batch: f.batch,
                    spp: f.spp,
                    status_context: f.status_context,
                };
                self.readback = Some((job.start_readback(&ctx), finished));
            }
            changed = true;
        }
        if let Some(a) = &self.arriving
            && let Some(result) = a.pixels.poll(&ctx)
        {
            let a = self.arriving.take().expect("checked above");
            match result {
                Ok(rgba) => self.show(a, &rgba),
                Err(e) => self.error = Some(e.to_string()),
            }
            changed = true;
        }
        if let Some((rb, f)) = &mut self.readback
            && let Some(result) = rb.poll(&ctx)
        {
            let (f, paths) = (*f, rb.key().path);
            self.readback = None;
            match result {
                Ok((image, counts, status)) if status != 0 || !paths => {
                    self.warning = status_warning(status, &f.status_context);
                    self.accumulation = None;
                    let (revision, gpu_ms, samples) = (f.revision, f.gpu_ms, f.spp);
                    self.latest = Some(GpuImage { revision, image, counts, status, gpu_ms, samples });
                }
                Ok((image, counts, status)) => self.accumulate(f, image, counts, status),
                Err(e) => self.error = Some(e.to_string()),
            }
            changed = true;
        }
        changed
    }

    /// Adds a path render's batch to its revision's mean, and shows the mean of more than one.
    fn accumulate(&mut self, f: Finished, image: HdrImage, counts: RayCounts, status: u32) {
        let Finished { revision, gpu_ms, batch, spp, .. } = f;
        self.warning = None;
        if batch == 0 {
            self.accumulation = Some(Accumulation::new(revision, image, spp, gpu_ms, counts));
        } else if !self.accumulation.as_mut().is_some_and(|a| a.add(revision, batch, &image, spp, gpu_ms, counts)) {
            // A batch of an edited revision, finished after the edit: dropped.
            return;
        }
        let Some(a) = &self.accumulation else { return };
        self.latest = Some(GpuImage {
            revision,
            image: a.mean.clone(),
            counts: a.counts,
            status,
            gpu_ms: a.gpu_time.as_secs_f64() * 1e3,
            samples: a.samples,
        });
        if batch > 0 && self.shown.is_none_or(|s| s.0 <= revision) {
            let size = (a.mean.width, a.mean.height);
            let pixels = egui::ColorImage::from_rgb([size.0 as usize, size.1 as usize], &a.mean.to_srgb8());
            self.show_image(revision, false, size, pixels);
        }
    }

    /// The path batches still to come for `revision`, none while one is in flight: the next
    /// batch's index, once the mean of the earlier ones is in (path mode, not full).
    pub fn next_batch(&self, revision: u64) -> Option<u32> {
        let a = self.accumulation.as_ref().filter(|a| a.revision == revision && !a.is_full())?;
        (self.in_flight.is_none() && self.readback.is_none() && self.arriving.is_none()).then_some(a.batches)
    }
}

impl GpuView {
    /// Puts a render's landed pixels on screen, unless a newer render's are there already.
    fn show(&mut self, a: Arriving, rgba: &[u8]) {
        if self.shown.is_some_and(|s| s.0 > a.revision) {
            return;
        }
        let size = (a.pixels.width, a.pixels.height);
        let image = egui::ColorImage::from_rgba_unmultiplied([size.0 as usize, size.1 as usize], rgba);
        self.show_image(a.revision, a.preview, size, image);
    }

    /// Puts sRGB pixels of `revision` on screen.
    fn show_image(&mut self, revision: u64, preview: bool, size: (u32, u32), image: egui::ColorImage) {
        // Nearest, like the CPU view: magnified pixels stay pixels and the wipe compares like
        // with like.
        let options = egui::TextureOptions::NEAREST;
        let image = crate::images::within_texture_side(image, self.egui.input(|i| i.max_texture_side));
        let texture = match &mut self.texture {
            Some(t) => {
                t.set(image, options);
                t
            }
            None => self.texture.insert(self.egui.load_texture("gpu render", image, options)),
        };
        self.shown = Some((revision, preview, size, texture.id()));
    }
}

/// What a status word from the shader means for the user.
pub fn status_warning(status: u32, context: &StatusContext) -> Option<String> {
    let messages = glint_gpu::status::messages(status, context);
    (!messages.is_empty()).then(|| messages.join("; "))
}
