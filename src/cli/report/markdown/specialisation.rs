//! "What specialisation buys": time, pipeline and shader size specialised against full, and
//! whether the images are identical (they must be).

use std::fmt::Write as _;

use super::super::plan::Config;
use super::super::sweep::{GpuExtra, SceneResult};
use super::find;
use super::prose::{Block, prose};
use crate::cli::units::{ms, ms_cell};

pub fn shader_summary(md: &mut String, scenes: &[SceneResult]) {
    if !scenes.iter().flat_map(|s| &s.rows).any(|r| !r.config.specialise) {
        md.push_str(&prose(Block::SpecialisationNotMeasured, &[]));
        return;
    }
    md.push_str(&prose(Block::Specialisation, &[]));
    let _ = writeln!(
        md,
        "| scene | backend | spp, depth | render ms specialised · full | full / specialised | pipeline ms \
         specialised · full | shader statements specialised · full | identical images |"
    );
    let _ = writeln!(md, "|---|---|---|--:|--:|--:|--:|---|");
    for s in scenes {
        for full in s.rows.iter().filter(|r| !r.config.specialise) {
            let Some(spec) = find(s, &Config { specialise: true, ..full.config }) else { continue };
            let gpu = |f: &dyn Fn(&GpuExtra) -> String| match (spec.gpu, full.gpu) {
                (Some(a), Some(b)) => format!("{} · {}", f(&a), f(&b)),
                _ => "—".into(),
            };
            let _ = writeln!(
                md,
                "| {} | {} | {}, {} | {} · {} | {:.2} | {} | {} | {} |",
                s.name,
                full.config.backend.name(),
                full.config.spp,
                full.config.depth,
                ms_cell(spec.median_ms()),
                ms_cell(full.median_ms()),
                full.median_ms() / spec.median_ms(),
                gpu(&|g| ms_cell(ms(g.pipeline))),
                gpu(&|g| g.statements.to_string()),
                match full.same_as_specialised {
                    Some(true) => "yes",
                    Some(false) => "**no**",
                    None => "—",
                }
            );
        }
    }
    let _ = writeln!(md);
}
