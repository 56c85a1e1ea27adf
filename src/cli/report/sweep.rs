//! Runs the planned configurations of one scene: a warm-up and timed renders each, errors
//! against the reference, and the GPU rows against their CPU twins.

use std::collections::HashMap;
use std::time::Duration;

use anyhow::Context;
use glint_core::compare::{ImageErrors, compare_images};
use glint_core::cpu::RayCounts;
use glint_core::{Backend, CpuOptions, FlatScene, HdrImage};
use glint_gpu::{GpuOptions, GpuTracer, ShaderKey};
use glint_io::LoadedScene;
use glint_scene::{Integrator, RenderSettings, SpecularModel, overflow_causes};
use indicatif::ProgressBar;
use serde::{Deserialize, Serialize};

use super::cpu_render::cpu_render;
use super::plan::{Config, Group, Planned, SceneNeeds};
use super::reference::{ReferenceStats, render_reference};
use crate::cli::console::tell;
use crate::cli::units::{median, mrays_per_s, ms};

/// What the sweep needs to render: CPU threads and, unless `--cpu-only`, one GPU tracer whose
/// pipeline cache lives for the whole report.
#[derive(Debug)]
pub struct Engines {
    pub threads: usize,
    pub gpu: Option<GpuTracer>,
    /// Creation time of every shader variant, measured once when it was first built.
    pub pipelines: HashMap<ShaderKey, Duration>,
}

/// One render's image and what it cost.
pub struct Sample {
    pub image: HdrImage,
    pub counts: RayCounts,
    pub time: Duration,
    pub gpu: Option<GpuExtra>,
}

#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GpuExtra {
    /// Creation time of the row's shader variant (compiled once, then cached).
    pub pipeline: Duration,
    pub statements: usize,
    pub status: u32,
}

/// A GPU row whose ray count differs from its CPU twin's by more than this (%) is noted:
/// f32 branching alone moves counts by a few in a million at robust offsets, while a small ε
/// with `tmin` or `nudge_ray` offsets lets f32 self-hits spawn extra rays.
pub const RAY_MISMATCH_PCT: f64 = 0.1;

/// One measured configuration.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Row {
    pub config: Config,
    pub groups: Vec<Group>,
    /// Timed render times, sorted.
    pub times: Vec<Duration>,
    pub counts: RayCounts,
    pub gpu: Option<GpuExtra>,
    pub errors: ImageErrors,
    /// The image's mean over pixels and channels, held against the reference's for its bias
    /// (`SceneResult::bias`).
    pub mean: f64,
    /// GPU rows: RMSE against the CPU render of the same configuration (arithmetic alone).
    pub twin_rmse: Option<f64>,
    /// GPU rows: how many more rays (%) the GPU traced than its CPU twin. A few in a million
    /// differ where f32 takes another branch (total internal reflection, a missed shadow
    /// ray); more where f32 self-hits spawn rays the CPU's f64 does not (small ε).
    pub twin_rays_pct: Option<f64>,
    /// One camera ray per sample: width × height × spp.
    pub camera_expected: u64,
    /// Whether the image equals, bit for bit, that of the same configuration specialised
    /// (full-shader rows only).
    pub same_as_specialised: Option<bool>,
    pub pareto_all: bool,
    pub pareto_backend: bool,
    /// The shard of `glint report --shard` that timed it (`None` in a one-machine run).
    pub shard: Option<u32>,
}

impl Row {
    pub fn median(&self) -> Duration {
        median(&self.times)
    }

    pub fn median_ms(&self) -> f64 {
        ms(self.median())
    }

    pub fn mrays(&self) -> f64 {
        mrays_per_s(self.counts.total(), self.median())
    }

    /// Whether the render lost work: fewer camera rays than samples, or a GPU status flag (a
    /// loop bound, the ray stack, or the driver's loop budget) raised. Its error is then not
    /// that of its arithmetic.
    pub fn dropped_work(&self) -> bool {
        self.counts.camera != self.camera_expected || self.gpu.is_some_and(|g| g.status != 0)
    }

    /// Whether a GPU row traced noticeably more or fewer rays than its CPU twin.
    pub fn rays_diverge(&self) -> bool {
        self.twin_rays_pct.is_some_and(|p| p.abs() > RAY_MISMATCH_PCT)
    }

    pub fn is_reference(&self) -> bool {
        self.groups.contains(&Group::Reference)
    }
}

/// One specular model on one backend (`specular::measure`).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpecularRow {
    pub model: SpecularModel,
    pub config: Config,
    /// Timed render times, sorted.
    pub times: Vec<Duration>,
    pub counts: RayCounts,
    pub gpu: Option<GpuExtra>,
    /// The shard that timed it (`--shard`), as a row's.
    pub shard: Option<u32>,
}

impl SpecularRow {
    pub fn median_ms(&self) -> f64 {
        ms(median(&self.times))
    }
}

