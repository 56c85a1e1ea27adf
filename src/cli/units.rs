//! Durations in milliseconds, the unit of every time glint prints: the render table, the JSON,
//! PNG metadata, the report's CSV, tables and plot axes.

use std::time::Duration;

/// The median of timed runs, one definition for every table and the JSON: the middle run, or
/// the mean of the two middle runs of an even count (the upper of the two was taken: with two
/// runs, the slower; a tester). Zero for no runs.
pub fn median(times: &[Duration]) -> Duration {
    let mut sorted = times.to_vec();
    sorted.sort();
    match sorted.len() {
        0 => Duration::ZERO,
        n if n % 2 == 1 => sorted[n / 2],
        n => (sorted[n / 2 - 1] + sorted[n / 2]) / 2,
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_of_an_even_count_is_the_mean_of_the_two_middle_runs() {
        let ms = Duration::from_millis;
        assert_eq!(median(&[]), Duration::ZERO);
        assert_eq!(median(&[ms(7)]), ms(7));
        assert_eq!(median(&[ms(9), ms(1), ms(5)]), ms(5));
        assert_eq!(median(&[ms(1), ms(9)]), ms(5));
        assert_eq!(median(&[ms(4), ms(1), ms(100), ms(2)]), ms(3));
    }
}
