//! The render jobs of the document: the GPU view, the CPU reference, their comparison and the
//! pixel probe; which of them the current revision still needs, and their results on screen.

use std::time::{Duration, Instant};

use glint_scene::RenderSettings;

use crate::accumulation::batch_seed;
use crate::comparison::{Compared, Comparison};
use crate::cpu_worker::{CpuWorker, Finished, PROGRESS_INTERVAL};
use crate::document::Document;
use crate::gpu_view::{GpuImage, GpuView};
use crate::images::CpuTexture;
use crate::panels::messages::RenderMessages;
use crate::panels::status::{Samples, Status};
use crate::probe::{GpuProbe, ProbeState};
use crate::view::{Shown, Textures};
use crate::whitted_vs_gi::{Paths, WhittedVsGi};

/// How long a full-resolution GPU render runs before the status bar says it is rendering.
const GPU_PROGRESS_AFTER: Duration = Duration::from_millis(500);

/// How long a render of a new shader variant runs before the status bar says it is compiling.
const COMPILING_AFTER: Duration = Duration::from_millis(300);

#[derive(Debug)]
pub struct Renders {
    pub gpu: Option<GpuView>,
    /// Why there is no GPU view, when there is none.
    pub no_gpu_reason: Option<String>,
    pub cpu: CpuWorker,
    pub comparison: Comparison,
    /// Whitted's image and its difference from the paths, while the Whitted vs GI view is on.
    pub gi: WhittedVsGi,
    pub probe: Option<ProbeState>,
    cpu_texture: CpuTexture,
    diff_texture: CpuTexture,
    /// The revision the CPU reference was last started for.
    cpu_revision: Option<u64>,
    /// The revision (and whether as a preview) the GPU was last given.
    gpu_submitted: Option<(u64, bool)>,
    /// The revision the GPU last rendered at full resolution.
    gpu_full_revision: Option<u64>,
    cpu_uploaded: Option<Instant>,
    repaint: egui::Context,
    /// In path mode, the GPU stops adding batches (the toolbar's Pause); an edit still renders.
    pub paused: bool,
}

impl Renders {
    pub fn new(cc: &eframe::CreationContext<'_>, no_gpu_reason: Option<String>) -> Self {
        let gpu = cc.wgpu_render_state.as_ref().map(|state| GpuView::new(state, &cc.egui_ctx));
        let no_gpu_reason =
            gpu.is_none().then(|| no_gpu_reason.unwrap_or_else(|| "the window has no wgpu renderer".into()));
        let repaint = cc.egui_ctx.clone();
        Self {
            gpu,
            no_gpu_reason,
            cpu: CpuWorker::new(repaint.clone()),
            comparison: Comparison::new(repaint.clone()),
            gi: WhittedVsGi::new(repaint.clone()),
            probe: None,
            cpu_texture: CpuTexture::default(),
            diff_texture: CpuTexture::default(),
            cpu_revision: None,
            gpu_submitted: None,
            gpu_full_revision: None,
            cpu_uploaded: None,
            repaint,
            paused: false,
        }
    }

    /// The finished CPU render of `revision`.
    pub fn cpu_of(&self, revision: u64) -> Option<&Finished> {
        self.cpu.finished.as_ref().filter(|(r, _)| *r == revision).map(|(_, f)| f)
    }

    /// The GPU image of `revision` read back to the host.
    pub fn gpu_of(&self, revision: u64) -> Option<&GpuImage> {
        self.gpu.as_ref().and_then(|g| g.latest.as_ref()).filter(|l| l.revision == revision)
    }

    /// The comparison of the two renders of `revision`.
    pub fn comparison_of(&self, revision: u64) -> Option<&Compared> {
        self.comparison.latest.as_ref().filter(|c| c.revision == revision)
    }