/// All rows of one scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneResult {
    pub name: String,
    pub description: String,
    /// The scene's own settings with the report's size: epsilon value and seed come from here.
    pub settings: RenderSettings,
    pub reference: Config,
    /// A path-traced scene's reference: the seeds and samples of its renders, none at the rows'
    /// seed, and the noise their spread estimates (`reference::render_reference`). `None` for a
    /// Whitted scene, whose reference is one render at the rows' seed, and where this shard
    /// rendered no reference (none of the scene's rows are its).
    pub reference_stats: Option<ReferenceStats>,
    /// What decided which configurations the scene needs (`Planned::measured_for`).
    pub needs: SceneNeeds,
    pub rows: Vec<Row>,
    /// The render time of each specular model on each backend (`specular::measure`).
    pub specular: Vec<SpecularRow>,
}

impl SceneResult {
    /// Median render time of the reference configuration (its CPU row), ms.
    pub fn reference_ms(&self) -> f64 {
        self.rows.iter().find(|r| r.config == self.reference).map_or(f64::NAN, Row::median_ms)
    }

    /// `row`'s bias: its image mean's relative difference from the reference's, signed (−0.05:
    /// 5 % darker), and whether it lies beyond the reference's noise (`ReferenceStats::biased`;
    /// `None` for a reference without a noise estimate, a Whitted scene's).
    pub fn bias(&self, row: &Row) -> Option<(f64, Option<bool>)> {
        let reference = match &self.reference_stats {
            Some(stats) => stats.mean,
            None => self.rows.iter().find(|r| r.config == self.reference)?.mean,
        };
        let relative = if reference == 0.0 { 0.0 } else { (row.mean - reference) / reference };
        Some((relative, self.reference_stats.as_ref().map(|s| s.biased(row.mean, row.config.spp))))
    }

    /// Whether `row` converges to another image than the reference's: a path row shallower than
    /// the reference leaves out the light of the longer paths, however many samples it takes.
    pub fn shallower_paths(&self, row: &Row) -> bool {
        self.settings.integrator == Integrator::Path && row.config.depth < self.reference.depth
    }

    pub fn pixels(&self) -> u64 {
        u64::from(self.settings.width) * u64::from(self.settings.height)
    }
}

/// The scene's settings for `config` at the report's size.
pub fn settings_for(base: &RenderSettings, config: &Config) -> RenderSettings {
    RenderSettings {
        spp: config.spp,
        max_depth: config.depth,
        bailout: config.bailout.value(),
        epsilon_mode: config.epsilon_mode,
        ..base.clone()
    }
}

pub fn render(engines: &mut Engines, flat: &FlatScene, config: &Config) -> anyhow::Result<Sample> {
    match config.backend {
        Backend::Cpu => {
            let options =
                CpuOptions { threads: engines.threads, specialise: config.specialise, ..CpuOptions::default() };
            let r = cpu_render(flat, &options)?;
            Ok(Sample { image: r.image, counts: r.counts, time: r.elapsed, gpu: None })
        }
        Backend::Gpu => {
            let tracer = engines.gpu.as_ref().context("no GPU tracer (this is a bug)")?;
            let options = GpuOptions { specialise: config.specialise, ..GpuOptions::default() };
            let r = tracer.render(flat, &options).context("GPU render failed")?;
            crate::cli::interrupt::check()?;
            // The tracer reports a creation time only when it built the variant; later rows
            // that reuse it get the time it took then.
            let pipeline = *engines.pipelines.entry(r.key).or_insert(r.pipeline_time);
            let gpu = GpuExtra { pipeline, statements: r.statements, status: r.status };
            Ok(Sample { image: r.image, counts: r.counts, time: r.render_time, gpu: Some(gpu) })
        }
    }
}

/// `runs` timed passes over `jobs` (scenes with their configurations), each job once a pass so
/// that a load change hits every job alike, after their warm-up; each job's times, sorted. The
/// progress bar says `what` and the job.
pub fn timed_passes(
    engines: &mut Engines,
    jobs: &[(&FlatScene, Config)],
    integrator: &dyn Fn(usize) -> Integrator,
    runs: u32,
    bar: &ProgressBar,
    what: &str,
) -> anyhow::Result<Vec<Vec<Duration>>> {
    let mut times = vec![Vec::with_capacity(runs as usize); jobs.len()];
    for pass in 1..=runs {
        for (i, ((flat, c), t)) in jobs.iter().zip(&mut times).enumerate() {
            bar.set_message(format!(
                "{what}: timed pass {pass}/{runs}: {} {}",
                c.backend.name(),
                c.describe(integrator(i))
            ));
            t.push(render(engines, flat, c).with_context(|| format!("{what}: {c:?}"))?.time);
            bar.inc(1);
        }
    }
    for t in &mut times {
        t.sort();
    }
    Ok(times)
}

