//! `glint render`: one scene on the CPU, the GPU or both, to PNG/EXR; or a benchmark.

use std::path::PathBuf;

use anyhow::anyhow;
use clap::Args;
use clap::builder::{PossibleValuesParser, TypedValueParser};
use glint_core::compare::compare_images;
use glint_core::cpu::DEFAULT_MAX_RAYS_PER_SAMPLE;
use glint_core::memory::{self, RenderPlan, render_estimate};
use glint_core::render::CpuRenderError;
use glint_core::{Accel, Backend, CpuOptions, FlatScene};
use glint_gpu::GpuOptions;
use glint_io::{BUILTIN_SCENES, RESOLUTIONS};
use glint_scene::{Integrator, RenderSettings, SceneDesc, ray_tree_bound, unbounded_ray_tree};

use super::backend::{Run, check_adapter, open_gpu, run_cpu, run_gpu};
use super::console::{say, tell};
use super::interrupt;
use super::output::{
    BenchResult, Incomplete, SceneTags, check_writable, fmt_counts, gpu_cpu_ratio, metadata, print_bench_json,
    print_json, print_table, suffixed, write_diff, write_run,
};
use super::output_path::{check_not_read, check_outputs, default_output};
use super::settings::{LoadArgs, SettingsArgs, load_with_estimate, parse_ray_cap, parse_threads, tell_warnings};
use super::tile::{TileJob, TileSpec, parse_tile, render_tile};
use super::units::{mrays_per_s, ms};
use crate::cli::usage::usage;

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A scene file (.toml), a model file (.gltf, .glb, .obj) opened in a lab scene, or the name of a built-in scene (see --list)
    #[arg(default_value = "whitted", value_parser = clap::value_parser!(std::ffi::OsString))]
    pub scene: std::ffi::OsString,
    /// Output image: .png (sRGB, settings in metadata) or .exr (linear f32). Default: SCENE.png;
    /// with --backend both, NAME-cpu, NAME-gpu and NAME-diff images
    #[arg(short, long, conflicts_with = "bench")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub scene_size: LoadArgs,
    /// Which tracer renders: the CPU reference, the GPU mirror, or both (then compared)
    #[arg(long, default_value = "cpu", value_parser = backends())]
    pub backend: &'static [Backend],
    /// GPU adapter: a case-insensitive part of its name (default: WGPU_ADAPTER_NAME, else the best GPU)
    #[arg(long)]
    pub adapter: Option<String>,
    /// CPU worker threads: 0 = one per core, at most 4 per core (and never more than 1024)
    #[arg(long, default_value_t = 0, allow_hyphen_values = true, value_parser = parse_threads)]
    pub threads: usize,
    /// The CPU's bound on one camera sample's ray tree [1, 2^40]: a pixel that reaches it is an
    /// error naming the pixel, never a silently cut tree (default 2^22 = 4,194,304)
    #[arg(long, value_name = "RAYS", allow_hyphen_values = true, value_parser = parse_ray_cap)]
    pub max_rays_per_sample: Option<u64>,
    /// Run every feature of both tracers even where the scene does not need it
    #[arg(long)]
    pub no_specialise: bool,
    /// How both tracers find primitives: the BVH from 24 spheres and triangles on (auto), always the BVH, or brute force (none); the CPU image is bit-identical either way, and on the GPU brute force is limited to 65,535 primitives of a kind
    #[arg(long, default_value = "auto", value_parser = accels())]
    pub accel: Accel,
    /// Render one block of a fixed grid of the image for a scheduler's array task: I/N (tile I
    /// of N, from 0), or N to take I from SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or
    /// AWS_BATCH_JOB_ARRAY_INDEX. Writes an EXR whose data window is the tile (default
    /// SCENE-tile-I.exr); `glint merge` joins the tiles
    #[arg(long, value_name = "I/N|N", allow_hyphen_values = true, value_parser = parse_tile)]
    pub tile: Option<TileSpec>,
    /// Print the results as JSON instead of a table (with --bench, the benchmark's figures)
    #[arg(long)]
    pub json: bool,
    /// List the built-in scenes and exit
    // Alone: with other flags it listed and ignored them (`--list whitted --width 0`).
    #[arg(long, exclusive = true)]
    pub list: bool,
    /// Benchmark: one warm-up, then --runs timed renders; prints median and min
    #[arg(long)]
    pub bench: bool,
    /// Timed runs of --bench [1, 1000] (default 5)
    // Checked by `check_backend_flags`: clap's `requires = "bench"` counts the flag's default
    // (false) as given, and `--runs` without `--bench` rendered once without a word.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<1, 1000>)]
    pub runs: Option<u32>,
    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
    /// Replace an output file even if it is read-only
    #[arg(long)]
    pub force: bool,
    /// Write a GPU image whose shader raised a status flag (a loop bound, the driver's loop
    /// cut-off, a stack overflow: work is missing) instead of failing; its PNG metadata says so
    #[arg(long)]
    pub allow_incomplete: bool,
}

