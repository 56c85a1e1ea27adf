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
    let paths: Vec<&str> = scenes
        .iter()
        .filter(|s| s.settings.integrator == Integrator::Path && find(s, &s.reference.on(Backend::Gpu)).is_some())
        .map(|s| s.name.as_str())
        .collect();
    if !paths.is_empty() {
        md.push_str(&prose(Block::F32FloorPaths, &[("scenes", &paths.join(", "))]));
    }
}
