//! The GPU view's render rate, as the status bar shows it.

use std::time::{Duration, Instant};

/// Renders per second from the completion times within the last two seconds. With fewer than
/// two (at the start, when idle) the rate the last render's GPU time allows, so the figure is
/// there from the first frame; and while a render has been running longer than that rate
/// implies, at most one over its running time, so a long render does not keep a stale rate.
pub(super) fn renders_per_second(
    now: Instant,
    completions: impl Iterator<Item = Instant>,
    last_ms: Option<f64>,
    running: Option<Duration>,
) -> Option<f64> {
    let recent: Vec<_> = completions.filter(|t| now - *t < Duration::from_secs(2)).collect();
    let measured = if recent.len() < 2 {
        last_ms.filter(|ms| *ms > 0.0).map(|ms| 1e3 / ms)
    } else {
        let span = (recent[recent.len() - 1] - recent[0]).as_secs_f64();
        (span > 0.0).then(|| (recent.len() - 1) as f64 / span)
    };
    match (measured, running.map(|d| d.as_secs_f64()).filter(|s| *s > 0.0)) {
        (Some(rate), Some(secs)) => Some(rate.min(1.0 / secs)),
        (None, Some(secs)) if secs >= 1.0 => Some(1.0 / secs),
        (rate, _) => rate,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_render_brings_the_rate_down_instead_of_keeping_the_last_one() {
        let now = Instant::now();
        let before = |ms: u64| now - Duration::from_millis(ms);
        // Idle after a 550 ms render: 1.8 fps, the stale figure.
        let idle = renders_per_second(now, std::iter::empty(), Some(550.0), None).unwrap();
        assert!((idle - 1.818).abs() < 1e-3, "{idle}");
        // 20 s into the next render: at most 0.05 fps.
        let long = renders_per_second(now, std::iter::empty(), Some(550.0), Some(Duration::from_secs(20))).unwrap();
        assert!((long - 0.05).abs() < 1e-9, "{long}");
        // Renders following each other: their rate, not lowered by the short one in flight.
        let steady = [before(1500), before(1000), before(500), before(0)].into_iter();
        let rate = renders_per_second(now, steady, Some(10.0), Some(Duration::from_millis(100))).unwrap();
        assert!((rate - 2.0).abs() < 1e-6, "{rate}");
    }
}