/// The choices of `--backend` and the tracers each runs, CPU first.
const BACKEND_CHOICES: [(&str, &[Backend]); 3] =
    [("cpu", &[Backend::Cpu]), ("gpu", &[Backend::Gpu]), ("both", &[Backend::Cpu, Backend::Gpu])];

fn backends() -> impl TypedValueParser<Value = &'static [Backend]> {
    PossibleValuesParser::new(BACKEND_CHOICES.map(|(name, _)| name)).map(|choice| {
        let (_, backends) = BACKEND_CHOICES.iter().find(|(name, _)| *name == choice).expect("clap admits only these");
        *backends
    })
}

fn accels() -> impl TypedValueParser<Value = Accel> {
    PossibleValuesParser::new(Accel::CHOICES.map(|(name, _)| name)).map(|choice| {
        let (_, accel) = Accel::CHOICES.iter().find(|(name, _)| *name == choice).expect("clap admits only these");
        *accel
    })
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    if args.list {
        for b in BUILTIN_SCENES {
            // A generated scene is described at a small resolution: the text is the same.
            let (desc, _) = b.load(b.is_generated().then_some(*RESOLUTIONS.start()))?;
            say!("{:<12} {}", b.name, desc.description)?;
        }
        return Ok(());
    }
    check_backend_flags(args)?;
    let (loaded, load_estimate) =
        load_with_estimate(&args.scene, &args.scene_size.options(Some(&args.settings)), args.scene_size.memory_limit)?;
    let settings = args.settings.apply(&loaded.desc.render)?;
    tell_warnings(&loaded, &settings);
    let specialise = !args.no_specialise;
    let cpu_options = CpuOptions {
        threads: args.threads,
        specialise,
        accel: args.accel,
        max_rays_per_sample: args.max_rays_per_sample.unwrap_or(DEFAULT_MAX_RAYS_PER_SAMPLE),
        region: None,
    };
    let gpu_options = GpuOptions { specialise, accel: args.accel, ..GpuOptions::default() };
    if let Some(spec) = args.tile {
        let [backend] = args.backend else {
            usage!("--tile renders on one backend: give --backend cpu or --backend gpu");
        };
        if args.bench || args.json {
            usage!("--tile writes one tile; it has no --bench or --json");
        }
        if args.allow_incomplete {
            usage!(
                "--tile writes no incomplete tile (a merge would hide which tile lost work), so --allow-incomplete \
                 does nothing there: leave it out"
            );
        }
        return render_tile(TileJob {
            loaded: &loaded,
            settings: &settings,
            spec,
            backend: *backend,
            output: args.output.clone(),
            cpu: cpu_options,
            gpu: gpu_options,
            adapter: args.adapter.as_deref(),
            load_flags: args.scene_size.flags(),
            specialise,
            force: args.force,
            quiet: args.quiet,
        });
    }
    let output = args.output.clone().unwrap_or_else(|| default_output(&loaded, ".png"));
    let plan = RenderPlan {
        cpu: args.backend.contains(&Backend::Cpu),
        gpu: args.backend.contains(&Backend::Gpu),
        exr: output.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")),
    };
    let estimate = render_estimate(&loaded.desc, &settings, plan);
    // Only the remedies this render can take.
    let mut remedies = vec!["lower --width and --height"];
    if plan.cpu && plan.gpu {
        remedies.push("render on one backend");
    }
    if plan.exr {
        remedies.push("write a PNG instead of an EXR");
    }
    if args.scene_size.memory_limit.is_some() {
        remedies.push("raise --memory-limit");
    }
    let remedy = glint_scene::or_list(&remedies);
    memory::check(
        format!("rendering {} at {}x{}", loaded.name, settings.width, settings.height),
        &estimate,
        args.scene_size.memory_limit,
        &remedy,
    )?;
    // After the memory check: a benchmark builds and renders the same (it writes no image).
    if args.bench {
        let flat = FlatScene::build(&loaded.desc, &settings);
        return bench(args, &loaded.name, &flat, &settings, &cpu_options, &gpu_options);
    }
    let both = args.backend.len() > 1;
    let image_path = |run: &Run| if both { suffixed(&output, run.backend.name()) } else { output.clone() };
    // A heat map beside PNG images, the linear difference beside EXR ones (`write_diff`).
    let diff_path = suffixed(&output, "diff");
    let planned: Vec<PathBuf> = if both {
        vec![suffixed(&output, "cpu"), suffixed(&output, "gpu"), diff_path.clone()]
    } else {
        vec![output.clone()]
    };
    let planned_paths: Vec<&std::path::Path> = planned.iter().map(PathBuf::as_path).collect();
    check_outputs(&planned_paths, &loaded.source, args.force)?;
    check_not_read(&planned_paths, &loaded)?;
    interrupt::check()?;
    let flat = FlatScene::build(&loaded.desc, &settings);
    let scene_tags = SceneTags::new(&loaded, args.scene_size.flags(), &flat);
    interrupt::check()?;

    let gpu = if args.backend.contains(&Backend::Gpu) { Some(open_gpu(args.adapter.as_deref())?) } else { None };
    // The GPU renders first: a scene it cannot take (size, limits) fails before a long CPU render.
    let gpu_run =
        gpu.as_ref().map(|tracer| run_gpu(tracer, &flat, &gpu_options, args.quiet || args.json)).transpose()?;
    let mut runs = Vec::new();
    if args.backend.contains(&Backend::Cpu) {
        let run = run_cpu(&flat, &cpu_options, args.quiet || args.json);
        runs.push(run.map_err(|e| explain_ray_cap(e, &loaded.desc, &settings))?);
    }
    runs.extend(gpu_run);
    // Every image is checked before any is written: a failure leaves no file at all.
    for run in &runs {
        check_writable(run, &loaded.desc, &settings, Incomplete::allowed(args.allow_incomplete))?;
    }
    // `--backend both`'s three images appear together or not at all (`all_or_nothing`): a
    // full disk on the GPU's image left the CPU's in place, and the message did not say so.
    let written = glint_io::atomic::all_or_nothing(|| -> anyhow::Result<_> {
        let mut outputs = Vec::new();
        for run in &runs {
            let path = image_path(run);
            let tags = metadata(&scene_tags, &settings, run, specialise);
            write_run(&path, run, &tags)?;
            outputs.push(path);
        }
        let errors = if let [cpu, gpu] = runs.as_slice() {
            // The CPU's image as its file holds it (f32): identical files compare as identical.
            let stored = cpu.image.as_stored();
            write_diff(&diff_path, &stored, &gpu.image, metadata(&scene_tags, &settings, gpu, specialise))?;
            outputs.push(diff_path.clone());
            Some(compare_images(&stored, &gpu.image))
        } else {
            None
        };
        Ok((outputs, errors))
    });
    let (outputs, errors) = written.map_err(|e| not_written(e, &planned))?;
    if args.json {
        print_json(&loaded.name, &settings, &runs, errors.as_ref(), &outputs, load_estimate.as_ref(), &estimate)?;
    } else {
        print_table(&loaded.name, &settings, &runs, errors.as_ref(), &outputs)?;
        if settings.integrator == Integrator::Path {
            let transport = if settings.indirect {
                "every lobe"
            } else {
                "only k_r and k_t with direct light (--indirect off: Whitted's transport)"
            };
            let paths = if settings.spp == 1 { "1 path".to_string() } else { format!("{} paths", settings.spp) };
            let bounces = if settings.max_depth == 1 {
                "1 bounce".to_string()
            } else {
                format!("{} bounces", settings.max_depth)
            };
            say!(
                "  path tracer: {paths} a pixel, at most {bounces}, {transport}; no ambient term (I_a·k_a and \
                 the lights' I_a,j stand in for the indirect light the paths compute)"
            )?;
        }
    }
    Ok(())
}

