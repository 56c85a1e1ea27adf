//! What `glint render` writes and prints: images with metadata, the timing/error table, JSON.

use std::path::{Path, PathBuf};

use anyhow::bail;
use glint_core::HdrImage;
use glint_core::compare::{HEATMAP_LOG10_MAX, HEATMAP_LOG10_MIN, ImageErrors, abs_difference, diff_heatmap};
use glint_core::cpu::RayCounts;
use glint_core::flat::FlatScene;
use glint_core::image::{RenderInfo, render_metadata};
use glint_core::memory::{self, MemoryEstimate, MemoryPart};
use glint_io::LoadedScene;
use glint_io::image_file::{write_image, write_png_rgb8};
use glint_scene::{Integrator, RenderSettings, SceneDesc, overflow_causes};
use serde::Serialize;

use super::backend::Run;
use super::console::{say, tell};
use super::units::{mrays_per_s, ms};

/// Render settings as PNG tEXt chunks (`glint:*` keys).
/// What names a render's scene in its metadata: the short name (`glint:scene`), where it came
/// from (`glint:source`: the scene argument as given, or `builtin:NAME`), the flags that shaped it
/// as loaded (`glint:load_flags`, when any), and the content hash of the scene as the tracers
/// read it (`glint:scene_hash`), which tells two edits of one file apart.
pub struct SceneTags {
    pub name: String,
    pub source: String,
    pub load_flags: String,
    pub hash: String,
}

impl SceneTags {
    pub fn new(loaded: &LoadedScene, load_flags: String, flat: &FlatScene) -> Self {
        Self {
            name: loaded.name.clone(),
            source: loaded.source.display().to_string(),
            load_flags,
            hash: flat.content_hash(),
        }
    }
}

pub fn metadata(scene: &SceneTags, s: &RenderSettings, run: &Run, specialised: bool) -> Vec<(String, String)> {
    let mut m = render_metadata(
        s,
        &RenderInfo {
            scene: &scene.name,
            backend: run.backend.name(),
            device: &run.device,
            specialised,
            time_ms: Some(ms(run.render)),
            rays: Some(run.counts.total()),
        },
    );
    m.push(("glint:source".into(), scene.source.clone()));
    if !scene.load_flags.is_empty() {
        m.push(("glint:load_flags".into(), scene.load_flags.clone()));
    }
    m.push(("glint:scene_hash".into(), scene.hash.clone()));
    // Written only with --allow-incomplete: the image is missing work, and says which.
    if !run.incomplete.is_empty() {
        m.push(("glint:gpu_status".into(), format!("{:#x}", run.gpu_status)));
        m.push(("glint:incomplete".into(), run.incomplete.join("; ")));
    }
    m
}

/// `out.png` → `out-cpu.png` (and so on) when several images come from one run.
pub fn suffixed(path: &Path, suffix: &str) -> PathBuf {
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let ext = path.extension().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "png".into());
    path.with_file_name(format!("{stem}-{suffix}.{ext}"))
}

pub fn write_run(path: &Path, run: &Run, metadata: &[(String, String)]) -> anyhow::Result<()> {
    write_image(path, &run.image, metadata)?;
    Ok(())
}

/// The difference of the GPU's image from the CPU's (`cpu` as its file stores it) at `path`,
/// whose extension is the outputs': for EXR the linear |gpu − cpu| per channel, for PNG a
/// false-colour heat map with its scale in the metadata.
pub fn write_diff(
    path: &Path,
    cpu: &HdrImage,
    gpu: &HdrImage,
    mut metadata: Vec<(String, String)>,
) -> anyhow::Result<()> {
    metadata.retain(|(k, _)| k != "glint:backend" && k != "glint:time_ms" && k != "glint:rays" && k != "glint:device");
    metadata.push(("glint:backend".into(), "diff gpu-cpu".into()));
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        metadata.push((
            "glint:diff".into(),
            "|gpu - cpu| per channel of linear radiance, the CPU's image rounded to f32 as its EXR holds it; 0 = identical"
                .into(),
        ));
        write_image(path, &abs_difference(cpu, gpu), &metadata)?;
        return Ok(());
    }
    metadata.push((
        "glint:diff_scale".into(),
        format!(
            "per-pixel max-channel |gpu - cpu| of linear radiance, the CPU's image rounded to f32 as an EXR holds it; \
             black = identical; magma colour map over log10 |diff| from {HEATMAP_LOG10_MIN} (dark) to \
             {HEATMAP_LOG10_MAX} (bright)"
        ),
    ));
    write_png_rgb8(path, cpu.width, cpu.height, &diff_heatmap(cpu, gpu), &metadata)?;
    Ok(())
}

