//! The side panels: each edits one part of the document and says whether it changed it.

pub mod lights;
pub mod materials;
pub mod messages;
pub mod probe;
pub mod scene;
pub mod status;

use egui::Ui;

use crate::document::Document;
use crate::layout::Tab;
use crate::probe::ProbeState;
use crate::selection::Selection;

/// The side panel: the tabs, the panel of the current one, and the document's validation
/// problems. Records an edit in the document when a panel made one.
pub fn side(ui: &mut Ui, tab: &mut Tab, doc: &mut Document, selection: &mut Selection, probed: Option<&ProbeState>) {
    ui.horizontal(|ui| {
        ui.selectable_value(tab, Tab::Scene, "Scene");
        ui.selectable_value(tab, Tab::Lights, "Lights");
        ui.selectable_value(tab, Tab::Materials, "Materials");
        ui.selectable_value(tab, Tab::Probe, "Probe");
    });
    ui.separator();
    // Both directions: a wide probe table scrolls instead of widening the panel.
    egui::ScrollArea::both().show(ui, |ui| {
        let changed = match tab {
            Tab::Scene => scene::ui(ui, doc),
            Tab::Lights => lights::ui(ui, doc, &mut selection.light),
            Tab::Materials => materials::ui(ui, doc, selection.object, &mut selection.material),
            Tab::Probe => {
                probe::ui(ui, probed, doc);
                false
            }
        };
        if changed {
            doc.edited();
        }
        if !doc.issues.is_empty() {
            ui.separator();
            ui.colored_label(ui.visuals().error_fg_color, "Invalid values (the last valid render stays on screen):");
            for i in &doc.issues {
                ui.colored_label(ui.visuals().error_fg_color, i.to_string());
            }
        }
    });
}