/// The error of a failed `all_or_nothing` write of `planned`, saying which of them changed.
fn not_written(e: glint_io::atomic::BatchError<anyhow::Error>, planned: &[PathBuf]) -> anyhow::Error {
    use glint_io::atomic::BatchError;
    let names = |paths: &[&PathBuf]| paths.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", ");
    match e {
        BatchError::Written(e) if planned.len() > 1 => {
            anyhow!("{e:#}; nothing was written (none of {})", names(&planned.iter().collect::<Vec<_>>()))
        }
        BatchError::Written(e) => e,
        BatchError::Renamed { error, replaced } => {
            let kept: Vec<&PathBuf> = planned.iter().filter(|p| !replaced.contains(p)).collect();
            let replaced =
                if replaced.is_empty() { "none".to_string() } else { names(&replaced.iter().collect::<Vec<_>>()) };
            anyhow!("{error}; of this run's images {replaced} were written, {} were not", names(&kept))
        }
    }
}

/// Flags of a backend the render does not use would do nothing: errors, as `--runs` without
/// `--bench` is.
fn check_backend_flags(args: &RenderArgs) -> anyhow::Result<()> {
    check_adapter(args.adapter.as_deref(), args.backend.contains(&Backend::Gpu))?;
    if args.runs.is_some() && !args.bench {
        usage!("--runs counts the timed renders of --bench: give --bench, or leave --runs out");
    }
    if args.allow_incomplete && !args.backend.contains(&Backend::Gpu) {
        usage!(
            "--allow-incomplete keeps a GPU image its shader flagged, and --backend cpu renders none (the CPU's \
             images are never incomplete): give --backend gpu or both, or leave it out"
        );
    }
    if args.max_rays_per_sample.is_some() && !args.backend.contains(&Backend::Cpu) {
        usage!(
            "--max-rays-per-sample bounds the CPU's ray trees, and --backend gpu does not run the CPU (the GPU's \
             trees are bounded by its stack): give --backend cpu or both, or leave it out"
        );
    }
    Ok(())
}