/// The ray counts in the integrator's words: a path's bounce off a diffuse or glossy lobe is
/// counted with the mirror's (it is no reflection in Whitted's sense), and paths have no bailout.
pub fn fmt_counts(c: &RayCounts, integrator: Integrator) -> String {
    match integrator {
        Integrator::Whitted => format!(
            "rays: {} camera, {} shadow, {} reflection, {} refraction ({} total), {} saved by bailout",
            c.camera,
            c.shadow,
            c.reflection,
            c.refraction,
            c.total(),
            c.bailout_saved
        ),
        Integrator::Path => format!(
            "rays: {} camera, {} shadow, {} reflected or scattered, {} refracted ({} total)",
            c.camera,
            c.shadow,
            c.reflection,
            c.refraction,
            c.total()
        ),
    }
}

#[derive(Serialize)]
struct JsonRun<'a> {
    backend: &'a str,
    device: &'a str,
    render_ms: f64,
    total_ms: f64,
    mrays_per_s: f64,
    rays: JsonCounts,
    gpu_status: u32,
    /// What the raised status bits mean (only with --allow-incomplete; empty otherwise).
    incomplete: &'a [String],
}

#[derive(Serialize)]
struct JsonCounts {
    camera: u64,
    shadow: u64,
    reflection: u64,
    refraction: u64,
    total: u64,
    /// Null for the path tracer, which has no bailout.
    saved_by_bailout: Option<u64>,
}

impl JsonCounts {
    fn of(c: &RayCounts, integrator: Integrator) -> Self {
        Self {
            camera: c.camera,
            shadow: c.shadow,
            reflection: c.reflection,
            refraction: c.refraction,
            total: c.total(),
            saved_by_bailout: (integrator == Integrator::Whitted).then_some(c.bailout_saved),
        }
    }
}

/// One backend's `glint render --bench`: its warm-up run (rays, device, status) and the timed
/// runs' median and least render time.
pub struct BenchResult {
    pub warm: Run,
    pub median: std::time::Duration,
    pub min: std::time::Duration,
}

impl BenchResult {
    /// Camera samples a second, in millions.
    pub fn msamples_per_s(&self, s: &RenderSettings) -> f64 {
        f64::from(s.width) * f64::from(s.height) * f64::from(s.spp) / self.median.as_secs_f64() / 1e6
    }
}

#[derive(Serialize)]
struct JsonBenchRun<'a> {
    backend: &'a str,
    device: &'a str,
    median_ms: f64,
    min_ms: f64,
    mrays_per_s: f64,
    msamples_per_s: f64,
    rays: JsonCounts,
    gpu_status: u32,
    incomplete: &'a [String],
}

#[derive(Serialize)]
struct JsonBench<'a> {
    scene: &'a str,
    width: u32,
    height: u32,
    spp: u32,
    depth: u32,
    integrator: &'a str,
    /// Whitted's bailout; null for the path tracer, which ends its paths by Russian roulette.
    bailout: Option<f64>,
    runs: u32,
    backends: Vec<JsonBenchRun<'a>>,
    /// The GPU's median render time over the CPU's, with both backends.
    gpu_cpu_ratio: Option<f64>,
}

/// The GPU's median render time over the CPU's, when `results` has both (CPU first).
pub fn gpu_cpu_ratio(results: &[BenchResult]) -> Option<f64> {
    match results {
        [cpu, gpu] => Some(gpu.median.as_secs_f64() / cpu.median.as_secs_f64()),
        _ => None,
    }
}

