//! Whitted against global illumination (issue 33's report part, first slice): for each scene,
//! the error against a path-traced reference of Whitted's images (depths, samples, and the
//! ambient term as written, without it and fitted to the reference) and of the path tracer's at
//! increasing samples, on each backend, against render time. The reference is eight CPU path
//! renders with consecutive seeds after the rows', averaged; their spread estimates its own noise.
//! The path tracer's log-log slope of error against time is measured (−1/2 while noise
//! dominates), and so is the time from which its error falls below Whitted's best. What
//! Whitted's error is made of comes from the reference's paths split by kind
//! (`glint_core::path_kinds`): the light Whitted has no term for, its direct light against the
//! paths', and what its ambient adds.

use std::time::Duration;

use anyhow::Context;
use glint_core::ambient_fit::fit_ambient;
use glint_core::compare::compare_images;
use glint_core::{Backend, CpuOptions, FlatScene, HdrImage};
use glint_io::LoadedScene;
use glint_scene::{Integrator, PathKind, RenderSettings, Rgb, path_gain_warning};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use super::plan::{Bailout, Config};
use super::reference::{REFERENCE_GROUPS, render_reference};
use super::sweep::{Engines, render, timed_passes};
use crate::cli::console::tell;

/// How a Whitted row's ambient term was set.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Ambient {
    AsWritten,
    Without,
    Fitted,
}

impl Ambient {
    fn name(self) -> &'static str {
        match self {
            Self::AsWritten => "as written",
            Self::Without => "none",
            Self::Fitted => "fitted",
        }
    }
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GiRow {
    pub integrator: Integrator,
    pub backend: Backend,
    pub spp: u32,
    pub depth: u32,
    /// Whitted's rows only.
    pub ambient: Option<Ambient>,
    /// The I_a a Whitted row rendered with: as written, 0, or fitted at its own depth and samples.
    pub ambient_rgb: Option<[f64; 3]>,
    pub median: Duration,
    pub rmse: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GiResult {
    pub scene: String,
    pub reference_spp: u32,
    pub reference_depth: u32,
    /// The reference's own error (RMSE), from the spread of its `REFERENCE_GROUPS` renders.
    pub reference_noise: f64,
    /// The fitted I_a of Whitted's deepest, most sampled rows (each fitted row has its own fit
    /// at its depth and samples, `GiRow::ambient_rgb`).
    pub fitted: [f64; 3],
    /// Whether the ambient term changes Whitted's image at all (a material in view has k_a).
    pub fit_determined: bool,
    /// Validation's warning that materials return more light than they receive under paths:
    /// the reference then grows with its depth.
    pub gain_warning: Option<String>,
    pub written: [f64; 3],
    pub rows: Vec<GiRow>,
    /// The shard of `glint report --shard` that measured it (`None` in a one-machine run).
    pub shard: Option<u32>,
    pub kinds: KindSplit,
}

mod kinds;
mod tables;

use kinds::split_by_kind;
pub use kinds::{DIRECT_CAUSES, KindSplit};
pub use tables::{render_csv, render_markdown};

/// The sweep's axes: (reference spp, path depth, Whitted depths, Whitted spp, path spp).
fn axes(quick: bool) -> (u32, u32, &'static [u32], &'static [u32], &'static [u32]) {
    if quick { (64, 8, &[5], &[1], &[1, 4, 16]) } else { (1024, 16, &[2, 5], &[1, 4], &[1, 4, 16, 64]) }
}

/// What names a row of the sweep: `measure` renders these, and the merge holds a shard's rows
/// to them (a row of depth 99999 was merged into the report; a tester).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GiRowKey {
    pub integrator: Integrator,
    pub backend: Backend,
    pub spp: u32,
    pub depth: u32,
    /// Whitted's rows only.
    pub ambient: Option<Ambient>,
}

impl GiRowKey {
    pub fn describe(&self) -> String {
        let ambient = self.ambient.map_or(String::new(), |a| format!(", ambient {}", a.name()));
        format!("{} {}, {} spp, depth {}{ambient}", self.backend.name(), self.integrator.name(), self.spp, self.depth)
    }
}

impl GiRow {
    pub fn key(&self) -> GiRowKey {
        GiRowKey {
            integrator: self.integrator,
            backend: self.backend,
            spp: self.spp,
            depth: self.depth,
            ambient: self.ambient,
        }
    }
}

