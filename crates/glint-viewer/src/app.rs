//! The viewer application: owns the document and the renderers, lays out the panels, and
//! decides each frame what to re-render.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui::Ui;
use glint_core::FlatScene;
use glint_core::image::{RenderInfo, render_metadata};
use glint_core::layout::NO_HIT;
use glint_core::scene::BUILTIN_SCENES;

use crate::automation::{Automation, Frame};
use crate::camera_control;
use crate::comparison::Comparison;
use crate::cpu_worker::CpuWorker;
use crate::document::Document;
use crate::error::ViewerError;
use crate::export::{ExportView, Sources, export};
use crate::gizmos::gizmos;
use crate::gpu_view::GpuView;
use crate::images::CpuTexture;
use crate::panels;
use crate::probe::ProbeState;
use crate::recent::Recent;
use crate::view::{self, Textures, ViewAction, ViewMode};

/// How the viewer starts.
#[derive(Clone, Debug, Default)]
pub struct ViewerOptions {
    /// A scene file or a built-in scene name.
    pub scene: String,
    /// Render settings replacing the scene's own (command-line flags).
    pub settings: Option<glint_core::scene::RenderSettings>,
    /// The view to start in (default: side by side, or the CPU view without a GPU).
    pub view: Option<ViewMode>,
    /// Render, save a screenshot of the window here, and close.
    pub screenshot: Option<PathBuf>,
    /// Simulate an orbit drag for this many seconds, then report the frame rates and close.
    pub drag_benchmark: Option<f64>,
    /// Why there is no GPU, when the window was opened without one.
    pub no_gpu_reason: Option<String>,
    /// Do not read or write the list of recent files (tests).
    pub no_recent: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tab {
    Scene,
    Lights,
    Materials,
    Probe,
}

#[derive(Debug)]
struct ExportDialog {
    open: bool,
    view: ExportView,
    path: String,
}

/// The viewer. Public fields are read by the UI tests.
#[derive(Debug)]
pub struct ViewerApp {
    pub doc: Document,
    pub gpu: Option<GpuView>,
    pub no_gpu_reason: Option<String>,
    pub cpu: CpuWorker,
    pub comparison: Comparison,
    pub mode: ViewMode,
    pub tab: Tab,
    pub wipe: f32,
    pub show_gizmos: bool,
    pub selected_object: Option<usize>,
    pub selected_material: Option<String>,
    pub selected_light: usize,
    pub probe: Option<ProbeState>,
    /// The last message for the user (errors of loading, saving, validation).
    pub message: Option<String>,
    pub recent: Recent,
    pub ui_ms: f64,
    cpu_texture: CpuTexture,
    diff_texture: CpuTexture,
    cpu_revision: Option<u64>,
    gpu_submitted: Option<(u64, bool)>,
    gpu_full_revision: Option<u64>,
    export: ExportDialog,
    pub automation: Automation,
    /// A scene file dropped on the window or chosen in a dialog, loaded next frame.
    pending_open: Option<PathBuf>,
    last_frame: Option<Instant>,
    cpu_uploaded: Option<Instant>,
    /// Where the images were drawn last frame (screen points), for mapping pixels to clicks.
    pub view_rects: Vec<egui::Rect>,
    /// Where the status bar was drawn (its timings change from run to run).
    pub status_rect: egui::Rect,
}

impl ViewerApp {
    pub fn new(cc: &eframe::CreationContext<'_>, options: ViewerOptions) -> Self {
        let (doc, message) = match Document::load(&options.scene) {
            Ok(mut d) => {
                if let Some(s) = &options.settings {
                    d.desc.render = s.clone();
                    d.edited();
                    d.dirty = false;
                }
                (d, None)
            }
            Err(e) => {
                let fallback = Document::load("whitted").unwrap_or_else(|_| Document::empty());
                (fallback, Some(format!("{e}; showing the built-in 'whitted' scene instead")))
            }
        };
        let gpu = cc.wgpu_render_state.as_ref().map(GpuView::new);
        let no_gpu_reason = if gpu.is_none() {
            Some(options.no_gpu_reason.clone().unwrap_or_else(|| "the window has no wgpu renderer".into()))
        } else {
            None
        };
        let mode = match (options.view, gpu.is_some()) {
            (_, false) => ViewMode::Cpu,
            (Some(v), true) => v,
            (None, true) => ViewMode::SideBySide,
        };
        Self {
            doc,
            gpu,
            no_gpu_reason,
            cpu: CpuWorker::new(cc.egui_ctx.clone()),
            comparison: Comparison::new(cc.egui_ctx.clone()),
            mode,
            tab: Tab::Scene,
            wipe: 0.5,
            show_gizmos: true,
            selected_object: None,
            selected_material: None,
            selected_light: 0,
            probe: None,
            message,
            recent: if options.no_recent { Recent::in_memory() } else { Recent::load() },
            ui_ms: 0.0,
            cpu_texture: CpuTexture::default(),
            diff_texture: CpuTexture::default(),
            cpu_revision: None,
            gpu_submitted: None,
            gpu_full_revision: None,
            export: ExportDialog { open: false, view: ExportView::All, path: String::new() },
            automation: Automation::new(options.screenshot, options.drag_benchmark),
            pending_open: None,
            last_frame: None,
            cpu_uploaded: None,
            view_rects: Vec::new(),
            status_rect: egui::Rect::NOTHING,
        }
    }

