//! "What the bailout saves": rays, time and error at bailout 0, 1/255 and 1/32.

use std::fmt::Write as _;

use super::super::plan::{Bailout, Config, Group};
use super::super::sweep::{Row, SceneResult};
use super::cells::{sci, triple};
use super::prose::{Block, prose};
use super::{backends, find};
use crate::cli::units::ms_cell;
use glint_scene::Integrator;

pub fn bailout_summary(md: &mut String, scenes: &[SceneResult]) {
    // The deepest, most sampled configuration of the bailout sweep: where the bailout matters most.
    let base = scenes
        .iter()
        .flat_map(|s| &s.rows)
        .filter(|r| r.groups.contains(&Group::Bailout))
        .map(|r| r.config)
        .max_by_key(|c| (c.depth, c.spp));
    // The bailout prunes Whitted's child rays only, so the sweep leaves out the bailout rows of
    // a path scene, of a scene without child rays and of one whose weights no bailout of the
    // sweep reaches (`Planned::groups_for`).
    let (left_out, whitted): (Vec<&SceneResult>, Vec<&SceneResult>) = scenes
        .iter()
        .partition(|s| s.needs.integrator == Integrator::Path || !s.needs.recurses || !s.needs.bailout_cuts);
    match base {
        Some(base) => md.push_str(&prose(Block::Bailout, &[("spp", &base.spp), ("depth", &base.depth)])),
        // Every scene left the sweep out: the heading, then why.
        None if !left_out.is_empty() => md.push_str("### What the bailout saves\n\n"),
        None => return,
    }
    if let Some(base) = base
        && !whitted.is_empty()
    {
        saving_table(md, scenes, &whitted, base);
    }
    let _ = writeln!(md);
    let names = |path: bool| -> Vec<&str> {
        left_out.iter().filter(|s| (s.needs.integrator == Integrator::Path) == path).map(|s| s.name.as_str()).collect()
    };
    let (paths, whitted_left_out) = (names(true), names(false));
    let uncut = |name: &&str| left_out.iter().any(|s| s.name == *name && s.needs.recurses);
    let (uncut, flat): (Vec<&str>, Vec<&str>) = whitted_left_out.into_iter().partition(uncut);
    if !paths.is_empty() {
        let _ = writeln!(
            md,
            "Left out: {}, whose paths end by Russian roulette, which the bailout does not change \
             (`glint render --integrator path --bailout` is refused): {} rows are the grid's, at bailout \
             1/255.\n",
            paths.join(", "),
            if paths.len() == 1 { "its" } else { "their" }
        );
    }
    if !flat.is_empty() {
        let _ = writeln!(
            md,
            "Left out: {}, where no material an object uses has k_r or k_t: no ray goes past the camera's, so the \
             bailout has nothing to prune.\n",
            flat.join(", ")
        );
    }
    if !uncut.is_empty() {
        let _ = writeln!(
            md,
            "Left out: {}, where every k_r and k_t an object has keeps a path's weight above each bailout of the \
             sweep at its depths: no bailout cuts a ray, so each would render the grid's image, at bailout 1/255, \
             again, and the times would differ only by noise.\n",
            uncut.join(", ")
        );
    }
}

/// Rays, time and error of each Whitted scene with child rays at bailout 0 · 1/255 · 1/32, at
/// `base`'s other settings, per backend.
fn saving_table(md: &mut String, scenes: &[SceneResult], whitted: &[&SceneResult], base: Config) {
    let px = |s: &SceneResult| s.pixels() as f64;
    let _ = writeln!(md, "| scene | backend | rays per pixel | render ms | RMSE |");
    let _ = writeln!(md, "|---|---|--:|--:|--:|");
    for s in whitted {
        for b in backends(scenes) {
            let rows: Vec<Option<&Row>> = [Bailout::Off, Bailout::Per255, Bailout::Per32]
                .iter()
                .map(|&bailout| find(s, &Config { bailout, backend: b, ..base }))
                .collect();
            if rows.iter().all(Option::is_none) {
                continue;
            }
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} |",
                s.name,
                b.name(),
                triple(&rows, |r| format!("{:.2}", r.counts.total() as f64 / px(s))),
                triple(&rows, |r| ms_cell(r.median_ms())),
                triple(&rows, |r| sci(r.errors.rmse))
            );
        }
    }
}
