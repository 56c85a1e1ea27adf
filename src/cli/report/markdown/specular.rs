//! "The seed's claim: what each specular model costs": render time per specular model, every
//! material set to it, on each backend, with the ray counts that show the work is the same.

use std::fmt::Write as _;

use glint_scene::SpecularModel;

use super::super::specular::{DEPTH, SPP};
use super::super::sweep::SceneResult;
use super::super::sweep::SpecularRow;
use super::backends;
use super::prose::{Block, prose};
use crate::cli::units::{count, ms, ms_cell};

pub fn specular_summary(md: &mut String, scenes: &[SceneResult]) {
    // A scene without a specular lobe is not measured (`SceneNeeds::specular`): its three models
    // render one image with one shader, and a Cook–Torrance / Blinn ratio of it was noise.
    let left_out: Vec<&str> = scenes.iter().filter(|s| !s.needs.specular).map(|s| s.name.as_str()).collect();
    if scenes.iter().all(|s| s.specular.is_empty()) {
        if !left_out.is_empty() {
            let _ = writeln!(md, "### The seed's claim: what each specular model costs\n");
            left_out_sentence(md, &left_out);
        }
        return;
    }
    md.push_str(&prose(Block::Specular, &[("spp", &SPP), ("depth", &DEPTH)]));
    let models = SpecularModel::ALL;
    let names = models.map(SpecularModel::label).join(" · ");
    let _ = writeln!(
        md,
        "| scene | backend | rays {names} | same rays | render ms, median (min–max): {} | Cook–Torrance / Blinn \
         | pipeline ms {names} | shader statements {names} |",
        models.map(SpecularModel::label).join(" | ")
    );
    let _ = writeln!(md, "|---|---|--:|---|{}--:|--:|--:|", "--:|".repeat(models.len()));
    for s in scenes {
        for b in backends(scenes) {
            let rows: Vec<Option<&SpecularRow>> =
                models.iter().map(|&m| s.specular.iter().find(|r| r.model == m && r.config.backend == b)).collect();
            if rows.iter().all(Option::is_none) {
                continue;
            }
            let each = |f: &dyn Fn(&SpecularRow) -> String| {
                rows.iter().map(|r| r.map_or("—".into(), f)).collect::<Vec<_>>().join(" · ")
            };
            let totals: Vec<Option<u64>> = rows.iter().map(|r| r.map(|r| r.counts.total())).collect();
            let same = if totals.windows(2).all(|w| w[0] == w[1] && w[0].is_some()) { "yes" } else { "**no**" };
            let times: Vec<String> = rows
                .iter()
                .map(|r| {
                    r.map_or("—".into(), |r| {
                        let (lo, hi) = (ms(r.times[0]), ms(r.times[r.times.len() - 1]));
                        format!("{} ({}–{})", ms_cell(r.median_ms()), ms_cell(lo), ms_cell(hi))
                    })
                })
                .collect();
            let ratio = match (rows[0], rows[models.len() - 1]) {
                (Some(blinn), Some(ct)) => format!("{:.2}", ct.median_ms() / blinn.median_ms()),
                _ => "—".into(),
            };
            let gpu = |f: &dyn Fn(&SpecularRow) -> Option<String>| {
                if rows.iter().flatten().any(|r| r.gpu.is_some()) {
                    each(&|r| f(r).unwrap_or("—".into()))
                } else {
                    "—".into()
                }
            };
            let _ = writeln!(
                md,
                "| {} | {} | {} | {same} | {} | {ratio} | {} | {} |",
                s.name,
                b.name(),
                each(&|r| count(r.counts.total())),
                times.join(" | "),
                gpu(&|r| r.gpu.map(|g| ms_cell(ms(g.pipeline)))),
                gpu(&|r| r.gpu.map(|g| g.statements.to_string())),
            );
        }
    }
    let _ = writeln!(md);
    if !left_out.is_empty() {
        left_out_sentence(md, &left_out);
    }
}

fn left_out_sentence(md: &mut String, scenes: &[&str]) {
    let _ = writeln!(
        md,
        "Left out: {}, where no material an object uses has a specular lobe (k_s with a light or paths to weigh \
         it): Blinn, Phong and Cook–Torrance render one image with one shader there, so a ratio of their times \
         would be noise.\n",
        scenes.join(", ")
    );
}
