//! Every character the viewer draws is in its fonts: a missing glyph shows as a box.

use egui::epaint::Shape;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_viewer::ViewerApp;

use super::support::viewer;

/// Each drawn text's characters the fonts lack, with the text they are in.
fn missing_glyphs(h: &Harness<'static, ViewerApp>) -> Vec<(char, String)> {
    let mut missing = Vec::new();
    for clipped in &h.output().shapes {
        let Shape::Text(t) = &clipped.shape else { continue };
        for section in &t.galley.job.sections {
            let text = &t.galley.job.text[section.byte_range.start.0..section.byte_range.end.0];
            for c in text.chars().filter(|c| !c.is_whitespace()) {
                if !h.ctx.fonts_mut(|f| f.has_glyph(&section.format.font_id, c)) {
                    missing.push((c, text.to_string()));
                }
            }
        }
    }
    missing
}

#[test]
fn the_colour_picker_draws_only_glyphs_the_fonts_have() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.get_by_label("Scene").click();
    h.run_steps(2);
    h.query_all_by_label("Color").next().expect("a colour button on the Scene tab").click();
    h.run_steps(3);
    // The picker is open: its copy button (egui's, labelled with an emoji) is shown.
    assert!(h.query_by_label("📋").is_some(), "the colour picker did not open");
    let missing = missing_glyphs(&h);
    assert!(missing.is_empty(), "characters without a glyph: {missing:?}");
}
