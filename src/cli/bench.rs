//! `glint bench rays`: the acceleration structure alone. The BVH build, then the closest hit
//! of two fixed ray sets (`glint_core::rays`: primary rays of a 1280×720 pinhole, incoherent
//! rays from a seeded splitmix64) on the CPU (rayon, T threads) and the GPU (raycast.wgsl, the
//! tracer's own WGSL closest_hit), with the hit fraction and how often the two disagree.
//! `--export` writes the mesh, rays and hits for an outside tracer (`bench_export.rs`).
//!
//! Every measurement is one warm-up run, then `--runs` timed runs; the table shows the median
//! and the best, and throughputs are computed from the median.

use std::borrow::Cow;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use clap::{Args, Subcommand};
use glint_core::bvh::{self, BvhNodes};
use glint_core::cpu::TraceContext;
use glint_core::cpu::raycast::cast_rays;
use glint_core::cpu::raycast::{HitRecord, RayRecord};
use glint_core::memory::{self, RenderPlan, render_estimate};
use glint_core::rays::{HitAgreement, RaySet, compare_hits, hit_fraction};
use glint_core::{Backend, FlatScene};
use glint_gpu::GpuContext;
use glint_gpu::raycast::RayCaster;
use serde::Serialize;

use super::backend::{check_adapter, open_gpu};
use super::console::say;
use super::settings::{LoadArgs, load, parse_threads};
use super::units::{mrays_per_s, ms};

#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub what: BenchCommand,
}

#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// The BVH alone: build time, then closest-hit throughput of primary and incoherent rays
    Rays(RaysArgs),
}

#[derive(Debug, Args)]
pub struct RaysArgs {
    /// A scene file (.toml) or the name of a built-in scene; `bumpy` is made for this
    #[arg(default_value = "bumpy", value_parser = clap::value_parser!(std::ffi::OsString))]
    pub scene: std::ffi::OsString,
    #[command(flatten)]
    pub scene_size: LoadArgs,
    /// CPU threads for the build and the casts: 0 = one per core (the default), at most 4 per
    /// core, as `glint render --threads`
    #[arg(long, default_value_t = 0, allow_hyphen_values = true, value_parser = parse_threads)]
    pub threads: usize,
    /// Which side casts the rays: the CPU (f64), the GPU (WGSL), or both (then their hits are compared)
    #[arg(long, default_value = "cpu", value_parser = ["cpu", "gpu", "both"])]
    pub backend: String,
    /// GPU adapter: a case-insensitive part of its name (default: WGPU_ADAPTER_NAME, else the best GPU)
    #[arg(long)]
    pub adapter: Option<String>,
    /// Timed runs after the warm-up run [1, 100]
    #[arg(long, default_value_t = 5, allow_hyphen_values = true, value_parser = crate::cli::settings::parse_in::<1, 100>)]
    pub runs: u32,
    /// Print the results as JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Also write the mesh, both ray sets and the CPU's hits into this folder, for an outside
    /// tracer (crates/glint-core/benches/embree_rays.cpp); triangles only
    #[arg(long, value_name = "DIR")]
    pub export: Option<std::path::PathBuf>,
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    match &args.what {
        BenchCommand::Rays(a) => rays(a),
    }
}

/// The median and the best of the timed runs.
#[derive(Clone, Copy, Debug, Serialize)]
struct Timing {
    median_ms: f64,
    best_ms: f64,
    runs: u32,
}

/// A warm-up call of `f`, then `runs` timed ones: the warm-up's value and the timing.
fn measure<T>(runs: u32, mut f: impl FnMut() -> anyhow::Result<(T, Duration)>) -> anyhow::Result<(T, Timing)> {
    let (value, _) = f()?;
    let mut times = Vec::with_capacity(runs as usize);
    for _ in 0..runs {
        times.push(f()?.1);
    }
    times.sort();
    Ok((value, Timing { median_ms: ms(super::units::median(&times)), best_ms: ms(times[0]), runs }))
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let start = Instant::now();
    let value = f();
    (value, start.elapsed())
}

