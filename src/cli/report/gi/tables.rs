//! The report's Whitted-against-GI section: gi.csv, the Markdown per scene (the path tracer's
//! slope, when its error falls below Whitted's best, what Whitted's error is made of) and its
//! table.

use std::fmt::Write as _;

use glint_core::Backend;
use glint_scene::Integrator;

use super::kinds::kinds_sentence;
use super::{Ambient, GiResult, GiRow};
use crate::cli::units::ms;

/// The least-squares slope of log(error) against log(time) of the path tracer's rows on
/// `backend`; `None` with fewer than two.
pub fn path_slope(result: &GiResult, backend: Backend) -> Option<f64> {
    let points: Vec<(f64, f64)> = result
        .rows
        .iter()
        .filter(|r| r.integrator == Integrator::Path && r.backend == backend && r.rmse > 0.0)
        .map(|r| (ms(r.median).max(1e-6).ln(), r.rmse.ln()))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Errors this close, relative, are one: the GPU's f32 against the CPU's f64 of the same row
/// differ by rounding (1e-8 relative on highlights, 1e-3 on cornell-gi, whose GPU row ranked
/// 0.1 % better at twice the CPU's time), and the faster row is Whitted's best, not the one a
/// rounding favours. A chart tells nothing finer apart.
const SAME_ERROR: f64 = 0.01;

/// The fastest path row whose error is below Whitted's best, and Whitted's best: its least
/// error, the fastest of the rows within `SAME_ERROR` of it.
pub fn crossover(result: &GiResult) -> (Option<&GiRow>, Option<&GiRow>) {
    let whitted = || result.rows.iter().filter(|r| r.integrator == Integrator::Whitted);
    let least = whitted().map(|r| r.rmse).fold(f64::INFINITY, f64::min);
    let best_whitted =
        whitted().filter(|r| r.rmse <= least * (1.0 + SAME_ERROR)).min_by(|a, b| a.median.cmp(&b.median));
    (best_whitted.and_then(|w| first_path_below(result, w.rmse)), best_whitted)
}

/// The fastest path row whose error is below `rmse`.
fn first_path_below(result: &GiResult, rmse: f64) -> Option<&GiRow> {
    result
        .rows
        .iter()
        .filter(|r| r.integrator == Integrator::Path && r.rmse < rmse)
        .min_by(|a, b| a.median.cmp(&b.median))
}

pub const HEADER: &[&str] = &[
    "scene",
    "integrator",
    "backend",
    "spp",
    "max_depth",
    "ambient",
    "ambient_r",
    "ambient_g",
    "ambient_b",
    "render_ms_median",
    "rmse_vs_path_reference",
    "reference_spp",
    "reference_noise_rmse",
    "shard",
];

pub fn render_csv(results: &[GiResult]) -> String {
    let mut out = HEADER.join(",");
    out.push('\n');
    for g in results {
        for r in &g.rows {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{:e},{},{:e},{}",
                g.scene,
                r.integrator.name(),
                r.backend.name(),
                r.spp,
                r.depth,
                r.ambient.map_or("", Ambient::name),
                r.ambient_rgb.map_or(",,".to_string(), |a| format!("{:e},{:e},{:e}", a[0], a[1], a[2])),
                crate::cli::units::ms_csv(r.median),
                r.rmse,
                g.reference_spp,
                g.reference_noise,
                g.shard.map_or(String::new(), |s| s.to_string())
            );
        }
    }
    out
}

/// The depth and samples of the fitted row `GiResult::fitted` belongs to: the deepest, most
/// sampled Whitted row's.
fn deepest_fit(g: &GiResult) -> Option<(u32, u32)> {
    g.rows.iter().filter(|r| r.ambient == Some(Ambient::Fitted)).map(|r| (r.depth, r.spp)).max()
}

