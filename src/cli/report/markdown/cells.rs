//! How numbers are written in the report's tables (times: `units::ms_cell`).

use super::super::sweep::{Row, SceneResult};

/// Errors in three significant digits; an exact 0 as "0".
pub fn sci(v: f64) -> String {
    if v == 0.0 { "0".into() } else { format!("{v:.2e}") }
}

/// PSNR in dB; an image equal to the reference (PSNR +∞) says so, and a PSNR that is not a
/// number or −∞ (an error that overflowed) is flagged, never tabulated as a value.
pub fn psnr(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.1}")
    } else if v == f64::INFINITY {
        "∞ (identical)".into()
    } else {
        format!("⚠ {v}")
    }
}

/// RMSE and the like, flagged when not finite (an error beyond f64: never a measurement).
pub fn error(v: f64) -> String {
    if v.is_finite() { sci(v) } else { format!("⚠ {v}") }
}

/// ε as written in scene files: 1e-6, 0.001.
pub fn eps(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 { format!("{v:e}") } else { v.to_string() }
}

/// A fraction as a percentage with three decimals.
pub fn pct(v: f64) -> String {
    format!("{:.3}", 100.0 * v)
}

/// Three values of one sweep axis in a cell: "a · b · c".
pub fn triple(rows: &[Option<&Row>], f: impl Fn(&Row) -> String) -> String {
    rows.iter().map(|r| r.map_or("—".into(), &f)).collect::<Vec<_>>().join(" · ")
}

/// A row's bias as the tables show it: its image mean's signed difference from the reference's,
/// in %, "⚠" where it lies beyond the reference's noise, and for a path row shallower than the
/// reference the depth that makes it converge to another image.
pub fn bias(scene: &SceneResult, r: &Row) -> String {
    let Some((relative, beyond)) = scene.bias(r) else { return "—".into() };
    let mut s = format!("{:+.2} %", 100.0 * relative);
    if beyond == Some(true) {
        s.push_str(" ⚠");
    }
    if scene.shallower_paths(r) {
        s.push_str(&format!(" (depth {} < {})", r.config.depth, scene.reference.depth));
    }
    s
}
