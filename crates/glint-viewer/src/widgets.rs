//! Small editing widgets shared by the panels. Each returns whether the value changed; every
//! widget is labelled so that screen readers (and the UI tests, through AccessKit) find it.
//! Ranges come from validation's table (`glint_scene::ranges`): an editor accepts every
//! valid value, typed or dragged, and clamps only what validation would refuse anyway. A typed
//! value is taken on Return or when the field loses focus, not keystroke by keystroke: egui's
//! default applied each partial text, so typing −0.5 set 0 (from "-0") before −0.5 was
//! refused, and 2000000 left 200000 (a viewer tester).

use std::cell::Cell;

use egui::{DragValue, Response, Slider, SliderClamping, Ui, WidgetInfo};

use crate::help::{hint, option_tooltip, with_tooltip};
use glint_scene::{Range, Rgb, ranges};

/// The smallest positive value a logarithmic slider reaches by dragging (ε goes down to 1e-9);
/// 0 itself sits at the left end and can be typed.
const SMALLEST_POSITIVE: f64 = 1e-9;

/// A typed number, read as egui reads one (spaces ignored, U+2212 a minus), or why not — the
/// field keeps its value — for what is not a finite number: egui's own reading takes "NaN" and
/// "inf" and then clamps them to the range's end (a typed NaN made the field of view 179°).
fn finite_number(text: &str) -> Result<f64, String> {
    let cleaned: String = text.chars().filter(|c| !c.is_whitespace()).map(|c| if c == '−' { '-' } else { c }).collect();
    match cleaned.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("{} is not a finite number; the value was kept", text.trim())),
        Err(_) if cleaned.is_empty() => Err("an empty field is not a number; the value was kept".into()),
        Err(_) => Err(format!("`{}` is not a number; the value was kept", text.trim())),
    }
}

/// `finite_number`, its refusal kept in `refused` (a typed `abc` or `nan` was left without a
/// word, while −1 was named; a viewer tester).
fn number_or_refused(text: &str, refused: &Cell<Option<String>>) -> Option<f64> {
    finite_number(text).map_err(|why| refused.set(Some(why))).ok()
}

/// A typed number inside `range`, or `None` (the field keeps its value) with why not kept in
/// `refused` for `refusal_note`: egui clamped a typed value to the range's end without a word
/// (a lecturer's I_d −1 became 0, shininess 1e30 became 1e6, and an ior of −2 became the
/// excluded 0, which validation then refused naming 0, not what was typed).
fn in_range(text: &str, range: Range<f64>, refused: &Cell<Option<String>>) -> Option<f64> {
    let v = number_or_refused(text, refused)?;
    if range.contains(v) {
        return Some(v);
    }
    refused.set(Some(format!(
        "{} is outside {}{}; the value was kept",
        glint_scene::format_number(v),
        range.bounds(),
        range.why_outside(v)
    )));
    None
}

/// `in_range` for whole numbers: a fraction or a number outside `range` is refused by name.
fn whole_in_range(text: &str, range: Range<u32>, refused: &Cell<Option<String>>) -> Option<f64> {
    let v = number_or_refused(text, refused)?;
    if v.fract() == 0.0 && (f64::from(range.min)..=f64::from(range.max)).contains(&v) {
        return Some(v);
    }
    let what = if v.fract() == 0.0 { "is outside" } else { "is not a whole number in" };
    let v = glint_scene::format_number(v);
    refused.set(Some(format!("{v} {what} [{}, {}]; the value was kept", range.min, range.max)));
    None
}

/// Under the editor of `response`, the last typed value it refused (`refused`, this frame's),
/// until the value next changes: a typed value outside the range is named, not clamped.
fn refusal_note(ui: &mut Ui, label: &str, response: &Response, refused: Option<String>) {
    if let Some(note) = refusal(ui, label, response, refused) {
        show_refusal(ui, &note);
    }
}

