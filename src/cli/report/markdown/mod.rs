//! `report.md`: the set-up on top, summaries across scenes, then per scene the plot, the
//! equal-time and equal-error comparisons of CPU and GPU, and every configuration. One file per
//! section; the prose is in methodology.md.

mod all_rows;
mod bailout;
mod cells;
mod epsilon;
mod equal;
mod f32_floor;
mod header;
mod prose;
mod specialisation;
mod specular;

use std::fmt::Write as _;

use glint_core::Backend;

use super::plan::Config;
use super::sweep::{Row, SceneResult};
use crate::cli::units::ms_cell;
pub use header::Setup;

pub fn render_markdown(setup: &Setup, scenes: &[SceneResult]) -> String {
    let mut md = String::new();
    header::header(&mut md, setup, scenes);
    let _ = writeln!(md, "## Summary\n");
    f32_floor::f32_floor(&mut md, scenes);
    bailout::bailout_summary(&mut md, scenes);
    specialisation::shader_summary(&mut md, scenes);
    epsilon::epsilon_summary(&mut md, scenes);
    specular::specular_summary(&mut md, scenes);
    for scene in scenes {
        scene_section(&mut md, scene);
    }
    md
}

/// The row of `config` in `scene`, if the sweep measured it.
fn find<'a>(scene: &'a SceneResult, config: &Config) -> Option<&'a Row> {
    scene.rows.iter().find(|r| r.config == *config)
}

/// The backends that have rows, CPU first.
fn backends(scenes: &[SceneResult]) -> Vec<Backend> {
    let mut b: Vec<Backend> = scenes.iter().flat_map(|s| s.rows.iter().map(|r| r.config.backend)).collect();
    b.sort();
    b.dedup();
    b
}

fn scene_section(md: &mut String, s: &SceneResult) {
    let _ = writeln!(md, "## {}\n", s.name);
    if !s.description.is_empty() {
        let _ = writeln!(md, "{}\n", s.description.trim());
    }
    let _ = writeln!(
        md,
        "ε = {}, seed {}. The reference configuration renders in {} ms (median).\n",
        cells::eps(s.settings.epsilon),
        s.settings.seed,
        ms_cell(s.reference_ms())
    );
    for left_out in s.needs.left_out() {
        let _ = writeln!(md, "{left_out}\n");
    }
    let _ = writeln!(md, "![{0}: RMSE against render time](error_vs_time_{0}.png)\n", s.name);
    reference_noise(md, s);
    // A path row's RMSE mixes noise with the light a shallow depth leaves out: ranked by RMSE
    // alone, cornell-gi's equal time picked 16 spp at depth 3, 5 % dark. Only rows whose mean
    // lies within the reference's noise are ranked.
    let ranked: Vec<&Row> = s
        .rows
        .iter()
        .filter(|r| !r.is_reference() && s.bias(r).is_none_or(|(_, beyond)| beyond != Some(true)))
        .collect();
    let per_backend: Vec<(Backend, Vec<&Row>)> = [Backend::Cpu, Backend::Gpu]
        .into_iter()
        .map(|b| (b, ranked.iter().copied().filter(|r| r.config.backend == b).collect::<Vec<_>>()))
        .filter(|(_, rows)| !rows.is_empty())
        .collect();
    if per_backend.len() == 2 {
        equal::equal_time(md, s, &ranked, &per_backend);
        equal::equal_error(md, s, &ranked, &per_backend);
    }
    all_rows::all_rows(md, s);
}

/// A path-traced scene's reference: its renders' seeds and samples, its own noise, and what a
/// row's error against it holds (nothing for a Whitted scene, whose reference is one render).
fn reference_noise(md: &mut String, s: &SceneResult) {
    let Some(stats) = &s.reference_stats else { return };
    let seeds = match (stats.seeds.first(), stats.seeds.last()) {
        (Some(a), Some(b)) if a != b => format!("{a}–{b}"),
        (Some(a), _) => a.to_string(),
        _ => "none".into(),
    };
    let (lo, hi) = (stats.spp.iter().min().copied().unwrap_or(0), stats.spp.iter().max().copied().unwrap_or(0));
    let spp = if lo == hi { lo.to_string() } else { format!("{lo}–{hi}") };
    let own = find(s, &s.reference).map(|r| r.errors.rmse);
    md.push_str(&prose::prose(
        prose::Block::ReferenceNoise,
        &[
            ("renders", &stats.seeds.len()),
            ("seeds", &seeds),
            ("seed", &s.settings.seed),
            ("group_spp", &spp),
            ("spp", &stats.spp.iter().sum::<u32>()),
            ("noise", &cells::sci(stats.noise_rmse)),
            ("mean", &format!("{:.4}", stats.mean)),
            ("mean_se", &format!("{:.2}", 100.0 * stats.mean_se / stats.mean.abs().max(f64::MIN_POSITIVE))),
            ("own", &own.map_or("—".into(), cells::sci)),
            ("sigmas", &super::reference::BIAS_SIGMAS),
        ],
    ));
}
