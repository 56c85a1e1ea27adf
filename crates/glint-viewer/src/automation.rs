//! Scripted runs of the real window: `--screenshot` (render, save the window, close), the
//! drag benchmark (orbit for a while as a user would, then report the frame rates) and the
//! features benchmark (use each feature that needs a shader variant of its own for the first
//! time, and report the longest frame interval while its renders ran).

use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glint_io::image_file::write_png_rgb8;

use crate::camera_control;
use crate::document::Document;

/// A run gives up after this long (a render that never settles must not hang CI).
const TIMEOUT: Duration = Duration::from_secs(300);

/// How an automated run ended: a line to print, or an error.
pub type Outcome = Arc<Mutex<Option<Result<String, String>>>>;

#[derive(Debug, Default)]
struct FrameLog {
    intervals_ms: Vec<f64>,
    ui_ms: Vec<f64>,
}

impl FrameLog {
    fn summary(&self) -> String {
        if self.intervals_ms.is_empty() {
            return "no frames".into();
        }
        let mut iv = self.intervals_ms.clone();
        iv.sort_by(f64::total_cmp);
        let mean = iv.iter().sum::<f64>() / iv.len() as f64;
        let p95 = iv[((iv.len() - 1) as f64 * 0.95).round() as usize];
        let max_ui = self.ui_ms.iter().copied().fold(0.0, f64::max);
        let mean_ui = self.ui_ms.iter().sum::<f64>() / self.ui_ms.len().max(1) as f64;
        format!(
            "{} frames, {:.1} fps, frame interval mean {mean:.1} ms, p95 {p95:.1} ms, max {:.1} ms; app logic mean {mean_ui:.1} ms, max {max_ui:.1} ms",
            iv.len(),
            1e3 / mean,
            iv[iv.len() - 1]
        )
    }
}

#[derive(Debug)]
enum Phase {
    Idle,
    /// Dragging until the deadline; GPU renders completed so far are counted.
    Dragging {
        until: Instant,
        renders_at_start: usize,
    },
    /// The drag is over: the CPU reference renders while frames are logged.
    CpuRender,
    /// The paths benchmark: the GPU adds samples until the deadline while frames are logged.
    Accumulating {
        until: Instant,
    },
    /// Feature `k` of `FEATURE_EDITS` was applied; its renders run while frames are logged.
    Feature(usize),
    Screenshot,
    Closing,
}

#[derive(Debug)]
pub struct Automation {
    screenshot: Option<PathBuf>,
    drag_seconds: Option<f64>,
    features: bool,
    paths_seconds: Option<f64>,
    /// The GPU's samples a pixel when the paths benchmark began.
    samples_at_start: Option<u32>,
    paths_log: FrameLog,
    /// The longest frame interval (ms) while each feature's renders ran.
    feature_longest: Vec<f64>,
    phase: Phase,
    started: Instant,
    drag_log: FrameLog,
    cpu_log: FrameLog,
    drag_report: Option<String>,
    pub outcome: Outcome,
}

/// What the app tells the automation each frame.
#[derive(Debug)]
pub struct Frame<'a> {
    pub settled: bool,
    pub cpu_running: bool,
    pub gpu_renders: usize,
    /// Samples a pixel of the GPU's path image (path mode).
    pub gpu_samples: Option<u32>,
    pub metadata: &'a [(String, String)],
}

impl Automation {
    pub fn new(
        screenshot: Option<PathBuf>,
        drag_seconds: Option<f64>,
        features: bool,
        paths_seconds: Option<f64>,
    ) -> Self {
        Self {
            screenshot,
            drag_seconds,
            features,
            paths_seconds,
            samples_at_start: None,
            paths_log: FrameLog::default(),
            feature_longest: Vec::new(),
            phase: Phase::Idle,
            started: Instant::now(),
            drag_log: FrameLog::default(),
            cpu_log: FrameLog::default(),
            drag_report: None,
            outcome: Arc::new(Mutex::new(None)),
        }
    }

