//! Durations in milliseconds, the unit of every time glint prints: the render table, the JSON,
//! PNG metadata, the report's CSV, tables and plot axes.

use std::time::Duration;

pub fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Throughput: millions of rays per second of `d`.
pub fn mrays_per_s(rays: u64, d: Duration) -> f64 {
    rays as f64 / d.as_secs_f64().max(1e-9) / 1e6
}

/// A CSV cell: four decimals (0.1 µs), the same for every row so the column sorts as text.
pub fn ms_csv(d: Duration) -> String {
    format!("{:.4}", ms(d))
}

/// A Markdown table cell: three or four significant digits, fewer decimals as times grow.
pub fn ms_cell(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A ray count as people read it: 950, 12.3 k, 4.56 M, 7.89 G.
pub fn count(n: u64) -> String {
    let n = n as f64;
    match n {
        n if n >= 1e9 => format!("{:.2} G", n / 1e9),
        n if n >= 1e6 => format!("{:.2} M", n / 1e6),
        n if n >= 1e3 => format!("{:.1} k", n / 1e3),
        n => format!("{n}"),
    }
}

/// "1 scene", "2 scenes": `n` and the noun, plural where `n` is not 1.
pub fn counted(n: usize, noun: &str) -> String {
    if n == 1 { format!("1 {noun}") } else { format!("{n} {noun}s") }
}
