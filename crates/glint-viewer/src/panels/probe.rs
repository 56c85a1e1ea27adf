//! Pixel probe panel: each term of the model at a pixel, CPU (f64), GPU (f32) and their
//! difference by channel, the first difference highlighted.

use egui::Ui;
use glint_types::layout::NO_HIT;

use glint_core::glam::DVec3;
use glint_core::path_kinds::PathProbe;
use glint_scene::PathKind;

use super::term_table::{HIGHLIGHT, cell, term_grid};
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
    // With paths, their light first: what Whitted's terms below leave out.
    if let Some(paths) = &p.paths {
        path_split(ui, paths);
        ui.separator();
        ui.strong("Whitted's terms at this pixel");
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
        GpuProbe::Done(Ok(g)) if let Some(lobe) = glint_core::probe_terms::lobe_difference(&p.cpu, g) => {
            ui.colored_label(ui.visuals().error_fg_color, format!("Specular lobe differs: {lobe}"));
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

/// The pixel's path-traced radiance by bounce (rows) and kind of light (columns), as the mean
/// of R, G and B, with each kind's total: what the terms above, Whitted's, leave out.
fn path_split(ui: &mut Ui, p: &PathProbe) {
    // Its own CPU samples, not the images' means (the Whitted − GI readout is the GPU's mean).
    let samples = if p.spp == 1 { "1 sample".to_string() } else { format!("{} samples", p.spp) };
    ui.strong(format!("Paths: the pixel's light by bounce and kind (the CPU's {samples} of this pixel)"));
    ui.weak("Mean of R, G, B. Bounce 0 is the first hit; Whitted's terms below are its direct light and ambient.");
    let mean = |v: DVec3| v.element_sum() / 3.0;
    egui::Grid::new("path split").striped(true).show(ui, |ui| {
        ui.label("bounce");
        for k in PathKind::ALL {
            ui.label(k.name());
        }
        ui.end_row();
        for (depth, row) in p.by_bounce.iter().enumerate() {
            if row.iter().all(|v| *v == DVec3::ZERO) {
                continue;
            }
            ui.label(depth.to_string());
            for v in row {
                ui.label(cell(mean(*v)));
            }
            ui.end_row();
        }
        ui.strong("sum");
        for v in p.by_kind() {
            ui.strong(cell(mean(v)));
        }
        ui.end_row();
    });
    let total = p.total();
    ui.label(format!(
        "The paths' pixel: {} (R {}, G {}, B {})",
        cell(mean(total)),
        cell(total.x),
        cell(total.y),
        cell(total.z)
    ));
}