/// Keeps `refused` (this frame's refusal of the editor of `response`) until the value next
/// changes, and gives the note to show for it, if any.
fn refusal(ui: &mut Ui, label: &str, response: &Response, refused: Option<String>) -> Option<String> {
    // Keyed by the row and the label: the editor's own id differs while its text is edited.
    let id = ui.scope_id().with(("refused", label));
    if let Some(why) = refused {
        ui.data_mut(|d| d.insert_temp(id, why));
    } else if response.changed() {
        ui.data_mut(|d| d.remove::<String>(id));
    }
    ui.data(|d| d.get_temp::<String>(id)).map(|why| format!("{label}: {why}"))
}

fn show_refusal(ui: &mut Ui, note: &str) {
    ui.colored_label(ui.visuals().error_fg_color, note);
}

/// Values of a logarithmic slider, four digits as a class reads them aloud: 32 and 1.5, not
/// 3.200e1 and 1.500e0; scientific only beyond [1e-4, 1e15) (1e-6).
fn scientific(v: f64) -> String {
    glint_scene::format_rounded(v, 4)
}

/// A slider over `range` (linear; `log_slider` for what spans decades).
pub fn slider(ui: &mut Ui, label: &str, value: &mut f64, range: Range<f64>) -> bool {
    let wanted = ui.spacing().slider_width;
    let refused = Cell::new(None);
    let response = fitted(ui, label, wanted, |ui, text| {
        let slider = Slider::new(value, range.min..=range.max)
            .clamping(SliderClamping::Edits)
            .custom_parser(|t| in_range(t, range, &refused))
            .update_while_editing(false)
            .text(text);
        labelled(hint(ui.add(slider), label), label, text)
    });
    refusal_note(ui, label, &response, refused.take());
    response.changed()
}

/// A slider's `response` labelled `label` for screen readers (and the UI tests) where the
/// label stands above it (`text` empty) rather than in it.
fn labelled(response: Response, label: &str, text: &str) -> Response {
    if text.is_empty() {
        response.widget_info(|| WidgetInfo::labeled(egui::Role::Slider, true, label));
    }
    response
}

/// Points of slider per decade of a logarithmic slider: a 40-point drag moves a value by about
/// one decade (over the whole valid range of shininess, 15 decades in 100 points, it moved n
/// from 200 to 3e-5).
pub const POINTS_PER_DECADE: f32 = 40.0;

/// The width of a slider's value field ("1.000e-6"), with its margins.
const VALUE_FIELD_WIDTH: f32 = 78.0;

/// The narrowest slider: at the side panel's minimum width a long label leaves this.
const MIN_SLIDER_WIDTH: f32 = 36.0;

/// What a row leaves a slider beside its value field and its label, which must not be cut off
/// at the panel's width; `None` where not even the narrowest slider fits beside the label.
fn slider_room(ui: &Ui, label: &str) -> Option<f32> {
    let font = egui::TextStyle::Body.resolve(ui.style());
    let label_width = ui.painter().layout_no_wrap(label.to_string(), font, egui::Color32::WHITE).size().x;
    let room = ui.available_width() - label_width - VALUE_FIELD_WIDTH - 2.0 * ui.spacing().item_spacing.x;
    (room >= MIN_SLIDER_WIDTH).then_some(room)
}

/// `add` with the slider `wanted` wide where the row has room, else with its label on a line
/// of its own above a slider of the row's width (`add` gets the label to give the slider: the
/// label, or none when it stands above).
fn fitted<R>(ui: &mut Ui, label: &str, wanted: f32, add: impl FnOnce(&mut Ui, &str) -> R) -> R {
    let (width, text) = match slider_room(ui, label) {
        Some(room) => (wanted.min(room), label),
        None => {
            hint(ui.label(label), label);
            ((ui.available_width() - VALUE_FIELD_WIDTH - ui.spacing().item_spacing.x).max(MIN_SLIDER_WIDTH), "")
        }
    };
    ui.scope(|ui| {
        ui.spacing_mut().slider_width = width;
        add(ui, text)
    })
    .inner
}

