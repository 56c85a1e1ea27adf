//! "Equal time" and "Equal error": CPU and GPU side by side, the best error each reaches within
//! a time budget and the least time each needs to reach an error.

use std::fmt::Write as _;

use glint_core::Backend;

use super::super::pareto::{Point, best_within, fastest_reaching, nice_levels, point};
use super::super::sweep::{Row, SceneResult};
use super::cells::{bias, sci};
use super::prose::{Block, prose};
use crate::cli::units::ms_cell;

fn points(rows: &[&Row]) -> Vec<Point> {
    rows.iter().map(|r| point(r)).collect()
}

pub fn equal_time(md: &mut String, s: &SceneResult, ranked: &[&Row], per_backend: &[(Backend, Vec<&Row>)]) {
    let all = points(ranked);
    let lo = all.iter().map(|p| p.time).fold(f64::INFINITY, f64::min);
    let hi = all.iter().map(|p| p.time).fold(0.0, f64::max);
    md.push_str(&prose(Block::EqualTime, &[]));
    let _ =
        writeln!(md, "| budget ms | CPU RMSE | CPU configuration | GPU RMSE | GPU configuration | GPU / CPU RMSE |");
    let _ = writeln!(md, "|--:|--:|---|--:|---|--:|");
    let mut budgets = nice_levels(lo, hi);
    // The slowest time as the last budget: the best each backend reaches in the whole sweep.
    if budgets.last().is_none_or(|&b| b < hi * (1.0 - 1e-9)) {
        budgets.push(hi);
    }
    for budget in budgets {
        let best: Vec<Option<&Row>> =
            per_backend.iter().map(|(_, rows)| best_within(&points(rows), budget).map(|i| rows[i])).collect();
        let cell = |r: Option<&Row>| {
            r.map_or(("—".into(), "—".into()), |r| {
                let c = r.config.describe(s.settings.integrator);
                (sci(r.errors.rmse), format!("{c} ({} ms; bias {})", ms_cell(r.median_ms()), bias(s, r)))
            })
        };
        let (ce, cc) = cell(best[0]);
        let (ge, gc) = cell(best[1]);
        let ratio = match (best[0], best[1]) {
            (Some(c), Some(g)) if c.errors.rmse > 0.0 => format!("{:.2}", g.errors.rmse / c.errors.rmse),
            _ => "—".into(),
        };
        let _ = writeln!(md, "| {} | {ce} | {cc} | {ge} | {gc} | {ratio} |", ms_cell(budget));
    }
    let _ = writeln!(md);
}

pub fn equal_error(md: &mut String, s: &SceneResult, ranked: &[&Row], per_backend: &[(Backend, Vec<&Row>)]) {
    let errors: Vec<f64> = ranked.iter().map(|r| r.errors.rmse).filter(|e| *e > 0.0).collect();
    let lo = errors.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = errors.iter().copied().fold(0.0, f64::max);
    md.push_str(&prose(Block::EqualError, &[]));
    let _ = writeln!(md, "| RMSE ≤ | CPU ms | CPU configuration | GPU ms | GPU configuration | GPU / CPU time |");
    let _ = writeln!(md, "|--:|--:|---|--:|---|--:|");
    for target in nice_levels(lo, hi).into_iter().rev() {
        let fastest: Vec<Option<&Row>> =
            per_backend.iter().map(|(_, rows)| fastest_reaching(&points(rows), target).map(|i| rows[i])).collect();
        let cell = |r: Option<&Row>| {
            r.map_or(("—".into(), "—".into()), |r| {
                let c = r.config.describe(s.settings.integrator);
                (ms_cell(r.median_ms()), format!("{c} (RMSE {}; bias {})", sci(r.errors.rmse), bias(s, r)))
            })
        };
        let (ct, cc) = cell(fastest[0]);
        let (gt, gc) = cell(fastest[1]);
        let ratio = match (fastest[0], fastest[1]) {
            (Some(c), Some(g)) => format!("{:.2}", g.median_ms() / c.median_ms()),
            _ => "—".into(),
        };
        let _ = writeln!(md, "| {} | {ct} | {cc} | {gt} | {gc} | {ratio} |", sci(target));
    }
    let _ = writeln!(md);
}