/// The sweep's rows in the order `measure` renders them: on each backend, Whitted at each depth
/// and samples with the ambient as written, without it and fitted, then paths at each samples.
pub fn planned_rows(backends: &[Backend], quick: bool) -> Vec<GiRowKey> {
    let (_, path_depth, depths, spps, path_spps) = axes(quick);
    let mut keys = Vec::new();
    for &backend in backends {
        for &depth in depths {
            for &spp in spps {
                for ambient in [Ambient::AsWritten, Ambient::Without, Ambient::Fitted] {
                    keys.push(GiRowKey {
                        integrator: Integrator::Whitted,
                        backend,
                        spp,
                        depth,
                        ambient: Some(ambient),
                    });
                }
            }
        }
        for &spp in path_spps {
            keys.push(GiRowKey { integrator: Integrator::Path, backend, spp, depth: path_depth, ambient: None });
        }
    }
    keys
}

/// The reference's samples and depth in a sweep (`--quick` or not).
pub fn reference_axes(quick: bool) -> (u32, u32) {
    let (spp, depth, ..) = axes(quick);
    (spp, depth)
}

/// The depth and samples of the Whitted images the split by kind holds the paths against: the
/// sweep's deepest Whitted depth at the reference's samples.
pub fn split_whitted_axes(quick: bool) -> (u32, u32) {
    let (spp, _, depths, ..) = axes(quick);
    (*depths.last().expect("Whitted depths"), spp)
}

/// Renders per scene, for the progress bar: the reference's groups, each row's warm-up and
/// runs, and the kinds.
pub fn renders(backends: &[Backend], runs: u32, quick: bool) -> usize {
    REFERENCE_GROUPS as usize
        + CONVERGED_WHITTED
        + PathKind::ALL.len()
        + planned_rows(backends, quick).len() * (1 + runs as usize)
}

/// Whitted's CPU images at the reference's samples (the ambient as written and without it):
/// what the split by kind holds the paths against.
const CONVERGED_WHITTED: usize = 2;

