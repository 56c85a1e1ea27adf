//! Glint's viewer: an eframe/egui live editor that shows the GPU tracer (on eframe's own
//! wgpu device, without a CPU round trip) beside the exact CPU reference, their difference,
//! and a per-term pixel probe.

mod accumulation;
mod ambient_fit;
mod app;
mod automation;
mod background;
mod camera_control;
mod comparison;
mod cpu_worker;
mod device;
mod dialogs;
mod document;
mod error;
mod error_history;
mod export;
mod field_place;
mod frame_clock;
mod gizmos;
mod gpu_view;
pub mod help;
mod images;
mod layout;
mod light_kind;
mod menu;
mod outline;
mod panels;
mod probe;
mod ray_tree_view;
mod recent;
mod render_inputs;
mod renders;
mod selection;
mod signal_watch;
mod undo;
mod view;
mod whitted_vs_gi;
mod widgets;
mod worker;

pub use app::{ViewerApp, ViewerOptions};
pub use automation::FEATURE_EDITS;
pub use background::{background, over_background};
pub use device::with_tracer_limits;
pub use error::ViewerError;
pub use export::ExportView;
pub use layout::Tab;
pub use panels::status::SOFTWARE_ADAPTER;
pub use panels::term_table::{BROUGHT_BACK_HINT, DELTA_HINT, cell as probe_cell};
pub use probe::{GpuProbe, first_difference, terms};
pub use ray_tree_view::LEGEND as RAY_TREE_LEGEND;
pub use view::{GiView, ViewMode, placement as view_placement};

/// Window size at start: room for the panels and two 480×270 previews side by side. Not
/// larger: on a software rasterizer (lavapipe) every frame costs time per window pixel.
pub const WINDOW_SIZE: [f32; 2] = [1200.0, 720.0];

/// The smallest window the window manager is asked to allow: the side panel at its least and the
/// images at their least beside it, with room for the toolbar's rows. At 400×300 no image was
/// shown and the view's toolbar lost its buttons; at 640×420 with the panel the view was blank.
pub const MIN_WINDOW_SIZE: [f32; 2] = [layout::SIDE_PANEL_MIN + layout::VIEW_MIN_WIDTH + 60.0, 480.0];

/// Whether a display server is reachable (X11 or Wayland; other systems always have one).
pub fn has_display() -> bool {
    if cfg!(any(target_os = "windows", target_os = "macos")) {
        return true;
    }
    ["DISPLAY", "WAYLAND_DISPLAY"].iter().any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

fn native_options(renderer: eframe::Renderer) -> eframe::NativeOptions {
    eframe::NativeOptions {
        renderer,
        viewport: egui::ViewportBuilder::default()
            .with_inner_size(WINDOW_SIZE)
            .with_min_inner_size(MIN_WINDOW_SIZE)
            .with_title("Glint viewer")
            .with_drag_and_drop(true),
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: with_tracer_limits(egui_wgpu::WgpuConfiguration::default().wgpu_setup),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Opens the viewer window and runs it until it is closed. Returns the line an automated run
/// (`--screenshot`, drag benchmark) reports.
pub fn run(options: ViewerOptions) -> Result<Option<String>, ViewerError> {
    if !has_display() {
        return Err(ViewerError::NoDisplay);
    }
    match run_with(options.clone(), eframe::Renderer::Wgpu) {
        // No event loop (no display server there, say): winit makes one per process, so an
        // OpenGL retry could only fail with "EventLoop can't be recreated" and hide the cause.
        Err(ViewerError::Window(reason)) if reason.contains("EventLoopError") => {
            Err(ViewerError::Window(with_display(&reason)))
        }
        Err(ViewerError::Window(reason)) => {
            // No usable wgpu adapter: the viewer still runs, with the CPU reference alone.
            log::warn!("wgpu window failed ({reason}); retrying with OpenGL and no GPU tracer");
            let options = ViewerOptions { no_gpu_reason: Some(reason.clone()), ..options };
            match run_with(options, eframe::Renderer::Glow) {
                // The retry cannot tell why: winit makes one event loop per process, so a
                // window that failed for want of a display fails again with "EventLoop can't be
                // recreated". The first failure is the cause.
                Err(ViewerError::Window(_)) => Err(ViewerError::Window(with_display(&reason))),
                other => other,
            }
        }
        other => other,
    }
}

/// `reason` without winit's source location, with the display it was tried on.
fn with_display(reason: &str) -> String {
    let mut reason = reason.to_string();
    if let Some(at) = reason.find("os error at ")
        && let Some(end) = reason[at..].find(": ")
    {
        reason.replace_range(at..at + end + 2, "");
    }
    let named = |v: &str| std::env::var(v).ok().filter(|s| !s.is_empty()).map(|s| format!("{v}={s}"));
    let displays: Vec<String> = ["DISPLAY", "WAYLAND_DISPLAY"].into_iter().filter_map(named).collect();
    if displays.is_empty() {
        reason
    } else {
        format!("{reason}; on {}: is a display server running there?", displays.join(", "))
    }
}

fn run_with(options: ViewerOptions, renderer: eframe::Renderer) -> Result<Option<String>, ViewerError> {
    let slot: automation::Outcome = Default::default();
    let app_slot = slot.clone();
    eframe::run_native(
        "Glint viewer",
        native_options(renderer),
        Box::new(move |cc| {
            signal_watch::start(&cc.egui_ctx);
            let app = ViewerApp::new(cc, options);
            let shared = app.automation.outcome.clone();
            // An interactive run that ends by closing the window reports nothing; an automated
            // one must have reported by then.
            if !app.automation.active() {
                *app_slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(Ok(String::new()));
            }
            Ok(Box::new(OutcomeForwarder { app, shared, slot: app_slot }))
        }),
    )
    .map_err(|e| ViewerError::Window(e.to_string()))?;
    let result = slot.lock().unwrap_or_else(|e| e.into_inner()).take();
    match result {
        Some(Ok(line)) if line.is_empty() => Ok(None),
        Some(Ok(line)) => Ok(Some(line)),
        Some(Err(e)) => Err(ViewerError::Automation(e)),
        None => Err(ViewerError::Automation("the window closed before the automated run finished".into())),
    }
}

/// Copies an automated run's outcome out of the app when the window closes.
struct OutcomeForwarder {
    app: ViewerApp,
    shared: automation::Outcome,
    slot: automation::Outcome,
}

impl eframe::App for OutcomeForwarder {
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        self.app.clear_color(visuals)
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.app.ui(ui, frame);
        if let Some(r) = self.shared.lock().unwrap_or_else(|e| e.into_inner()).clone() {
            *self.slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_window_keeps_room_for_the_panel_and_the_images() {
        let options = super::native_options(eframe::Renderer::Wgpu);
        let min = options.viewport.min_inner_size.expect("a least window size");
        assert!(min.x >= crate::layout::SIDE_PANEL_MIN + crate::layout::VIEW_MIN_WIDTH, "{min:?}");
        assert!(min.x <= super::WINDOW_SIZE[0] && min.y <= super::WINDOW_SIZE[1], "{min:?}");
    }
}