#[derive(Debug, Serialize)]
struct BuildResult {
    #[serde(flatten)]
    timing: Timing,
    primitives: usize,
    mtris_per_s: f64,
    nodes: usize,
    /// The CPU walk's nodes of `bvh::WIDTH` children (`BvhNodes::wide`).
    wide_nodes: usize,
    /// The whole `FlatScene::build` once (layout flattening and the BVH).
    flat_scene_ms: f64,
    /// Loading the scene once: reading, parsing or importing, validation (a model's lab scene).
    load_ms: f64,
}

#[derive(Debug, Serialize)]
struct CastResult {
    set: &'static str,
    backend: &'static str,
    rays: usize,
    #[serde(flatten)]
    timing: Timing,
    mrays_per_s: f64,
    hit_fraction: f64,
    #[serde(skip)]
    hits: Vec<HitRecord>,
}

#[derive(Debug, Serialize)]
struct Disagreement {
    set: &'static str,
    rays: usize,
    differing_rays: usize,
    differing_fraction: f64,
    max_rel_t_difference: f64,
}

#[derive(Debug, Serialize)]
struct Report {
    scene: String,
    resolution: Option<u32>,
    triangles: usize,
    spheres: usize,
    planes: usize,
    cpu_threads: u32,
    gpu_adapter: Option<String>,
    statistic: &'static str,
    build: BuildResult,
    casts: Vec<CastResult>,
    gpu_vs_cpu: Vec<Disagreement>,
}

