//! The viewer application: the document, what is selected, the render jobs, the dialogs and
//! the layout; each frame collects results, draws the panels, applies the edits and starts the
//! renders the current revision still needs.

use std::borrow::Cow;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use egui::Ui;
use glint_core::FlatScene;
use glint_core::image::{RenderInfo, render_metadata};
use glint_io::LoadOptions;

use crate::ambient_fit::AmbientFitter;
use crate::automation::{Automation, Frame};
use crate::camera_control;
use crate::dialogs::{Dialogs, PathPurpose, Then};
use crate::document::Document;
use crate::error::ViewerError;
use crate::error_history::{Axis, ErrorHistory, ErrorPoint};
use crate::export::{ExportView, GiSources, Sources, export};
use crate::frame_clock::FrameClock;
use crate::gizmos::gizmos;
use crate::layout::{Layout, SIDE_PANEL_DEFAULT, SIDE_PANEL_MIN, Tab, VIEW_MIN_WIDTH};
use crate::menu;
use crate::panels;
use crate::ray_tree_view;
use crate::recent::Recent;
use crate::renders::Renders;
use crate::selection::{Hits, Selection};
use crate::undo::EditHistory;
use crate::view::{GiView, ViewAction, ViewMode};

mod file_flow;

/// How the viewer starts.
#[derive(Clone, Debug, Default)]
pub struct ViewerOptions {
    /// A scene file (its path as the system gives it, UTF-8 or not) or a built-in scene name.
    pub scene: std::ffi::OsString,
    /// How the scene is opened: a generated scene's resolution, a model file's import options.
    pub load: LoadOptions,
    /// The scene as the caller already loaded it (from `scene` with `load`): it is read once,
    /// since a named pipe cannot be read twice and its second read would wait for ever.
    pub loaded: Option<glint_io::LoadedScene>,
    /// Render settings replacing the scene's own (command-line flags).
    pub settings: Option<glint_scene::RenderSettings>,
    /// The view to start in (default: side by side, or the CPU view without a GPU).
    pub view: Option<ViewMode>,
    /// How Whitted vs GI starts holding its two images against each other.
    pub gi_view: GiView,
    /// Render with paths, let the GPU add samples for this many seconds, then report the
    /// samples, their rate and the frame intervals, and close.
    pub paths_benchmark: Option<f64>,
    /// Start with the GPU's path batches paused: each revision's path image is its first
    /// render alone (tests that need the same image every run).
    pub paused: bool,
    /// Render, save a screenshot of the window here, and close.
    pub screenshot: Option<PathBuf>,
    /// Simulate an orbit drag for this many seconds, then report the frame rates and close.
    pub drag_benchmark: Option<f64>,
    /// Use each feature that needs a shader variant of its own for the first time, then report
    /// the longest frame interval while each rendered, and close.
    pub features_benchmark: bool,
    /// Why there is no GPU, when the window was opened without one.
    pub no_gpu_reason: Option<String>,
    /// Do not read or write the list of recent files (tests).
    pub no_recent: bool,
    /// Why the system's file dialogs must not be used: the typed path is asked for instead
    /// (tests; otherwise the viewer finds out whether they can open).
    pub no_file_dialogs: Option<String>,
}

/// The viewer. Public fields are read by the UI tests.
#[derive(Debug)]
pub struct ViewerApp {
    pub doc: Document,
    pub recent: Recent,
    /// The last message for the user (errors of loading, saving, validation).
    pub message: Option<String>,
    pub selection: Selection,
    pub renders: Renders,
    pub layout: Layout,
    dialogs: Dialogs,
    pub automation: Automation,
    clock: FrameClock,
    /// The comparisons of the current scene, for the Errors panel's plot.
    pub history: ErrorHistory,
    error_axis: Axis,
    /// The Scene panel's Fit ambient job and its last result.
    pub fitter: AmbientFitter,
    /// The scene's undo and redo steps.
    pub edits: EditHistory,
    /// The user chose to quit (or had nothing to save): the next close request goes through.
    pub quitting: bool,
    /// Whether the raised stop flag (SIGINT, SIGTERM) was answered already: one quit a signal.
    signal_answered: bool,
    /// Close the window at the end of this frame (after "unsaved changes" was answered).
    close_pending: bool,
}

