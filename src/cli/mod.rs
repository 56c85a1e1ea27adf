//! Command-line definitions and dispatch.

mod backend;
mod output;
mod render;
mod report;
mod settings;

use clap::{Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(name = "glint", version, about = "Phong/Whitted ray-tracing lab: exact CPU reference and its GPU mirror")]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Render a scene to PNG (sRGB, with the settings as metadata) or EXR (linear f32).
    Render(render::RenderArgs),
    /// Sweep render configurations and report error against run time (CSV, Markdown, plots).
    Report(report::ReportArgs),
}

pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Report(args) => report::run(&args),
    }
}
