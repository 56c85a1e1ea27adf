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

use std::fmt::Write as _;
use std::time::Duration;

use anyhow::Context;
use glint_core::ambient_fit::fit_ambient;
use glint_core::compare::compare_images;
use glint_core::glam::DVec3;
use glint_core::path_kinds::kind_alone;
use glint_core::{Backend, CpuOptions, FlatScene, HdrImage};
use glint_io::LoadedScene;
use glint_scene::{Integrator, PathKind, RenderSettings, Rgb, path_gain_warning};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use super::plan::{Bailout, Config};
use super::sweep::{Engines, render, timed_passes};
use crate::cli::console::tell;
use crate::cli::units::ms;

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
pub struct GiRow {
    pub integrator: Integrator,
    pub backend: Backend,
    pub spp: u32,
    pub depth: u32,
    /// Whitted's rows only.
    pub ambient: Option<Ambient>,
    pub median: Duration,
    pub rmse: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct GiResult {
    pub scene: String,
    pub reference_spp: u32,
    pub reference_depth: u32,
    /// The reference's own error (RMSE), from the spread of its `REFERENCE_GROUPS` renders.
    pub reference_noise: f64,
    pub fitted: [f64; 3],
    /// Whether the ambient term changes Whitted's image at all (a material in view has k_a).
    #[serde(default = "yes")]
    pub fit_determined: bool,
    /// Validation's warning that materials return more light than they receive under paths:
    /// the reference then grows with its depth.
    #[serde(default)]
    pub gain_warning: Option<String>,
    pub written: [f64; 3],
    pub rows: Vec<GiRow>,
    /// The shard of `glint report --shard` that measured it (`None` in a one-machine run).
    pub shard: Option<u32>,
    pub kinds: KindSplit,
}

fn yes() -> bool {
    true
}

/// What Whitted's error is made of: the reference's light by kind (`PathKind::ALL` order),
/// from a path render of `spp` samples at the rows' seed split four ways, against
/// Whitted's CPU image at the sweep's deepest, most sampled setting.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct KindSplit {
    pub spp: u32,
    /// Each kind's share of the paths' mean.
    pub share: [f64; 4],
    /// Each kind's root mean square over the pixels and channels: the error of an image that
    /// lacks it.
    pub rms: [f64; 4],
    /// The RMS difference of Whitted's image without its ambient from the paths' direct light
    /// (point lights against area lights' soft shadows, the glossy lobe against k_s·(H·N)^n).
    pub direct_rmse: f64,
    /// What the ambient as written adds, as a share of the paths' mean.
    pub ambient_share: f64,
    /// The paths' mean (`None` from a shard of a glint that did not say): a black reference
    /// has no shares.
    #[serde(default)]
    pub paths_mean: Option<f64>,
    /// The RMS difference of what the ambient as written adds from the indirect light the paths
    /// bring (all kinds but the direct): the error of the ambient as the stand-in it is, which
    /// is the largest part where it adds more than that light (`None` from an older shard).
    #[serde(default)]
    pub ambient_rmse: Option<f64>,
    /// Whitted's RMSE with the ambient as written, for scale.
    pub whitted_rmse: f64,
    /// What makes Whitted's direct light differ from the paths' in this scene (`None` from a
    /// shard of a glint that did not say).
    #[serde(default)]
    pub direct_causes: Option<Vec<String>>,
}

/// The root mean square of `image` over its pixels and channels.
fn rms(image: &HdrImage) -> f64 {
    let sq: f64 = image.pixels.iter().map(|p| p.length_squared()).sum();
    (sq / (3 * image.pixels.len().max(1)) as f64).sqrt()
}

/// `a − b`, pixel by pixel.
fn minus(a: &HdrImage, b: &HdrImage) -> HdrImage {
    let mut d = a.clone();
    for (p, q) in d.pixels.iter_mut().zip(&b.pixels) {
        *p -= *q;
    }
    d
}

