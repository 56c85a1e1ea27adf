//! Errors panel: GPU against CPU for the current revision — the figures, a histogram of
//! |GPU − CPU| in decades split by first-hit agreement, the worst pixel (probed on request) —
//! and the live plot of error against samples, depth or GPU time from the comparisons made so far.

use egui::{Color32, Ui};
use egui_plot::{Bar, BarChart, Legend, Line, Plot, PlotPoints, Points, uniform_grid_spacer};
use glint_scene::RenderSettings;

use crate::comparison::Compared;
use crate::error_history::{Axis, ErrorHistory};

/// Shading differences (first hit agrees) and first-hit disagreements, in the histogram.
const SAME_HIT: Color32 = Color32::from_rgb(90, 150, 230);
const HIT_DIFFERS: Color32 = Color32::from_rgb(240, 140, 40);

/// The panel; returns a pixel to probe when "Go to worst pixel" was clicked.
pub fn ui(
    ui: &mut Ui,
    compared: Option<&Compared>,
    history: &ErrorHistory,
    axis: &mut Axis,
    current: &RenderSettings,
) -> Option<(u32, u32)> {
    let mut probe = None;
    match compared {
        None => {
            ui.weak("No comparison of this revision yet: it needs the GPU image and the CPU reference.");
        }
        Some(c) => {
            let e = &c.errors;
            ui.label(format!(
                "RMSE {:.3e}   PSNR {}   FLIP {:.5}   first-hit mismatch {:.3} %",
                e.rmse,
                if e.psnr.is_finite() { format!("{:.1} dB", e.psnr) } else { "∞".into() },
                e.flip_mean,
                100.0 * e.first_hit_mismatch
            ));
            histogram(ui, c);
            match c.diffs.worst() {
                Some((x, y, d)) => {
                    if ui
                        .button(format!("Go to worst pixel ({x}, {y}): |GPU − CPU| = {d:.2e}"))
                        .on_hover_text("Probe it: every term of the model at that pixel, CPU beside GPU")
                        .clicked()
                    {
                        probe = Some((x, y));
                    }
                }
                None => {
                    ui.label("The images are identical.");
                }
            }
        }
    }
    ui.separator();
    error_plot(ui, history, axis, current);
    probe
}

fn histogram(ui: &mut Ui, c: &Compared) {
    let bar = |i: usize, n: usize, name: &str| Bar::new(i as f64, n as f64).width(0.8).name(name);
    let same: Vec<Bar> = c.histogram.iter().enumerate().map(|(i, b)| bar(i, b.same_hit, &b.label())).collect();
    let differs: Vec<Bar> = c.histogram.iter().enumerate().map(|(i, b)| bar(i, b.hit_differs, &b.label())).collect();
    let same = BarChart::new("first hit agrees", same).color(SAME_HIT);
    let differs = BarChart::new("first hit differs", differs).color(HIT_DIFFERS).stack_on(&[&same]);
    let labels: Vec<String> = c.histogram.iter().map(glint_core::compare::DiffBin::label).collect();
    ui.label("Pixels by |GPU − CPU| (max channel, linear radiance):");
    Plot::new("difference histogram")
        .height(140.0)
        .legend(Legend::default())
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        // A grid mark, and so a label, at every bin.
        .x_grid_spacer(uniform_grid_spacer(|_| [1.0, 2.0, 4.0]))
        .x_axis_formatter(move |mark, _range| {
            let i = mark.value.round();
            if (mark.value - i).abs() < 1e-6 && i >= 0.0 {
                labels.get(i as usize).cloned().unwrap_or_default()
            } else {
                String::new()
            }
        })
        .show(ui, |plot| {
            plot.bar_chart(same);
            plot.bar_chart(differs);
        });
}

fn error_plot(ui: &mut Ui, history: &ErrorHistory, axis: &mut Axis, current: &RenderSettings) {
    ui.horizontal_wrapped(|ui| {
        ui.label("Error against");
        for a in Axis::ALL {
            ui.selectable_value(axis, a, a.label());
        }
    });
    let points = history.along(*axis, current);
    if points.is_empty() {
        ui.weak("Change samples or depth: each finished comparison adds a point.");
        return;
    }
    // Log10 of the errors: they span decades. An identical image (RMSE 0) sits at −12.
    let log = |v: f64| if v > 0.0 { v.log10() } else { -12.0 };
    let series = |f: &dyn Fn(&crate::error_history::ErrorPoint) -> f64| -> Vec<[f64; 2]> {
        points.iter().map(|p| [axis.value(p), log(f(p))]).collect()
    };
    let rmse = series(&|p| p.errors.rmse);
    let flip = series(&|p| p.errors.flip_mean);
    let comparisons =
        if points.len() == 1 { "1 comparison".to_string() } else { format!("{} comparisons", points.len()) };
    ui.label(format!("{comparisons} of this scene; log10 of the error"));
    let plot = Plot::new("error plot").height(160.0).legend(Legend::default().position(egui_plot::Corner::RightTop));
    plot.x_axis_label(axis.label()).y_axis_label("log10 error").show(ui, |plot| {
        plot.line(Line::new("RMSE", PlotPoints::from(rmse.clone())).color(SAME_HIT));
        // The same name as the line: one legend entry for both.
        plot.points(Points::new("RMSE", PlotPoints::from(rmse)).radius(3.0).color(SAME_HIT));
        plot.line(Line::new("FLIP", PlotPoints::from(flip.clone())).color(HIT_DIFFERS));
        plot.points(Points::new("FLIP", PlotPoints::from(flip)).radius(3.0).color(HIT_DIFFERS));
    });
}
