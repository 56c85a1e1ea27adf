//! "All configurations, fastest first": every row of one scene with its marks on the Pareto
//! fronts.

use std::fmt::Write as _;

use super::super::sweep::{Row, SceneResult};
use super::cells::{bias, error, pct, psnr, sci};
use super::prose::{Block, prose};
use crate::cli::units::{ms, ms_cell};

pub fn all_rows(md: &mut String, s: &SceneResult) {
    md.push_str(&prose(Block::AllConfigurations, &[]));
    let _ = writeln!(
        md,
        "| | backend | spp | depth | bailout | shader | ε mode | render ms (min–max) | pipeline ms | Mrays/s \
         | rays/px | RMSE | bias (mean vs reference) | relMSE | PSNR dB | FLIP | max abs | first-hit mismatch % \
         | vs CPU twin | sweeps |"
    );
    let _ = writeln!(md, "|---|---|--:|--:|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|");
    let mut rows: Vec<&Row> = s.rows.iter().collect();
    rows.sort_by_key(|r| r.median());
    for r in rows {
        let c = &r.config;
        let front = if r.pareto_all {
            "★"
        } else if r.pareto_backend {
            "☆"
        } else {
            ""
        };
        let mark = match flag(r) {
            Some(why) => format!("{front} ⚠ {why}").trim_start().to_string(),
            None => front.to_string(),
        };
        let _ = writeln!(
            md,
            "| {mark} | {} | {} | {} | {} | {} | {} | {} ({}–{}) | {} | {:.2} | {:.2} | {} | {} | {} | {} | {:.4} | {} | {} | {} | {} |",
            c.backend.name(),
            c.spp,
            c.depth,
            c.bailout_label(s.settings.integrator),
            if c.specialise { "specialised" } else { "full" },
            c.epsilon_mode.name(),
            ms_cell(r.median_ms()),
            ms_cell(ms(r.times[0])),
            ms_cell(ms(r.times[r.times.len() - 1])),
            r.gpu.map_or(String::new(), |g| ms_cell(ms(g.pipeline))),
            r.mrays(),
            r.counts.total() as f64 / s.pixels() as f64,
            error(r.errors.rmse),
            bias(s, r),
            error(r.errors.rel_mse),
            psnr(r.errors.psnr),
            r.errors.flip_mean,
            error(r.errors.max_abs),
            pct(r.errors.first_hit_mismatch),
            r.twin_rmse.map_or(String::new(), |t| if r.dropped_work() {
                format!(
                    "{} ⚠ rays {:+.3} %, camera rays {:+}, status {}",
                    sci(t),
                    r.twin_rays_pct.unwrap_or_default(),
                    r.counts.camera as i64 - r.camera_expected as i64,
                    r.gpu.map_or(0, |g| g.status)
                )
            } else if r.rays_diverge() {
                format!("{} (rays {:+.3} %)", sci(t), r.twin_rays_pct.unwrap_or_default())
            } else {
                sci(t)
            }),
            r.groups.iter().map(|g| g.name()).collect::<Vec<_>>().join(", ")
        );
    }
    let _ = writeln!(md);
}

/// Why a row is not a valid measurement, if it is not: it lost work (a GPU status flag, or
/// fewer camera rays than samples), or its error is not a finite number.
pub fn flag(r: &Row) -> Option<&'static str> {
    if r.dropped_work() {
        Some("incomplete")
    } else if !(r.errors.rmse.is_finite() && r.errors.rel_mse.is_finite() && r.errors.max_abs.is_finite())
        || r.errors.psnr.is_nan()
        || r.errors.psnr == f64::NEG_INFINITY
    {
        Some("error not finite")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use glint_core::Backend;
    use glint_core::compare::ImageErrors;
    use glint_core::cpu::RayCounts;
    use glint_scene::{EpsilonMode, RenderSettings};

    use super::super::super::plan::{Bailout, Config, Group, SceneNeeds};
    use super::super::super::sweep::{GpuExtra, Row, SceneResult};
    use super::*;

    fn row(rmse: f64, psnr: f64, status: u32) -> Row {
        let config = Config {
            backend: Backend::Gpu,
            spp: 1,
            depth: 5,
            bailout: Bailout::Per255,
            specialise: true,
            epsilon_mode: EpsilonMode::Robust,
        };
        let counts = RayCounts { camera: 4, ..RayCounts::default() };
        let gpu = GpuExtra { pipeline: Duration::from_millis(1), statements: 1, status };
        Row {
            config,
            groups: vec![Group::Grid],
            times: vec![Duration::from_millis(2)],
            counts,
            gpu: Some(gpu),
            errors: ImageErrors { rmse, psnr, ..ImageErrors::default() },
            mean: 0.5,
            twin_rmse: None,
            twin_rays_pct: None,
            camera_expected: 4,
            same_as_specialised: None,
            pareto_all: false,
            pareto_backend: false,
            shard: None,
        }
    }

    fn table(rows: Vec<Row>) -> String {
        let settings = RenderSettings { width: 2, height: 2, ..RenderSettings::default() };
        let reference = rows[0].config;
        let scene = SceneResult {
            name: "s".into(),
            description: String::new(),
            settings,
            reference,
            reference_stats: None,
            needs: SceneNeeds {
                integrator: glint_scene::Integrator::Whitted,
                recurses: true,
                bailout_cuts: true,
                specular: true,
            },
            rows,
            specular: Vec::new(),
        };
        let mut md = String::new();
        all_rows(&mut md, &scene);
        md
    }

    #[test]
    fn incomplete_rows_and_errors_that_are_not_finite_are_flagged_never_tabulated_plainly() {
        assert_eq!(flag(&row(0.1, 20.0, 0)), None);
        assert_eq!(flag(&row(0.1, 20.0, glint_types::layout::STATUS_DRIVER_LOOP_CUTOFF)), Some("incomplete"));
        assert_eq!(flag(&row(f64::INFINITY, f64::NEG_INFINITY, 0)), Some("error not finite"));
        let md = table(vec![row(0.1, 20.0, 0), row(0.1, 20.0, 2), row(f64::INFINITY, f64::NEG_INFINITY, 0)]);
        let lines: Vec<&str> = md.lines().filter(|l| l.starts_with("| ") && l.contains("| gpu |")).collect();
        assert_eq!(lines.len(), 3, "{md}");
        assert_eq!(lines.iter().filter(|l| l.starts_with("| ⚠ incomplete |")).count(), 1, "{md}");
        let overflow = lines.iter().find(|l| l.starts_with("| ⚠ error not finite |")).expect("flagged");
        assert!(overflow.contains("| ⚠ inf | ") && overflow.contains("| ⚠ -inf |"), "{overflow}");
        // An image equal to the reference says so instead of a bare "inf".
        assert_eq!(psnr(f64::INFINITY), "∞ (identical)");
        assert_eq!(psnr(f64::NAN), "⚠ NaN");
        assert_eq!(error(f64::NAN), "⚠ NaN");
        assert_eq!(error(1.5e-3), "1.50e-3");
    }
}