/// The sweep's axes: (reference spp, path depth, Whitted depths, Whitted spp, path spp).
fn axes(quick: bool) -> (u32, u32, &'static [u32], &'static [u32], &'static [u32]) {
    if quick { (64, 8, &[5], &[1], &[1, 4, 16]) } else { (1024, 16, &[2, 5], &[1, 4], &[1, 4, 16, 64]) }
}

/// The reference is this many CPU path renders with consecutive seeds, averaged: their spread
/// estimates its noise. Two (one degree of freedom a pixel) let one firefly set the estimate:
/// the highlights scene's came out 0.249 where other seeds gave 0.063–0.071, above the error
/// of a 16-sample row.
const REFERENCE_GROUPS: u32 = 8;

/// The seed of the reference's render `k`: the rows' seed plus 1 + k, so that none shares its
/// random numbers with the rows (rendered at the rows' seed). A row whose samples were the
/// reference's first would correlate with it (0.37 measured on cornell-gi at 16 spp), and its
/// squared error would hold the reference's noise with the wrong sign.
fn reference_seed(rows: u32, k: u32) -> u32 {
    rows.wrapping_add(1).wrapping_add(k)
}

/// Renders per scene, for the progress bar: the reference's groups, each row's warm-up and
/// runs, and the kinds.
pub fn renders(backends: &[Backend], runs: u32, quick: bool) -> usize {
    let (_, _, depths, spps, path_spps) = axes(quick);
    REFERENCE_GROUPS as usize
        + PathKind::ALL.len()
        + backends.len() * (depths.len() * spps.len() * 3 + path_spps.len()) * (1 + runs as usize)
}