/// A logarithmic slider whose drag covers the decades people use, `span`; a value typed into
/// its field may be anything in validation's `range` (outside `span` the handle rests at an
/// end).
pub fn log_slider(ui: &mut Ui, label: &str, value: &mut f64, range: Range<f64>, span: (f64, f64)) -> bool {
    let decades = (span.1 / span.0.max(SMALLEST_POSITIVE)).log10() as f32;
    let refused = Cell::new(None);
    let response = fitted(ui, label, POINTS_PER_DECADE * decades, |ui, text| {
        let slider = Slider::new(value, span.0..=span.1)
            .clamping(SliderClamping::Never)
            .text(text)
            .logarithmic(true)
            .smallest_positive(span.0.max(SMALLEST_POSITIVE))
            .custom_formatter(|v, _| scientific(v))
            .custom_parser(|t| in_range(t, range, &refused))
            .update_while_editing(false);
        labelled(hint(ui.add(slider), label), label, text)
    });
    refusal_note(ui, label, &response, refused.take());
    let changed = response.changed();
    if changed {
        *value = value.clamp(range.min, range.max);
    }
    changed
}

/// A slider over whole numbers (recursion depth, samples, image sides); on a logarithmic scale
/// small values get most of its length, and the largest valid value can still be reached.
pub fn int_slider(ui: &mut Ui, label: &str, value: &mut u32, range: Range<u32>) -> bool {
    let wanted = ui.spacing().slider_width;
    let refused = Cell::new(None);
    let response = fitted(ui, label, wanted, |ui, text| {
        let slider = Slider::new(value, range.min..=range.max)
            .logarithmic(range.log)
            .custom_parser(|t| whole_in_range(t, range, &refused))
            .update_while_editing(false);
        labelled(hint(ui.add(slider.clamping(SliderClamping::Edits).text(text)), label), label, text)
    });
    refusal_note(ui, label, &response, refused.take());
    response.changed()
}

/// A drag value whose accessible label is `label`, and the note of its last refused value, for
/// the caller to show under the whole row: shown in the row, it pushed the row's next fields
/// onto another line (k_t R = −1 split R from G and B; a lecturer).
fn labelled_drag(
    ui: &mut Ui,
    label: String,
    value: &mut f64,
    speed: f64,
    range: Range<f64>,
) -> (Response, Option<String>) {
    let refused = Cell::new(None);
    let r = ui.add(
        DragValue::new(value)
            .speed(speed)
            .range(range.min..=range.max)
            .max_decimals(4)
            .custom_parser(|t| in_range(t, range, &refused))
            .update_while_editing(false),
    );
    let v = *value;
    r.widget_info(|| WidgetInfo { label: Some(label.clone()), ..WidgetInfo::drag_value(true, v) });
    let r = hint(r, &label);
    let note = refusal(ui, &label, &r, refused.take());
    (r, note)
}

/// An RGB colour or intensity: a colour picker for values in [0, 1] and one drag value per
/// channel over the whole valid range (intensities may exceed 1). The channels are labelled
/// "LABEL R/G/B".
pub fn rgb_edit(ui: &mut Ui, label: &str, value: &mut Rgb) -> bool {
    let mut changed = false;
    let mut notes = Vec::new();
    ui.horizontal_wrapped(|ui| {
        hint(ui.label(label), label);
        let before = value.0.map(|v| v.clamp(0.0, 1.0) as f32);
        let mut c = before;
        if ui.color_edit_button_rgb(&mut c).changed() {
            changed = picked_colour(&mut value.0, before, c);
        }
        for (i, ch) in ["R", "G", "B"].iter().enumerate() {
            let (r, note) = labelled_drag(ui, format!("{label} {ch}"), &mut value.0[i], 0.005, ranges::COLOUR);
            changed |= r.changed();
            notes.extend(note);
        }
    });
    notes.iter().for_each(|n| show_refusal(ui, n));
    changed
}

