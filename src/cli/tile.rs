//! `glint render --tile I/N`: one block of a fixed grid of the image, for renders spread over a
//! scheduler's array of tasks (Slurm, Kubernetes Indexed Jobs, AWS Batch), written as an EXR
//! whose data window is the block and whose display window the whole image, with what
//! `glint merge` checks before it joins the blocks: the scene's content hash, the settings, the
//! grid, the backend and the version.

use std::path::PathBuf;

use glint_core::{Backend, CpuOptions, FlatScene, TileGrid};
use glint_gpu::GpuOptions;
use glint_io::LoadedScene;
use glint_io::image_file::write_exr_tile;
use glint_scene::RenderSettings;

use super::backend::{open_gpu, run_cpu, run_gpu};
use super::console::say;
use super::interrupt;
use super::output::{Incomplete, SceneTags, check_writable, metadata};
use super::output_path::{check_not_read, check_outputs, default_output};
use crate::cli::usage::usage;

/// The array-index variables of the schedulers, in the order they are looked for.
pub const INDEX_VARIABLES: [(&str, &str); 3] = [
    ("SLURM_ARRAY_TASK_ID", "Slurm job arrays"),
    ("JOB_COMPLETION_INDEX", "Kubernetes Indexed Jobs"),
    ("AWS_BATCH_JOB_ARRAY_INDEX", "AWS Batch array jobs"),
];

/// `--tile I/N`, or `--tile N` with I from the scheduler.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileSpec {
    pub index: Option<u32>,
    pub count: u32,
}

pub fn parse_tile(s: &str) -> Result<TileSpec, String> {
    let (index, count) = super::job_array::parse_part(s, "tile", true)?;
    Ok(TileSpec { index, count })
}

/// The tile's index, and where it came from (the flag, or a scheduler's variable); `tiles` is
/// the grid's count, for the range a bad variable is told.
fn resolve_index(spec: TileSpec, tiles: u32) -> anyhow::Result<(u32, String)> {
    if let Some(i) = spec.index {
        return Ok((i, "--tile".into()));
    }
    // Two schedulers' indices that disagree (a Slurm job launched from a Kubernetes pod): which
    // is this task's is not glint's to guess; taking the first rendered one tile twice.
    let set: Vec<(&str, &str, String)> = INDEX_VARIABLES
        .iter()
        .filter_map(|&(name, scheduler)| std::env::var(name).ok().map(|v| (name, scheduler, v)))
        .collect();
    if let [(first, _, a), rest @ ..] = set.as_slice()
        && let Some((other, _, b)) = rest.iter().find(|(_, _, b)| b.trim() != a.trim())
    {
        usage!(
            "--tile {} takes the tile's index from the scheduler, but {first}='{a}' and {other}='{b}' disagree; \
             unset the one that is not this task's, or give the index as --tile I/{}",
            spec.count,
            spec.count
        );
    }
    if let Some((name, scheduler, value)) = set.first() {
        // The parser's own words ("invalid digit found in string") add nothing to these.
        let i = value.trim().parse::<u32>().map_err(|_| {
            // A whole number too large is said so, not called no number.
            let what = if value.trim().bytes().all(|b| b.is_ascii_digit()) && !value.trim().is_empty() {
                format!("is beyond {}", u32::MAX)
            } else {
                "is not a whole number".into()
            };
            let last = tiles.saturating_sub(1);
            let range = if tiles == 1 {
                "the one tile is numbered 0 (Slurm: --array=0)".to_string()
            } else {
                format!("the {tiles} tiles are numbered 0 to {last} (Slurm: --array=0-{last})")
            };
            anyhow::anyhow!("{name}='{value}' ({scheduler}) {what}, so it names no tile: {range}")
        })?;
        return Ok((i, format!("{name} ({scheduler})")));
    }
    let names: Vec<&str> = INDEX_VARIABLES.iter().map(|(n, _)| *n).collect();
    usage!(
        "--tile {} takes the tile's index from the scheduler, but none of {} is set; give it as --tile I/{}",
        spec.count,
        names.join(", "),
        spec.count
    )
}

