//! `glint render`: one scene to PNG/EXR, or a benchmark of the render.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context, bail};
use clap::Args;
use glint_core::cpu::RayCounts;
use glint_core::image::write_image;
use glint_core::render::tile_count;
use glint_core::scene::{BUILTIN_SCENES, RenderSettings, parse_scene};
use glint_core::{CpuOptions, CpuRender, FlatScene, RenderControl, render_cpu};
use indicatif::{ProgressBar, ProgressStyle};

use super::settings::{SettingsArgs, load};

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// A scene file (.toml) or the name of a built-in scene (see --list)
    #[arg(default_value = "whitted")]
    pub scene: String,
    /// Output image: .png (sRGB, settings in metadata) or .exr (linear f32). Default: SCENE.png
    #[arg(short, long)]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// CPU worker threads; 0 = one per core
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Run every feature of the tracer even where the scene does not need it
    #[arg(long)]
    pub no_specialise: bool,
    /// List the built-in scenes and exit
    #[arg(long)]
    pub list: bool,
    /// Benchmark: one warm-up, then --runs timed renders; prints median and min
    #[arg(long)]
    pub bench: bool,
    /// Timed runs of --bench
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub runs: u32,
    /// No progress bar
    #[arg(short, long)]
    pub quiet: bool,
}

pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    if args.list {
        for b in BUILTIN_SCENES {
            let (desc, _) = parse_scene(b.text, std::path::Path::new(b.name))?;
            println!("{:<12} {}", b.name, desc.description);
        }
        return Ok(());
    }
    let loaded = load(&args.scene)?;
    let settings = args.settings.apply(&loaded.desc.render)?;
    let flat = FlatScene::build(&loaded.desc, &settings);
    let options = CpuOptions { threads: args.threads, specialise: !args.no_specialise };
    if args.bench {
        return bench(&loaded.name, &flat, &options, args.runs);
    }
    let output = args.output.clone().unwrap_or_else(|| PathBuf::from(format!("{}.png", loaded.name)));
    check_output(&output)?;

    let total_start = Instant::now();
    let result = render_with_progress(&flat, &options, args.quiet)?;
    let metadata = metadata(&loaded.name, &settings, &result, &options);
    write_image(&output, &result.image, &metadata)?;
    if !result.image.all_finite() {
        bail!("internal error: the render produced non-finite pixels (written to {})", output.display());
    }
    println!(
        "{}: {}x{} {} spp depth {} in {} (total {}), {}, {:.2} Mrays/s, {} threads -> {}",
        loaded.name,
        settings.width,
        settings.height,
        settings.spp,
        settings.max_depth,
        fmt_ms(result.elapsed),
        fmt_ms(total_start.elapsed()),
        fmt_counts(&result.counts),
        mrays(&result.counts, result.elapsed),
        result.threads,
        output.display()
    );
    Ok(())
}

fn check_output(path: &std::path::Path) -> anyhow::Result<()> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("png" | "exr") => {}
        _ => bail!("{}: unsupported output format; use a .png or .exr file name", path.display()),
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty() && !d.is_dir()) {
        bail!("{}: the output folder {} does not exist", path.display(), dir.display());
    }
    Ok(())
}

fn render_with_progress(flat: &FlatScene, options: &CpuOptions, quiet: bool) -> anyhow::Result<CpuRender> {
    let tiles = tile_count(flat.header.width, flat.header.height) as u64;
    let bar = if quiet || !std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        ProgressBar::hidden()
    } else {
        let bar = ProgressBar::new(tiles);
        bar.set_style(
            ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent:>3}% {elapsed_precise} eta {eta}")
                .context("progress bar template")?
                .progress_chars("=> "),
        );
        bar
    };
    let on_tile = |_: &glint_core::render::Tile| bar.inc(1);
    let result = render_cpu(flat, options, RenderControl { cancel: None, on_tile: Some(&on_tile) })?;
    bar.finish_and_clear();
    Ok(result)
}

fn bench(name: &str, flat: &FlatScene, options: &CpuOptions, runs: u32) -> anyhow::Result<()> {
    let h = &flat.header;
    render_cpu(flat, options, RenderControl::default())?;
    let mut times = Vec::new();
    let mut counts = RayCounts::default();
    let mut threads = 0;
    for _ in 0..runs {
        let r = render_cpu(flat, options, RenderControl::default())?;
        times.push(r.elapsed);
        counts = r.counts;
        threads = r.threads;
    }
    times.sort();
    let median = times[times.len() / 2];
    println!(
        "bench {name}: {}x{} {} spp depth {} bailout {} cpu {} threads: median {} min {} over {runs} runs, {}, {:.2} Mrays/s (median)",
        h.width,
        h.height,
        h.spp,
        h.max_depth,
        h.bailout,
        threads,
        fmt_ms(median),
        fmt_ms(times[0]),
        fmt_counts(&counts),
        mrays(&counts, median)
    );
    Ok(())
}

pub fn fmt_ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

pub fn fmt_counts(c: &RayCounts) -> String {
    format!(
        "rays: {} camera, {} shadow, {} reflection, {} refraction ({} total), {} saved by bailout",
        c.camera,
        c.shadow,
        c.reflection,
        c.refraction,
        c.total(),
        c.bailout_saved
    )
}

pub fn mrays(c: &RayCounts, d: Duration) -> f64 {
    c.total() as f64 / d.as_secs_f64().max(1e-9) / 1e6
}

fn metadata(name: &str, s: &RenderSettings, r: &CpuRender, options: &CpuOptions) -> Vec<(String, String)> {
    [
        ("Software", format!("glint {}", env!("CARGO_PKG_VERSION"))),
        ("glint:scene", name.to_string()),
        ("glint:size", format!("{}x{}", s.width, s.height)),
        ("glint:spp", s.spp.to_string()),
        ("glint:depth", s.max_depth.to_string()),
        ("glint:epsilon", s.epsilon.to_string()),
        ("glint:epsilon_mode", s.epsilon_mode.name().to_string()),
        ("glint:bailout", s.bailout.to_string()),
        ("glint:seed", s.seed.to_string()),
        ("glint:backend", "cpu".to_string()),
        ("glint:specialised", options.specialise.to_string()),
        ("glint:threads", r.threads.to_string()),
        ("glint:time_ms", format!("{:.3}", r.elapsed.as_secs_f64() * 1e3)),
        ("glint:rays", r.counts.total().to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}