/// A ray tree stopped at `--max-rays-per-sample` in a scene whose own tree is bounded (its
/// bailout and depth keep it within `WARN_RAYS_PER_SAMPLE`): the cap is the cause, not the
/// scene, whose remedies the core's message offers first (`--max-rays-per-sample 1` on whitted
/// was told to set the bailout it has), and the scene's bound is the cap that suffices.
fn explain_ray_cap(e: anyhow::Error, desc: &SceneDesc, settings: &RenderSettings) -> anyhow::Error {
    let Some(&CpuRenderError::RayCap { x, y, cap }) = e.downcast_ref::<CpuRenderError>() else { return e };
    match unbounded_ray_tree(desc, settings) {
        // The scene's own trees can pass any cap: the load warning's cause and remedy (the
        // core's generic one asked for a bailout a scene had, under a global attenuation).
        Some(why) => anyhow!(
            "pixel ({x}, {y}): a camera sample's ray tree reached the cap of {cap} rays (--max-rays-per-sample), so \
             the render stopped: {why}; or raise the cap"
        ),
        None => {
            // The cap counts the tree's rays and at most one shadow ray from each hit to each light.
            let tree = ray_tree_bound(desc, settings);
            let lights = desc.lights.len();
            let shadows = match lights {
                0 => String::new(),
                n => format!(
                    " ({tree} reflected and refracted, each hit with a shadow ray to each of {n} light{})",
                    if n == 1 { "" } else { "s" }
                ),
            };
            anyhow!(
                "pixel ({x}, {y}): a camera sample's ray tree reached the cap of {cap} rays (--max-rays-per-sample), \
                 so the render stopped; the scene's own bailout and depth keep every tree within {} rays{shadows}: \
                 raise the cap to that",
                tree * (1.0 + lights as f64)
            )
        }
    }
}