    /// Whether every frame is painted (a drag, or the features benchmark measuring frame
    /// intervals: an idle window paints only every 250 ms, which is no stall).
    pub fn paints_every_frame(&self) -> bool {
        matches!(self.phase, Phase::Dragging { .. } | Phase::Feature(_) | Phase::Accumulating { .. })
    }

    pub fn active(&self) -> bool {
        self.screenshot.is_some() || self.drag_seconds.is_some() || self.features || self.paths_seconds.is_some()
    }

    /// During the drag benchmark, orbits the camera a little (as a drag would); returns whether
    /// the view counts as being dragged (preview resolution).
    pub fn drive(&mut self, doc: &mut Document, gpu_renders: usize, settled: bool) -> bool {
        match self.phase {
            Phase::Idle if self.features && settled => self.next_feature(doc, 0),
            Phase::Feature(k) if settled => self.next_feature(doc, k + 1),
            Phase::Idle if self.drag_seconds.is_some() && settled => {
                let secs = self.drag_seconds.unwrap_or(0.0);
                self.phase = Phase::Dragging {
                    until: Instant::now() + Duration::from_secs_f64(secs),
                    renders_at_start: gpu_renders,
                };
                self.started = Instant::now();
                true
            }
            Phase::Dragging { until, renders_at_start } => {
                if Instant::now() >= until {
                    let secs = self.started.elapsed().as_secs_f64();
                    let renders = gpu_renders.saturating_sub(renders_at_start);
                    self.drag_report = Some(format!(
                        "drag: {renders} GPU preview renders in {secs:.1} s = {:.1} renders/s; UI {}",
                        renders as f64 / secs,
                        self.drag_log.summary()
                    ));
                    self.phase = Phase::CpuRender;
                    return false;
                }
                // 4 points a frame over a 400-point view: π/100 a frame, as the benchmark always turned.
                camera_control::orbit(&mut doc.desc.camera, 4.0, 0.0, 400.0, None);
                doc.edited();
                true
            }
            _ => false,
        }
    }

    /// Applies feature `k` (none past the last: the benchmark is over).
    fn next_feature(&mut self, doc: &mut Document, k: usize) -> bool {
        match FEATURE_EDITS.get(k) {
            Some((_, edit)) => {
                edit(&mut doc.desc);
                doc.edited();
                self.feature_longest.push(0.0);
                self.phase = Phase::Feature(k);
            }
            None => self.phase = Phase::CpuRender,
        }
        false
    }

    /// The paths benchmark's report: the samples the GPU added and the frames meanwhile.
    fn paths_report(&self, samples: Option<u32>) -> String {
        let secs = self.started.elapsed().as_secs_f64();
        let (from, to) = (self.samples_at_start.unwrap_or(0), samples.unwrap_or(0));
        format!(
            "paths: the GPU image went from {from} to {to} samples a pixel in {secs:.1} s ({:.1} samples/s); UI {}",
            f64::from(to.saturating_sub(from)) / secs,
            self.paths_log.summary()
        )
    }

    /// The features benchmark's report: each feature's longest frame interval.
    fn features_report(&self) -> String {
        let each: Vec<String> = FEATURE_EDITS
            .iter()
            .zip(&self.feature_longest)
            .map(|((what, _), ms)| format!("{what} {ms:.0} ms"))
            .collect();
        let worst = self.feature_longest.iter().copied().fold(0.0, f64::max);
        format!(
            "first use of each feature, longest frame interval while it rendered: {}; worst {worst:.0} ms",
            each.join(", ")
        )
    }

    pub fn record_frame(&mut self, interval: Duration, ui_ms: f64) {
        if let Phase::Feature(k) = self.phase
            && let Some(longest) = self.feature_longest.get_mut(k)
        {
            *longest = longest.max(interval.as_secs_f64() * 1e3);
            return;
        }
        let log = match self.phase {
            Phase::Dragging { .. } => &mut self.drag_log,
            Phase::CpuRender => &mut self.cpu_log,
            Phase::Accumulating { .. } => &mut self.paths_log,
            _ => return,
        };
        log.intervals_ms.push(interval.as_secs_f64() * 1e3);
        log.ui_ms.push(ui_ms);
    }

