//! Pareto fronts in (time, error) and the equal-time / equal-error selections.
//!
//! A point is Pareto-optimal when no other point is at least as fast and at least as accurate
//! and strictly better in one of the two (here: with a 1 % tolerance on the error). Both
//! coordinates are "lower is better".

use glint_core::Backend;

use super::sweep::Row;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    pub time: f64,
    pub error: f64,
}

impl Point {
    fn usable(&self) -> bool {
        self.time.is_finite() && self.error.is_finite()
    }
}

/// A row as a point: median render time (ms) and RMSE. Reference rows are not ranked (NaN):
/// the CPU one has error 0 by construction; nor are rows that lost work, whose time and
/// error are not those of their configuration.
pub fn point(row: &Row) -> Point {
    let error = if row.is_reference() || row.dropped_work() { f64::NAN } else { row.errors.rmse };
    Point { time: row.median_ms(), error }
}

/// Sets `pareto_all` (front of every ranked row) and `pareto_backend` (front of its backend's).
pub fn mark_fronts(rows: &mut [Row]) {
    let points: Vec<Point> = rows.iter().map(point).collect();
    for i in front(&points) {
        rows[i].pareto_all = true;
    }
    for backend in [Backend::Cpu, Backend::Gpu] {
        let own: Vec<Point> = rows
            .iter()
            .map(|r| if r.config.backend == backend { point(r) } else { Point { time: f64::NAN, error: f64::NAN } })
            .collect();
        for i in front(&own) {
            rows[i].pareto_backend = true;
        }
    }
}

/// An error must beat every faster point's by more than this fraction to count as better:
/// differences of a fraction of a percent (f32 against f64 at the same settings) would
/// otherwise put invisible steps into the front.
pub const ERROR_TOLERANCE: f64 = 0.01;

/// Indices of the non-dominated points, fastest first: the points whose error is lower, by
/// more than `ERROR_TOLERANCE`, than that of every faster point. Of duplicates the first is kept.
pub fn front(points: &[Point]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len()).filter(|&i| points[i].usable()).collect();
    order.sort_by(|&a, &b| {
        points[a].time.total_cmp(&points[b].time).then(points[a].error.total_cmp(&points[b].error)).then(a.cmp(&b))
    });
    let mut best = f64::INFINITY;
    let mut out = Vec::new();
    for i in order {
        // Sorted by time, a point is non-dominated iff it beats every faster point's error.
        if points[i].error < best * (1.0 - ERROR_TOLERANCE) {
            best = points[i].error;
            out.push(i);
        }
    }
    out
}

/// The most accurate point that renders within `budget`; of those within `ERROR_TOLERANCE` of
/// the best error, the fastest (a 0.1 % gain is not worth twice the time).
pub fn best_within(points: &[Point], budget: f64) -> Option<usize> {
    let within = || (0..points.len()).filter(|&i| points[i].usable() && points[i].time <= budget);
    let best = within().map(|i| points[i].error).min_by(f64::total_cmp)?;
    within()
        .filter(|&i| points[i].error <= best * (1.0 + ERROR_TOLERANCE))
        .min_by(|&a, &b| points[a].time.total_cmp(&points[b].time).then(points[a].error.total_cmp(&points[b].error)))
}

/// The fastest point whose error is at most `target` (ties: the more accurate).
pub fn fastest_reaching(points: &[Point], target: f64) -> Option<usize> {
    (0..points.len())
        .filter(|&i| points[i].usable() && points[i].error <= target)
        .min_by(|&a, &b| points[a].time.total_cmp(&points[b].time).then(points[a].error.total_cmp(&points[b].error)))
}

/// "Nice" levels 1, 2, 5 × 10^k from the first at or above `lo` to the last at or below `hi`
/// (for time budgets and error targets that read well in a table).
pub fn nice_levels(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi >= lo && hi.is_finite()) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut decade = 10f64.powi(lo.log10().floor() as i32);
    while decade <= hi {
        for m in [1.0, 2.0, 5.0] {
            let v = m * decade;
            // Relative slack so that a level equal to an end point is not lost to rounding.
            if v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9) {
                out.push(v);
            }
        }
        decade *= 10.0;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(time: f64, error: f64) -> Point {
        Point { time, error }
    }

    #[test]
    fn front_keeps_exactly_the_non_dominated_points() {
        let pts = [p(1.0, 0.5), p(2.0, 0.6), p(2.0, 0.2), p(4.0, 0.1), p(3.0, 0.3), p(5.0, 0.1), p(0.5, f64::NAN)];
        // (2, 0.6) is dominated by (1, 0.5); (3, 0.3) by (2, 0.2); (5, 0.1) by (4, 0.1).
        assert_eq!(front(&pts), vec![0, 2, 3]);
        assert_eq!(front(&[]), Vec::<usize>::new());
        assert_eq!(front(&[p(1.0, 1.0), p(1.0, 1.0)]), vec![0]);
        // 0.5 % better is not better.
        assert_eq!(front(&[p(1.0, 1.0), p(2.0, 0.995), p(3.0, 0.9)]), vec![0, 2]);
    }

    #[test]
    fn equal_time_and_equal_error_selections() {
        let pts = [p(1.0, 0.5), p(2.0, 0.2), p(4.0, 0.1), p(8.0, 0.1)];
        assert_eq!(best_within(&pts, 0.5), None);
        assert_eq!(best_within(&pts, 1.0), Some(0));
        assert_eq!(best_within(&pts, 3.0), Some(1));
        assert_eq!(best_within(&pts, 100.0), Some(2));
        // Within 1 % of the best error, the faster wins.
        assert_eq!(best_within(&[p(1.0, 0.1005), p(2.0, 0.1)], 5.0), Some(0));
        assert_eq!(best_within(&[p(1.0, 0.102), p(2.0, 0.1)], 5.0), Some(1));
        assert_eq!(fastest_reaching(&pts, 0.05), None);
        assert_eq!(fastest_reaching(&pts, 0.1), Some(2));
        assert_eq!(fastest_reaching(&pts, 0.3), Some(1));
    }

    #[test]
    fn nice_levels_are_1_2_5_and_inclusive() {
        assert_eq!(nice_levels(1.0, 10.0), vec![1.0, 2.0, 5.0, 10.0]);
        let v = nice_levels(0.0031, 0.06);
        assert_eq!(v.len(), 4, "{v:?}");
        assert!((v[0] - 0.005).abs() < 1e-15 && (v[3] - 0.05).abs() < 1e-15, "{v:?}");
        assert!(nice_levels(0.0, 1.0).is_empty());
        assert!(nice_levels(2.0, 1.0).is_empty());
    }
}