/// Renders the reference, then every planned configuration: first a warm-up pass over all of
/// them (it builds the GPU pipelines and gives the images), then `runs` timed passes. Passes
/// rather than back-to-back runs of one configuration, so that a load change on a shared
/// machine spreads over every configuration instead of biasing the few measured during it.
/// A path-traced scene's reference is the mean of CPU renders at seeds no row uses
/// (`reference::render_reference`, as the Whitted-against-GI section's): at the rows' seed, a
/// row's k-th path was the reference's k-th, and its error came out below that against an
/// independent reference (cornell-gi 48×48, 16 spp: 0.1195 against 0.1269). A Whitted scene's is
/// one render at the rows' seed, its settings' row reproducing it bit for bit.
/// The rows, in `planned`'s order, and a path-traced reference's noise.
pub fn run_scene(
    engines: &mut Engines,
    loaded: &LoadedScene,
    base: &RenderSettings,
    reference: &Config,
    planned: &[Planned],
    runs: u32,
    bar: &ProgressBar,
) -> anyhow::Result<(Vec<Row>, Option<ReferenceStats>)> {
    let name = &loaded.name;
    bar.set_message(format!("{name}: reference ({} spp, depth {})", reference.spp, reference.depth));
    let build = |c: &Config| FlatScene::build(&loaded.desc, &settings_for(base, c));
    let (ref_image, stats) = if independent_reference(base) {
        let options =
            CpuOptions { threads: engines.threads, specialise: reference.specialise, ..CpuOptions::default() };
        let settings = settings_for(base, reference);
        let averaged = render_reference(&loaded.desc, &settings, &options, || {})
            .with_context(|| format!("{name}: the reference"))?;
        (averaged.image, Some(averaged.stats))
    } else {
        (render(engines, &build(reference), reference)?.image, None)
    };
    if let Some(found) = ref_image.unrepresentable() {
        anyhow::bail!(
            "{name}: the reference render is not a valid image: {found}. In this scene: {}",
            overflow_causes(&loaded.desc, reference.depth, base.integrator, found.all_nan())
        );
    }
    bar.inc(1);
    let scenes: Vec<FlatScene> = planned.iter().map(|p| build(&p.config)).collect();
    let mut rows = Vec::with_capacity(planned.len());
    let mut images = Vec::with_capacity(planned.len());
    for (p, flat) in planned.iter().zip(&scenes) {
        let c = &p.config;
        bar.set_message(format!("{name}: warm-up: {} {}", c.backend.name(), c.describe(base.integrator)));
        let warm = render(engines, flat, c).with_context(|| format!("{name}: {c:?}"))?;
        let expected_camera = u64::from(base.width) * u64::from(base.height) * u64::from(c.spp);
        if warm.counts.camera != expected_camera {
            bar.suspend(|| {
                tell!(
                    "warning: {name}: the {} render of {} traced {} camera rays, not {expected_camera}: \
                     samples were dropped",
                    c.backend.name(),
                    c.describe(base.integrator),
                    warm.counts.camera
                );
            });
        }
        if let Some(found) = warm.image.unrepresentable() {
            anyhow::bail!(
                "{name}: the {} render of {} is not a valid image: {found}. In this scene: {}",
                c.backend.name(),
                c.describe(base.integrator),
                overflow_causes(&loaded.desc, c.depth, base.integrator, found.all_nan())
            );
        }
        rows.push(Row {
            config: *c,
            groups: p.groups.clone(),
            times: Vec::new(),
            counts: warm.counts,
            gpu: warm.gpu,
            errors: compare_images(&ref_image, &warm.image),
            mean: warm.image.mean(),
            twin_rmse: None,
            twin_rays_pct: None,
            camera_expected: expected_camera,
            same_as_specialised: None,
            pareto_all: false,
            pareto_backend: false,
            shard: None,
        });
        images.push(warm.image);
        bar.inc(1);
    }
    let jobs: Vec<(&FlatScene, Config)> = scenes.iter().zip(&rows).map(|(f, r)| (f, r.config)).collect();
    for (row, times) in rows.iter_mut().zip(timed_passes(engines, &jobs, &|_| base.integrator, runs, bar, name)?) {
        row.times = times;
    }
    let index: HashMap<Config, usize> = rows.iter().enumerate().map(|(i, r)| (r.config, i)).collect();
    for i in 0..rows.len() {
        let c = rows[i].config;
        if c.backend == Backend::Gpu
            && let Some(&j) = index.get(&c.on(Backend::Cpu))
        {
            rows[i].twin_rmse = Some(compare_images(&images[j], &images[i]).rmse);
            let (gpu, cpu) = (rows[i].counts.total() as f64, rows[j].counts.total() as f64);
            rows[i].twin_rays_pct = Some(100.0 * (gpu - cpu) / cpu.max(1.0));
        }
        if !c.specialise
            && let Some(&j) = index.get(&Config { specialise: true, ..c })
        {
            rows[i].same_as_specialised = Some(images[j] == images[i]);
        }
    }
    Ok((rows, stats))
}

/// Whether the scene's reference is rendered at seeds no row uses: a path-traced scene's,
/// whose rows draw every bounce from the seed. Whitted's rows draw only the camera's jitter
/// from it, within cells that differ between the rows' samples and the reference's.
pub fn independent_reference(base: &RenderSettings) -> bool {
    base.integrator == Integrator::Path
}