    /// Takes the screenshot once everything is rendered, and closes the window when done.
    pub fn step(&mut self, ctx: &egui::Context, frame: &Frame) {
        if !self.active() {
            return;
        }
        if self.started.elapsed() > TIMEOUT && !matches!(self.phase, Phase::Closing) {
            self.finish(ctx, Err(format!("the render did not finish within {} s", TIMEOUT.as_secs())));
            return;
        }
        match self.phase {
            Phase::Idle if self.paths_seconds.is_some() && frame.settled => {
                let secs = self.paths_seconds.unwrap_or(0.0);
                self.phase = Phase::Accumulating { until: Instant::now() + Duration::from_secs_f64(secs) };
                self.samples_at_start = frame.gpu_samples;
                self.started = Instant::now();
            }
            Phase::Accumulating { until } if Instant::now() >= until => {
                let report = self.paths_report(frame.gpu_samples);
                self.finish(ctx, Ok(report));
            }
            Phase::Idle if self.drag_seconds.is_none() && !self.features && frame.settled => {
                self.take_screenshot(ctx, frame.metadata);
            }
            Phase::CpuRender if self.features && frame.settled => {
                let report = self.features_report();
                self.finish(ctx, Ok(report));
            }
            Phase::CpuRender if frame.settled && !frame.cpu_running => {
                let report = format!(
                    "{}\nwhile the CPU reference rendered: UI {}",
                    self.drag_report.take().unwrap_or_default(),
                    self.cpu_log.summary()
                );
                if self.screenshot.is_some() {
                    self.drag_report = Some(report);
                    self.take_screenshot(ctx, frame.metadata);
                } else {
                    self.finish(ctx, Ok(report));
                }
            }
            Phase::Screenshot => {
                let done = self.outcome.lock().unwrap_or_else(|e| e.into_inner()).is_some();
                if done {
                    self.phase = Phase::Closing;
                    ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                }
            }
            _ => {}
        }
    }

    fn take_screenshot(&mut self, ctx: &egui::Context, metadata: &[(String, String)]) {
        let Some(path) = self.screenshot.clone() else { return };
        let slot = self.outcome.clone();
        let repaint = ctx.clone();
        let mut metadata = metadata.to_vec();
        metadata.push(("glint:view".into(), "viewer window".into()));
        let prefix = self.drag_report.take().map(|r| format!("{r}\n")).unwrap_or_default();
        ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::ScreenshotCallback::new(move |image| {
            let [w, h] = image.size;
            let rgb: Vec<u8> = image.pixels.iter().flat_map(|c| [c.r(), c.g(), c.b()]).collect();
            let result = write_png_rgb8(&path, w as u32, h as u32, &rgb, &metadata)
                .map(|()| format!("{prefix}saved the viewer window ({w}x{h}) to {}", path.display()))
                .map_err(|e| e.to_string());
            *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
            repaint.request_repaint();
        })));
        self.phase = Phase::Screenshot;
    }

    fn finish(&mut self, ctx: &egui::Context, result: Result<String, String>) {
        *self.outcome.lock().unwrap_or_else(|e| e.into_inner()) = Some(result);
        self.phase = Phase::Closing;
        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
    }
}

/// An edit of the scene.
pub type SceneEdit = fn(&mut glint_scene::SceneDesc);

/// Edits that each need a shader variant of their own (a feature the scene did not use), in
/// the order the features benchmark applies them.
pub const FEATURE_EDITS: [(&str, SceneEdit); 5] = [
    ("4 samples per pixel", |d| d.render.spp = 4),
    ("max depth 0", |d| d.render.max_depth = 0),
    ("a spot light", |d| {
        if let Some(l) = d.lights.first_mut() {
            l.kind = glint_scene::LightKind::Spot;
            l.direction = Some([0.0, -1.0, 0.0]);
            l.position.get_or_insert([0.0, 5.0, 0.0]);
        }
    }),
    ("Phong", |d| d.materials.values_mut().for_each(|m| m.specular_model = glint_scene::SpecularModel::Phong)),
    ("Cook–Torrance", |d| {
        d.materials.values_mut().for_each(|m| m.specular_model = glint_scene::SpecularModel::CookTorrance)
    }),
];