/// The mean of `groups` (images of equal size and samples) and the RMS over pixels and
/// channels of that mean's standard error, from the groups' sample variance.
fn mean_and_noise(groups: &[HdrImage]) -> (HdrImage, f64) {
    let k = groups.len() as f64;
    let mut mean = groups[0].clone();
    let mut variance = 0.0;
    for (i, p) in mean.pixels.iter_mut().enumerate() {
        *p = groups.iter().map(|g| g.pixels[i]).sum::<DVec3>() / k;
        variance += groups.iter().map(|g| (g.pixels[i] - *p).length_squared()).sum::<f64>() / (k - 1.0);
    }
    let per_value = variance / (3 * mean.pixels.len().max(1)) as f64;
    (mean, (per_value / k).sqrt())
}

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
    let (reference_spp, path_depth, depths, spps, path_spps) = axes(quick);
    let paths = RenderSettings { integrator: Integrator::Path, indirect: true, max_depth: path_depth, ..base.clone() };
    bar.set_message(format!("{name}: path-traced reference ({reference_spp} spp)"));
    let options = CpuOptions { threads: engines.threads, ..CpuOptions::default() };
    let gain_warning = path_gain_warning(&loaded.desc);
    if let Some(problem) = &gain_warning {
        bar.suspend(|| tell!("warning: {name}: the path-traced reference: {problem}"));
    }
    let group = |k: u32| -> anyhow::Result<HdrImage> {
        let s = RenderSettings {
            spp: reference_spp / REFERENCE_GROUPS,
            seed: reference_seed(base.seed, k),
            ..paths.clone()
        };
        let r = glint_core::render_cpu(&FlatScene::build(&loaded.desc, &s), &options, Default::default())
            .with_context(|| format!("{name}: the path-traced reference"))?;
        bar.inc(1);
        Ok(r.image)
    };
    let groups = (0..REFERENCE_GROUPS).map(group).collect::<anyhow::Result<Vec<_>>>()?;
    let (reference, reference_noise) = mean_and_noise(&groups);
    drop(groups);
    let whitted = RenderSettings { integrator: Integrator::Whitted, indirect: true, ..base.clone() };
    let fit = fit_ambient(&loaded.desc, &whitted, &reference, &options)
        .with_context(|| format!("{name}: fitting the ambient term"))?;
    // The CPU's Whitted images at the deepest, most sampled setting, as written and without the
    // ambient, are what the split by kind holds the paths' kinds against (kept from the warm-up).
    let deepest = (*depths.last().expect("Whitted depths"), *spps.last().expect("Whitted spp"));
    let (mut written, mut without) = (None, None);

    let mut planned: Vec<(GiRow, FlatScene)> = Vec::new();
    for &backend in backends {
        for &depth in depths {
            for &spp in spps {
                for ambient in [Ambient::AsWritten, Ambient::Without, Ambient::Fitted] {
                    let mut desc = loaded.desc.clone();
                    desc.world.ambient = match ambient {
                        Ambient::AsWritten => desc.world.ambient,
                        Ambient::Without => Rgb([0.0; 3]),
                        Ambient::Fitted => Rgb(fit.ambient),
                    };
                    let s = RenderSettings { spp, max_depth: depth, ..whitted.clone() };
                    let row = GiRow {
                        integrator: Integrator::Whitted,
                        backend,
                        spp,
                        depth,
                        ambient: Some(ambient),
                        median: Duration::ZERO,
                        rmse: 0.0,
                    };
                    planned.push((row, FlatScene::build(&desc, &s)));
                }
            }
        }
        for &spp in path_spps {
            let s = RenderSettings { spp, ..paths.clone() };
            let row = GiRow {
                integrator: Integrator::Path,
                backend,
                spp,
                depth: path_depth,
                ambient: None,
                median: Duration::ZERO,
                rmse: 0.0,
            };
            planned.push((row, FlatScene::build(&loaded.desc, &s)));
        }
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
        if row.backend == Backend::Cpu && (row.depth, row.spp) == deepest {
            match row.ambient {
                Some(Ambient::AsWritten) => written = Some(warm.image),
                Some(Ambient::Without) => without = Some(warm.image),
                Some(Ambient::Fitted) | None => {}
            }
        }
    }
    let (Some(written), Some(without)) = (written, without) else {
        anyhow::bail!("{name}: the Whitted against GI sweep has no CPU row at depth {}, {} spp", deepest.0, deepest.1)
    };
    let kinds = split_by_kind(loaded, &paths, [&written, &without], &reference, reference_spp / 4, &options, bar)?;
    let jobs: Vec<(&FlatScene, Config)> = planned.iter().map(|(row, flat)| (flat, config(row))).collect();
    let times = timed_passes(engines, &jobs, runs, bar, &format!("{name}: GI"))?;
    let rows = planned
        .into_iter()
        .zip(times)
        .map(|((mut row, _), t)| {
            row.median = t[t.len() / 2];
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

/// The reference's light by kind against Whitted's CPU images `written` (the ambient as
/// written) and `without` (none).
fn split_by_kind(
    loaded: &LoadedScene,
    paths: &RenderSettings,
    [written, without]: [&HdrImage; 2],
    reference: &HdrImage,
    spp: u32,
    options: &CpuOptions,
    bar: &ProgressBar,
) -> anyhow::Result<KindSplit> {
    let name = &loaded.name;
    let cpu = |flat: &FlatScene, what: &str| -> anyhow::Result<HdrImage> {
        bar.set_message(format!("{name}: {what}"));
        let r = glint_core::render_cpu(flat, options, Default::default()).with_context(|| format!("{name}: {what}"))?;
        bar.inc(1);
        Ok(r.image)
    };
    let flat = FlatScene::build(&loaded.desc, &RenderSettings { spp, ..paths.clone() });
    let mut split = KindSplit { spp, ..KindSplit::default() };
    let mut direct = None;
    let ambient = minus(written, without);
    // What the ambient adds less the indirect light, kind by kind.
    let mut ambient_less_indirect = ambient.clone();
    let paths_mean = reference.mean();
    for (i, kind) in PathKind::ALL.into_iter().enumerate() {
        let image = cpu(&kind_alone(&flat, kind), &format!("{} alone ({spp} spp)", kind.label()))?;
        (split.share[i], split.rms[i]) = (image.mean() / paths_mean.max(f64::MIN_POSITIVE), rms(&image));
        if kind == PathKind::Direct {
            direct = Some(image);
        } else {
            ambient_less_indirect = minus(&ambient_less_indirect, &image);
        }
    }
    split.direct_rmse = rms(&minus(without, &direct.expect("the direct kind is rendered")));
    split.ambient_share = ambient.mean() / paths_mean.max(f64::MIN_POSITIVE);
    split.paths_mean = Some(paths_mean);
    split.ambient_rmse = Some(rms(&ambient_less_indirect));
    split.whitted_rmse = compare_images(reference, written).rmse;
    split.direct_causes = Some(direct_causes(&loaded.desc));
    Ok(split)
}

/// What makes Whitted's direct light differ from the paths' in `desc`: its emitters and its sky
/// light nothing (the paths' direct light is E S* D L, the background among the L), and its
/// highlight is not the normalised lobe the paths reflect (path-tracing.md's factors). Point
/// lights, spots and directional lights are the same in both.
fn direct_causes(desc: &glint_scene::SceneDesc) -> Vec<String> {
    let mut causes = Vec::new();
    if desc.materials.values().any(|m| !m.emission.is_zero()) {
        causes.push("an emitter lights nothing in Whitted's model".to_string());
    }
    if !desc.world.background.is_zero() {
        causes.push("the background lights nothing in Whitted's model, only what it is seen by".to_string());
    }
    if desc.materials.values().any(|m| !m.ks.is_zero()) && desc.traced_lights().next().is_some() {
        causes.push("its highlight k_s·spec_j is not the normalised lobe the paths reflect".to_string());
    }
    causes
}

/// A sentence on what Whitted's remaining error is made of.
pub fn kinds_sentence(g: &GiResult) -> String {
    let k = &g.kinds;
    let pct = |v: f64| format!("{:.0} %", 100.0 * v);
    let direct = match k.direct_causes.as_deref() {
        None => "its direct light differing from the paths'".to_string(),
        Some([]) => {
            "its direct light differing from the paths' (by their noise alone: lights are the same in both)".to_string()
        }
        Some(causes) => format!("its direct light differing from the paths' ({})", causes.join("; ")),
    };
    let black = k.paths_mean.is_some_and(|m| m <= 0.0);
    let indirect_share = k.share[1] + k.share[2] + k.share[3];
    let mut parts = vec![
        (direct, k.direct_rmse),
        ("the indirect diffuse light it has no term for".to_string(), k.rms[1]),
        ("the caustics it has no term for".to_string(), k.rms[2]),
        (
            "the rest of the light it has no term for (a mirror or glass between two diffuse bounces)".to_string(),
            k.rms[3],
        ),
    ];
    // An ambient that adds more than the indirect light it stands in for is an error of its own;
    // one that adds less leaves the kinds above missing, in part.
    let ambient_over = black && k.ambient_share > 0.0 || !black && k.ambient_share > indirect_share;
    if let (Some(rmse), true) = (k.ambient_rmse, ambient_over) {
        parts.push((
            "its ambient term as written, I_a·k_a, which adds more light than the indirect light it stands in for"
                .to_string(),
            rmse,
        ));
    }
    let (largest, _) = parts.iter().max_by(|a, b| a.1.total_cmp(&b.1)).expect("four parts");
    let ambient = match k.ambient_rmse {
        Some(rmse) => {
            format!("; what its ambient as written adds differs from the paths' indirect light by RMS {rmse:.3e}")
        }
        None => String::new(),
    };
    let shares = if black {
        "The paths' image is black (no light reaches the camera), so it has no shares by kind; the ambient as \
         written adds light to it."
            .to_string()
    } else {
        format!(
            "The paths' light is {} direct, {} indirect diffuse, {} caustics and {} the rest (a {}-sample split); the \
             ambient as written adds {} of the paths' light where the indirect kinds bring {}.",
            pct(k.share[0]),
            pct(k.share[1]),
            pct(k.share[2]),
            pct(k.share[3]),
            k.spp,
            pct(k.ambient_share),
            pct(indirect_share),
        )
    };
    format!(
        "Whitted's error (RMSE {:.3e}, ambient as written) is mostly {largest}: its direct light differs from the \
         paths' by RMS {:.3e}, and it lacks indirect diffuse light (RMS {:.3e}), caustics ({:.3e}) and the rest \
         ({:.3e}){ambient}. {shares}",
        k.whitted_rmse, k.direct_rmse, k.rms[1], k.rms[2], k.rms[3],
    )
}

/// The least-squares slope of log(error) against log(time) of the path tracer's rows on
/// `backend`; `None` with fewer than two.
pub fn path_slope(result: &GiResult, backend: Backend) -> Option<f64> {
    let points: Vec<(f64, f64)> = result
        .rows
        .iter()
        .filter(|r| r.integrator == Integrator::Path && r.backend == backend && r.rmse > 0.0)
        .map(|r| (ms(r.median).max(1e-6).ln(), r.rmse.ln()))
        .collect();
    if points.len() < 2 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = (points.iter().map(|p| p.0).sum::<f64>() / n, points.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// Errors this close, relative, are one: the GPU's f32 against the CPU's f64 of the same row
/// differ by rounding (1e-8 relative on highlights, 1e-3 on cornell-gi, whose GPU row ranked
/// 0.1 % better at twice the CPU's time), and the faster row is Whitted's best, not the one a
/// rounding favours. A chart tells nothing finer apart.
const SAME_ERROR: f64 = 0.01;

/// The fastest path row whose error is below Whitted's best, and Whitted's best: its least
/// error, the fastest of the rows within `SAME_ERROR` of it.
pub fn crossover(result: &GiResult) -> (Option<&GiRow>, Option<&GiRow>) {
    let whitted = || result.rows.iter().filter(|r| r.integrator == Integrator::Whitted);
    let least = whitted().map(|r| r.rmse).fold(f64::INFINITY, f64::min);
    let best_whitted =
        whitted().filter(|r| r.rmse <= least * (1.0 + SAME_ERROR)).min_by(|a, b| a.median.cmp(&b.median));
    let first_path = best_whitted.and_then(|w| {
        result
            .rows
            .iter()
            .filter(|r| r.integrator == Integrator::Path && r.rmse < w.rmse)
            .min_by(|a, b| a.median.cmp(&b.median))
    });
    (first_path, best_whitted)
}

pub const HEADER: &[&str] = &[
    "scene",
    "integrator",
    "backend",
    "spp",
    "max_depth",
    "ambient",
    "render_ms_median",
    "rmse_vs_path_reference",
    "reference_spp",
    "reference_noise_rmse",
    "shard",
];

pub fn render_csv(results: &[GiResult]) -> String {
    let mut out = HEADER.join(",");
    out.push('\n');
    for g in results {
        for r in &g.rows {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{:e},{},{:e},{}",
                g.scene,
                r.integrator.name(),
                r.backend.name(),
                r.spp,
                r.depth,
                r.ambient.map_or("", Ambient::name),
                crate::cli::units::ms_csv(r.median),
                r.rmse,
                g.reference_spp,
                g.reference_noise,
                g.shard.map_or(String::new(), |s| s.to_string())
            );
        }
    }
    out
}

/// The report's section: per scene, the fitted ambient, the path tracer's slope and the time
/// its error falls below Whitted's best, and the table.
pub fn render_markdown(results: &[GiResult]) -> String {
    let mut md = String::from(
        "\n## Whitted against global illumination\n\nEach scene's Whitted images and path-traced images are \
         held against a path-traced reference (eight CPU renders with consecutive seeds, averaged; the spread \
         between them estimates the reference's own noise, which every row's squared error includes on average, \
         so rows approach it as their own noise falls; the estimate is itself uncertain where fireflies dominate). \
         Whitted's rows come with the \
         ambient term as the scene writes it, without it, and fitted to the reference (the I_a per channel that \
         minimises Whitted's error, `glint_core::ambient_fit`). gi.csv has every row.\n",
    );
    let fmt3 = |v: [f64; 3]| format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2]);
    for g in results {
        let fitted = if g.fit_determined {
            fmt3(g.fitted)
        } else {
            "none (I_a changes no pixel: no material in view has k_a)".to_string()
        };
        let _ = writeln!(
            md,
            "\n### {}\n\nReference: {} paths a pixel, depth {}, its noise {:.2e} RMSE. Ambient as written {}, fitted {fitted}.",
            g.scene,
            g.reference_spp,
            g.reference_depth,
            g.reference_noise,
            fmt3(g.written),
        );
        if let Some(problem) = &g.gain_warning {
            let _ = writeln!(
                md,
                "**Warning:** {problem}. The reference, at depth {}, carries that growth, and so do the fitted ambient \
                 and every error against the reference.",
                g.reference_depth
            );
        }
        for backend in [Backend::Cpu, Backend::Gpu] {
            if let Some(slope) = path_slope(g, backend) {
                let _ = writeln!(
                    md,
                    "The path tracer's error against time on the {}: slope {slope:.2} in log-log (−0.5 where noise \
                     dominates; flatter as it nears the reference's noise).",
                    backend.name()
                );
            }
        }
        let _ = writeln!(md, "{}", kinds_sentence(g));
        let (first, best) = crossover(g);
        match (first, best) {
            (Some(p), Some(w)) => {
                let _ = writeln!(
                    md,
                    "Paths beat Whitted's best ({} {} spp depth {}, ambient {}: RMSE {:.3e} in {:.1} ms) from {} {} spp \
                     (RMSE {:.3e} in {:.1} ms).",
                    w.backend.name(),
                    w.spp,
                    w.depth,
                    w.ambient.map_or("", Ambient::name),
                    w.rmse,
                    ms(w.median),
                    p.backend.name(),
                    p.spp,
                    p.rmse,
                    ms(p.median)
                );
            }
            (None, Some(w)) if w.rmse == 0.0 => {
                let _ = writeln!(md, "Whitted's best is the reference exactly (RMSE 0): no path row can beat it.");
            }
            (None, Some(w)) => {
                let _ = writeln!(md, "Paths do not beat Whitted's best (RMSE {:.3e}) within the sweep.", w.rmse);
            }
            _ => {}
        }
        md.push_str("\n| integrator | backend | spp | depth | ambient | ms (median) | RMSE vs reference |\n|---|---|---|---|---|---|---|\n");
        for r in &g.rows {
            let _ = writeln!(
                md,
                "| {} | {} | {} | {} | {} | {:.2} | {:.3e} |",
                r.integrator.name(),
                r.backend.name(),
                r.spp,
                r.depth,
                r.ambient.map_or("—", Ambient::name),
                ms(r.median),
                r.rmse
            );
        }
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(integrator: Integrator, backend: Backend, ms: u64, rmse: f64) -> GiRow {
        let ambient = (integrator == Integrator::Whitted).then_some(Ambient::Fitted);
        GiRow { integrator, backend, spp: 1, depth: 5, ambient, median: Duration::from_millis(ms), rmse }
    }

    #[test]
    fn the_reference_is_its_groups_mean_and_its_noise_their_standard_error() {
        // One pixel, four groups of 1, 2, 3, 4 in every channel: mean 2.5, sample variance
        // 5/3 (k − 1 in the divisor), standard error of the mean √(5/3 / 4).
        let groups: Vec<HdrImage> = (1..=4)
            .map(|v| {
                let mut image = HdrImage::new(1, 1);
                image.pixels[0] = DVec3::splat(f64::from(v));
                image
            })
            .collect();
        let (mean, noise) = mean_and_noise(&groups);
        assert_eq!(mean.pixels[0], DVec3::splat(2.5));
        assert!((noise - (5.0f64 / 3.0 / 4.0).sqrt()).abs() < 1e-15, "{noise}");
    }

    #[test]
    fn no_reference_render_shares_the_rows_seed() {
        for rows in [0, 7, u32::MAX] {
            let seeds: Vec<u32> = (0..REFERENCE_GROUPS).map(|k| reference_seed(rows, k)).collect();
            assert!(!seeds.contains(&rows), "{rows}: {seeds:?}");
            let mut distinct = seeds.clone();
            distinct.sort_unstable();
            distinct.dedup();
            assert_eq!(distinct.len(), seeds.len(), "{rows}: {seeds:?}");
        }
    }

    #[test]
    fn whitteds_best_is_the_fastest_of_the_rows_rounding_alone_tells_apart() {
        let result = GiResult {
            scene: "s".into(),
            reference_spp: 64,
            reference_depth: 8,
            reference_noise: 0.01,
            fitted: [0.1; 3],
            fit_determined: true,
            gain_warning: None,
            written: [0.1; 3],
            rows: vec![
                row(Integrator::Whitted, Backend::Gpu, 35, 0.5),
                row(Integrator::Whitted, Backend::Cpu, 19, 0.5 * (1.0 + 1e-3)),
                row(Integrator::Whitted, Backend::Cpu, 10, 0.6),
                row(Integrator::Path, Backend::Cpu, 40, 0.45),
            ],
            shard: None,
            kinds: KindSplit::default(),
        };
        let (first, best) = crossover(&result);
        let best = best.expect("a Whitted row");
        assert_eq!((best.backend, best.median), (Backend::Cpu, Duration::from_millis(19)));
        assert_eq!(first.map(|r| r.rmse), Some(0.45));
    }

    fn with_kinds(kinds: KindSplit) -> GiResult {
        GiResult {
            scene: "s".into(),
            reference_spp: 64,
            reference_depth: 8,
            reference_noise: 0.01,
            fitted: [0.0; 3],
            fit_determined: true,
            gain_warning: None,
            written: [2.0; 3],
            rows: Vec::new(),
            shard: None,
            kinds,
        }
    }

    #[test]
    fn an_ambient_that_adds_more_than_the_indirect_light_is_named_when_it_is_the_largest_part() {
        // A lit sphere under an ambient of 2 (a helper's scene): the ambient adds ten times the
        // paths' light, which has no indirect part.
        let over = KindSplit {
            spp: 16,
            share: [1.0, 0.0, 0.0, 0.0],
            rms: [0.1, 0.0, 0.0, 0.0],
            direct_rmse: 0.0157,
            ambient_share: 10.09,
            paths_mean: Some(0.08),
            ambient_rmse: Some(0.866),
            whitted_rmse: 0.868,
            direct_causes: Some(Vec::new()),
        };
        let said = kinds_sentence(&with_kinds(over.clone()));
        assert!(said.contains("is mostly its ambient term as written"), "{said}");
        // An ambient under the indirect light leaves the kinds to name, as before.
        let under =
            KindSplit { share: [0.5, 0.4, 0.05, 0.05], rms: [0.1, 0.2, 0.01, 0.01], ambient_share: 0.2, ..over };
        let said = kinds_sentence(&with_kinds(under.clone()));
        assert!(said.contains("is mostly the indirect diffuse light it has no term for"), "{said}");
        // A black reference (no light, an ambient): no shares, no division by its zero mean.
        let black = KindSplit {
            share: [0.0; 4],
            rms: [0.0; 4],
            direct_rmse: 0.0,
            ambient_share: 0.5 / f64::MIN_POSITIVE,
            paths_mean: Some(0.0),
            ambient_rmse: Some(0.2165),
            ..under
        };
        let said = kinds_sentence(&with_kinds(black));
        assert!(said.contains("is mostly its ambient term as written") && said.contains("The paths' image is black"));
        assert!(!said.contains("inf") && !said.contains(" %"), "{said}");
    }
}
