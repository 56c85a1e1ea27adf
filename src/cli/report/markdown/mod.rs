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
    let ranked: Vec<&Row> = s.rows.iter().filter(|r| !r.is_reference()).collect();
    let per_backend: Vec<(Backend, Vec<&Row>)> = [Backend::Cpu, Backend::Gpu]
        .into_iter()
        .map(|b| (b, ranked.iter().copied().filter(|r| r.config.backend == b).collect::<Vec<_>>()))
        .filter(|(_, rows)| !rows.is_empty())
        .collect();
    if per_backend.len() == 2 {
        equal::equal_time(md, &ranked, &per_backend);
        equal::equal_error(md, &ranked, &per_backend);
    }
    all_rows::all_rows(md, s);
}