fn rays(args: &RaysArgs) -> anyhow::Result<()> {
    let backends: &[Backend] = match args.backend.as_str() {
        "cpu" => &[Backend::Cpu],
        "gpu" => &[Backend::Gpu],
        _ => &[Backend::Cpu, Backend::Gpu],
    };
    check_adapter(args.adapter.as_deref(), backends.contains(&Backend::Gpu))?;
    let threads = match args.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        t => t,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("glint-bench-{i}"))
        .build()
        .with_context(|| format!("cannot start {threads} threads (--threads)"))?;
    // The GPU first: a device that cannot be opened fails before minutes of CPU work.
    let gpu = if backends.contains(&Backend::Gpu) { Some(open_gpu(args.adapter.as_deref())?) } else { None };

    let (loaded, load_time) = timed(|| load(&args.scene, &args.scene_size.options(None), args.scene_size.memory_limit));
    let loaded = loaded?;
    // The flat scene, its BVH and the walk's nodes as a render on these backends holds them,
    // without the images a render makes and the benchmark does not (no pixels: the rays are a
    // few MB beside), and one more BVH for the timed build's own: `--memory-limit` bounds the
    // benchmark as it bounds a render.
    let plan = RenderPlan { cpu: backends.contains(&Backend::Cpu), gpu: gpu.is_some(), exr: false };
    let no_image = glint_scene::RenderSettings { width: 0, height: 0, ..loaded.desc.render.clone() };
    let mut estimate = render_estimate(&loaded.desc, &no_image, plan);
    if let Some(bvh) = estimate.parts.iter().find(|p| p.what == "BVH").map(|p| p.bytes) {
        estimate.parts.push(memory::MemoryPart { what: "the timed build's BVH", bytes: bvh });
    }
    let builtin = loaded.source.to_str().and_then(|s| s.strip_prefix("builtin:")).and_then(glint_io::builtin);
    let generated = builtin.is_some_and(|b| b.is_generated());
    let mut remedies = Vec::new();
    if generated {
        remedies.push("lower --resolution");
    }
    if args.scene_size.memory_limit.is_some() {
        remedies.push("raise --memory-limit");
    }
    remedies.push("run it on a machine with more memory");
    memory::check(
        format!("building {} for the benchmark", loaded.name),
        &estimate,
        args.scene_size.memory_limit,
        remedies.join(", or "),
    )?;
    let (flat, flat_time) = pool.install(|| timed(|| FlatScene::build(&loaded.desc, &loaded.desc.render)));
    if flat.bvh_nodes.is_empty() {
        bail!("scene '{}' has no spheres or triangles: there is no BVH to measure", loaded.name);
    }
    if let Some(dir) = &args.export {
        super::bench_export::prepare(dir, &flat)?;
    }
    // The BVH part of FlatScene::build, on the primitives it flattened, and the CPU walk's
    // wide nodes made from it (at the first CPU trace otherwise). FlatScene::build stores the
    // triangles in its leaves' order, so a build over them as stored may break ties (equal
    // centroids: the lights scene's axis-aligned partitions) otherwise than the build over the
    // order they were flattened in, and need not be FlatScene's tree (`bench rays lights` was
    // refused for that). The same input always gives the same tree: the first run against the
    // last.
    // A fingerprint, not a copy: at a million triangles a tree is tens of MB.
    let fingerprint = |bvh: &bvh::Bvh| {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        bytemuck::cast_slice::<_, u8>(&bvh.nodes).hash(&mut h);
        bvh.prims.hash(&mut h);
        h.finish()
    };
    let mut last = None;
    let (built, build_timing) = measure(args.runs, || {
        let (bvh, time) = pool.install(|| timed(|| BvhNodes::build_for_cpu(&flat.bounded()).0));
        last = Some(fingerprint(&bvh));
        Ok((bvh, time))
    })?;
    if last.is_some_and(|last| last != fingerprint(&built)) {
        bail!("two timed BVH builds over the same primitives differ; the build is not deterministic");
    }
    if built.nodes.is_empty() || built.prims.len() != flat.bvh_prims.len() {
        bail!(
            "the timed BVH build holds {} primitives in {} nodes, where FlatScene::build's holds {}",
            built.prims.len(),
            built.nodes.len(),
            flat.bvh_prims.len()
        );
    }
    let primitives = flat.spheres.len() + flat.triangles.len();
    let build = BuildResult {
        mtris_per_s: primitives as f64 / (build_timing.median_ms * 1e3).max(1e-9),
        timing: build_timing,
        primitives,
        nodes: flat.bvh_nodes.len(),
        wide_nodes: flat.bvh_nodes.wide().len(),
        flat_scene_ms: ms(flat_time),
        load_ms: ms(load_time),
    };

    let sets: Vec<(RaySet, Vec<RayRecord>)> = RaySet::ALL.iter().map(|&s| (s, s.rays())).collect();
    let mut casts = Vec::new();
    if backends.contains(&Backend::Cpu) {
        let ctx = TraceContext::new(&flat).context("invalid flat scene")?;
        for (set, rays) in &sets {
            let (hits, timing) = measure(args.runs, || Ok(pool.install(|| timed(|| cast_rays(&ctx, rays)))))?;
            casts.push(cast_result(*set, Backend::Cpu, rays.len(), timing, hits));
        }
    }
    if let Some(tracer) = &gpu {
        let ctx: &GpuContext = tracer.context();
        let caster = RayCaster::new(ctx, &flat).context("cannot set up the GPU ray-cast kernel")?;
        for (set, rays) in &sets {
            let batch = caster.upload(ctx, rays).context("cannot upload the rays")?;
            let what = || format!("GPU ray cast of the {} rays", set.name());
            let (_, timing) = measure(args.runs, || Ok(((), caster.cast(ctx, &batch).with_context(what)?)))?;
            let hits = caster.hits(ctx, &batch).context("cannot read the hits back")?;
            casts.push(cast_result(*set, Backend::Gpu, rays.len(), timing, hits));
        }
    }
    if let Some(dir) = &args.export {
        // The CPU's hits of the timed casts, or cast once now when only the GPU was timed.
        let ctx = TraceContext::new(&flat).context("invalid flat scene")?;
        let cpu_hits: Vec<Cow<[HitRecord]>> = sets
            .iter()
            .map(|(set, rays)| match casts.iter().find(|c| c.set == set.name() && c.backend == Backend::Cpu.name()) {
                Some(c) => Cow::Borrowed(&c.hits[..]),
                None => Cow::Owned(pool.install(|| cast_rays(&ctx, rays))),
            })
            .collect();
        let files: Vec<_> =
            sets.iter().zip(&cpu_hits).map(|((set, rays), hits)| (*set, &rays[..], &hits[..])).collect();
        super::bench_export::export(dir, &flat, &files)?;
    }
    let mut gpu_vs_cpu = Vec::new();
    for (set, _) in &sets {
        let of = |b: Backend| casts.iter().find(|c| c.set == set.name() && c.backend == b.name());
        if let (Some(cpu), Some(gpu)) = (of(Backend::Cpu), of(Backend::Gpu)) {
            let a: HitAgreement = compare_hits(&gpu.hits, &cpu.hits);
            gpu_vs_cpu.push(Disagreement {
                set: set.name(),
                rays: a.rays,
                differing_rays: a.differing,
                differing_fraction: a.differing_fraction(),
                max_rel_t_difference: a.max_t_rel,
            });
        }
    }
    let report = Report {
        scene: loaded.name.clone(),
        resolution: args.scene_size.resolution,
        triangles: flat.triangles.len(),
        spheres: flat.spheres.len(),
        planes: flat.planes.len(),
        cpu_threads: threads as u32,
        gpu_adapter: gpu.as_ref().map(|t| t.context().adapter.with_driver()),
        statistic: "one warm-up run, then the median and the best of `runs` timed runs; throughput from the median",
        build,
        casts,
        gpu_vs_cpu,
    };
    if args.json {
        say!("{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        print_table(&report)?;
    }
    Ok(())
}

