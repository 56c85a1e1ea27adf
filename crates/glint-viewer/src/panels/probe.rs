//! Pixel probe panel: CPU and GPU breakdowns side by side, the first difference highlighted.

use egui::{Color32, RichText, Ui};
use glint_core::glam::DVec3;
use glint_core::layout::NO_HIT;

use crate::document::Document;
use crate::probe::{GpuProbe, ProbeState, Term, first_difference, terms};

fn fmt(v: DVec3) -> String {
    if v.x == v.y && v.y == v.z { format!("{:.6}", v.x) } else { format!("{:.6} {:.6} {:.6}", v.x, v.y, v.z) }
}

/// Width of `text` in the table's monospace font.
fn text_width(ui: &Ui, text: &str) -> f32 {
    let font = egui::TextStyle::Monospace.resolve(ui.style());
    ui.ctx().fonts_mut(|f| f.layout_no_wrap(text.to_string(), font, Color32::WHITE).size().x)
}

/// `v` on one line when that fits `width` points, else one component a line: a vector such
/// as N (three signed components) is wider than the value column of a default-width panel.
fn fmt_fitting(ui: &Ui, v: DVec3, width: f32) -> String {
    let one = fmt(v);
    if text_width(ui, &one) <= width { one } else { one.replace(' ', "\n") }
}

pub fn ui(ui: &mut Ui, probe: Option<&ProbeState>, doc: &Document) {
    let Some(p) = probe else {
        ui.weak("Ctrl+click a pixel to see its radiance split into the terms of the model.");
        return;
    };
    let hit = |id: u32| {
        if id == NO_HIT { "background".to_string() } else { doc.object_label(id as usize) }
    };
    ui.label(format!("Pixel ({}, {}) — hit: {}", p.x, p.y, hit(p.cpu.object_id)));
    let spp = doc.desc.render.spp;
    if spp > 1 {
        // Both tracers probe the same jittered sample; the pixel shown is the mean of all.
        ui.weak(format!("Sample 0 of {spp}: the pixel shown is the mean of {spp} samples."));
    }
    let gpu = p.gpu_breakdown();
    match &p.gpu {
        GpuProbe::Pending(_) => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("GPU probe running…");
            });
        }
        GpuProbe::Done(Err(e)) | GpuProbe::Unavailable(e) => {
            ui.colored_label(ui.visuals().warn_fg_color, format!("GPU probe: {e}"));
        }
        GpuProbe::Done(Ok(g)) if g.object_id != p.cpu.object_id => {
            ui.colored_label(ui.visuals().error_fg_color, format!("GPU hit: {}", hit(g.object_id)));
        }
        GpuProbe::Done(Ok(_)) => {}
    }
    let rows = terms(&p.cpu, gpu);
    let first = first_difference(&rows);
    term_grid(ui, "probe terms", &rows, first);
    let sum = p.cpu.sum_of_terms();
    ui.label(format!("CPU: sum of terms − I = {:.2e}", (sum - p.cpu.total).abs().max_element()));
    if let Some(g) = gpu {
        ui.label(format!("GPU: sum of terms − I = {:.2e}", (g.sum_of_terms() - g.total).abs().max_element()));
    }
    match first {
        Some(i) => {
            ui.colored_label(
                Color32::from_rgb(255, 120, 90),
                format!("First difference beyond tolerance: {}", rows[i].name),
            );
        }
        None if gpu.is_some() => {
            ui.label("CPU and GPU agree on every term within tolerance.");
        }
        None => {}
    }
    super::ray_tree::ui(ui, p, doc);
}

/// The colour of a highlighted (first differing) row or node.
pub const HIGHLIGHT: Color32 = Color32::from_rgb(255, 120, 90);

/// `rows` as a striped grid, one row per term with CPU above GPU (narrow enough for the side
/// panel), row `first` highlighted.
pub fn term_grid(ui: &mut Ui, id: impl std::hash::Hash + std::fmt::Debug, rows: &[Term], first: Option<usize>) {
    // What the value column gets of the panel: the rest after the widest term name.
    let names = rows.iter().map(|t| text_width(ui, &t.name)).fold(text_width(ui, "term"), f32::max);
    let value_width = ui.available_width() - names - ui.spacing().item_spacing.x;
    egui::Grid::new(id).striped(true).num_columns(2).show(ui, |ui| {
        ui.strong("term");
        ui.strong("CPU (f64) / GPU (f32)");
        ui.end_row();
        for (i, t) in rows.iter().enumerate() {
            let highlight = Some(i) == first;
            let text = |s: String| {
                let r = RichText::new(s).monospace();
                if highlight { r.color(HIGHLIGHT).strong() } else { r }
            };
            ui.add(egui::Label::new(text(t.name.clone())).extend());
            ui.vertical(|ui| {
                // Six decimals in the table; the exact values (shortest round-trip form) on hover.
                // Never wrapped by egui (which would break inside a number): a vector too wide for
                // the column is laid out one component a line instead.
                let fitting = |v: DVec3| fmt_fitting(ui, v, value_width);
                let cpu = fitting(t.cpu);
                let gpu = t.gpu.map(fitting).unwrap_or_else(|| "—".into());
                ui.add(egui::Label::new(text(cpu)).extend()).on_hover_text(format!("CPU: {:?}", t.cpu.to_array()));
                let gpu = ui.add(egui::Label::new(text(gpu)).extend());
                if let Some(g) = t.gpu {
                    gpu.on_hover_text(format!("GPU: {:?}", g.to_array().map(|v| v as f32)));
                }
            });
            ui.end_row();
        }
    });
}
