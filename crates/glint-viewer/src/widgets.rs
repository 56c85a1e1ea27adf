//! Small editing widgets shared by the panels. Each returns whether the value changed; every
//! widget is labelled so that screen readers (and the UI tests, through AccessKit) find it.
//! Ranges come from validation's table (`glint_core::scene::ranges`): an editor accepts every
//! valid value, typed or dragged, and clamps only what validation would refuse anyway.

use egui::{DragValue, Response, Slider, SliderClamping, Ui, WidgetInfo};
use glint_core::scene::{Range, Rgb, ranges};

/// The smallest positive value a logarithmic slider reaches by dragging (ε goes down to 1e-9);
/// 0 itself sits at the left end and can be typed.
const SMALLEST_POSITIVE: f64 = 1e-9;

/// Values of a logarithmic slider: scientific, with exactly 0 written as such.
fn scientific(v: f64) -> String {
    if v == 0.0 { "0".into() } else { format!("{v:.3e}") }
}

/// A slider over `range`, logarithmic where the range spans decades (ε, shininess).
pub fn slider(ui: &mut Ui, label: &str, value: &mut f64, range: Range<f64>) -> bool {
    let slider = Slider::new(value, range.min..=range.max).clamping(SliderClamping::Edits).text(label);
    let slider = if range.log {
        slider.logarithmic(true).smallest_positive(SMALLEST_POSITIVE).custom_formatter(|v, _| scientific(v))
    } else {
        slider
    };
    ui.add(slider).changed()
}

/// A slider over whole numbers (recursion depth, samples, image sides); on a logarithmic scale
/// small values get most of its length, and the largest valid value can still be reached.
pub fn int_slider(ui: &mut Ui, label: &str, value: &mut u32, range: Range<u32>) -> bool {
    let slider = Slider::new(value, range.min..=range.max).logarithmic(range.log);
    ui.add(slider.clamping(SliderClamping::Edits).text(label)).changed()
}

/// A drag value whose accessible label is `label`.
fn labelled_drag(ui: &mut Ui, label: String, value: &mut f64, speed: f64, range: Range<f64>) -> Response {
    let r = ui.add(DragValue::new(value).speed(speed).range(range.min..=range.max).max_decimals(4));
    let v = *value;
    r.widget_info(|| WidgetInfo { label: Some(label.clone()), ..WidgetInfo::drag_value(true, v) });
    r
}

/// An RGB colour or intensity: a colour picker for values in [0, 1] and one drag value per
/// channel over the whole valid range (intensities may exceed 1). The channels are labelled
/// "LABEL R/G/B".
pub fn rgb_edit(ui: &mut Ui, label: &str, value: &mut Rgb) -> bool {
    let mut changed = false;
    ui.horizontal(|ui| {
        ui.label(label).on_hover_text(format!("{label}: red, green, blue"));
        let mut c = value.0.map(|v| v.clamp(0.0, 1.0) as f32);
        if ui.color_edit_button_rgb(&mut c).changed() {
            value.0 = c.map(f64::from);
            changed = true;
        }
        for (i, ch) in ["R", "G", "B"].iter().enumerate() {
            let r = labelled_drag(ui, format!("{label} {ch}"), &mut value.0[i], 0.005, ranges::COLOUR);
            changed |= r.changed();
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
            let r = labelled_drag(ui, format!("{label} {axis}"), &mut value[i], speed, ranges::COORD);
            changed |= r.changed();
        }
    });
    changed
}

/// A labelled drag value for one number.
pub fn number(ui: &mut Ui, label: &str, value: &mut f64, speed: f64, range: Range<f64>) -> bool {
    let r = ui.add(
        DragValue::new(value).speed(speed).range(range.min..=range.max).max_decimals(4).prefix(format!("{label} = ")),
    );
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
