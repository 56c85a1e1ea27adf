//! `glint report`: error against run time. Sweeps render configurations per scene, times
//! each (render only, median after a warm-up), measures its error against a CPU f64
//! reference, and writes report.csv, report.md and one log-log plot per scene; and measures
//! the render time of each specular model (specular.csv).

mod csv;
mod machine;
mod markdown;
mod pareto;
mod plan;
mod plot;
mod specular;
mod sweep;

use std::collections::HashMap;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, anyhow, bail};
use clap::Args;
use glint_core::Backend;
use glint_io::atomic::write_file_atomically;
use glint_scene::{Integrator, RenderSettings};
use indicatif::{ProgressBar, ProgressStyle};

use self::plan::Plan;
use self::sweep::Engines;
use super::backend::open_gpu;
use super::settings::{load, parse_integrator, parse_threads};

const DEFAULT_SCENES: &[&str] = &["whitted", "cornell", "spotlights", "highlights", "lights"];
const QUICK_SCENES: &[&str] = &["whitted", "highlights"];

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Scenes to sweep, comma-separated: built-in names or scene files (default: every built-in;
    /// with --quick: whitted,highlights)
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Folder for report.csv, report.md and the plots (created if missing)
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// A small sweep for CI: two scenes, 96x72, a reduced grid (under a minute on 2 cores)
    #[arg(long)]
    pub quick: bool,
    /// Image width for every scene (default 320; 96 with --quick)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub width: Option<u32>,
    /// Image height for every scene (default 240; 72 with --quick)
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=4096))]
    pub height: Option<u32>,
    /// Samples per pixel of the CPU reference
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(64..=4096))]
    pub reference_spp: u32,
    /// Timed runs per configuration after the warm-up; the median is reported
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u32).range(3..=100))]
    pub runs: u32,
    /// GPU adapter: a case-insensitive part of its name (default: WGPU_ADAPTER_NAME, else the best GPU)
    #[arg(long)]
    pub adapter: Option<String>,
    /// Sweep the CPU tracer only (no GPU needed)
    #[arg(long)]
    pub cpu_only: bool,
    /// CPU worker threads: 0 = one per core, at most 4 per core (and never more than 1024)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true, value_parser = parse_threads)]
    pub threads: usize,
    /// Render every scene with this integrator: whitted or path (default: each scene's own
    /// render.integrator). A path-traced reference is itself a Monte Carlo estimate at
    /// --reference-spp
    #[arg(long, value_parser = parse_integrator)]
    pub integrator: Option<Integrator>,
    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    let started = Instant::now();
    let plan = if args.quick { Plan::quick(args.reference_spp) } else { Plan::full(args.reference_spp) };
    let (width, height) = if args.quick { (96, 72) } else { (320, 240) };
    let (width, height) = (args.width.unwrap_or(width), args.height.unwrap_or(height));
    let names: Vec<String> = if args.scenes.is_empty() {
        (if args.quick { QUICK_SCENES } else { DEFAULT_SCENES }).iter().map(|s| s.to_string()).collect()
    } else {
        args.scenes.iter().map(|s| s.trim().to_string()).filter(|s| !s.is_empty()).collect()
    };
    if names.is_empty() {
        bail!(
            "--scenes names no scene; give built-in names or scene files, comma-separated (or leave it out for the default set)"
        );
    }
    let scenes =
        names.iter().map(|n| load(n, &glint_io::LoadOptions::default(), None)).collect::<anyhow::Result<Vec<_>>>()?;
    let mut seen = HashMap::new();
    for s in &scenes {
        if let Some(other) = seen.insert(s.name.clone(), s.source.clone()) {
            bail!(
                "two scenes are both called '{}' ({} and {}); their plots would collide",
                s.name,
                other.display(),
                s.source.display()
            );
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
    let gpu_device = gpu.as_ref().map(|g| {
        let a = &g.context().adapter;
        if a.driver.is_empty() { a.to_string() } else { format!("{a}, driver {}", a.driver) }
    });
    std::fs::create_dir_all(&args.out).with_context(|| format!("cannot create {}", args.out.display()))?;
    let backends: Vec<Backend> = if gpu.is_some() { vec![Backend::Cpu, Backend::Gpu] } else { vec![Backend::Cpu] };
    let threads =
        if args.threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { args.threads };
    let cpu_device = format!("{threads} threads");
    let mut engines = Engines { threads, gpu, pipelines: HashMap::new() };

    let planned = plan.configs(&backends);
    let reference = plan.reference();
    // One tick per render: the reference, then each configuration's warm-up and timed runs,
    // then each specular model's.
    let renders =
        scenes.len() * (1 + planned.len() * (1 + args.runs as usize) + specular::renders(&backends, args.runs));
    let bar = progress(args.quiet, renders as u64)?;
    let mut results = Vec::with_capacity(scenes.len());
    for loaded in &scenes {
        let scene = &loaded.desc.render;
        let base =
            RenderSettings { width, height, integrator: args.integrator.unwrap_or(scene.integrator), ..scene.clone() };
        let mut result = sweep::run_scene(&mut engines, loaded, &base, &reference, &planned, args.runs, &bar)?;
        result.specular = specular::measure(&mut engines, loaded, &base, &backends, args.runs, &bar)?;
        pareto::mark_fronts(&mut result.rows);
        let path = plot::write_plot(&args.out, &result, args.runs as usize)?;
        bar.suspend(|| println!("{}: {} configurations, wrote {}", result.name, result.rows.len(), path.display()));
        results.push(result);
    }
    bar.finish_and_clear();

    let machine = machine::Machine::probe();
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
    let csv_path = args.out.join("report.csv");
    write_report_file(&csv_path, &csv::render_csv(&results, &cpu_device, gpu_device.as_deref().unwrap_or("")))?;
    write_report_file(&args.out.join("specular.csv"), &csv::render_specular_csv(&results))?;
    let md_path = args.out.join("report.md");
    write_report_file(&md_path, &markdown::render_markdown(&setup, &results))?;
    println!(
        "report: {} scenes, {} configurations each, in {:.1} s; wrote {} and {}",
        results.len(),
        planned.len(),
        started.elapsed().as_secs_f64(),
        md_path.display(),
        csv_path.display()
    );
    Ok(())
}

/// Replaces `path` atomically: a reader (or a CI artefact upload) never sees a half-written report.
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