/// `glint render --bench --json`: the benchmark's results as one JSON object on stdout.
pub fn print_bench_json(scene: &str, s: &RenderSettings, runs: u32, results: &[BenchResult]) -> anyhow::Result<()> {
    let report = JsonBench {
        scene,
        width: s.width,
        height: s.height,
        spp: s.spp,
        depth: s.max_depth,
        integrator: s.integrator.name(),
        bailout: (s.integrator == Integrator::Whitted).then_some(s.bailout),
        runs,
        backends: results
            .iter()
            .map(|r| JsonBenchRun {
                backend: r.warm.backend.name(),
                device: &r.warm.device,
                median_ms: ms(r.median),
                min_ms: ms(r.min),
                mrays_per_s: mrays_per_s(r.warm.counts.total(), r.median),
                msamples_per_s: r.msamples_per_s(s),
                rays: JsonCounts::of(&r.warm.counts, s.integrator),
                gpu_status: r.warm.gpu_status,
                incomplete: &r.warm.incomplete,
            })
            .collect(),
        gpu_cpu_ratio: gpu_cpu_ratio(results),
    };
    say!("{}", serde_json::to_string_pretty(&report)?)?;
    Ok(())
}

#[derive(Serialize)]
struct JsonErrors {
    max_abs: f64,
    mean_abs: f64,
    rmse: f64,
    rel_mse: f64,
    /// null when the images are identical (infinite PSNR).
    psnr_db: Option<f64>,
    flip_mean: f64,
    first_hit_mismatch_percent: f64,
    p99_abs_same_hit: f64,
    nonfinite_pixels: usize,
}

#[derive(Serialize)]
struct JsonReport<'a> {
    scene: &'a str,
    width: u32,
    height: u32,
    spp: u32,
    depth: u32,
    integrator: &'a str,
    /// Whitted's bailout; null for the path tracer, which ends its paths by Russian roulette.
    bailout: Option<f64>,
    /// Whether paths follow every lobe (`--indirect`); null for Whitted's tree.
    indirect: Option<bool>,
    seed: u32,
    runs: Vec<JsonRun<'a>>,
    gpu_vs_cpu: Option<JsonErrors>,
    outputs: Vec<String>,
    memory: JsonMemory<'a>,
}

/// The memory estimated before the render (checked against the limit) and what the process
/// peaked at, to hold one against the other.
#[derive(Serialize)]
struct JsonMemory<'a> {
    /// Loading the file (null for a built-in scene), then rendering: each checked against
    /// the limit before it started.
    load_estimate_bytes: Option<u64>,
    load_estimate: Option<&'a [MemoryPart]>,
    render_estimate_bytes: u64,
    render_estimate: &'a [MemoryPart],
    /// The memory that was available when glint checked (null where it cannot be read).
    available_bytes: Option<u64>,
    /// Peak resident memory of the process at the end (Linux's VmHWM; null elsewhere).
    peak_rss_bytes: Option<u64>,
}

pub fn print_json(
    scene: &str,
    s: &RenderSettings,
    runs: &[Run],
    errors: Option<&ImageErrors>,
    outputs: &[PathBuf],
    load_estimate: Option<&MemoryEstimate>,
    render_estimate: &MemoryEstimate,
) -> anyhow::Result<()> {
    let report = JsonReport {
        scene,
        width: s.width,
        height: s.height,
        spp: s.spp,
        depth: s.max_depth,
        integrator: s.integrator.name(),
        bailout: (s.integrator == Integrator::Whitted).then_some(s.bailout),
        indirect: (s.integrator == Integrator::Path).then_some(s.indirect),
        seed: s.seed,
        runs: runs
            .iter()
            .map(|r| JsonRun {
                backend: r.backend.name(),
                device: &r.device,
                render_ms: ms(r.render),
                total_ms: ms(r.total),
                mrays_per_s: r.mrays(),
                rays: JsonCounts::of(&r.counts, s.integrator),
                gpu_status: r.gpu_status,
                incomplete: &r.incomplete,
            })
            .collect(),
        gpu_vs_cpu: errors.map(|e| JsonErrors {
            max_abs: e.max_abs,
            mean_abs: e.mean_abs,
            rmse: e.rmse,
            rel_mse: e.rel_mse,
            psnr_db: e.psnr.is_finite().then_some(e.psnr),
            flip_mean: e.flip_mean,
            first_hit_mismatch_percent: 100.0 * e.first_hit_mismatch,
            p99_abs_same_hit: e.p99_abs_same_hit,
            nonfinite_pixels: e.nonfinite,
        }),
        outputs: outputs.iter().map(|p| p.display().to_string()).collect(),
        memory: JsonMemory {
            load_estimate_bytes: load_estimate.map(MemoryEstimate::total),
            load_estimate: load_estimate.map(|e| e.parts.as_slice()),
            render_estimate_bytes: render_estimate.total(),
            render_estimate: &render_estimate.parts,
            available_bytes: memory::available(),
            peak_rss_bytes: memory::peak_rss(),
        },
    };
    say!("{}", serde_json::to_string_pretty(&report)?)?;
    Ok(())
}