/// The report's section: per scene, the fitted ambient, the path tracer's slope and the time
/// its error falls below Whitted's best, and the table.
pub fn render_markdown(results: &[GiResult]) -> String {
    let mut md = String::from(
        "\n## Whitted against global illumination\n\nEach scene's Whitted images and path-traced images are \
         held against a path-traced reference (eight CPU renders with consecutive seeds, averaged; the spread \
         between them estimates the reference's own noise, which every row's squared error includes on average, \
         so rows approach it as their own noise falls; the estimate is itself uncertain where fireflies dominate). \
         Whitted's rows come with the \
         ambient term as the scene writes it, without it, and fitted to the reference (the I_a per channel that \
         minimises Whitted's error at the row's own depth and samples, `glint_core::ambient_fit`). gi.csv has every \
         row, with the I_a it rendered with.\n",
    );
    // Three decimals, as a class reads an I_a; a fit of a scene whose k_a is tiny may be large.
    let one = |x: f64| if x.abs() < 1e6 { format!("{x:.3}") } else { format!("{x:.3e}") };
    let fmt3 = |v: [f64; 3]| format!("({}, {}, {})", one(v[0]), one(v[1]), one(v[2]));
    for g in results {
        let fitted = if g.fit_determined {
            fmt3(g.fitted)
        } else {
            "none (I_a changes no pixel: no material in view has k_a)".to_string()
        };
        let _ = writeln!(
            md,
            "\n### {}\n\nReference: {} paths a pixel, depth {}, its noise {:.2e} RMSE. Ambient as written {}, fitted {fitted}{}.",
            g.scene,
            g.reference_spp,
            g.reference_depth,
            g.reference_noise,
            fmt3(g.written),
            deepest_fit(g).filter(|_| g.fit_determined).map_or(String::new(), |(depth, spp)| format!(
                " at depth {depth}, {spp} spp (each fitted row at its own: gi.csv)"
            )),
        );
        if let Some(problem) = &g.gain_warning {
            let _ = writeln!(
                md,
                "**Warning:** {problem}. The reference, at depth {}, carries that growth, and so do the fitted ambient \
                 and every error against the reference.",
                g.reference_depth
            );
        }
        for backend in [Backend::Cpu, Backend::Gpu] {
            if let Some(slope) = path_slope(g, backend) {
                let _ = writeln!(
                    md,
                    "The path tracer's error against time on the {}: slope {slope:.2} in log-log (−0.5 where noise \
                     dominates; flatter as it nears the reference's noise).",
                    backend.name()
                );
            }
        }
        let _ = writeln!(md, "{}", kinds_sentence(g));
        let (first, best) = crossover(g);
        match (first, best) {
            (Some(p), Some(w)) => {
                let _ = writeln!(
                    md,
                    "Paths beat Whitted's best ({} {} spp depth {}, ambient {}: RMSE {:.3e} in {:.1} ms) from {} {} spp \
                     (RMSE {:.3e} in {:.1} ms).",
                    w.backend.name(),
                    w.spp,
                    w.depth,
                    w.ambient.map_or("", Ambient::name),
                    w.rmse,
                    ms(w.median),
                    p.backend.name(),
                    p.spp,
                    p.rmse,
                    ms(p.median)
                );
            }
            (None, Some(w)) if w.rmse == 0.0 => {
                let _ = writeln!(md, "Whitted's best is the reference exactly (RMSE 0): no path row can beat it.");
            }
            (None, Some(w)) => {
                let _ = writeln!(md, "Paths do not beat Whitted's best (RMSE {:.3e}) within the sweep.", w.rmse);
            }
            _ => {}
        }
        // Below what Whitted's model leaves out, which no number of its samples removes.
        let k = &g.kinds;
        if k.whitted_rmse > 0.0 {
            let below = first_path_below(g, k.whitted_rmse);
            let converged =
                format!("Whitted's error at {} spp, depth {} ({:.3e})", k.whitted_spp, k.whitted_depth, k.whitted_rmse);
            let _ = match below {
                Some(p) => writeln!(
                    md,
                    "Paths go below {converged}, which no number of Whitted's samples removes, from {} {} spp (RMSE \
                     {:.3e} in {:.1} ms).",
                    p.backend.name(),
                    p.spp,
                    p.rmse,
                    ms(p.median)
                ),
                None => writeln!(md, "No path row of the sweep goes below {converged}."),
            };
        }
        md.push_str("\n| integrator | backend | spp | depth | ambient | ms (median) | RMSE vs reference |\n|---|---|---|---|---|---|---|\n");
        for r in &g.rows {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {:.2} | {:.3e} |",
                r.integrator.name(),
                r.backend.name(),
                r.spp,
                r.depth,
                r.ambient.map_or("—", Ambient::name),
                ms(r.median),
                r.rmse
            );
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;
    use crate::cli::report::gi::KindSplit;

    fn row(integrator: Integrator, backend: Backend, ms: u64, rmse: f64) -> GiRow {
        let ambient = (integrator == Integrator::Whitted).then_some(Ambient::Fitted);
        GiRow {
            integrator,
            backend,
            spp: 1,
            depth: 5,
            ambient,
            ambient_rgb: None,
            median: Duration::from_millis(ms),
            rmse,
        }
    }

    #[test]
    fn whitteds_best_is_the_fastest_of_the_rows_rounding_alone_tells_apart() {
        let rows = vec![
            row(Integrator::Whitted, Backend::Gpu, 35, 0.5),
            row(Integrator::Whitted, Backend::Cpu, 19, 0.5 * (1.0 + 1e-3)),
            row(Integrator::Whitted, Backend::Cpu, 10, 0.6),
            row(Integrator::Path, Backend::Cpu, 40, 0.45),
        ];
        let result = super::super::result_for_tests(rows, KindSplit::default());
        let (first, best) = crossover(&result);
        let best = best.expect("a Whitted row");
        assert_eq!((best.backend, best.median), (Backend::Cpu, Duration::from_millis(19)));
        assert_eq!(first.map(|r| r.rmse), Some(0.45));
    }
}