    /// Whether every render of the document's revision is finished (GPU, CPU, comparison, probe).
    pub fn is_settled(&self, doc: &Document) -> bool {
        if !doc.is_valid() {
            // Nothing renders an invalid revision; only a GPU probe may still be on its way.
            return self.probe_settled();
        }
        let rev = doc.render_revision;
        let gpu_failed = self.gpu.as_ref().is_none_or(|g| g.error.is_some());
        let gpu_done =
            self.gpu.as_ref().is_none_or(|g| g.error.is_some() || (self.gpu_of(rev).is_some() && !g.is_busy()));
        self.cpu_of(rev).is_some()
            && gpu_done
            && (gpu_failed || self.comparison_of(rev).is_some())
            && self.probe_settled()
    }

    fn probe_settled(&self) -> bool {
        self.probe.as_ref().is_none_or(|p| !matches!(p.gpu, GpuProbe::Pending(_)))
    }

    /// Collects what the background jobs produced since the last frame.
    pub fn poll(&mut self, ctx: &egui::Context) {
        // Progressive tiles are uploaded at most ten times a second: each upload converts and
        // copies the whole image, which the UI thread should not do for every tile.
        let due = self.cpu_uploaded.is_none_or(|t| t.elapsed() >= PROGRESS_INTERVAL);
        if (due || !self.cpu.is_running())
            && let Some((w, h, rgba)) = self.cpu.poll()
        {
            self.cpu_texture.set_rgba(ctx, "cpu reference", w, h, &rgba);
            self.cpu_uploaded = Some(Instant::now());
        }
        if !due {
            ctx.request_repaint_after(PROGRESS_INTERVAL);
        }
        if let Some(g) = &mut self.gpu {
            g.poll();
        }
        if self.comparison.poll()
            && let Some(c) = &self.comparison.latest
        {
            self.diff_texture.set_rgb(ctx, "difference", c.width, c.height, &c.heatmap);
        }
        if let Some(p) = &mut self.probe {
            p.poll();
        }
        self.gi.poll(ctx);
    }

    /// Renders what the Whitted vs GI view of the document needs: its Whitted image, then the
    /// difference from the paths (the GPU's mean over its batches, else the CPU's) as they
    /// converge.
    pub fn schedule_gi(&mut self, doc: &Document) {
        // Whitted's image reads the ambient terms, the paths do not (`Document::render_revision`).
        let (rev, paths) = (doc.revision, doc.render_revision);
        // Built only when its render is to start, not every frame while it runs.
        let scene = if self.gi.needs_whitted(rev) { doc.flat_with(&whitted_settings(doc)) } else { None };
        // By field, as in `schedule`: `gi` is borrowed mutably beside the images.
        let shown = shown_paths(self.gpu.as_ref(), &self.cpu, paths, doc.desc.render.spp);
        self.gi.request(rev, scene, shown);
    }

