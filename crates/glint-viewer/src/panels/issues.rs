//! The document's validation messages, at the foot of the side panel whichever tab is open:
//! each names where the viewer edits its field ("Lights › key › Casts shadows") beside the
//! scene file's name for it, with a button that opens that tab and selects the light,
//! material or object.

use egui::{Color32, Ui};
use glint_scene::FieldIssue;

use crate::document::Document;
use crate::field_place::{Focus, Place, place};
use crate::layout::Tab;
use crate::selection::Selection;

/// Whether the document has a message to show.
pub fn any(doc: &Document) -> bool {
    !doc.issues.is_empty() || !doc.warnings.is_empty() || !doc.load_warnings.is_empty()
}

pub fn ui(ui: &mut Ui, doc: &Document, tab: &mut Tab, selection: &mut Selection) {
    let mut go = None;
    if !doc.issues.is_empty() {
        let title = format!("Invalid values ({}): render held", doc.issues.len());
        let why = "The last valid render stays on screen until every value is valid.";
        go = go.or(list(ui, doc, (&title, why), ui.visuals().error_fg_color, doc.issues.iter()));
    }
    let warnings = doc.load_warnings.len() + doc.warnings.len();
    if warnings > 0 {
        let (title, why) =
            (format!("Warnings ({warnings}): rendered anyway"), "Rendered anyway, as glint render does.");
        let all = doc.load_warnings.iter().chain(&doc.warnings);
        go = go.or(list(ui, doc, (&title, why), ui.visuals().warn_fg_color, all));
    }
    if let Some(p) = go {
        show(&p, doc, tab, selection);
    }
}

/// One collapsible list, its title short and what it means on hover (egui lays a header's
/// title out on one line: a long one widened the strip past a narrow panel, and the messages
/// wrapped to that width were cut at the panel's edge; a viewer tester at 760×480); returns the
/// place whose Show was clicked.
fn list<'a>(
    ui: &mut Ui,
    doc: &Document,
    (title, why): (&str, &str),
    colour: Color32,
    issues: impl Iterator<Item = &'a FieldIssue>,
) -> Option<Place> {
    let mut clicked = None;
    let list = egui::CollapsingHeader::new(egui::RichText::new(title).color(colour))
        .id_salt(title.split(' ').next())
        .default_open(true)
        .show(ui, |ui| {
            for issue in issues {
                let p = place(&issue.field, doc);
                ui.horizontal_wrapped(|ui| {
                    if ui.small_button("Show").on_hover_text(format!("Open {}", p.text())).clicked() {
                        clicked = Some(p.clone());
                    }
                    ui.label(p.text());
                });
                ui.colored_label(colour, issue.to_string());
            }
        });
    list.header_response.on_hover_text(why);
    ui.separator();
    clicked
}

fn show(p: &Place, doc: &Document, tab: &mut Tab, selection: &mut Selection) {
    *tab = p.tab;
    match &p.focus {
        Focus::Nothing => {}
        Focus::Light(i) => selection.light = *i,
        Focus::Material(name) => selection.material = Some(name.clone()),
        Focus::Object(i) => {
            selection.object = Some(*i);
            selection.material = doc.desc.objects.get(*i).map(|o| o.material().to_string());
        }
    }
}