/// What `glint render --tile` needs of the render's arguments.
pub struct TileJob<'a> {
    pub loaded: &'a LoadedScene,
    pub settings: &'a RenderSettings,
    pub spec: TileSpec,
    pub backend: Backend,
    pub output: Option<PathBuf>,
    pub cpu: CpuOptions,
    pub gpu: GpuOptions,
    pub adapter: Option<&'a str>,
    /// `LoadArgs::flags`, for the tile's metadata.
    pub load_flags: String,
    pub specialise: bool,
    pub force: bool,
    pub quiet: bool,
}

pub fn render_tile(job: TileJob) -> anyhow::Result<()> {
    let (w, h) = (job.settings.width, job.settings.height);
    // The grid first: `--tile 0` is no grid, whatever the scheduler says.
    // A count no grid of the image has is the command line's: a usage error (exit 2).
    let grid = match TileGrid::new(job.spec.count, w, h) {
        Ok(grid) => grid,
        Err(e) => usage!("--tile: {e}"),
    };
    let (index, source) = resolve_index(job.spec, grid.count())?;
    let rect = match (grid.rect(index), job.spec.index) {
        (Ok(rect), _) => rect,
        // The command line's own index: a usage error (exit 2), as `--shard 2/2` is.
        (Err(e), Some(_)) => usage!("--tile: {e}"),
        (Err(e), None) => {
            let last = grid.count() - 1;
            return Err(anyhow::Error::new(e).context(format!(
                "--tile {} with the index from {source}: an array of {} tasks numbers them 0 to {last} \
                 (Slurm: --array=0-{last})",
                grid.count(),
                grid.count()
            )));
        }
    };
    let output = job.output.unwrap_or_else(|| default_output(job.loaded, &format!("-tile-{index}.exr")));
    if !output.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        usage!(
            "{}: a tile is written as OpenEXR (its data window is the tile, its display window the image); \
             name the output .exr, and let `glint merge` write the PNG",
            output.display()
        );
    }
    check_outputs(&[output.as_path()], &job.loaded.source, job.force)?;
    check_not_read(&[output.as_path()], job.loaded)?;
    say!("tile {index}/{} (index from {source}) of a {} grid over {w}x{h}: {rect}", grid.count(), grid.describe())?;
    interrupt::check()?;
    let flat = FlatScene::build(&job.loaded.desc, job.settings);
    let scene = SceneTags::new(job.loaded, job.load_flags.clone(), &flat);
    interrupt::check()?;
    let run = match job.backend {
        Backend::Cpu => run_cpu(&flat, &CpuOptions { region: Some(rect), ..job.cpu }, job.quiet)?,
        Backend::Gpu => {
            let tracer = open_gpu(job.adapter)?;
            run_gpu(&tracer, &flat, &GpuOptions { region: Some(rect), ..job.gpu }, job.quiet)?
        }
    };
    // An incomplete tile is never written: a merge would hide which tile lost work.
    check_writable(&run, &job.loaded.desc, job.settings, Incomplete::RefuseTile)?;
    let mut tags = metadata(&scene, job.settings, &run, job.specialise);
    tags.extend([
        ("glint:grid".to_string(), grid.describe()),
        ("glint:tile".to_string(), format!("{index}/{}", grid.count())),
    ]);
    write_exr_tile(&output, &run.image, (w, h), (rect.x0, rect.y0), &tags)?;
    say!(
        "  {} {:.1} ms, {} rays; wrote {}",
        run.backend.name(),
        run.render.as_secs_f64() * 1e3,
        run.counts.total(),
        output.display()
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tile_specs_parse_or_say_what_is_wrong() {
        assert_eq!(parse_tile("3/8"), Ok(TileSpec { index: Some(3), count: 8 }));
        assert_eq!(parse_tile("8"), Ok(TileSpec { index: None, count: 8 }));
        assert!(
            parse_tile("a/8")
                .unwrap_err()
                .contains("'a' is not a whole number from 0 to 4294967295 (the tile's index)")
        );
        assert!(parse_tile("4294967296").unwrap_err().contains("from 1 to 4294967295 (the tile count)"));
        assert!(parse_tile("3/-1").unwrap_err().contains("the tile count"));
    }
}
