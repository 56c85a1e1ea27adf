//! `glint report`: error against run time. Sweeps render configurations per scene, times
//! each (render only, median after a warm-up), measures its error against a CPU f64
//! reference, and writes report.csv, report.md and one log-log plot per scene; and measures
//! the render time of each specular model (specular.csv).

mod cpu_render;
mod csv;
mod gi;
mod gi_plot;
mod machine;
mod markdown;
mod pareto;
mod plan;
mod plot;
mod reference;
mod reference_cost;
mod shard;
mod shard_check;
mod specular;
mod staging;
mod sweep;

use std::collections::HashMap;
use std::ffi::{OsStr, OsString};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, anyhow};
use clap::Args;
use glint_core::{Backend, FlatScene};
use glint_io::atomic::write_file_atomically;
use glint_scene::{Integrator, RenderSettings};
use indicatif::{ProgressBar, ProgressStyle};

use self::plan::{Plan, Planned, SceneNeeds};
use self::sweep::Engines;
use super::backend::open_gpu;
use super::console::{say, tell};
use super::settings::{load, parse_integrator, parse_threads};
use super::units::counted;
use crate::cli::usage::usage;

const DEFAULT_SCENES: &[&str] = &["whitted", "cornell", "spotlights", "highlights", "lights", "cornell-gi"];
const QUICK_SCENES: &[&str] = &["whitted", "highlights"];

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Scenes to sweep, comma-separated: built-in names or scene files (default: every built-in
    /// but the generated ones; with --quick: whitted,highlights)
    #[arg(long, value_parser = clap::value_parser!(OsString))]
    pub scenes: Vec<OsString>,
    /// Folder for report.csv, report.md and the plots (created if missing)
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// A small sweep for CI: two scenes, 96x72, a reduced grid (under a minute on 2 cores)
    #[arg(long)]
    pub quick: bool,
    /// Image width for every scene [1, 4096] (default 320; 96 with --quick)
    #[arg(long, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<1, 4096>)]
    pub width: Option<u32>,
    /// Image height for every scene [1, 4096] (default 240; 72 with --quick)
    #[arg(long, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<1, 4096>)]
    pub height: Option<u32>,
    /// Samples per pixel of the CPU reference [64, 4096]
    #[arg(long, default_value_t = 64, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<64, 4096>)]
    pub reference_spp: u32,
    /// Timed runs per configuration after the warm-up [3, 100]; the median is reported
    #[arg(long, default_value_t = 3, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<3, 100>)]
    pub runs: u32,
    /// GPU adapter: a case-insensitive part of its name (default: WGPU_ADAPTER_NAME, else the best GPU)
    #[arg(long, conflicts_with = "cpu_only")]
    pub adapter: Option<String>,
    /// Sweep the CPU tracer only (no GPU needed)
    #[arg(long)]
    pub cpu_only: bool,
    /// CPU worker threads: 0 = one per core, at most 4 per core (and never more than 1024)
    #[arg(long, default_value_t = 0, allow_hyphen_values = true, value_parser = parse_threads)]
    pub threads: usize,
    /// Render every scene with this integrator: whitted or path (default: each scene's own
    /// render.integrator). A path-traced reference is itself a Monte Carlo estimate at
    /// --reference-spp
    #[arg(long, value_parser = parse_integrator)]
    pub integrator: Option<Integrator>,
    /// Run shard I of N of the sweep (I from 0): the configurations the shards' fixed split by
    /// expected cost gives it; writes DIR/shard-I-of-N.toml for --merge
    #[arg(long, value_name = "I/N", allow_hyphen_values = true, value_parser = shard::parse_shard)]
    pub shard: Option<shard::ShardSpec>,
    /// Merge the shards' files found in these folders (comma-separated) into the report a
    /// one-machine run writes, in --out; names every missing shard
    /// (The sweep's flags would do nothing here: the shards' files say how they were run.)
    #[arg(
        long,
        value_name = "DIR",
        value_parser = clap::value_parser!(OsString),
        conflicts_with_all = [
            "shard", "scenes", "quick", "width", "height", "reference_spp", "runs", "adapter", "cpu_only",
            "threads", "integrator",
        ]
    )]
    pub merge: Vec<OsString>,
    /// Replace output files in --out even if they are read-only
    #[arg(long)]
    pub force: bool,
    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let started = Instant::now();
    if !args.merge.is_empty() {
        return merge(args, started);
    }
    let plan = if args.quick { Plan::quick(args.reference_spp) } else { Plan::full(args.reference_spp) };
    let (width, height) = if args.quick { (96, 72) } else { (320, 240) };
    let (width, height) = (args.width.unwrap_or(width), args.height.unwrap_or(height));
    let names: Vec<OsString> = if args.scenes.is_empty() {
        (if args.quick { QUICK_SCENES } else { DEFAULT_SCENES }).iter().map(OsString::from).collect()
    } else {
        let names: Vec<OsString> = args.scenes.iter().flat_map(|s| comma_list(s)).collect();
        // As `--merge` refuses one: `whitted,,cornell` swept two scenes without a word (a tester).
        if names.iter().any(|n| n.is_empty()) && names.iter().any(|n| !n.is_empty()) {
            usage!("--scenes: an empty scene name in the list: a doubled, leading or trailing comma?");
        }
        names.into_iter().filter(|s| !s.is_empty()).collect()
    };
    // `--adapter ""` ran a whole GPU sweep here, where render refuses it (a tester).
    super::backend::check_adapter(args.adapter.as_deref(), !args.cpu_only)?;
    if names.is_empty() {
        usage!(
            "--scenes names no scene; give built-in names or scene files, comma-separated (or leave it out for the default set)"
        );
    }
    let scenes =
        names.iter().map(|n| load(n, &glint_io::LoadOptions::default(), None)).collect::<anyhow::Result<Vec<_>>>()?;
    let mut seen = HashMap::new();
    for s in &scenes {
        if let Some(other) = seen.insert(s.name.clone(), s.source.clone()) {
            usage!(
                "two scenes are both called '{}' ({} and {}); their plots would collide",
                s.name,
                other.display(),
                s.source.display()
            );
        }
    }
    let bases: Vec<RenderSettings> = scenes
        .iter()
        .map(|s| {
            let integrator = args.integrator.unwrap_or(s.desc.render.integrator);
            RenderSettings { width, height, integrator, ..s.desc.render.clone() }
        })
        .collect();
    let needs: Vec<SceneNeeds> =
        scenes.iter().zip(&bases).map(|(s, base)| SceneNeeds::of(&s.desc, base, &plan)).collect();
    // Before the GPU opens or --out is made: a family is the same with either backend.
    if let Some(s) = args.shard {
        let families = shard::families(&plan.configs(&[Backend::Cpu]), &needs);
        if s.count as usize > families {
            let idle = if s.count as usize == families + 1 {
                format!("shard {families} would have nothing to run")
            } else {
                format!("shards {families} to {} would have nothing to run", s.count - 1)
            };
            usage!(
                "--shard {}/{}: this sweep has {families} families of configurations (each timed whole by one \
                 shard), so {idle}; use at most {families} shards",
                s.index,
                s.count
            );
        }
    }
    let threads =
        if args.threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { args.threads };
    // Before the GPU opens or --out is made: a reference that cannot finish is refused, one whose
    // worst case is large but whose probe fits is said (a panes scene ran for hours silently).
    let reference = plan.reference();
    for (loaded, base) in scenes.iter().zip(&bases) {
        if let Some(warning) = reference_cost::judge(&loaded.name, &loaded.desc, base, &reference, threads)? {
            tell!("{warning}");
        }
    }
    let gpu = if args.cpu_only {
        None
    } else {
        Some(
            open_gpu(args.adapter.as_deref())
                .context("glint report needs a GPU adapter; pass --cpu-only to sweep the CPU alone")?,
        )
    };
    let gpu_device = gpu.as_ref().map(|g| g.context().adapter.with_driver());
    let files = match args.shard {
        Some(spec) => vec![shard::file_name(spec)],
        None => report_files(scenes.iter().map(|s| s.name.as_str())),
    };
    let staging = staging::Staging::new(&args.out, &files, args.force)?;
    let out = staging.path();
    let backends: Vec<Backend> = if gpu.is_some() { vec![Backend::Cpu, Backend::Gpu] } else { vec![Backend::Cpu] };
    let cpu_device = format!("{threads} threads");
    let mut engines = Engines { threads, gpu, pipelines: HashMap::new() };

    let planned = plan.configs(&backends);
    // With --shard, which shard times each (scene, configuration); specular models go with the
    // shard of a scene's first configuration.
    let owners =
        args.shard.map(|s| shard::assign(&planned, &needs, u64::from(width) * u64::from(height), args.runs, s.count));
    let mine = |scene: usize, config: usize| match (&owners, args.shard) {
        (Some(o), Some(s)) => o[scene][config] == s.index,
        _ => true,
    };
    // One tick per render: the reference, then each configuration's warm-up and timed runs,
    // then each specular model's.
    let renders: usize = (0..scenes.len())
        .map(|si| {
            let configs = (0..planned.len()).filter(|&ci| mine(si, ci) && planned[ci].measured_for(needs[si])).count();
            let specular = if mine(si, 0) && needs[si].specular { specular::renders(&backends, args.runs) } else { 0 };
            let gi = if mine(si, 0) { gi::renders(&backends, args.runs, args.quick) } else { 0 };
            if configs == 0 { specular + gi } else { 1 + configs * (1 + args.runs as usize) + specular + gi }
        })
        .sum();
    let bar = progress(args.quiet, renders as u64)?;
    let mut results = Vec::with_capacity(scenes.len());
    let mut gi_results = Vec::new();
    let mut scene_hashes = Vec::new();
    for (si, loaded) in scenes.iter().enumerate() {
        let base = &bases[si];
        if args.shard.is_some() {
            scene_hashes.push(FlatScene::build(&loaded.desc, base).content_hash());
        }
        let ours: Vec<Planned> = planned
            .iter()
            .enumerate()
            .filter(|(ci, p)| mine(si, *ci) && p.measured_for(needs[si]))
            .map(|(_, p)| Planned { config: p.config, groups: p.groups_for(needs[si]) })
            .collect();
        let (rows, reference_stats) = if ours.is_empty() {
            (Vec::new(), None)
        } else {
            sweep::run_scene(&mut engines, loaded, base, &reference, &ours, args.runs, &bar)?
        };
        let mut result = sweep::SceneResult {
            name: loaded.name.clone(),
            description: loaded.desc.description.clone(),
            settings: base.clone(),
            reference,
            reference_stats,
            needs: needs[si],
            rows,
            specular: Vec::new(),
        };
        if mine(si, 0) {
            if needs[si].specular {
                result.specular = specular::measure(&mut engines, loaded, base, &backends, args.runs, &bar)?;
            }
            // Whitted against a path-traced reference: on the shard that measures the specular models.
            let mut gi = gi::measure(&mut engines, loaded, base, &backends, args.runs, args.quick, &bar)?;
            gi.shard = args.shard.map(|s| s.index);
            if args.shard.is_none() {
                gi_plot::write_gi_plot(out, &gi, args.runs as usize)?;
            }
            gi_results.push(gi);
        }
        if let Some(s) = args.shard {
            for row in &mut result.rows {
                row.shard = Some(s.index);
            }
            for row in &mut result.specular {
                row.shard = Some(s.index);
            }
        } else {
            pareto::mark_fronts(&mut result.rows);
            let path = staging.published(&plot::write_plot(out, &result, args.runs as usize)?);
            bar.suspend(|| say!("{}: {} configurations, writes {}", result.name, result.rows.len(), path.display()))?;
        }
        results.push(result);
    }
    bar.finish_and_clear();

    let machine = machine::Machine::probe();
    if let Some(spec) = args.shard {
        let file = shard::ShardFile {
            format: shard::SHARD_FORMAT,
            glint: env!("CARGO_PKG_VERSION").to_string(),
            shard: spec.index,
            count: spec.count,
            width,
            height,
            runs: args.runs,
            quick: args.quick,
            reference_spp: args.reference_spp,
            integrator: args.integrator,
            scenes: scenes.iter().map(|s| s.name.clone()).collect(),
            scene_hashes,
            backends,
            cpu_device,
            gpu_device,
            machine,
            results,
            gi: gi_results,
            path: PathBuf::new(),
        };
        let rows: usize = file.results.iter().map(|r| r.rows.len()).sum();
        let path = staging.published(&shard::write(out, spec, &file)?);
        staging.publish(args.force, false)?;
        say!(
            "report shard {}/{}: {rows} of {} configurations in {:.1} s; wrote {} (merge the shards with --merge)",
            spec.index,
            spec.count,
            needs.iter().map(|n| planned.iter().filter(|p| p.measured_for(*n)).count()).sum::<usize>(),
            started.elapsed().as_secs_f64(),
            path.display()
        )?;
        return Ok(());
    }
    let setup = markdown::Setup {
        machine: &machine,
        cpu_device: &cpu_device,
        gpu_device: gpu_device.as_deref(),
        width,
        height,
        runs: args.runs,
        quick: args.quick,
        plan: &plan,
        integrator: args.integrator,
    };
    let devices = [(cpu_device.clone(), gpu_device.clone().unwrap_or_default())];
    write_outputs(out, &setup, &results, &devices, &[], &gi_results)?;
    staging.publish(args.force, true)?;
    say!(
        "report: {}, {} configurations in all, in {:.1} s; {}",
        counted(results.len(), "scene"),
        results.iter().map(|r| r.rows.len()).sum::<usize>(),
        started.elapsed().as_secs_f64(),
        written(&args.out, results.iter().map(|r| r.name.as_str()))
    )?;
    Ok(())
}

