//! The side panels: each edits one part of the document and says whether it changed it.
//! Validation's messages head every tab.

pub mod errors;
pub mod issues;
pub mod lights;
pub mod materials;
pub mod messages;
pub mod probe;
pub mod ray_tree;
pub mod scene;
pub mod status;
pub mod term_table;

use egui::Ui;

use crate::ambient_fit::AmbientFitter;
use crate::comparison::Compared;
use crate::document::Document;
use crate::error_history::{Axis, ErrorHistory};
use crate::layout::Tab;
use crate::probe::ProbeState;
use crate::selection::Selection;

/// What the side panel reads besides the document: the probe's result, the comparison of
/// the current revision and the error history with its plot axis.
pub struct SideInputs<'a> {
    pub probed: Option<&'a ProbeState>,
    pub compared: Option<&'a Compared>,
    pub history: &'a ErrorHistory,
    pub axis: &'a mut Axis,
    /// The Scene panel's Fit ambient job.
    pub fitter: &'a mut AmbientFitter,
}

/// The side panel: the tabs, the panel of the current one, and the document's validation
/// problems. Records an edit in the document when a panel made one; returns a pixel to probe
/// (the Errors panel's "Go to worst pixel").
pub fn side(
    ui: &mut Ui,
    tab: &mut Tab,
    doc: &mut Document,
    selection: &mut Selection,
    inputs: SideInputs<'_>,
) -> Option<(u32, u32)> {
    ui.horizontal_wrapped(|ui| {
        ui.selectable_value(tab, Tab::Scene, "Scene");
        ui.selectable_value(tab, Tab::Lights, "Lights");
        ui.selectable_value(tab, Tab::Materials, "Materials");
        ui.selectable_value(tab, Tab::Probe, "Probe");
        ui.selectable_value(tab, Tab::Errors, "Errors");
    });
    ui.separator();
    let mut probe = None;
    // Vertical only, one scroll position per tab: every tab is laid out to the panel's width
    // (rows wrap, grids have two columns), so nothing hides sideways or under a horizontal bar.
    egui::ScrollArea::vertical().id_salt(("side panel", *tab)).auto_shrink([false, false]).show(ui, |ui| {
        // First, where the default window shows them: below a long tab they went unseen.
        let shown = *tab;
        issues::ui(ui, doc, tab, selection);
        if *tab != shown {
            return;
        }
        let changed = match tab {
            Tab::Scene => scene::ui(ui, doc, inputs.fitter),
            Tab::Lights => lights::ui(ui, doc, &mut selection.light),
            Tab::Materials => materials::ui(ui, doc, selection.object, &mut selection.material),
            Tab::Probe => {
                probe::ui(ui, inputs.probed, doc);
                false
            }
            Tab::Errors => {
                probe = errors::ui(ui, inputs.compared, inputs.history, inputs.axis, &doc.desc.render);
                false
            }
        };
        if changed {
            doc.edited();
        }
    });
    probe
}