impl ViewerApp {
    pub fn new(cc: &eframe::CreationContext<'_>, options: ViewerOptions) -> Self {
        let doc = match options.loaded.clone() {
            Some(loaded) => Ok(Document::from_loaded(loaded)),
            None => Document::load_with(&options.scene, &options.load),
        };
        let (doc, message) = match doc {
            Ok(mut d) => {
                if let Some(s) = &options.settings {
                    d.desc.render = s.clone();
                    d.edited();
                    d.dirty = false;
                }
                // Whitted against GI, and the paths benchmark, need the paths.
                if (options.view == Some(ViewMode::WhittedVsGi) || options.paths_benchmark.is_some())
                    && d.desc.render.integrator.is_whitted()
                {
                    d.desc.render.integrator = glint_scene::Integrator::Path;
                    d.view_changed();
                }
                (d, None)
            }
            Err(e) => {
                let fallback = Document::load("whitted").unwrap_or_else(|_| Document::empty());
                (fallback, Some(format!("{e}; showing the built-in 'whitted' scene instead")))
            }
        };
        crate::background::unfill_panels(&cc.egui_ctx);
        let mut renders = Renders::new(cc, options.no_gpu_reason.clone());
        renders.paused = options.paused;
        let mode = match (options.view, renders.gpu.is_some()) {
            (_, false) => ViewMode::Cpu,
            (Some(v), true) => v,
            (None, true) => ViewMode::SideBySide,
        };
        Self {
            edits: EditHistory::new(&doc),
            doc,
            recent: if options.no_recent { Recent::in_memory() } else { Recent::load() },
            message,
            selection: Selection::default(),
            renders,
            layout: Layout { gi_view: options.gi_view, ..Layout::new(mode) },
            dialogs: Dialogs::new(options.no_file_dialogs.clone()),
            automation: Automation::new(
                options.screenshot,
                options.drag_benchmark,
                options.features_benchmark,
                options.paths_benchmark,
            ),
            clock: FrameClock::default(),
            history: ErrorHistory::default(),
            error_axis: Axis::Samples,
            fitter: AmbientFitter::new(Some(cc.egui_ctx.clone())),
            quitting: false,
            signal_answered: false,
            close_pending: false,
        }
    }

    /// Whether every render of the current revision is finished (GPU, CPU and comparison).
    pub fn is_settled(&self) -> bool {
        let rev = self.doc.revision;
        let gi_done = self.layout.mode != ViewMode::WhittedVsGi
            || !self.doc.is_valid()
            || self.renders.gi.difference_of(rev).is_some()
            || self.renders.gi.error.is_some();
        self.renders.is_settled(&self.doc) && gi_done
    }

    /// Opens `arg` (a file or a built-in scene) in place of the document, asking first
    /// (Save / Discard / Cancel) when the document has unsaved edits.
    pub fn request_open(&mut self, arg: &str) {
        if self.doc.dirty {
            self.dialogs.confirm_unsaved(Then::Open(arg.to_string()));
        } else {
            self.open(arg);
        }
    }