/// The human-readable table: one row per backend, then the errors of GPU against CPU.
pub fn print_table(
    scene: &str,
    s: &RenderSettings,
    runs: &[Run],
    errors: Option<&ImageErrors>,
    outputs: &[PathBuf],
) -> std::io::Result<()> {
    say!("{scene}: {}x{} {} spp depth {}", s.width, s.height, s.spp, s.max_depth)?;
    say!("  {:<8} {:>12} {:>12} {:>9}  device", "backend", "render ms", "total ms", "Mrays/s")?;
    for r in runs {
        say!(
            "  {:<8} {:>12.1} {:>12.1} {:>9.2}  {}",
            r.backend.name(),
            ms(r.render),
            ms(r.total),
            r.mrays(),
            r.device
        )?;
        say!("           {}", fmt_counts(&r.counts, s.integrator))?;
    }
    if let Some(e) = errors {
        let psnr = if e.psnr.is_finite() { format!("{:.1} dB", e.psnr) } else { "inf (identical)".into() };
        say!(
            "  gpu vs cpu: max abs {:.3e}, mean abs {:.3e}, RMSE {:.3e}, relMSE {:.3e}, PSNR {psnr}, FLIP mean {:.5},",
            e.max_abs,
            e.mean_abs,
            e.rmse,
            e.rel_mse,
            e.flip_mean
        )?;
        say!(
            "              first-hit mismatch {:.3} %, p99 |diff| on same-hit pixels {:.3e}, non-finite pixels {}",
            100.0 * e.first_hit_mismatch,
            e.p99_abs_same_hit,
            e.nonfinite
        )?;
    }
    for o in outputs {
        say!("  wrote {}", o.display())?;
    }
    Ok(())
}

/// Whether a run may be written: its pixels must all fit a file (`HdrImage::unrepresentable`,
/// an error naming what in the scene overflows), and a GPU render whose shader raised a status
/// flag is missing work (`check_complete`).
pub fn check_writable(
    run: &Run,
    desc: &SceneDesc,
    settings: &RenderSettings,
    incomplete: Incomplete,
) -> anyhow::Result<()> {
    check_complete(run, incomplete)?;
    if let Some(found) = run.image.unrepresentable() {
        bail!(
            "the {} render is not a valid image: {found}; no image was written. In this scene: {}",
            run.backend.name(),
            overflow_causes(desc, settings.max_depth, settings.integrator, found.all_nan())
        );
    }
    Ok(())
}

/// A render whose shader raised a status flag is missing work: an error, or with
/// `--allow-incomplete` a warning (and its PNG metadata says so: `output::metadata`).
fn check_complete(run: &Run, incomplete: Incomplete) -> anyhow::Result<()> {
    if run.incomplete.is_empty() {
        return Ok(());
    }
    let remedy = match incomplete {
        Incomplete::Allow => {
            for message in &run.incomplete {
                tell!("warning: the {} image is incomplete: {message}", run.backend.name());
            }
            return Ok(());
        }
        Incomplete::Refuse => {
            "no image was written (pass --allow-incomplete to write it anyway, marked as incomplete \
                               in its metadata)"
        }
        Incomplete::RefuseTile => {
            "no tile was written (a tile is never written incomplete: the merge would hide \
                                   which tile lost work)"
        }
    };
    bail!(
        "the {} render is incomplete (status {:#x}): {}; {remedy}",
        run.backend.name(),
        run.gpu_status,
        run.incomplete.join("; ")
    )
}

/// What may become of an image whose shader raised a status flag (work is missing).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Incomplete {
    /// An error that names `--allow-incomplete`.
    Refuse,
    /// Written with a warning, marked in its metadata (`--allow-incomplete`).
    Allow,
    /// A tile: never written incomplete.
    RefuseTile,
}

impl Incomplete {
    pub fn allowed(allow: bool) -> Self {
        if allow { Self::Allow } else { Self::Refuse }
    }
}
