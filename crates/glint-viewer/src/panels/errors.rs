//! Errors panel: GPU against CPU for the current revision — the figures, a histogram of
//! |GPU − CPU| in decades split by first-hit agreement, the worst pixel (probed on request) —
//! and the live plot of error against samples, depth or GPU time from the comparisons made so far.

use egui::{Color32, Ui};
use egui_plot::{AxisHints, Bar, BarChart, GridMark, Legend, Line, Plot, PlotPoints, Points, uniform_grid_spacer};
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
    legend(ui, &[("RMSE", SAME_HIT), ("FLIP", HIT_DIFFERS)]);
    let integers = *axis != Axis::GpuTime;
    let x_axis = AxisHints::new_x()
        .label(axis.label())
        .label_spacing(LABEL_SPACING.0..=LABEL_SPACING.1)
        .formatter(|mark, _range| tick_label(mark.value, mark.step_size));
    let plot = Plot::new("error plot")
        .height(160.0)
        .x_grid_spacer(move |input| ticks(input.bounds, input.base_step_size / GRID_MIN, integers))
        .custom_x_axes(vec![x_axis]);
    plot.y_axis_label("log10 error").show(ui, |plot| {
        plot.line(Line::new("RMSE", PlotPoints::from(rmse.clone())).color(SAME_HIT));
        plot.points(Points::new("RMSE", PlotPoints::from(rmse)).radius(3.0).color(SAME_HIT));
        plot.line(Line::new("FLIP", PlotPoints::from(flip.clone())).color(HIT_DIFFERS));
        plot.points(Points::new("FLIP", PlotPoints::from(flip)).radius(3.0).color(HIT_DIFFERS));
    });
}

/// The plot's legend, as a row above it: inside, in any corner, it covered the newest point
/// (a lecturer), which lands anywhere as samples, depth or time go up or down.
fn legend(ui: &mut Ui, series: &[(&str, Color32)]) {
    ui.horizontal(|ui| {
        for (name, colour) in series {
            let (rect, _) = ui.allocate_exact_size(egui::vec2(18.0, 10.0), egui::Sense::hover());
            let painter = ui.painter();
            painter.line_segment([rect.left_center(), rect.right_center()], egui::Stroke::new(1.5, *colour));
            painter.circle_filled(rect.center(), 3.0, *colour);
            ui.label(*name);
        }
    });
}

/// egui_plot's finest grid spacing in points (`Plot::grid_spacing`'s least): its grid spacer
/// gets the plot units of that many points.
const GRID_MIN: f64 = 8.0;
/// The x axis paints a tick's label where ticks are more than the first apart, faintly up to
/// the second (egui_plot's 60 to 80 left a 230-point plot of 41.5 to 48.3 ms one label).
const LABEL_SPACING: (f32, f32) = (40.0, 45.0);
/// Labelled ticks are at least this far apart: at most 2.5 times that (a step of 2 rounded up
/// to 5), and so two labels or more on a plot of 225 points.
const LABEL_GAP: f64 = LABEL_SPACING.1 as f64;

/// The x axis's grid over `bounds` at `unit` plot units a point: labelled ticks at the smallest
/// step of 1, 2 or 5 × 10^k that leaves `LABEL_GAP` between them, finer lines between; whole
/// numbers only for samples and depth. egui_plot's default steps by tens only, so that from
/// 10 to 80 points a tick no label fitted: GPU times over a few milliseconds had none.
fn ticks(bounds: (f64, f64), unit: f64, integers: bool) -> Vec<GridMark> {
    let (lo, hi) = bounds;
    if !(unit > 0.0 && lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    let mut step = glint_core::compare::nice_ceiling(LABEL_GAP * unit);
    if integers {
        step = step.max(1.0);
    }
    // Finer lines at a fifth of a step of 1 or 5 × 10^k, at half of one of 2 × 10^k.
    let mantissa = (step / 10f64.powf(step.log10().floor())).round();
    let fine = if mantissa == 2.0 { step / 2.0 } else { step / 5.0 };
    let mut marks = Vec::new();
    for (size, skip) in [(step, None), (fine, Some(step))] {
        if integers && size < 1.0 {
            continue;
        }
        let first = (lo / size).ceil() as i64;
        let last = (hi / size).floor() as i64;
        for i in first..=last.min(first + 1000) {
            let value = i as f64 * size;
            if skip.is_some_and(|s| ((value / s).round() * s - value).abs() < 1e-9 * s) {
                continue;
            }
            marks.push(GridMark { value, step_size: size });
        }
    }
    marks
}

/// A tick's number with the decimals its step needs (a step of 0.5 gives one: "27.5").
fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10() - 1e-9).ceil().max(0.0) as usize;
    let v = if value.abs() < step * 1e-9 { 0.0 } else { value };
    format!("{v:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::{LABEL_GAP, LABEL_SPACING, tick_label, ticks};

    /// The labelled ticks egui_plot paints of `marks` over a plot `width` points wide: those
    /// more than `least` points from the next of their size.
    fn labelled(marks: &[egui_plot::GridMark], bounds: (f64, f64), width: f64, least: f32) -> Vec<f64> {
        let points_per_unit = width / (bounds.1 - bounds.0);
        marks.iter().filter(|m| m.step_size * points_per_unit > f64::from(least)).map(|m| m.value).collect()
    }

    #[test]
    fn the_x_axis_has_labelled_ticks_whatever_its_range() {
        // A lecturer's GPU times, 41.5 to 48.3 ms over a 230-point plot, had no label: egui_plot's
        // steps of 1 were 34 points apart and those of 10 had no tick in range.
        let width = 230.0;
        for (lo, hi, integers) in
            [(41.5, 48.3, false), (27.0, 56.0, false), (0.9, 4.1, true), (0.5, 64.5, true), (1e3, 9e3, false)]
        {
            let marks = ticks((lo, hi), (hi - lo) / width, integers);
            let shown = labelled(&marks, (lo, hi), width, LABEL_SPACING.0);
            assert!(shown.len() >= 2, "{lo}..{hi}: labels at {shown:?}");
            let gap = (shown[1] - shown[0]) * width / (hi - lo);
            assert!(gap >= LABEL_GAP - 1e-6, "{lo}..{hi}: labels {gap} points apart");
            if integers {
                assert!(marks.iter().all(|m| m.value.fract() == 0.0), "{lo}..{hi}: {marks:?}");
            }
        }
        let old = egui_plot::log_grid_spacer(10)(egui_plot::GridInput {
            bounds: (41.5, 48.3),
            base_step_size: 8.0 * 6.8 / width,
        });
        assert!(labelled(&old, (41.5, 48.3), width, 60.0).is_empty(), "the default's failure, as the lecturer saw it");
    }

    #[test]
    fn a_tick_label_has_the_decimals_its_step_needs() {
        assert_eq!(tick_label(30.0, 10.0), "30");
        assert_eq!(tick_label(27.5, 0.5), "27.5");
        assert_eq!(tick_label(0.2, 0.2), "0.2");
        assert_eq!(tick_label(-1e-17, 0.5), "0.0");
        assert_eq!(tick_label(4.0, 1.0), "4");
    }
}
