//! The messages above the status bar: why there is no GPU, render errors and warnings, and the
//! last message of the app (loading, saving).

use egui::Ui;

use crate::renders::Renders;

pub fn ui(ui: &mut Ui, renders: &Renders, message: Option<&str>) {
    let warn = ui.visuals().warn_fg_color;
    let err = ui.visuals().error_fg_color;
    if let Some(r) = &renders.no_gpu_reason {
        ui.colored_label(warn, format!("No GPU: {r}. Showing the CPU reference only."));
    }
    if let Some(g) = &renders.gpu {
        if let Some(e) = &g.error {
            ui.colored_label(err, format!("GPU: {e}"));
        }
        if let Some(w) = &g.warning {
            ui.colored_label(warn, format!("GPU: {w}"));
        }
    }
    if let Some(e) = &renders.cpu.error {
        ui.colored_label(err, format!("CPU: {e}"));
    }
    if let Some(m) = message {
        ui.label(m);
    }
}