fn cast_result(set: RaySet, backend: Backend, rays: usize, timing: Timing, hits: Vec<HitRecord>) -> CastResult {
    let median = Duration::from_secs_f64(timing.median_ms / 1e3);
    CastResult {
        set: set.name(),
        backend: backend.name(),
        rays,
        mrays_per_s: mrays_per_s(rays as u64, median),
        hit_fraction: hit_fraction(&hits),
        timing,
        hits,
    }
}

fn print_table(r: &Report) -> std::io::Result<()> {
    let b = &r.build;
    say!(
        "{}: {} triangles, {} spheres, {} planes (walked apart); BVH of {} nodes ({} of {} children on the CPU); {} CPU threads",
        r.scene,
        r.triangles,
        r.spheres,
        r.planes,
        b.nodes,
        b.wide_nodes,
        bvh::WIDTH,
        r.cpu_threads
    )?;
    say!("  warm-up, then median and best of {} runs; Mrays/s and Mtris/s from the median", b.timing.runs)?;
    say!(
        "  BVH build    {:>10.1} ms median {:>10.1} ms best {:>9.2} Mtris/s  (whole FlatScene::build {:.1} ms, load {:.1} ms)",
        b.timing.median_ms,
        b.timing.best_ms,
        b.mtris_per_s,
        b.flat_scene_ms,
        b.load_ms
    )?;
    say!(
        "  {:<11} {:<8} {:>10} {:>12} {:>12} {:>9} {:>8}",
        "rays",
        "backend",
        "count",
        "median ms",
        "best ms",
        "Mrays/s",
        "hit %"
    )?;
    for c in &r.casts {
        say!(
            "  {:<11} {:<8} {:>10} {:>12.1} {:>12.1} {:>9.2} {:>8.2}",
            c.set,
            c.backend,
            c.rays,
            c.timing.median_ms,
            c.timing.best_ms,
            c.mrays_per_s,
            100.0 * c.hit_fraction
        )?;
    }
    if let Some(adapter) = &r.gpu_adapter {
        say!("  gpu: {adapter}")?;
    }
    for d in &r.gpu_vs_cpu {
        say!(
            "  gpu vs cpu, {}: {} of {} rays hit another primitive ({:.4} %), max relative t difference {:.2e}",
            d.set,
            d.differing_rays,
            d.rays,
            100.0 * d.differing_fraction,
            d.max_rel_t_difference
        )?;
    }
    Ok(())
}
