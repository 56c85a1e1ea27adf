//! The table of a probe's terms (the Probe panel's and each ray-tree node's): per term its
//! name and colour over CPU (f64), GPU (f32) and their difference by channel.

use egui::{Color32, RichText, Ui};
use glint_core::glam::DVec3;

use crate::probe::{Channels, Term};

/// The colour of a highlighted (first differing) row or node.
pub const HIGHLIGHT: Color32 = Color32::from_rgb(255, 120, 90);

/// What the Δ row is, on hover (a lecturer found it unexplained).
/// The row of a node's radiance, and what it is, on hover (a lecturer found it unexplained).
pub const BROUGHT_BACK: &str = "I brought back (CPU only)";
pub const BROUGHT_BACK_HINT: &str = "The radiance this ray carries back: its hit's local terms plus k·I of the rays it \
     spawns (the camera ray's is the pixel's value); only the CPU keeps it, the GPU adding each ray's weighted terms \
     straight into the pixel.";

pub const DELTA_HINT: &str = "Δ = GPU − CPU: the GPU's f32 value less the CPU's f64 reference, per channel; the \
     first term where the two differ beyond the probe's tolerance is highlighted.";

/// The width of a table's row labels ("CPU", "GPU", "Δ").
const ROW_LABEL_WIDTH: f32 = 30.0;
/// The narrowest channel column: "-1.2e-7" in the table's font.
const MIN_CHANNEL_WIDTH: f32 = 46.0;

/// A term's value as its table shows it: four significant digits, scientific outside
/// [1e-3, 1e4), exactly 0 as "0".
pub fn cell(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        format!("{v:.decimals$}")
    } else {
        format!("{v:.1e}")
    }
}

/// The width of one character of the table's font (11 px monospace): "-1.2e-7" in 46 px.
const CHAR_WIDTH: f32 = MIN_CHANNEL_WIDTH / 7.0;

/// `cell(v)`, or where that is wider than `chars` characters its value in fewer digits, then
/// scientific: a narrow panel cut N's -0.006234 to "-0.006…" (a lecturer), where "-6.2e-3" fits.
/// The exact value is on hover either way.
fn cell_within(v: f64, chars: usize) -> String {
    let full = cell(v);
    if full.chars().count() <= chars {
        return full;
    }
    [format!("{v:.1e}"), format!("{v:.0e}")]
        .into_iter()
        .find(|s| s.chars().count() <= chars)
        .unwrap_or_else(|| format!("{v:.0e}"))
}

/// A difference as its table shows it: two significant digits, scientific.
fn delta(v: f64) -> String {
    if v == 0.0 { "0".into() } else { format!("{v:.1e}") }
}

/// A small square of the term's colour (linear RGB, clamped, shown as sRGB).
fn swatch(ui: &mut Ui, v: DVec3) {
    let [r, g, b] = v.to_array().map(glint_core::image::linear_to_srgb8);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
    ui.painter().rect_filled(rect, 1.0, Color32::from_rgb(r, g, b));
    ui.painter().rect_stroke(rect, 1.0, egui::Stroke::new(1.0, Color32::GRAY), egui::StrokeKind::Inside);
}

/// `rows` as a table that fits the side panel: per term its name (with a swatch of its colour)
/// over a grid of CPU (f64), GPU (f32) and their difference Δ = GPU − CPU, by channel R, G, B;
/// row `first` highlighted. Exact values (shortest round-trip form) on hover.
pub fn term_grid(ui: &mut Ui, id: impl std::hash::Hash + std::fmt::Debug + Copy, rows: &[Term], first: Option<usize>) {
    let spacing = ui.spacing().item_spacing.x;
    // Fixed cell widths, so that the grids of all terms line up under one header; a little
    // is kept for the cells' own margins.
    let channel = ((ui.available_width() - ROW_LABEL_WIDTH - 4.0 * spacing - 4.0) / 3.0).max(MIN_CHANNEL_WIDTH);
    let font = |s: String| RichText::new(s).monospace().size(11.0);
    let sized = |ui: &mut Ui, width: f32, text: RichText| {
        ui.add_sized([width, 14.0], egui::Label::new(text).truncate().halign(egui::Align::RIGHT))
    };
    let grid = |n: usize| egui::Grid::new(("term table", id, n)).num_columns(4).spacing([spacing, 1.0]);
    grid(usize::MAX).show(ui, |ui| {
        sized(ui, ROW_LABEL_WIDTH, RichText::new(""));
        for c in ["R", "G", "B"] {
            sized(ui, channel, RichText::new(c).strong());
        }
        ui.end_row();
    });
    for (i, t) in rows.iter().enumerate() {
        let highlight = Some(i) == first;
        let colour = |r: RichText| if highlight { r.color(HIGHLIGHT).strong() } else { r };
        // A colour has a swatch; one number is shown once, a direction's components are named.
        let (shown, names): (usize, [&str; 3]) = match t.channels {
            Channels::Rgb => (3, ["R", "G", "B"]),
            Channels::Scalar => (1, ["", "", ""]),
            Channels::Xyz => (3, ["x", "y", "z"]),
        };
        ui.horizontal_wrapped(|ui| {
            if t.channels == Channels::Rgb {
                swatch(ui, t.cpu);
            }
            let name = if t.channels == Channels::Xyz { format!("{} (x, y, z)", t.name) } else { t.name.clone() };
            let r = ui.label(colour(RichText::new(name).strong()));
            if t.name == BROUGHT_BACK {
                r.on_hover_text(BROUGHT_BACK_HINT);
            }
        });
        let values: [(&str, Option<[f64; 3]>, &str); 3] = [
            ("CPU", Some(t.cpu.to_array()), "CPU (f64)"),
            ("GPU", t.gpu.map(|g| g.to_array()), "GPU (f32)"),
            ("Δ", t.gpu.map(|g| (g - t.cpu).to_array()), "GPU − CPU"),
        ];
        grid(i).show(ui, |ui| {
            for (label, v, what) in values {
                let hint = if label == "Δ" { DELTA_HINT } else { what };
                sized(ui, ROW_LABEL_WIDTH, colour(font(label.into()))).on_hover_text(hint);
                for k in 0..3 {
                    let text = match v {
                        _ if k >= shown => String::new(),
                        None => "—".to_string(),
                        Some(v) if label == "Δ" => delta(v[k]),
                        Some(v) => cell_within(v[k], (channel / CHAR_WIDTH).floor() as usize),
                    };
                    let r = sized(ui, channel, colour(font(text)));
                    if let Some(v) = v.filter(|_| k < shown) {
                        let exact = if label == "GPU" { format!("{}", v[k] as f32) } else { format!("{:?}", v[k]) };
                        let of = if names[k].is_empty() { String::new() } else { format!(", {}", names[k]) };
                        r.on_hover_text(format!("{what}{of}: {exact}"));
                    }
                }
                ui.end_row();
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::{cell, cell_within};

    #[test]
    fn a_value_too_wide_for_its_column_keeps_its_magnitude_in_fewer_digits() {
        assert_eq!(cell(-0.006234), "-0.006234");
        assert_eq!(cell_within(-0.006234, 9), "-0.006234");
        assert_eq!(cell_within(-0.006234, 7), "-6.2e-3");
        assert_eq!(cell_within(0.4331, 7), "0.4331");
        assert_eq!(cell_within(-1.23e-12, 6), "-1e-12");
    }
}