    /// Whether every render of the current revision is finished (GPU, CPU and comparison).
    pub fn is_settled(&self) -> bool {
        let rev = self.doc.revision;
        let cpu_done = self.cpu.finished.as_ref().is_some_and(|(r, _)| *r == rev) || !self.doc.is_valid();
        let gpu_done = match &self.gpu {
            None => true,
            Some(g) => {
                !self.doc.is_valid()
                    || g.error.is_some()
                    || (g.latest.as_ref().is_some_and(|l| l.revision == rev) && !g.is_busy())
            }
        };
        let compared = self.gpu.as_ref().is_none_or(|g| g.error.is_some())
            || self.comparison.latest.as_ref().is_some_and(|c| c.revision == rev)
            || !self.doc.is_valid();
        cpu_done
            && gpu_done
            && compared
            && self.probe.as_ref().is_none_or(|p| !matches!(p.gpu, crate::probe::GpuProbe::Pending(_)))
    }

    /// Replaces the document (open file, built-in scene, drop).
    pub fn open(&mut self, arg: &str) {
        match Document::load(arg) {
            Ok(mut d) => {
                if let Some(p) = &d.path {
                    self.recent.add(p);
                }
                // A fresh revision number keeps old results of the previous scene from matching.
                d.revision = self.doc.revision + 1;
                self.doc = d;
                self.selected_object = None;
                self.selected_material = None;
                self.selected_light = 0;
                self.probe = None;
                self.message = None;
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    fn save_scene_as(&mut self) {
        let Some(path) = rfd::FileDialog::new()
            .add_filter("Glint scene", &["toml"])
            .set_file_name(format!("{}.toml", self.doc.name))
            .save_file()
        else {
            return;
        };
        self.save_scene(&path);
    }

    pub fn save_scene(&mut self, path: &Path) {
        match self.doc.save(path) {
            Ok(()) => {
                self.recent.add(path);
                self.message = Some(format!("Saved {}", path.display()));
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    /// Writes one of the views (see `export`), reporting in the UI.
    pub fn save_image(&mut self, path: &Path, view: ExportView) -> Result<(), ViewerError> {
        let rev = self.doc.revision;
        let adapter = self.gpu.as_ref().map(GpuView::adapter_name).unwrap_or_default();
        let sources = Sources {
            scene: &self.doc.name,
            settings: &self.doc.desc.render,
            cpu: self.cpu.finished.as_ref().filter(|(r, _)| *r == rev).map(|(_, f)| f),
            gpu: self.gpu.as_ref().and_then(|g| g.latest.as_ref()).filter(|l| l.revision == rev),
            diff: self.comparison.latest.as_ref().filter(|c| c.revision == rev),
            adapter: &adapter,
        };
        export(path, view, &sources)
    }

    fn poll_workers(&mut self, ctx: &egui::Context) {
        // Progressive tiles are uploaded at most ten times a second: each upload converts and
        // copies the whole image, which the UI thread should not do for every tile.
        let due = self.cpu_uploaded.is_none_or(|t| t.elapsed() >= Duration::from_millis(100));
        if (due || !self.cpu.is_running())
            && let Some((w, h, rgba)) = self.cpu.poll()
        {
            self.cpu_texture.set_rgba(ctx, "cpu reference", w, h, &rgba);
            self.cpu_uploaded = Some(Instant::now());
        }
        if !due {
            ctx.request_repaint_after(Duration::from_millis(100));
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
    }

    /// Starts whatever the current revision still needs.
    fn schedule(&mut self, ctx: &egui::Context, interacting: bool) {
        let rev = self.doc.revision;
        if self.cpu_revision != Some(rev) && self.cpu.running_revision() != Some(rev) {
            // The next edit cancels the reference at once; it restarts when the edit is done.
            self.cpu.cancel();
        }
        if !self.doc.is_valid() {
            return;
        }
        if let Some(g) = &mut self.gpu {
            let wanted = (rev, interacting);
            // A preview is only worth it for a new revision; a full render only once per revision
            // (pressing a slider without moving it renders nothing new).
            let needed = if interacting {
                self.gpu_submitted.map(|s| s.0) != Some(rev)
            } else {
                self.gpu_full_revision != Some(rev)
            };
            if needed
                && g.in_flight().is_none()
                && let Some(flat) = self.doc.flat(interacting)
                && g.submit(&flat, rev, interacting)
            {
                self.gpu_submitted = Some(wanted);
                if !interacting {
                    self.gpu_full_revision = Some(rev);
                }
            }
            if g.error.is_some() && needed {
                // A GPU error (e.g. a scene the GPU cannot take) is shown; do not retry every frame.
                self.gpu_submitted = Some(wanted);
                if !interacting {
                    self.gpu_full_revision = Some(rev);
                }
            }
        }
        if !interacting
            && self.cpu_revision != Some(rev)
            && let Some(flat) = self.doc.flat(false)
        {
            self.cpu.start(flat, rev);
            self.cpu_revision = Some(rev);
        }
        // The probed pixel follows the edits (not while dragging: a probe per preview is waste).
        if !interacting && let Some((x, y)) = self.probe.as_ref().filter(|p| p.revision != rev).map(|p| (p.x, p.y)) {
            self.start_probe(ctx, x, y);
        }
        let cpu = self.cpu.finished.as_ref().filter(|(r, _)| *r == rev).map(|(_, f)| &f.image);
        let gpu = self.gpu.as_ref().and_then(|g| g.latest.as_ref()).filter(|l| l.revision == rev).map(|l| &l.image);
        if let (Some(c), Some(g)) = (cpu, gpu) {
            self.comparison.request(rev, c, g);
        }
    }

    /// The settings and device, as `glint render` embeds them in its PNGs.
    pub fn window_metadata(&self) -> Vec<(String, String)> {
        let device = self.gpu.as_ref().map(GpuView::adapter_name).unwrap_or_else(|| "cpu only".into());
        let info = RenderInfo {
            scene: &self.doc.name,
            backend: "viewer",
            device: &device,
            specialised: true,
            time_ms: None,
            rays: None,
        };
        render_metadata(&self.doc.desc.render, &info)
    }

    fn full_scene(&self) -> Option<FlatScene> {
        self.doc.flat(false)
    }

    fn apply_view_actions(&mut self, ctx: &egui::Context, actions: &[ViewAction]) {
        for a in actions {
            match *a {
                ViewAction::Orbit(d) => {
                    camera_control::orbit(&mut self.doc.desc.camera, d.x, d.y);
                    self.doc.edited();
                }
                ViewAction::Pan(d, h) => {
                    camera_control::pan(&mut self.doc.desc.camera, d.x, d.y, h);
                    self.doc.edited();
                }
                ViewAction::Zoom(s) => {
                    camera_control::zoom(&mut self.doc.desc.camera, s);
                    self.doc.edited();
                }
                ViewAction::Pick(x, y) => self.pick(x, y),
                ViewAction::Probe(x, y) => self.probe_at(ctx, x, y),
            }
        }
    }

    /// Selects the object under pixel (x, y) (a CPU camera ray) and shows its material.
    pub fn pick(&mut self, x: u32, y: u32) {
        let Some(flat) = self.full_scene() else { return };
        let id = glint_core::pick_object(&flat, x, y);
        self.selected_object = if id == NO_HIT { None } else { self.doc.object_index(id) };
        if self.selected_object.is_some() {
            self.tab = Tab::Materials;
        }
    }

    /// Probes pixel (x, y) on both tracers and shows the breakdown.
    pub fn probe_at(&mut self, ctx: &egui::Context, x: u32, y: u32) {
        self.start_probe(ctx, x, y);
        self.tab = Tab::Probe;
    }

    fn start_probe(&mut self, ctx: &egui::Context, x: u32, y: u32) {
        let Some(flat) = self.full_scene() else { return };
        if x >= flat.header.width || y >= flat.header.height {
            // The image shrank past the probed pixel.
            self.probe = None;
            return;
        }
        let tracer = self.gpu.as_ref().map(|g| &g.tracer);
        let probe = ProbeState::start(&flat, x, y, self.doc.revision, tracer, ctx);
        self.probe = Some(probe);
    }

    fn menu_bar(&mut self, ui: &mut Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("Open scene…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("Glint scene", &["toml"]).pick_file()
                {
                    self.pending_open = Some(p);
                }
                ui.menu_button("Recent scenes", |ui| {
                    if self.recent.files.is_empty() {
                        ui.weak("none yet");
                    }
                    for f in self.recent.files.clone() {
                        if ui.button(f.display().to_string()).clicked() {
                            self.pending_open = Some(f);
                        }
                    }
                });
                ui.menu_button("Built-in scenes", |ui| {
                    for b in BUILTIN_SCENES {
                        if ui.button(b.name).clicked() {
                            self.open(b.name);
                        }
                    }
                });
                ui.separator();
                if ui.add_enabled(self.doc.path.is_some(), egui::Button::new("Save scene")).clicked()
                    && let Some(p) = self.doc.path.clone()
                {
                    self.save_scene(&p);
                }
                if ui.button("Save scene as…").clicked() {
                    self.save_scene_as();
                }
                if ui.button("Save image…  (Ctrl+S)").clicked() {
                    self.export.open = true;
                }
                ui.separator();
                if ui.button("Quit").clicked() {
                    ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
                }
            });
            ui.menu_button("View", |ui| {
                for m in ViewMode::ALL {
                    ui.radio_value(&mut self.mode, m, m.label());
                }
                ui.checkbox(&mut self.show_gizmos, "Light gizmos");
            });
            ui.separator();
            let dirty = if self.doc.dirty { " (edited)" } else { "" };
            ui.label(format!("{}{dirty}", self.doc.name));
        });
    }

    fn export_window(&mut self, ctx: &egui::Context) {
        if !self.export.open {
            return;
        }
        let mut open = true;
        let mut save = false;
        egui::Window::new("Save image").open(&mut open).collapsible(false).resizable(false).show(ctx, |ui| {
            for v in ExportView::ALL {
                ui.radio_value(&mut self.export.view, v, v.label());
            }
            ui.horizontal(|ui| {
                let label = ui.label("File");
                ui.add(egui::TextEdit::singleline(&mut self.export.path).hint_text("image.png or image.exr"))
                    .labelled_by(label.id);
                if ui.button("Browse…").clicked()
                    && let Some(p) = rfd::FileDialog::new()
                        .add_filter("PNG (settings embedded)", &["png"])
                        .add_filter("OpenEXR (linear)", &["exr"])
                        .set_file_name(format!("{}.png", self.doc.name))
                        .save_file()
                {
                    self.export.path = p.display().to_string();
                }
            });
            ui.weak("PNG: sRGB with the render settings as metadata. EXR: linear radiance.");
            save = ui.add_enabled(!self.export.path.trim().is_empty(), egui::Button::new("Save")).clicked();
        });
        self.export.open = open;
        if save {
            let path = PathBuf::from(self.export.path.trim());
            match self.save_image(&path, self.export.view) {
                Ok(()) => {
                    self.message = Some(format!("Saved {}", path.display()));
                    self.export.open = false;
                }
                Err(e) => self.message = Some(e.to_string()),
            }
        }
    }

    fn side_panel(&mut self, ui: &mut Ui) {
        ui.horizontal(|ui| {
            ui.selectable_value(&mut self.tab, Tab::Scene, "Scene");
            ui.selectable_value(&mut self.tab, Tab::Lights, "Lights");
            ui.selectable_value(&mut self.tab, Tab::Materials, "Materials");
            ui.selectable_value(&mut self.tab, Tab::Probe, "Probe");
        });
        ui.separator();
        // Both directions: a wide probe table scrolls instead of widening the panel.
        egui::ScrollArea::both().show(ui, |ui| {
            let changed = match self.tab {
                Tab::Scene => panels::scene::ui(ui, &mut self.doc),
                Tab::Lights => panels::lights::ui(ui, &mut self.doc, &mut self.selected_light),
                Tab::Materials => {
                    panels::materials::ui(ui, &mut self.doc, self.selected_object, &mut self.selected_material)
                }
                Tab::Probe => {
                    panels::probe::ui(ui, self.probe.as_ref(), &self.doc);
                    false
                }
            };
            if changed {
                self.doc.edited();
            }
            if !self.doc.issues.is_empty() {
                ui.separator();
                ui.colored_label(
                    ui.visuals().error_fg_color,
                    "Invalid values (the last valid render stays on screen):",
                );
                for i in &self.doc.issues {
                    ui.colored_label(ui.visuals().error_fg_color, i.to_string());
                }
            }
        });
    }

    fn status(&self) -> panels::status::Status {
        let rev = self.doc.revision;
        let gpu_latest = self.gpu.as_ref().and_then(|g| g.latest.as_ref());
        panels::status::Status {
            adapter: self.gpu.as_ref().map(GpuView::adapter_name),
            gpu_ms: self.gpu.as_ref().and_then(|g| g.last_ms),
            gpu_fps: self.gpu.as_ref().and_then(GpuView::renders_per_second),
            ui_ms: self.ui_ms,
            cpu_progress: self.cpu.progress(),
            cpu_time: self.cpu.finished.as_ref().map(|(_, f)| f.elapsed.as_secs_f64()),
            errors: self.comparison.latest.as_ref().filter(|c| c.revision == rev).map(|c| c.errors),
            comparing: self.comparison.is_running(),
            gpu_counts: gpu_latest.map(|l| l.counts),
            cpu_counts: self.cpu.finished.as_ref().map(|(_, f)| f.counts),
        }
    }

    fn messages(&self, ui: &mut Ui) {
        let warn = ui.visuals().warn_fg_color;
        let err = ui.visuals().error_fg_color;
        if let Some(r) = &self.no_gpu_reason {
            ui.colored_label(warn, format!("No GPU: {r}. Showing the CPU reference only."));
        }
        if let Some(g) = &self.gpu {
            if let Some(e) = &g.error {
                ui.colored_label(err, format!("GPU: {e}"));
            }
            if let Some(w) = &g.warning {
                ui.colored_label(warn, format!("GPU: {w}"));
            }
        }
        if let Some(e) = &self.cpu.error {
            ui.colored_label(err, format!("CPU: {e}"));
        }
        if let Some(m) = &self.message {
            ui.label(m);
        }
    }

    fn central(&mut self, ui: &mut Ui) -> Vec<ViewAction> {
        ui.horizontal(|ui| {
            for m in ViewMode::ALL {
                let enabled = self.gpu.is_some() || m == ViewMode::Cpu;
                ui.add_enabled_ui(enabled, |ui| ui.selectable_value(&mut self.mode, m, m.label()));
            }
            if self.mode == ViewMode::Wipe {
                ui.add(egui::Slider::new(&mut self.wipe, 0.0..=1.0).show_value(false).text("Wipe"));
            }
        });
        let rev = self.doc.revision;
        let shown = self.gpu.as_ref().and_then(|g| g.shown);
        let textures = Textures {
            gpu: shown.map(|s| s.3),
            cpu: self.cpu_texture.id(),
            diff: self.diff_texture.id().filter(|_| self.comparison.latest.as_ref().is_some_and(|c| c.revision == rev)),
        };
        let size = (self.doc.desc.render.width.max(1), self.doc.desc.render.height.max(1));
        let gizmos =
            self.doc.flat(false).map(|f| gizmos(&self.doc.desc, &f.camera, self.selected_light)).unwrap_or_default();
        let show_gizmos = self.show_gizmos;
        let (actions, rects) = view::show(ui, self.mode, &mut self.wipe, textures, size, &gizmos, show_gizmos);
        self.view_rects = rects;
        actions
    }

    /// The screen position of the centre of pixel (x, y) in the first image of the view.
    pub fn screen_pos_of_pixel(&self, x: u32, y: u32) -> Option<egui::Pos2> {
        let r = self.view_rects.first()?;
        let (w, h) = (self.doc.desc.render.width as f32, self.doc.desc.render.height as f32);
        Some(r.min + egui::vec2((x as f32 + 0.5) / w * r.width(), (y as f32 + 0.5) / h * r.height()))
    }
}

impl eframe::App for ViewerApp {
    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        let start = Instant::now();
        let ctx = ui.ctx().clone();
        self.poll_workers(&ctx);
        if let Some(p) = ctx.input(|i| {
            i.raw.dropped_files.iter().find_map(|f| {
                let p = f.path();
                (!p.as_os_str().is_empty()).then(|| p.to_path_buf())
            })
        }) {
            self.pending_open = Some(p);
        }
        if let Some(p) = self.pending_open.take() {
            self.open(&p.display().to_string());
        }
        if ctx.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, egui::Key::S)) {
            self.export.open = true;
            if self.export.path.is_empty() {
                self.export.path = format!("{}.png", self.doc.name);
            }
        }
        egui::Panel::top("menu").show(ui, |ui| self.menu_bar(ui));
        self.status_rect = egui::Panel::bottom("status")
            .show(ui, |ui| {
                self.messages(ui);
                panels::status::ui(ui, &self.status());
            })
            .response
            .rect;
        egui::Panel::left("panels").default_size(380.0).show(ui, |ui| self.side_panel(ui));
        // The view's dark background is the panel's own fill: no second full-area fill (each
        // costs a pass over its pixels on a software rasterizer).
        let frame = egui::Frame::central_panel(ui.style()).fill(egui::Color32::from_gray(12));
        let actions = egui::CentralPanel::default().frame(frame).show(ui, |ui| self.central(ui)).inner;
        self.apply_view_actions(&ctx, &actions);
        self.export_window(&ctx);
        let gpu_renders = self.gpu.as_ref().map_or(0, |g| g.renders);
        let settled = self.is_settled();
        let automated_drag = self.automation.drive(&mut self.doc, gpu_renders, settled);
        let interacting = automated_drag || ctx.dragged_id().is_some();
        self.schedule(&ctx, interacting);
        let metadata = self.window_metadata();
        let frame =
            Frame { settled: self.is_settled(), cpu_running: self.cpu.is_running(), gpu_renders, metadata: &metadata };
        self.automation.step(&ctx, &frame);
        let busy = self.gpu.as_ref().is_some_and(GpuView::is_busy) || self.comparison.is_running();
        if busy || self.automation.active() {
            // GPU completion is polled, not signalled: look again next frame.
            ctx.request_repaint_after(Duration::from_millis(4));
        }
        let now = Instant::now();
        self.ui_ms = now.duration_since(start).as_secs_f64() * 1e3;
        if let Some(last) = self.last_frame {
            self.automation.record_frame(now.duration_since(last), self.ui_ms);
        }
        self.last_frame = Some(now);
    }
}