    /// Replaces the document (open file, built-in scene, drop) without asking.
    pub fn open(&mut self, arg: &str) {
        match Document::load(arg) {
            Ok(mut d) => {
                if let Some(p) = &d.source {
                    self.recent.add(p);
                }
                // Whitted against GI needs the paths, for the scene opened in that view as for
                // the one it was chosen on: a Whitted scene opened there was shown on both sides,
                // its copy labelled "GI (paths)" (a lecturer).
                if self.layout.mode == ViewMode::WhittedVsGi && d.desc.render.integrator.is_whitted() {
                    d.desc.render.integrator = glint_scene::Integrator::Path;
                    d.view_changed();
                }
                // A fresh revision number keeps old results of the previous scene from matching.
                d.revision = self.doc.revision + 1;
                (d.opened, d.hits_revision, d.render_revision, d.fit_revision) =
                    (d.revision, d.revision, d.revision, d.revision);
                self.doc = d;
                self.edits = EditHistory::new(&self.doc);
                self.selection = Selection::default();
                self.renders.probe = None;
                self.history.clear();
                self.message = None;
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    pub fn save_scene(&mut self, path: &Path) {
        match self.doc.save(path) {
            Ok(()) => {
                self.edits.saved(&self.doc);
                self.recent.add(path);
                self.message = Some(format!("Saved {}", path.display()));
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    /// Writes one of the views (see `export`), reporting in the UI.
    pub fn save_image(&mut self, path: &Path, view: ExportView) -> Result<(), ViewerError> {
        let rev = self.doc.render_revision;
        let adapter = self.renders.adapter_name().unwrap_or_default();
        let whitted_settings = crate::renders::whitted_settings(&self.doc);
        let gi = match (self.renders.gi.whitted_of(self.doc.revision), self.renders.gi_paths(&self.doc)) {
            (Some(whitted), Some((paths, samples, paths_on_gpu))) => {
                Some(GiSources { whitted, whitted_settings: &whitted_settings, paths, samples, paths_on_gpu })
            }
            _ => None,
        };
        let sources = Sources {
            scene: &self.doc.name,
            settings: &self.doc.desc.render,
            cpu: self.renders.cpu_of(rev),
            gpu: self.renders.gpu_of(rev),
            diff: self.renders.comparison_of(rev),
            adapter: &adapter,
            gi,
        };
        export(path, view, &sources)
    }

    /// The settings and device, as `glint render` embeds them in its PNGs.
    pub fn window_metadata(&self) -> Vec<(String, String)> {
        let device = self.renders.adapter_name().unwrap_or_else(|| "cpu only".into());
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

    /// Selects the object under pixel (x, y) (a CPU camera ray) and shows the material there:
    /// of a model's several, the one of the face clicked.
    pub fn pick(&mut self, x: u32, y: u32) {
        if self.select_at(x, y) {
            self.layout.tab = Tab::Materials;
            self.layout.show_side_panel = true;
        }
    }

    /// `pick` without changing the tab (a Ctrl+click probes and selects); whether an object is
    /// under the pixel.
    fn select_at(&mut self, x: u32, y: u32) -> bool {
        let Some(flat) = self.doc.flat(false) else { return false };
        let picked = glint_core::pick(&flat, x, y).inspect_err(|e| log::error!("pick ({x}, {y}): {e}")).ok().flatten();
        self.selection.object = picked.and_then(|p| self.doc.object_index(p.object));
        let Some(p) = picked.filter(|_| self.selection.object.is_some()) else { return false };
        self.selection.material = flat.material_names.get(p.material as usize).cloned();
        true
    }

    /// Adds the comparison of the current revision to the error history, once.
    fn record_comparison(&mut self) {
        let rev = self.doc.render_revision;
        let (Some(c), Some(gpu), Some(cpu)) =
            (self.renders.comparison_of(rev), self.renders.gpu_of(rev), self.renders.cpu_of(rev))
        else {
            return;
        };
        let point = ErrorPoint {
            revision: rev,
            settings: self.doc.desc.render.clone(),
            errors: c.errors,
            gpu_ms: gpu.gpu_ms,
            cpu_ms: cpu.elapsed.as_secs_f64() * 1e3,
        };
        self.history.record(&self.doc.desc, point);
    }

    /// Probes pixel (x, y) on both tracers and shows the breakdown.
    pub fn probe_at(&mut self, x: u32, y: u32) {
        self.renders.start_probe(&self.doc, x, y);
        self.layout.tab = Tab::Probe;
        self.layout.show_side_panel = true;
    }

    /// The screen position of the centre of pixel (x, y) in the first image of the view.
    pub fn screen_pos_of_pixel(&self, x: u32, y: u32) -> Option<egui::Pos2> {
        let size = (self.doc.desc.render.width, self.doc.desc.render.height);
        self.layout.screen_pos_of_pixel(x, y, size)
    }

    /// The windows of the app: "Save image", a typed path, "unsaved changes".
    fn windows(&mut self, ctx: &egui::Context) {
        // Escape closes one window a frame, the dialogs before Help ("unsaved changes" answers
        // it itself); not while a field has focus, which Escape leaves first.
        if !self.dialogs.asking_unsaved()
            && ctx.memory(|m| m.focused().is_none())
            && ctx.input(|i| i.key_pressed(egui::Key::Escape))
            && !self.dialogs.close_on_escape()
        {
            self.layout.help = crate::help::HelpWindow::None;
        }
        crate::help::window(ctx, &mut self.layout.help);
        self.export_window(ctx);
        if let Some((purpose, path, then_open)) = self.dialogs.path_window(ctx) {
            match purpose {
                PathPurpose::OpenScene => self.request_open(&path.display().to_string()),
                PathPurpose::SaveSceneAs => self.save_then_open(&path, then_open),
            }
        }
        if let Some((answer, target)) = self.dialogs.unsaved_window(ctx, &self.doc.name) {
            self.apply_unsaved(answer, target);
        }
    }

    fn apply_view_action(&mut self, action: ViewAction) {
        let floor = camera_control::floor_height(&self.doc.desc);
        let camera = &mut self.doc.desc.camera;
        match action {
            ViewAction::Orbit(d, width) => camera_control::orbit(camera, d.x, d.y, width, floor),
            ViewAction::Pan(d, h) => camera_control::pan(camera, d.x, d.y, h),
            ViewAction::Zoom(s) => camera_control::zoom(camera, s),
            ViewAction::Pick(x, y) => return self.pick(x, y),
            ViewAction::Probe(x, y) => {
                self.select_at(x, y);
                return self.probe_at(x, y);
            }
            ViewAction::Pause(p) => {
                self.renders.paused = p;
                return;
            }
            // A file's `indirect = false` stays under Whitted (warned of, changing nothing there),
            // so that switching back to paths keeps it.
            ViewAction::Integrator(i) => self.doc.desc.render.integrator = i,
        }
        self.doc.edited();
    }

    /// Ctrl+Z, Ctrl+Shift+Z and Ctrl+Y, unless a field being typed into takes them for its text.
    fn undo_shortcuts(&mut self, ctx: &egui::Context) {
        use egui::{Key, KeyboardShortcut, Modifiers};
        if ctx.text_edit_focused() {
            return;
        }
        // Shift+Z before Z: egui's match ignores an extra Shift.
        let (redo, undo) = ctx.input_mut(|i| {
            let redo = i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z))
                || i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::Y));
            (redo, i.consume_shortcut(&KeyboardShortcut::new(Modifiers::COMMAND, Key::Z)))
        });
        if redo || undo {
            self.step_history(redo);
        }
    }

    /// Undo (or redo) a step, with what the view forces on the scene given back with it.
    pub(super) fn step_history(&mut self, redo: bool) {
        let gi = self.layout.mode == ViewMode::WhittedVsGi;
        let view = |d: &mut Document| {
            if gi && d.desc.render.integrator.is_whitted() {
                d.desc.render.integrator = glint_scene::Integrator::Path;
            }
        };
        if redo {
            self.edits.redo(&mut self.doc, view);
        } else {
            self.edits.undo(&mut self.doc, view);
        }
    }

    fn export_window(&mut self, ctx: &egui::Context) {
        let (chosen, failed) = self.dialogs.export_window(ctx, &self.doc.name);
        if let Some(why) = failed {
            self.message = Some(why);
        }
        let Some((path, view)) = chosen else { return };
        match self.save_image(&path, view) {
            Ok(()) => {
                self.message = Some(format!("Saved {}", path.display()));
                self.dialogs.close_export();
            }
            Err(e) => self.message = Some(e.to_string()),
        }
    }

    fn central(&mut self, ui: &mut Ui) -> Vec<ViewAction> {
        let textures = self.renders.textures(&self.doc);
        let textures = if self.doc.is_valid() { textures } else { textures.held() };
        let size = (self.doc.desc.render.width.max(1), self.doc.desc.render.height.max(1));
        let gizmos = if self.doc.is_valid() {
            let camera = FlatScene::world_camera(&self.doc.desc, &self.doc.desc.render);
            gizmos(&self.doc.desc, &camera, self.selection.light)
        } else {
            Vec::new()
        };
        let probed = self.renders.probe.as_ref().map(|p| (p.x, p.y));
        let tree = self.ray_tree_segments();
        // The outline of the revision shown (never of another camera): where a render's first
        // hits are jittered (paths, or Whitted's several samples), each pixel's centre traced
        // on the CPU; else the GPU's first hits when read back, else the CPU's.
        let rev = self.doc.render_revision;
        let render = &self.doc.desc.render;
        let jittered = render.integrator == glint_scene::Integrator::Path || render.spp > 1;
        let source = match (jittered, self.renders.gpu_of(rev), self.renders.cpu_of(rev)) {
            (true, _, _) => self.doc.is_valid().then_some(Hits::Centres),
            (false, Some(_), _) => Some(Hits::Gpu),
            (false, None, Some(_)) => Some(Hits::Cpu),
            (false, None, None) => None,
        };
        let (doc, renders) = (&self.doc, &self.renders);
        let hits = |source| match source {
            Hits::Centres => doc.flat(false).and_then(|f| {
                let hits = glint_core::centre_hits(&f).inspect_err(|e| log::error!("outline: {e}")).ok()?;
                Some((f.header.width, Cow::Owned(hits)))
            }),
            Hits::Gpu => renders.gpu_of(rev).map(|g| (g.image.width, Cow::Borrowed(&g.image.first_hit[..]))),
            Hits::Cpu => renders.cpu_of(rev).map(|c| (c.image.width, Cow::Borrowed(&c.image.first_hit[..]))),
        };
        let name = self.selection.object.map(|i| self.doc.object_label(i));
        // Centres move only with the objects, the camera or the size: not found again on
        // every revision of a value dragged (each built the scene and traced every pixel on
        // this thread).
        let of = if source == Some(Hits::Centres) { self.doc.hits_revision } else { rev };
        let segments = self.selection.outline(of, source, hits);
        let selected = name.as_deref().map(|n| (n, segments));
        let integrator = self.doc.desc.render.integrator;
        self.layout.central(
            ui,
            self.renders.gpu.is_some(),
            textures,
            size,
            &gizmos,
            probed,
            selected,
            &tree,
            integrator,
            self.renders.paused,
        )
    }

    /// The probed pixel's CPU ray tree as segments seen through the current camera; none
    /// while the probe is of another revision (another camera, perhaps).
    fn ray_tree_segments(&self) -> Vec<ray_tree_view::TreeSegment> {
        let Some(p) = self.renders.probe.as_ref().filter(|p| p.revision == self.doc.revision) else {
            return Vec::new();
        };
        if !self.doc.is_valid() {
            return Vec::new();
        }
        let camera = FlatScene::world_camera(&self.doc.desc, &self.doc.desc.render);
        let reach = 2.0 * self.doc.desc.camera.framing_distance();
        ray_tree_view::segments(&p.cpu_tree, &camera, reach)
    }
}

impl eframe::App for ViewerApp {
    /// The background the transparent panels (`unfill_panels`, in `new`) let through.
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        crate::background::background(visuals).to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        let start = Instant::now();
        let ctx = ui.ctx().clone();
        self.hold_close_for_unsaved_edits(&ctx);
        self.answer_signal();
        self.renders.poll(&ctx);
        self.dialogs.take_dropped_file(&ctx);
        if let Some(p) = self.dialogs.pending_open.take() {
            self.request_open(&p.display().to_string());
        }
        self.dialogs.export_shortcut(&ctx, &self.doc.name, self.layout.mode == ViewMode::WhittedVsGi);

        self.undo_shortcuts(&ctx);
        let menu = egui::Panel::top("menu")
            .show(ui, |ui| menu::bar(ui, &self.doc, &self.recent, &self.edits, &mut self.layout));
        if let Some(action) = menu.inner {
            self.apply_menu_action(action);
        }
        self.layout.status_rect = egui::Panel::bottom("status")
            .show(ui, |ui| {
                if panels::messages::ui(ui, self.renders.messages(), self.message.as_deref()) {
                    self.message = None;
                }
                let mut status = self.renders.status(self.doc.render_revision, self.doc.opened, self.clock.ui_ms);
                status.held = !self.doc.is_valid();
                let r = &self.doc.desc.render;
                if r.integrator == glint_scene::Integrator::Path {
                    status.samples = Some(self.renders.samples(self.doc.render_revision, r.spp));
                }
                panels::status::ui(ui, &status);
            })
            .response
            .rect;
        self.record_comparison();
        if ctx.input(|i| i.key_pressed(egui::Key::F9)) {
            self.layout.show_side_panel = !self.layout.show_side_panel;
        }
        self.layout.side_rect = egui::Rect::NOTHING;
        if self.layout.show_side_panel {
            // Resizable, never so wide that the images get less than VIEW_MIN_WIDTH.
            let widest = (ui.available_width() - VIEW_MIN_WIDTH).max(SIDE_PANEL_MIN);
            let mut panel = egui::Panel::left("panels")
                .default_size(SIDE_PANEL_DEFAULT.min(widest))
                .size_range(SIDE_PANEL_MIN..=widest)
                .resizable(true);
            // Clamped by a narrower window before, and there is room again: back to the width
            // the user left it at.
            let wanted = self.layout.panel_wanted.min(widest);
            let restoring = self.layout.panel_drawn.is_some_and(|drawn| drawn + 0.5 < wanted);
            if restoring {
                panel = panel.exact_size(wanted);
            }
            let side = panel.show(ui, |ui| {
                let inputs = panels::SideInputs {
                    probed: self.renders.probe.as_ref(),
                    compared: self.renders.comparison_of(self.doc.render_revision),
                    history: &self.history,
                    axis: &mut self.error_axis,
                    fitter: &mut self.fitter,
                    paths_held: self.layout.mode == ViewMode::WhittedVsGi,
                };
                // Scoped by the scene opened: what a field keeps of its last edit (a refused
                // value's note) is of that scene's field, not the next one's (a viewer tester
                // saw a refusal under a freshly opened scene's valid value).
                let (tab, doc, selection) = (&mut self.layout.tab, &mut self.doc, &mut self.selection);
                ui.push_id(("opened", doc.opened), |ui| panels::side(ui, tab, doc, selection, inputs)).inner
            });
            self.layout.side_rect = side.response.rect;
            let drawn = side.response.rect.width();
            // Narrower than the window allows is the user's choice; at the window's limit it is
            // the user's only where wider than before (a clamp only narrows it).
            if !restoring && (drawn + 0.5 < widest || drawn > self.layout.panel_wanted) {
                self.layout.panel_wanted = drawn;
            }
            self.layout.panel_drawn = Some(drawn);
            if let Some((x, y)) = side.inner {
                self.probe_at(x, y);
            }
        }
        // No fill: the view's background is the window's clear colour (crate::background).
        let actions = egui::CentralPanel::default().show(ui, |ui| self.central(ui)).inner;
        for action in actions {
            self.apply_view_action(action);
        }
        self.windows(&ctx);
        if std::mem::take(&mut self.close_pending) {
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
        }

        // Whitted vs GI needs the paths, however it was chosen (the toolbar, the View menu,
        // `--view`): a Whitted scene there showed Whitted's image on both sides. As the
        // toolbar's Paths does.
        if self.layout.mode == ViewMode::WhittedVsGi && self.doc.desc.render.integrator.is_whitted() {
            self.apply_view_action(ViewAction::Integrator(glint_scene::Integrator::Path));
        }
        // After every edit of the frame: a drag, or a value being typed, is one step when done.
        let still = !ctx.input(|i| i.pointer.any_down()) && !ctx.text_edit_focused();
        self.edits.track(&self.doc, ctx.input(|i| i.time), still);
        let gpu_renders = self.renders.gpu_renders();
        let settled = self.is_settled();
        let automated_drag = self.automation.drive(&mut self.doc, gpu_renders, settled);
        let interacting = automated_drag || ctx.dragged_id().is_some();
        self.renders.schedule(&self.doc, interacting);
        if self.layout.mode == ViewMode::WhittedVsGi && !interacting {
            self.renders.schedule_gi(&self.doc);
        }
        let metadata = self.window_metadata();
        let cpu_running = self.renders.cpu.is_running();
        let gpu_samples = self.renders.samples(self.doc.render_revision, self.doc.desc.render.spp).gpu;
        let frame = Frame { settled: self.is_settled(), cpu_running, gpu_renders, gpu_samples, metadata: &metadata };
        self.automation.step(&ctx, &frame);
        if self.renders.needs_polling() || automated_drag || self.automation.paints_every_frame() {
            // A readback is polled, not signalled, and a drag paints every frame.
            ctx.request_repaint_after(Duration::from_millis(4));
        } else if self.renders.is_busy() || self.automation.active() {
            // Workers wake the UI when they finish; this only refreshes progress labels. A
            // frame every few milliseconds would, on a CPU adapter, take the cores the
            // renders need (a frame of this window costs about 25 ms of CPU there).
            ctx.request_repaint_after(Duration::from_millis(250));
        }
        if let Some(interval) = self.clock.end_frame(start) {
            self.automation.record_frame(interval, self.clock.ui_ms);
        }
    }
}
