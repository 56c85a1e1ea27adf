//! "Self-intersection strategy": RMSE and first-hit mismatch per ε strategy.

use std::fmt::Write as _;

use glint_scene::EpsilonMode;

use super::super::plan::{Config, Group};
use super::super::sweep::{Row, SceneResult};
use super::cells::{eps, pct, sci};
use super::prose::{Block, prose};
use super::{backends, find};

pub fn epsilon_summary(md: &mut String, scenes: &[SceneResult]) {
    let modes = EpsilonMode::ALL;
    md.push_str(&prose(Block::Epsilon, &[]));
    let _ = writeln!(md, "| scene | ε | backend | {} |", modes.map(EpsilonMode::name).join(" | "));
    let _ = writeln!(md, "|---|--:|---|{}", "--:|".repeat(modes.len()));
    for s in scenes {
        for b in backends(scenes) {
            let eps_rows: Vec<&Row> =
                s.rows.iter().filter(|r| r.groups.contains(&Group::Epsilon) && r.config.backend == b).collect();
            let Some(first) = eps_rows.first() else { continue };
            let cells: Vec<String> = modes
                .iter()
                .map(|&m| {
                    find(s, &Config { epsilon_mode: m, ..first.config }).map_or("—".into(), |r| {
                        format!("{} ({} %)", sci(r.errors.rmse), pct(r.errors.first_hit_mismatch))
                    })
                })
                .collect();
            let _ = writeln!(md, "| {} | {} | {} | {} |", s.name, eps(s.settings.epsilon), b.name(), cells.join(" | "));
        }
    }
    let _ = writeln!(md);
}
