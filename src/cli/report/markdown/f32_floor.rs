//! "The f32 floor of the GPU": per scene, the GPU's error at the reference settings against
//! its error relative to its CPU twins.

use std::fmt::Write as _;

use glint_core::Backend;
use glint_scene::{EpsilonMode, Integrator};

use super::super::sweep::SceneResult;
use super::cells::{psnr, sci};
use super::prose::{Block, prose};
use super::{backends, find};
use crate::cli::units::ms_cell;

pub fn f32_floor(md: &mut String, scenes: &[SceneResult]) {
    if !backends(scenes).contains(&Backend::Gpu) {
        return;
    }
    let whitted: Vec<&SceneResult> = scenes
        .iter()
        .filter(|s| s.settings.integrator == Integrator::Whitted && find(s, &s.reference.on(Backend::Gpu)).is_some())
        .collect();
    if !whitted.is_empty() {
        floor(md, &whitted);
    }
    parity(md, scenes);
}

/// Whitted scenes: the GPU's error at the reference settings, its f32 floor.
fn floor(md: &mut String, scenes: &[&SceneResult]) {
    md.push_str(&prose(Block::F32Floor, &[]));
    let _ = writeln!(
        md,
        "| scene | reference render (CPU) ms | GPU at reference settings: RMSE | PSNR dB | its rays vs CPU % \
         | GPU vs CPU twin RMSE, median (min–max) | lowest CPU RMSE of the sweep (reference excluded) |"
    );
    let _ = writeln!(md, "|---|--:|--:|--:|--:|--:|--:|");
    let mut notes = Vec::new();
    for s in scenes {
        let Some(g) = find(s, &s.reference.on(Backend::Gpu)) else { continue };
        let mut twins: Vec<f64> = s
            .rows
            .iter()
            .filter(|r| r.config.epsilon_mode == EpsilonMode::Robust && !r.dropped_work())
            .filter_map(|r| r.twin_rmse)
            .collect();
        twins.sort_by(f64::total_cmp);
        let twin = match twins.as_slice() {
            [] => "—".into(),
            t => format!("{} ({}–{})", sci(t[t.len() / 2]), sci(t[0]), sci(t[t.len() - 1])),
        };
        let cpu_best = s
            .rows
            .iter()
            .filter(|r| r.config.backend == Backend::Cpu && !r.is_reference())
            .map(|r| r.errors.rmse)
            .min_by(f64::total_cmp)
            .map_or("—".into(), sci);
        let rays = g.twin_rays_pct.map_or("—".into(), |p| format!("{p:+.3}"));
        let _ = writeln!(
            md,
            "| {} | {} | {}{} | {} | {} | {} | {} |",
            s.name,
            ms_cell(s.reference_ms()),
            sci(g.errors.rmse),
            if g.dropped_work() { " ⚠" } else { "" },
            psnr(g.errors.psnr),
            rays,
            twin,
            cpu_best
        );
        if g.dropped_work() {
            let status = match g.gpu.map_or(0, |x| x.status) {
                0 => "no status flag raised".to_string(),
                f => format!("status flags {f}"),
            };
            notes.push(prose(
                Block::F32FloorDroppedWork,
                &[
                    ("scene", &s.name),
                    ("rays", &rays),
                    ("camera_rays", &g.counts.camera),
                    ("camera_expected", &g.camera_expected),
                    ("status", &status),
                ],
            ));
        }
    }
    let _ = writeln!(md);
    for n in notes {
        md.push_str(&n);
    }
}

/// Path-traced scenes: the GPU against its CPU twin at the reference settings and the rows'
/// seed, which agree sample for sample until f32 and f64 round a bounce apart. A check that the
/// tracers implement one estimator, not an error against the reference (which is independent).
fn parity(md: &mut String, scenes: &[SceneResult]) {
    let paths: Vec<&SceneResult> = scenes
        .iter()
        .filter(|s| s.settings.integrator == Integrator::Path && find(s, &s.reference.on(Backend::Gpu)).is_some())
        .collect();
    if paths.is_empty() {
        return;
    }
    let names: Vec<&str> = paths.iter().map(|s| s.name.as_str()).collect();
    md.push_str(&prose(Block::F32FloorPaths, &[("scenes", &names.join(", "))]));
    let _ = writeln!(
        md,
        "| scene | parity: GPU vs CPU at the reference settings, same seed, RMSE | its rays vs CPU % \
         | the reference's own noise, RMSE | GPU at the reference settings against the reference, RMSE |"
    );
    let _ = writeln!(md, "|---|--:|--:|--:|--:|");
    for s in paths {
        let Some(g) = find(s, &s.reference.on(Backend::Gpu)) else { continue };
        let _ = writeln!(
            md,
            "| {} | {}{} | {} | {} | {} |",
            s.name,
            g.twin_rmse.map_or("—".into(), sci),
            if g.dropped_work() { " ⚠ lost work" } else { "" },
            g.twin_rays_pct.map_or("—".into(), |p| format!("{p:+.3}")),
            s.reference_stats.as_ref().map_or("—".into(), |r| sci(r.noise_rmse)),
            sci(g.errors.rmse),
        );
    }
    let _ = writeln!(md);
}