/// A 3-vector (position or direction) as three labelled drag values.
pub fn vec3_edit(ui: &mut Ui, label: &str, value: &mut [f64; 3], speed: f64) -> bool {
    let mut changed = false;
    let mut notes = Vec::new();
    ui.horizontal_wrapped(|ui| {
        hint(ui.label(label), label);
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            let (r, note) = labelled_drag(ui, format!("{label} {axis}"), &mut value[i], speed, ranges::COORD);
            changed |= r.changed();
            notes.extend(note);
        }
    });
    notes.iter().for_each(|n| show_refusal(ui, n));
    changed
}

/// A labelled drag value for one number.
pub fn number(ui: &mut Ui, label: &str, value: &mut f64, speed: f64, range: Range<f64>) -> bool {
    let refused = Cell::new(None);
    let r = ui.add(
        DragValue::new(value)
            .speed(speed)
            .range(range.min..=range.max)
            .max_decimals(4)
            .custom_parser(|t| in_range(t, range, &refused))
            .update_while_editing(false)
            .prefix(format!("{label} = ")),
    );
    let v = *value;
    r.widget_info(|| WidgetInfo { label: Some(label.to_string()), ..WidgetInfo::drag_value(true, v) });
    let r = hint(r, label);
    refusal_note(ui, label, &r, refused.take());
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
    let combo = egui::ComboBox::from_label(label).selected_text(name(*value)).show_ui(ui, |ui| {
        for &o in options {
            let r = ui.selectable_value(value, o, name(o));
            changed |= with_tooltip(r, option_tooltip(label, name(o))).changed();
        }
    });
    hint(combo.response, label);
    changed
}

/// The colour picker's change to `value`, shown to it as `before`: a channel it moved by less
/// than `PICKER_NOISE` keeps its exact value, and whether any channel changed. Opening and
/// closing the picker sends f32 channels through HSV and back, an ulp or two off: k_a = 0.05
/// was saved as 0.04999999701976776 and the scene marked edited, with nothing touched.
fn picked_colour(value: &mut [f64; 3], before: [f32; 3], after: [f32; 3]) -> bool {
    let moved = |k: usize| (after[k] - before[k]).abs() > PICKER_NOISE;
    if !(0..3).any(moved) {
        return false;
    }
    for k in 0..3 {
        // A channel beyond the picker's [0, 1] (an emission of 12) was shown clamped: once the
        // colour is picked, it is the picker's value too, not 12 beside the picked others.
        if moved(k) || !(0.0..=1.0).contains(&value[k]) {
            value[k] = f64::from(after[k]);
        }
    }
    true
}

/// Far below the picker's own steps (its sliders move by 1/255 of the range and more), and far
/// above its round trip's rounding (a few f32 ulps of a value ≤ 1).
const PICKER_NOISE: f32 = 1e-6;

#[cfg(test)]
mod tests {
    use super::picked_colour;

    #[test]
    fn the_pickers_rounding_changes_nothing_and_a_pick_changes_its_channel() {
        let mut value = [0.05, 0.3, 0.05];
        let before = value.map(|v| v as f32);
        let round_trip = [0.049_999_997, 0.300_000_04, 0.050_000_05];
        assert!(!picked_colour(&mut value, before, round_trip));
        assert_eq!(value, [0.05, 0.3, 0.05], "the typed values are kept exactly");
        let picked = [0.049_999_997, 0.5, 0.050_000_05];
        assert!(picked_colour(&mut value, before, picked));
        assert_eq!(value, [0.05, f64::from(0.5f32), 0.05], "only the channel picked changes");
        // A lamp's E_m of (12, 11.4, 10.2) is shown as (1, 1, 1): picking (1, 0.9, 0.8) makes it
        // that colour, not (12, 0.9, 0.8) (a reviewer's find).
        let mut lamp = [12.0, 11.4, 10.2];
        assert!(!picked_colour(&mut lamp, [1.0; 3], [1.0; 3]), "opening the picker changes nothing");
        assert_eq!(lamp, [12.0, 11.4, 10.2]);
        assert!(picked_colour(&mut lamp, [1.0; 3], [1.0, 0.9, 0.8]));
        assert_eq!(lamp, [1.0, f64::from(0.9f32), f64::from(0.8f32)]);
    }
}
