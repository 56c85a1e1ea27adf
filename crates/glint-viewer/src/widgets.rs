//! Small editing widgets shared by the panels. Each returns whether the value changed; every
//! widget is labelled so that screen readers (and the UI tests, through AccessKit) find it.

use egui::{DragValue, Response, Slider, SliderClamping, Ui, WidgetInfo};
use glint_core::scene::Rgb;

/// A logarithmic slider for values spanning decades (ε, shininess).
pub fn log_slider(ui: &mut Ui, label: &str, value: &mut f64, range: std::ops::RangeInclusive<f64>) -> bool {
    ui.add(
        Slider::new(value, range)
            .logarithmic(true)
            .clamping(SliderClamping::Edits)
            .smallest_positive(1e-9)
            .custom_formatter(|v, _| format!("{v:.3e}"))
            .text(label),
    )
    .changed()
}

/// A logarithmic slider over whole numbers (recursion depth, samples): small values get most
/// of its length, and the largest valid value can still be reached.
pub fn int_log_slider(ui: &mut Ui, label: &str, value: &mut u32, range: std::ops::RangeInclusive<u32>) -> bool {
    ui.add(Slider::new(value, range).logarithmic(true).clamping(SliderClamping::Edits).text(label)).changed()
}

/// A linear slider with a label.
pub fn slider<N: egui::emath::Numeric>(
    ui: &mut Ui,
    label: &str,
    value: &mut N,
    range: std::ops::RangeInclusive<N>,
) -> bool {
    ui.add(Slider::new(value, range).clamping(SliderClamping::Edits).text(label)).changed()
}

/// A drag value whose accessible label is `label`.
fn labelled_drag(
    ui: &mut Ui,
    label: String,
    value: &mut f64,
    speed: f64,
    range: std::ops::RangeInclusive<f64>,
) -> Response {
    let r = ui.add(DragValue::new(value).speed(speed).range(range).max_decimals(4));
    let v = *value;
    r.widget_info(|| WidgetInfo { label: Some(label.clone()), ..WidgetInfo::drag_value(true, v) });
    r
}

/// An RGB colour or intensity: a colour picker for values in [0, 1] and one drag value per
/// channel (intensities may exceed 1). The channels are labelled "LABEL R/G/B".
pub fn rgb_edit(ui: &mut Ui, label: &str, value: &mut Rgb, max: f64) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label(label).on_hover_text(format!("{label}: red, green, blue"));
        let mut c = value.0.map(|v| v.clamp(0.0, 1.0) as f32);
        if ui.color_edit_button_rgb(&mut c).changed() {
            value.0 = c.map(f64::from);
            changed = true;
        }
        for (i, ch) in ["R", "G", "B"].iter().enumerate() {
            changed |= labelled_drag(ui, format!("{label} {ch}"), &mut value.0[i], 0.005, 0.0..=max).changed();
        }
    });
    changed
}

/// A 3-vector (position or direction) as three labelled drag values.
pub fn vec3_edit(ui: &mut Ui, label: &str, value: &mut [f64; 3], speed: f64) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label(label);
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            let r = labelled_drag(ui, format!("{label} {axis}"), &mut value[i], speed, -1e6..=1e6);
            changed |= r.changed();
        }
    });
    changed
}

/// A labelled drag value for one number.
pub fn number(ui: &mut Ui, label: &str, value: &mut f64, speed: f64, range: std::ops::RangeInclusive<f64>) -> bool {
    let r = ui.add(DragValue::new(value).speed(speed).range(range).max_decimals(4).prefix(format!("{label} = ")));
    let v = *value;
    r.widget_info(|| WidgetInfo { label: Some(label.to_string()), ..WidgetInfo::drag_value(true, v) });
    r.changed()
}

/// A combo box over `options`, shown by `name`.
pub fn choice<T: PartialEq + Copy>(
    ui: &mut Ui,
    label: &str,
    value: &mut T,
    options: &[T],
    name: impl Fn(T) -> &'static str,
) -> bool {
    let mut changed = false;
    egui::ComboBox::from_label(label).selected_text(name(*value)).show_ui(ui, |ui| {
        for &o in options {
            changed |= ui.selectable_value(value, o, name(o)).changed();
        }
    });
    changed
}