/// `--merge DIR…`: the shards' rows joined into the files a one-machine run writes.
fn merge(args: &ReportArgs, started: Instant) -> anyhow::Result<()> {
    let mut files = shard::read_all(&merge_folders(&args.merge)?)?;
    let first = &files[0];
    let plan = if first.quick { Plan::quick(first.reference_spp) } else { Plan::full(first.reference_spp) };
    let planned = plan.configs(&first.backends);
    let (mut machine, width, height, runs, quick, integrator) =
        (first.machine.clone(), first.width, first.height, first.runs, first.quick, first.integrator);
    // The report says the merge made it, and when; the shards' own commands and machines are
    // listed in its Shards section.
    let now = machine::Machine::probe();
    (machine.command, machine.date) = (now.command, now.date);
    // The Setup's machine is one shard's; say which.
    machine.cpu_model = format!("{} (shard 0's; every shard's is under Shards)", machine.cpu_model);
    let devices: Vec<(String, String)> =
        files.iter().map(|f| (f.cpu_device.clone(), f.gpu_device.clone().unwrap_or_default())).collect();
    let machines: Vec<String> = files
        .iter()
        .map(|f| {
            let m = &f.machine;
            format!(
                "shard {}: {}, {} logical cores, {}; {}{}",
                f.shard,
                m.cpu_model,
                m.logical_cores,
                m.date,
                f.cpu_device,
                f.gpu_device.as_deref().map_or(String::new(), |g| format!(", GPU {g}"))
            )
        })
        .collect();
    let gpu_device = files[0].gpu_device.clone();
    let gi_results = shard::join_gi(&mut files)?;
    let mut results = shard::join(&mut files, &planned)?;
    let staging = staging::Staging::new(&args.out, &report_files(results.iter().map(|r| r.name.as_str())), args.force)?;
    let out = staging.path();
    for result in &mut results {
        pareto::mark_fronts(&mut result.rows);
        let path = staging.published(&plot::write_plot(out, result, runs as usize)?);
        say!("{}: {} configurations, writes {}", result.name, result.rows.len(), path.display())?;
    }
    for gi in &gi_results {
        gi_plot::write_gi_plot(out, gi, runs as usize)?;
    }
    let setup = markdown::Setup {
        machine: &machine,
        cpu_device: &devices[0].0,
        gpu_device: gpu_device.as_deref(),
        width,
        height,
        runs,
        quick,
        plan: &plan,
        integrator,
    };
    write_outputs(out, &setup, &results, &devices, &machines, &gi_results)?;
    staging.publish(args.force, true)?;
    say!(
        "report: {} merged, {}, {} configurations in all, in {:.1} s; {}",
        counted(devices.len(), "shard"),
        counted(results.len(), "scene"),
        results.iter().map(|r| r.rows.len()).sum::<usize>(),
        started.elapsed().as_secs_f64(),
        written(&args.out, results.iter().map(|r| r.name.as_str()))
    )?;
    Ok(())
}

