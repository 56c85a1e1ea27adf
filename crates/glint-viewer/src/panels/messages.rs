//! The messages above the status bar: why there is no GPU, render errors and warnings, and the
//! last message of the app (loading, saving).

use egui::Ui;

/// What the renders have to say, gathered by the app (`Renders::messages`).
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderMessages<'a> {
    pub no_gpu_reason: Option<&'a str>,
    pub gpu_error: Option<&'a str>,
    pub gpu_warning: Option<&'a str>,
    pub cpu_error: Option<&'a str>,
}

/// Shows the messages; returns whether the app's message was dismissed (it stays until then,
/// or until the next load or save says something else).
pub fn ui(ui: &mut Ui, renders: RenderMessages<'_>, message: Option<&str>) -> bool {
    let warn = ui.visuals().warn_fg_color;
    let err = ui.visuals().error_fg_color;
    if let Some(r) = renders.no_gpu_reason {
        ui.colored_label(warn, format!("No GPU: {r}. Showing the CPU reference only."));
    }
    if let Some(e) = renders.gpu_error {
        ui.colored_label(err, format!("GPU: {e}"));
    }
    if let Some(w) = renders.gpu_warning {
        ui.colored_label(warn, format!("GPU: {w}"));
    }
    if let Some(e) = renders.cpu_error {
        ui.colored_label(err, format!("CPU: {e}"));
    }
    let mut dismissed = false;
    if let Some(m) = message {
        ui.horizontal_wrapped(|ui| {
            dismissed = ui.small_button("Dismiss").clicked();
            ui.label(m);
        });
    }
    dismissed
}
