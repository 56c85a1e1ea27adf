//! What the window shows and where: the view mode, the side panel's tab, the wipe, the light
//! gizmos, and where the images and the status bar were drawn last frame.

use egui::Ui;

use crate::gizmos::Gizmo;
use crate::outline::Segment;
use crate::ray_tree_view::TreeSegment;
use crate::view::{self, GiView, Textures, ViewAction, ViewMode};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Tab {
    Scene,
    Lights,
    Materials,
    Probe,
    Errors,
}

#[derive(Debug)]
pub struct Layout {
    pub mode: ViewMode,
    /// How Whitted vs GI holds the two images against each other.
    pub gi_view: GiView,
    pub tab: Tab,
    /// Where the split wipe divides GPU from CPU, in [0, 1] of the image width.
    pub wipe: f32,
    pub show_gizmos: bool,
    /// The probed pixel's ray tree drawn over the images (View → Ray tree overlay).
    pub show_ray_tree: bool,
    /// The side panel with the tabs; hidden, the images get the whole window (F9 toggles).
    pub show_side_panel: bool,
    /// Where the images were drawn last frame (screen points), for mapping pixels to clicks.
    pub view_rects: Vec<egui::Rect>,
    /// Where the status bar was drawn (its timings change from run to run).
    pub status_rect: egui::Rect,
    /// Where the side panel was drawn (nothing when hidden), for checking what fits in it.
    pub side_rect: egui::Rect,
    /// The side panel's width as the user left it, and as it was last drawn: a narrower window
    /// clamps the panel, and a wider one gives that width back (it stayed at 220).
    pub panel_wanted: f32,
    pub panel_drawn: Option<f32>,
    /// The Help window open (Help menu).
    pub help: crate::help::HelpWindow,
}

/// The side panel's default width, and the width it always leaves to the images: at
/// 1024×768 the panel takes 29 % of the window by default and at most what leaves 480 points.
pub const SIDE_PANEL_DEFAULT: f32 = 300.0;
pub const SIDE_PANEL_MIN: f32 = 220.0;
pub const VIEW_MIN_WIDTH: f32 = 480.0;

impl Layout {
    pub fn new(mode: ViewMode) -> Self {
        Self {
            mode,
            gi_view: GiView::SideBySide,
            tab: Tab::Scene,
            wipe: 0.5,
            show_gizmos: true,
            show_ray_tree: true,
            show_side_panel: true,
            view_rects: Vec::new(),
            status_rect: egui::Rect::NOTHING,
            side_rect: egui::Rect::NOTHING,
            panel_wanted: SIDE_PANEL_DEFAULT,
            panel_drawn: None,
            help: crate::help::HelpWindow::None,
        }
    }

    /// The central panel: the view modes (only the CPU one without a GPU) over the view of a
    /// `size` image, with the `probed` pixel marked and the `selected` object (name, outline) outlined; returns what the pointer did on it.
    pub fn central(
        &mut self,
        ui: &mut Ui,
        has_gpu: bool,
        textures: Textures<'_>,
        size: (u32, u32),
        gizmos: &[Gizmo],
        probed: Option<(u32, u32)>,
        selected: Option<(&str, &[Segment])>,
        tree: &[TreeSegment],
        integrator: glint_scene::Integrator,
        paused: bool,
    ) -> Vec<ViewAction> {
        let mut chosen = integrator;
        let mut pause = paused;
        // Wrapped: in a narrow window the integrator switch goes to a second row, not off screen.
        // A button moves whole to the next row (`keep_whole`).
        ui.horizontal_wrapped(|ui| {
            for m in ViewMode::ALL {
                keep_whole(ui, m.label());
                let enabled = has_gpu || m == ViewMode::Cpu;
                ui.add_enabled_ui(enabled, |ui| ui.selectable_value(&mut self.mode, m, m.label()));
            }
            ui.separator();
            // What both tracers compute, as the Scene panel's Integrator choice. Whitted vs GI
            // holds the paths: "Whitted" there made both sides Whitted's image (a lecturer).
            let paths_held = self.mode == ViewMode::WhittedVsGi;
            for (i, label) in [(glint_scene::Integrator::Whitted, "Whitted"), (glint_scene::Integrator::Path, "Paths")]
            {
                keep_whole(ui, label);
                let enabled = !(paths_held && i.is_whitted());
                let button = ui.add_enabled_ui(enabled, |ui| ui.selectable_value(&mut chosen, i, label)).inner;
                crate::help::hint(button, "Integrator").on_disabled_hover_text(crate::whitted_vs_gi::PATHS_HELD);
            }
            if integrator == glint_scene::Integrator::Path {
                let label = if paused { "Continue" } else { "Pause" };
                keep_whole(ui, label);
                let tip = if paused {
                    "Go on adding path samples to the GPU image"
                } else {
                    "Stop adding path samples to the GPU image (an edit still renders)"
                };
                if ui.button(label).on_hover_text(tip).clicked() {
                    pause = !paused;
                }
            }
            if self.mode == ViewMode::WhittedVsGi {
                ui.separator();
                for v in GiView::ALL {
                    keep_whole(ui, v.label());
                    ui.selectable_value(&mut self.gi_view, v, v.label());
                }
            }
            if self.mode == ViewMode::Wipe || (self.mode == ViewMode::WhittedVsGi && self.gi_view == GiView::Wipe) {
                ui.add(egui::Slider::new(&mut self.wipe, 0.0..=1.0).show_value(false).text("Wipe"));
            }
        });
        let tree = if self.show_ray_tree { tree } else { &[] };
        let (mut actions, rects) = view::show(
            ui,
            self.mode,
            self.gi_view,
            &mut self.wipe,
            textures,
            size,
            gizmos,
            self.show_gizmos,
            probed,
            selected,
            tree,
        );
        self.view_rects = rects;
        if chosen != integrator {
            actions.push(ViewAction::Integrator(chosen));
        }
        if pause != paused {
            actions.push(ViewAction::Pause(pause));
        }
        actions
    }

    /// The screen position of the centre of pixel (x, y) of a `size` image in the first image
    /// of the view.
    pub fn screen_pos_of_pixel(&self, x: u32, y: u32, size: (u32, u32)) -> Option<egui::Pos2> {
        let r = self.view_rects.first()?;
        let (w, h) = (size.0 as f32, size.1 as f32);
        Some(r.min + egui::vec2((x as f32 + 0.5) / w * r.width(), (y as f32 + 0.5) / h * r.height()))
    }
}

/// Ends the row of a wrapped toolbar before a button labelled `text` that the rest of the row
/// cannot hold, so that the button moves whole to the next row: egui would wrap its label in
/// the room left instead ("Whitt / ed vs / GI" at 760 points wide). Not at a row's start, where
/// a new row would hold it no better.
fn keep_whole(ui: &mut Ui, text: &str) {
    let label = egui::WidgetText::from(text).into_galley(
        ui,
        Some(egui::TextWrapMode::Extend),
        f32::INFINITY,
        egui::TextStyle::Button,
    );
    // A wrapped row's available width is all of it; what is left is from the cursor on.
    let left = ui.max_rect().right() - ui.cursor().min.x;
    let at_start = ui.cursor().min.x <= ui.max_rect().left();
    if !at_start && label.size().x + 2.0 * ui.spacing().button_padding.x > left {
        ui.end_row();
    }
}