/// report.csv, specular.csv, gi.csv and report.md (ending with the Whitted-against-paths
/// section of `gi_results`); `machines` lists a merged report's shards.
fn write_outputs(
    out: &Path,
    setup: &markdown::Setup,
    results: &[sweep::SceneResult],
    devices: &[(String, String)],
    machines: &[String],
    gi_results: &[gi::GiResult],
) -> anyhow::Result<()> {
    let [report_csv, specular_csv, gi_csv, report_md] = TABLES;
    write_report_file(&out.join(report_csv), &csv::render_csv(results, devices))?;
    write_report_file(&out.join(specular_csv), &csv::render_specular_csv(results))?;
    write_report_file(&out.join(gi_csv), &gi::render_csv(gi_results))?;
    let mut md = markdown::render_markdown(setup, results);
    md.push_str(&gi::render_markdown(gi_results));
    if !machines.is_empty() {
        md.push_str(&format!(
            "\n## Shards\n\nThis report was measured in {} shards (`glint report --shard I/N`, merged by \
             `--merge`). Every row's timing comes from the machine of its shard (the `shard` column of \
             report.csv, specular.csv and gi.csv); the header's machine is shard 0's. A scene's families of \
             configurations go to different shards, so the tables above that set times side by side (the \
             bailout's, the Pareto fronts, equal time and equal error) compare machines, or one machine at \
             two moments, wherever their rows' shards differ: a time ratio between two shards is not the \
             configurations' alone. A GPU row and its CPU twin, and a specialised row and its full-shader \
             twin, always share a shard. \
             Errors are measured against each shard's own CPU reference, which is the same image on every \
             machine.\n\n",
            machines.len()
        ));
        for m in machines {
            md.push_str(&format!("- {m}\n"));
        }
    }
    write_report_file(&out.join(report_md), &md)
}