    /// The paths the Whitted vs GI view shows beside Whitted's image: the GPU's mean over its
    /// batches, else the CPU's.
    pub fn gi_paths(&self, doc: &Document) -> Option<Paths<'_>> {
        shown_paths(self.gpu.as_ref(), &self.cpu, doc.render_revision, doc.desc.render.spp)
    }

    /// Starts whatever the document's revision still needs; `interacting` (a value or the
    /// view being dragged) asks for GPU previews only.
    pub fn schedule(&mut self, doc: &Document, interacting: bool) {
        let rev = doc.render_revision;
        if self.cpu_revision != Some(rev) && self.cpu.running_revision() != Some(rev) {
            // The next edit cancels the reference at once; it restarts when the edit is done.
            self.cpu.cancel();
        }
        if !doc.is_valid() {
            return;
        }
        if let Some(g) = &mut self.gpu {
            g.cancel_full_render_unless(rev);
            // A full render of several samples takes many times a preview: when the image on
            // screen is of another revision (the camera moved), a preview of this one goes
            // first, so the screen never shows another camera for the seconds it takes.
            let preview_first = !interacting
                && doc.desc.render.spp > 1
                && g.shown_revision() != Some(rev)
                && self.gpu_submitted != Some((rev, true));
            let preview = interacting || preview_first;
            // A preview is only worth it for a new revision; a full render only once per revision
            // (pressing a slider without moving it renders nothing new).
            let needed = if preview {
                self.gpu_submitted.map(|s| s.0) != Some(rev) || preview_first
            } else {
                self.gpu_full_revision != Some(rev)
            };
            let submitted = needed
                && g.in_flight().is_none()
                && doc.flat(preview).is_some_and(|flat| g.submit(&flat, rev, preview));
            // A GPU error (e.g. a scene the GPU cannot take) is shown; do not retry every frame.
            if submitted || (g.error.is_some() && needed) {
                self.gpu_submitted = Some((rev, preview));
                if !preview {
                    self.gpu_full_revision = Some(rev);
                }
            }
        }
        // Paths: the next batch once the last is in, while not paused or dragged.
        if !interacting
            && !self.paused
            && doc.desc.render.integrator == glint_scene::Integrator::Path
            && let Some(g) = &mut self.gpu
            && g.error.is_none()
            && let Some(batch) = g.next_batch(rev)
            && let Some(mut flat) = doc.flat(false)
        {
            flat.header.seed = batch_seed(flat.header.seed, batch);
            let rate = g.accumulation.as_ref().and_then(|a| a.rate());
            flat.header.spp = batch_spp(flat.header.spp, rate);
            g.submit_batch(&flat, rev, batch);
        }
        // Idle, everything of this revision done: compile what an edit is likely to need next.
        if !interacting
            && self.is_settled(doc)
            && let Some(g) = &mut self.gpu
        {
            g.prewarm();
        }
        if !interacting
            && self.cpu_revision != Some(rev)
            && let Some(flat) = doc.flat(false)
        {
            self.cpu.start(flat, rev);
            self.cpu_revision = Some(rev);
        }
        // The probed pixel follows the edits (not while dragging: a probe per preview is waste).
        if !interacting
            && let Some((x, y)) = self.probe.as_ref().filter(|p| p.revision != doc.revision).map(|p| (p.x, p.y))
        {
            self.start_probe(doc, x, y);
        }
        // By field, not through `cpu_of`/`gpu_of`: the comparison is borrowed mutably beside them.
        let cpu = self.cpu.finished.as_ref().filter(|(r, _)| *r == rev).map(|(_, f)| &f.image);
        // In path mode the GPU's first batch: the CPU reference's own paths, which a mirror
        // must match; the later batches are other paths.
        let gpu = self.gpu.as_ref().and_then(|g| match &g.accumulation {
            Some(a) if a.revision == rev => Some(&a.first),
            _ => g.latest.as_ref().filter(|l| l.revision == rev).map(|l| &l.image),
        });
        if let (Some(c), Some(g)) = (cpu, gpu) {
            self.comparison.request(rev, c, g);
        }
    }

    /// Probes pixel (x, y) of the document on both tracers.
    pub fn start_probe(&mut self, doc: &Document, x: u32, y: u32) {
        let Some(flat) = doc.flat(false) else { return };
        // Whitted's terms in either mode; in path mode beside the paths' split.
        let (whitted, paths) = if doc.desc.render.integrator.is_whitted() {
            (flat, None)
        } else {
            let Some(w) = doc.flat_with(&whitted_settings(doc)) else { return };
            (w, Some(flat))
        };
        // None when the image shrank past the probed pixel.
        if x >= whitted.header.width || y >= whitted.header.height {
            self.probe = None;
            return;
        }
        let tracer = self.gpu.as_ref().map(|g| &g.tracer);
        self.probe = ProbeState::start(&whitted, paths.as_ref(), x, y, doc.revision, tracer, &self.repaint)
            .inspect_err(|e| log::error!("probe ({x}, {y}): {e}"))
            .ok();
    }

    /// The textures of the view of `doc` (each difference only while it is of the revision).
    pub fn textures(&self, doc: &Document) -> Textures<'_> {
        // The renders are of `render_revision`, Whitted's side of the GI view of every edit.
        let (render, edit) = (doc.render_revision, doc.revision);
        Textures {
            gpu: self.textures_gpu(render),
            cpu: self.cpu_texture.id().map(|id| Shown {
                id,
                size: self.cpu_texture.size,
                stale: self.cpu_of(render).is_none(),
                held: false,
            }),
            diff: self.diff_texture.id().filter(|_| self.comparison_of(render).is_some()),
            gpu_incomplete: self.gpu.as_ref().and_then(|g| g.warning.as_deref()),
            diffs: self.comparison_of(render).map(|c| &c.diffs),
            whitted: self.gi.whitted_texture.id().map(|id| Shown {
                id,
                size: self.gi.whitted_texture.size,
                stale: self.gi.whitted_of(edit).is_none(),
                held: false,
            }),
            gi: self.gi_texture(render, edit),
            gi_diff: self.gi.diff_texture.id().filter(|_| self.gi.difference_of(edit).is_some()),
            gi_signed: self.gi.difference_of(edit).map(|d| &d.diff),
            gi_samples: self.gi.difference_of(edit).map(|d| d.samples),
            gi_kind: glint_scene::PathKind::ALL.into_iter().find(|k| k.alone() == doc.omit_kinds),
        }
    }

    /// The paths beside Whitted's: those the difference of revision `edit` was taken from (the
    /// GPU's, else the CPU's; `schedule_gi`), and until there is one, the GPU's full render of
    /// `render`, else the CPU's, else whatever the GPU shows (a preview, an earlier revision).
    /// The GPU's half-size preview stood beside Whitted while the difference was of the CPU's
    /// 64 samples.
    fn gi_texture(&self, render: u64, edit: u64) -> Option<Shown> {
        let cpu = self.cpu_texture.id().map(|id| Shown {
            id,
            size: self.cpu_texture.size,
            stale: self.cpu_of(render).is_none(),
            held: false,
        });
        let from_gpu = match self.gi.difference_of(edit) {
            Some(d) => d.from_gpu,
            None => {
                let gpu_full = self.gpu.as_ref().and_then(|g| g.latest.as_ref()).is_some_and(|l| l.revision == render);
                gpu_full || cpu.is_none_or(|c| c.stale)
            }
        };
        if from_gpu { self.textures_gpu(render).or(cpu) } else { cpu.or_else(|| self.textures_gpu(render)) }
    }

    fn textures_gpu(&self, revision: u64) -> Option<Shown> {
        self.gpu.as_ref().and_then(|g| g.shown).map(|s| Shown {
            id: s.3,
            size: s.2,
            stale: s.0 != revision,
            held: false,
        })
    }

    /// What the messages above the status bar say of the renders.
    pub fn messages(&self) -> RenderMessages<'_> {
        RenderMessages {
            no_gpu_reason: self.no_gpu_reason.as_deref(),
            gpu_error: self.gpu.as_ref().and_then(|g| g.error.as_deref()),
            gpu_warning: self.gpu.as_ref().and_then(|g| g.warning.as_deref()),
            cpu_error: self.cpu.error.as_deref(),
        }
    }

    /// What the status bar shows; `ui_ms` is the app's own time per frame. The figures of
    /// renders before revision `opened` are another scene's, and are not shown (a scene opened
    /// kept the last one's rays and frame time for minutes while its own rendered).
    pub fn status(&self, revision: u64, opened: u64, ui_ms: f64) -> Status {
        let gpu_latest = self.gpu.as_ref().and_then(|g| g.latest.as_ref()).filter(|l| l.revision >= opened);
        let cpu_finished = self.cpu.finished.as_ref().filter(|(r, _)| *r >= opened).map(|(_, f)| f);
        Status {
            adapter: self.gpu.as_ref().map(GpuView::adapter_name),
            software: self.gpu.as_ref().is_some_and(GpuView::is_software),
            gpu_ms: self.gpu.as_ref().and_then(|g| g.last_ms).filter(|_| gpu_latest.is_some()),
            // Said only once it is long enough to look like nothing is happening.
            gpu_compiling: self
                .gpu
                .as_ref()
                .and_then(GpuView::compiling)
                .filter(|(t, _)| *t >= COMPILING_AFTER)
                .map(|(t, what)| (what.to_string(), t.as_secs_f64())),
            gpu_rendering: self
                .gpu
                .as_ref()
                .and_then(GpuView::full_render_progress)
                .filter(|(t, _)| *t >= GPU_PROGRESS_AFTER)
                .map(|(t, passes)| (t.as_secs_f64(), passes)),
            gpu_fps: self.gpu.as_ref().and_then(GpuView::renders_per_second).filter(|_| gpu_latest.is_some()),
            ui_ms,
            cpu_progress: self.cpu.progress(),
            cpu_time: cpu_finished.map(|f| f.elapsed.as_secs_f64()),
            errors: self.comparison_of(revision).map(|c| c.errors),
            comparing: self.comparison.is_running(),
            gpu_counts: gpu_latest.map(|l| l.counts),
            cpu_counts: cpu_finished.map(|f| f.counts),
            samples: None,
            held: false,
        }
    }

    /// Path mode's samples for the status bar: the GPU's mean of `revision` and the CPU's.
    pub fn samples(&self, revision: u64, spp: u32) -> Samples {
        let a = self.gpu.as_ref().and_then(|g| g.accumulation.as_ref()).filter(|a| a.revision == revision);
        Samples {
            gpu: a.map(|a| a.samples),
            gpu_rate: a.and_then(|a| a.rate()),
            accumulating: self.gpu.as_ref().is_some_and(GpuView::is_accumulating),
            paused: self.paused,
            full: a.is_some_and(|a| a.is_full()),
            cpu: self.cpu_of(revision).map(|_| spp),
        }
    }

    /// Whether a job is under way that is polled rather than signalled (GPU, comparison).
    pub fn is_busy(&self) -> bool {
        self.gpu.as_ref().is_some_and(GpuView::is_busy) || self.comparison.is_running()
    }

    /// Whether the UI must poll the GPU each frame (`GpuView::needs_polling`).
    pub fn needs_polling(&self) -> bool {
        self.gpu.as_ref().is_some_and(GpuView::needs_polling)
    }

    pub fn gpu_renders(&self) -> usize {
        self.gpu.as_ref().map_or(0, |g| g.renders)
    }

    pub fn adapter_name(&self) -> Option<String> {
        self.gpu.as_ref().map(GpuView::adapter_name)
    }
}

