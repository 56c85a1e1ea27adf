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
            // A parse error quotes the file with a caret under the fault, which lines up only
            // in a fixed-width font (under `shinyness` it pointed at the line's start; a lecturer).
            if quotes_source(m) {
                ui.label(egui::RichText::new(m).monospace());
            } else {
                ui.label(m);
            }
        });
    }
    dismissed
}

/// Whether `message` quotes a source line with a gutter: a numbered line ("9 | shinyness = 20.0")
/// and a bare one ("  | ^^^^^^^^^"), as the TOML reader's errors write them.
fn quotes_source(message: &str) -> bool {
    let gutter = |line: &str| line.split_once('|').map(|(before, _)| before.trim().to_string());
    let numbered = message.lines().any(|l| gutter(l).is_some_and(|g| !g.is_empty() && g.parse::<u32>().is_ok()));
    let bare = message.lines().any(|l| gutter(l).is_some_and(|g| g.is_empty()));
    numbered && bare
}

#[cfg(test)]
mod tests {
    use super::quotes_source;

    #[test]
    fn a_parse_error_with_a_source_excerpt_is_told_from_a_plain_message() {
        let toml = "broken.toml: TOML parse error at line 9, column 1\n  |\n9 | shinyness = 20.0\n  | ^^^^^^^^^\nunknown field";
        assert!(quotes_source(toml));
        assert!(!quotes_source("saved cpu.png"));
        assert!(!quotes_source("kr | kt: a table, not a source line"));
    }
}