/// The tables and text a whole report writes beside its plots.
const TABLES: [&str; 4] = ["report.csv", "specular.csv", "gi.csv", "report.md"];

/// The parts of one comma-separated value (`--scenes`, `--merge`), each trimmed of ASCII white
/// space, empty ones kept (for the caller to judge). Split as bytes where names are bytes: a
/// file's name need not be UTF-8 (clap's list of strings refused one without naming the flag).
fn comma_list(value: &OsStr) -> Vec<OsString> {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        let parts = value.as_bytes().split(|&b| b == b',').map(<[u8]>::trim_ascii);
        parts.map(|part| OsStr::from_bytes(part).to_os_string()).collect()
    }
    #[cfg(not(unix))]
    {
        value.to_string_lossy().split(',').map(|part| OsString::from(part.trim())).collect()
    }
}

/// `--merge`'s folders, from every value given; an empty one (a doubled, leading or trailing
/// comma) is an error, whose clap word ("a value is required … but none was supplied") hid
/// the comma that made it. Trimmed as `--scenes` is: `s0, s1` named " s1", a folder that did
/// not exist, and a shard that had run was called missing.
fn merge_folders(values: &[OsString]) -> anyhow::Result<Vec<PathBuf>> {
    let parts: Vec<OsString> = values.iter().flat_map(|v| comma_list(v)).collect();
    if parts.iter().any(|p| p.is_empty()) {
        usage!("--merge: an empty folder name in the list: a doubled, leading or trailing comma?");
    }
    Ok(parts.into_iter().map(PathBuf::from).collect())
}

