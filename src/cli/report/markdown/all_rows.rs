//! "All configurations, fastest first": every row of one scene with its marks on the Pareto
//! fronts.

use std::fmt::Write as _;

use super::super::sweep::{Row, SceneResult};
use super::cells::{pct, psnr, sci};
use super::prose::{Block, prose};
use crate::cli::units::{ms, ms_cell};

pub fn all_rows(md: &mut String, s: &SceneResult) {
    md.push_str(&prose(Block::AllConfigurations, &[]));
    let _ = writeln!(
        md,
        "| | backend | spp | depth | bailout | shader | ε mode | render ms (min–max) | pipeline ms | Mrays/s \
         | rays/px | RMSE | relMSE | PSNR dB | FLIP | max abs | first-hit mismatch % | vs CPU twin | sweeps |"
    );
    let _ = writeln!(md, "|---|---|--:|--:|--:|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|");
    let mut rows: Vec<&Row> = s.rows.iter().collect();
    rows.sort_by_key(|r| r.median());
    for r in rows {
        let c = &r.config;
        let mark = if r.pareto_all {
            "★"
        } else if r.pareto_backend {
            "☆"
        } else {
            ""
        };
        let _ = writeln!(
            md,
            "| {mark} | {} | {} | {} | {} | {} | {} | {} ({}–{}) | {} | {:.2} | {:.2} | {} | {} | {} | {:.4} | {} | {} | {} | {} |",
            c.backend.name(),
            c.spp,
            c.depth,
            c.bailout.label(),
            if c.specialise { "specialised" } else { "full" },
            c.epsilon_mode.name(),
            ms_cell(r.median_ms()),
            ms_cell(ms(r.times[0])),
            ms_cell(ms(r.times[r.times.len() - 1])),
            r.gpu.map_or(String::new(), |g| ms_cell(ms(g.pipeline))),
            r.mrays(),
            r.counts.total() as f64 / s.pixels() as f64,
            sci(r.errors.rmse),
            sci(r.errors.rel_mse),
            psnr(r.errors.psnr),
            r.errors.flip_mean,
            sci(r.errors.max_abs),
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
