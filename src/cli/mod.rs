//! Command-line definitions and dispatch.

mod adapters;
mod backend;
mod bench;
mod bench_export;
pub mod console;
pub mod interrupt;
mod job_array;
mod merge;
mod output;
mod output_path;
mod render;
mod report;
mod settings;
mod tile;
mod units;
pub mod usage;
mod view;

use clap::{Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(name = "glint", version, about = "Phong/Whitted ray-tracing lab: exact CPU reference and its GPU mirror")]
pub struct Cli {
    /// Without a subcommand, `glint` opens the viewer on the built-in `whitted` scene.
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Render a scene to PNG (sRGB, with the settings as metadata) or EXR (linear f32).
    Render(render::RenderArgs),
    /// Sweep render configurations and report error against run time (CSV, Markdown, plots).
    Report(report::ReportArgs),
    /// Open the interactive viewer: GPU and CPU side by side, difference, pixel probe.
    View(view::ViewArgs),
    /// Benchmarks of parts of the tracer (`bench rays`: the BVH build and closest-hit throughput).
    Bench(bench::BenchArgs),
    /// Join the EXR tiles of `glint render --tile` into one image (.exr or .png), after checking
    /// that they are one render's and that none is missing or given twice.
    Merge(merge::MergeArgs),
    /// List the GPU adapters a render can choose from (name, backend, type, driver).
    Adapters(adapters::AdaptersArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Some(Command::Render(args)) => render::run(&args),
        Some(Command::Report(args)) => report::run(&args),
        Some(Command::View(args)) => view::run(&args),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::Merge(args)) => merge::run(&args),
        Some(Command::Adapters(args)) => adapters::run(&args),
        None => view::run(&view::ViewArgs::default()),
    }
}