/// Every file a whole report over scenes named `scenes` writes into `--out`.
fn report_files<'a>(scenes: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    let plots = scenes.into_iter().flat_map(|s| [plot::file_name(s), gi_plot::file_name(s)]);
    TABLES.iter().map(|t| t.to_string()).chain(plots).collect()
}

/// What a finished report wrote into `out`, every file named (its last line said only
/// report.md and report.csv of the four tables and the plots).
fn written<'a>(out: &Path, scenes: impl IntoIterator<Item = &'a str>) -> String {
    let files: Vec<String> = report_files(scenes).into_iter().filter(|f| out.join(f).is_file()).collect();
    format!("wrote {} in {}: {}", counted(files.len(), "file"), out.display(), files.join(", "))
}

/// Replaces `path` atomically, as every file glint writes (`glint_io::atomic`).
fn write_report_file(path: &Path, text: &str) -> anyhow::Result<()> {
    write_file_atomically(path, text.as_bytes()).map_err(|e| anyhow!("cannot write {}: {}", e.path.display(), e.error))
}

/// The sweep's progress; hidden when stderr is not a terminal.
fn progress(quiet: bool, total: u64) -> anyhow::Result<ProgressBar> {
    if quiet || !std::io::stderr().is_terminal() {
        return Ok(ProgressBar::hidden());
    }
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{spinner} report [{bar:30}] {pos}/{len} {elapsed_precise} eta {eta}  {wide_msg}")
            .context("progress bar template")?
            .progress_chars("=> "),
    );
    Ok(bar)
}
