//! The side panels: each edits one part of the document and says whether it changed it.
//! Validation's messages stand at the panel's foot under every tab.

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
    /// The Whitted vs GI view is shown: the integrator stays Paths.
    pub paths_held: bool,
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
    // Validation's messages in a strip at the panel's foot, seen whatever the tab's length and
    // scroll (below a long tab they went unseen), and apart from the tab's controls: the tab
    // keeps its top, so a message that goes as its value is fixed moves nothing under the
    // pointer (above the tab, the controls jumped as it went). The tab takes the height the
    // strip left last frame.
    let strip_id = ui.scope_id().with("side panel messages height");
    let strip = if issues::any(doc) { ui.ctx().data(|d| d.get_temp::<f32>(strip_id)).unwrap_or(0.0) } else { 0.0 };
    let total = ui.available_height();
    // Vertical only, one scroll position per tab: every tab is laid out to the panel's width
    // (rows wrap, grids have two columns), so nothing hides sideways or under a horizontal bar.
    egui::ScrollArea::vertical()
        .id_salt(("side panel", *tab))
        .auto_shrink([false, false])
        .max_height((total - strip).max(MIN_TAB_HEIGHT))
        .show(ui, |ui| {
            let changed = match tab {
                Tab::Scene => scene::ui(ui, doc, inputs.fitter, inputs.paths_held),
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
    let height = if issues::any(doc) {
        let shown = *tab;
        let top = ui.cursor().top();
        ui.separator();
        let drawn = egui::ScrollArea::vertical()
            .id_salt("side panel messages")
            .max_height(MESSAGES_MAX_SHARE * total)
            .auto_shrink([false, true])
            .show(ui, |ui| issues::ui(ui, doc, tab, selection));
        if *tab != shown {
            ui.ctx().request_repaint();
        }
        // What the strip wants, not what was left for it: the separator and its messages, at
        // most its share.
        let separator = drawn.inner_rect.top() - top;
        separator + drawn.content_size.y.min(MESSAGES_MAX_SHARE * total)
    } else {
        0.0
    };
    if (height - strip).abs() > 0.5 {
        ui.ctx().data_mut(|d| d.insert_temp(strip_id, height));
        ui.ctx().request_repaint();
    }
    probe
}

/// The most of the side panel's height the messages take; beyond it they scroll.
const MESSAGES_MAX_SHARE: f32 = 0.4;

/// The least height the tab keeps beside the messages.
const MIN_TAB_HEIGHT: f32 = 120.0;