pub fn measure(
    engines: &mut Engines,
    loaded: &LoadedScene,
    base: &RenderSettings,
    backends: &[Backend],
    runs: u32,
    quick: bool,
    bar: &ProgressBar,
) -> anyhow::Result<GiResult> {
    let name = &loaded.name;
    let (reference_spp, path_depth, depths, spps, _) = axes(quick);
    let paths = RenderSettings { integrator: Integrator::Path, indirect: true, max_depth: path_depth, ..base.clone() };
    bar.set_message(format!("{name}: path-traced reference ({reference_spp} spp)"));
    let options = CpuOptions { threads: engines.threads, ..CpuOptions::default() };
    let gain_warning = path_gain_warning(&loaded.desc);
    if let Some(problem) = &gain_warning {
        bar.suspend(|| tell!("warning: {name}: the path-traced reference: {problem}"));
    }
    let s = RenderSettings { spp: reference_spp, ..paths.clone() };
    let averaged = render_reference(&loaded.desc, &s, &options, || bar.inc(1))
        .with_context(|| format!("{name}: the path-traced reference"))?;
    let (reference, reference_noise) = (averaged.image, averaged.stats.noise_rmse);
    let whitted = RenderSettings { integrator: Integrator::Whitted, indirect: true, ..base.clone() };
    // The fitted rows' I_a, each fitted at the row's own depth and samples: the I_a that brings
    // Whitted's image closest to the reference depends on both (fitted once at the scene's own
    // settings, a 1-spp depth-5 row of cornell-gi got 0.225 where its own fit is 0.243).
    let mut fits = Vec::new();
    for &depth in depths {
        for &spp in spps {
            let s = RenderSettings { spp, max_depth: depth, ..whitted.clone() };
            let fit = fit_ambient(&loaded.desc, &s, &reference, &options)
                .with_context(|| format!("{name}: fitting the ambient term at depth {depth}, {spp} spp"))?;
            fits.push(((depth, spp), fit));
        }
    }
    let fit_at = |depth: u32, spp: u32| &fits.iter().find(|(at, _)| *at == (depth, spp)).expect("a fit per row").1;
    let deepest = (*depths.last().expect("Whitted depths"), *spps.last().expect("Whitted spp"));
    let fit = fit_at(deepest.0, deepest.1);
    // What the split by kind holds the paths against: the CPU's Whitted images at the deepest
    // depth and the reference's samples, as written and without the ambient. At the rows' few
    // samples Whitted's own anti-aliasing error counted as light its model leaves out: a
    // quarter of cornell-gi's 4-spp RMSE was the lamp's edges (a lecturer).
    let whitted_at = split_whitted_axes(quick);
    let converged = |ambient: Option<Rgb>| -> anyhow::Result<HdrImage> {
        let mut desc = loaded.desc.clone();
        let what = if let Some(a) = ambient {
            desc.world.ambient = a;
            "without the ambient"
        } else {
            "the ambient as written"
        };
        bar.set_message(format!("{name}: Whitted at {reference_spp} spp, {what}"));
        let s = RenderSettings { spp: whitted_at.1, max_depth: whitted_at.0, ..whitted.clone() };
        let r = super::cpu_render::cpu_render(&FlatScene::build(&desc, &s), &options)
            .with_context(|| format!("{name}: Whitted at the reference's {reference_spp} spp, {what}"))?;
        bar.inc(1);
        Ok(r.image)
    };
    let (written, without) = (converged(None)?, converged(Some(Rgb([0.0; 3])))?);

    let mut planned: Vec<(GiRow, FlatScene)> = Vec::new();
    for key in planned_rows(backends, quick) {
        let (desc, s) = match key.ambient {
            Some(ambient) => {
                let mut desc = loaded.desc.clone();
                desc.world.ambient = match ambient {
                    Ambient::AsWritten => desc.world.ambient,
                    Ambient::Without => Rgb([0.0; 3]),
                    Ambient::Fitted => Rgb(fit_at(key.depth, key.spp).ambient),
                };
                (desc, RenderSettings { spp: key.spp, max_depth: key.depth, ..whitted.clone() })
            }
            None => (loaded.desc.clone(), RenderSettings { spp: key.spp, ..paths.clone() }),
        };
        let row = GiRow {
            integrator: key.integrator,
            backend: key.backend,
            spp: key.spp,
            depth: key.depth,
            ambient: key.ambient,
            ambient_rgb: key.ambient.map(|_| desc.world.ambient.0),
            median: Duration::ZERO,
            rmse: 0.0,
        };
        planned.push((row, FlatScene::build(&desc, &s)));
    }
    let config = |row: &GiRow| Config {
        backend: row.backend,
        spp: row.spp,
        depth: row.depth,
        bailout: Bailout::Per255,
        specialise: true,
        epsilon_mode: base.epsilon_mode,
    };
    // A warm-up pass (the images), then timed passes over every row, as the main sweep does.
    for (row, flat) in &mut planned {
        bar.set_message(format!(
            "{name}: GI warm-up: {} {} {} spp",
            row.backend.name(),
            row.integrator.name(),
            row.spp
        ));
        let warm = render(engines, flat, &config(row)).with_context(|| format!("{name}: {row:?}"))?;
        row.rmse = compare_images(&reference, &warm.image).rmse;
        bar.inc(1);
    }
    let kinds =
        split_by_kind(loaded, &paths, [&written, &without], whitted_at, &reference, reference_spp / 4, &options, bar)?;
    let jobs: Vec<(&FlatScene, Config)> = planned.iter().map(|(row, flat)| (flat, config(row))).collect();
    let integrators: Vec<Integrator> = planned.iter().map(|(row, _)| row.integrator).collect();
    let times = timed_passes(engines, &jobs, &|i| integrators[i], runs, bar, &format!("{name}: GI"))?;
    let rows = planned
        .into_iter()
        .zip(times)
        .map(|((mut row, _), t)| {
            row.median = crate::cli::units::median(&t);
            row
        })
        .collect();
    Ok(GiResult {
        scene: name.clone(),
        reference_spp,
        reference_depth: path_depth,
        reference_noise,
        fitted: fit.ambient,
        fit_determined: fit.determined,
        gain_warning,
        written: loaded.desc.world.ambient.0,
        rows,
        shard: None,
        kinds,
    })
}

/// A result of `rows` and `kinds` for the sections' tests (the rest as a sweep of one scene).
#[cfg(test)]
fn result_for_tests(rows: Vec<GiRow>, kinds: KindSplit) -> GiResult {
    GiResult {
        scene: "s".into(),
        reference_spp: 64,
        reference_depth: 8,
        reference_noise: 0.01,
        fitted: [0.1; 3],
        fit_determined: true,
        gain_warning: None,
        written: [0.1; 3],
        rows,
        shard: None,
        kinds,
    }
}