/// `--bench`'s timed runs without `--runs`.
const DEFAULT_BENCH_RUNS: u32 = 5;

fn bench(
    args: &RenderArgs,
    name: &str,
    flat: &FlatScene,
    settings: &RenderSettings,
    cpu: &CpuOptions,
    gpu_options: &GpuOptions,
) -> anyhow::Result<()> {
    let runs = args.runs.unwrap_or(DEFAULT_BENCH_RUNS);
    let gpu = if args.backend.contains(&Backend::Gpu) { Some(open_gpu(args.adapter.as_deref())?) } else { None };
    let mut backends: Vec<Box<dyn Fn() -> anyhow::Result<Run>>> = Vec::new();
    if args.backend.contains(&Backend::Cpu) {
        backends.push(Box::new(|| run_cpu(flat, cpu, true)));
    }
    if let Some(tracer) = &gpu {
        backends.push(Box::new(move || run_gpu(tracer, flat, gpu_options, true)));
    }
    let mut results = Vec::new();
    for render in &backends {
        let warm = render()?;
        for message in &warm.incomplete {
            tell!("warning: the {} render is incomplete: {message}", warm.backend.name());
        }
        let mut times = Vec::new();
        for _ in 0..runs {
            times.push(render()?.render);
        }
        times.sort();
        let result = BenchResult { median: super::units::median(&times), min: times[0], warm };
        if !args.json {
            say_bench_line(name, settings, runs, &result)?;
        }
        results.push(result);
    }
    if args.json {
        return print_bench_json(name, settings, runs, &results);
    }
    if let Some(ratio) = gpu_cpu_ratio(&results) {
        say!("bench {name}: gpu/cpu render time ratio {ratio:.2}")?;
    }
    Ok(())
}

/// One backend's `--bench` line.
fn say_bench_line(name: &str, s: &RenderSettings, runs: u32, r: &BenchResult) -> anyhow::Result<()> {
    // The bailout is Whitted's; a path render gives its samples per second instead.
    let mode = match s.integrator {
        Integrator::Whitted => format!("bailout {}", glint_scene::format_rounded(s.bailout, 3)),
        Integrator::Path => format!("path tracer, {:.3} Msamples/s", r.msamples_per_s(s)),
    };
    say!(
        "bench {name} {}: {}x{} {} spp depth {} {mode}, {}: median {:.1} ms, min {:.1} ms over {runs} runs, {:.2} Mrays/s; {}",
        r.warm.backend.name(),
        s.width,
        s.height,
        s.spp,
        s.max_depth,
        r.warm.device,
        ms(r.median),
        ms(r.min),
        mrays_per_s(r.warm.counts.total(), r.median),
        fmt_counts(&r.warm.counts, s.integrator)
    )?;
    Ok(())
}
