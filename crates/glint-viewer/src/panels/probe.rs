//! Pixel probe panel: each term of the model at a pixel, CPU (f64), GPU (f32) and their
//! difference by channel, the first difference highlighted.

use egui::Ui;
use glint_types::layout::NO_HIT;

use super::term_table::{HIGHLIGHT, term_grid};
use crate::document::Document;
use crate::probe::{GpuProbe, ProbeState, first_difference, terms};

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
            ui.colored_label(HIGHLIGHT, format!("First difference beyond tolerance: {}", rows[i].name));
        }
        None if gpu.is_some() => {
            ui.label("CPU and GPU agree on every term within tolerance.");
        }
        None => {}
    }
    super::ray_tree::ui(ui, p, doc);
}