/// GPU time a later path batch aims at: short enough that the image and its sample count move
/// on visibly, long enough that a batch's readback and upload stay a small part of it.
const BATCH_SECONDS: f64 = 0.5;

/// Samples a pixel of a later path batch: what `rate` (samples a pixel per second so far) does
/// in `BATCH_SECONDS`, at least 1 and at most the scene's own `spp`.
fn batch_spp(spp: u32, rate: Option<f64>) -> u32 {
    rate.map_or(spp, |r| (r * BATCH_SECONDS).floor().clamp(1.0, f64::from(spp.max(1))) as u32)
}

/// `Renders::gi_paths` from the fields it reads (`schedule_gi` borrows `gi` mutably beside them).
fn shown_paths<'a>(gpu: Option<&'a GpuView>, cpu: &'a CpuWorker, revision: u64, spp: u32) -> Option<Paths<'a>> {
    let gpu = gpu.and_then(|g| g.latest.as_ref()).filter(|l| l.revision == revision);
    let cpu = cpu.finished.as_ref().filter(|(r, _)| *r == revision).map(|(_, f)| (&f.image, spp, false));
    gpu.map(|l| (&l.image, l.samples, true)).or(cpu)
}

/// The document's render settings with Whitted's integrator.
pub fn whitted_settings(doc: &Document) -> RenderSettings {
    RenderSettings { integrator: glint_scene::Integrator::Whitted, indirect: true, ..doc.desc.render.clone() }
}
