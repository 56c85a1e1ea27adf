//! `gi_vs_time_SCENE.png`: Whitted's images and the path tracer's against the path-traced
//! reference on one log-log chart of error against render time: colour by integrator (and,
//! for Whitted, by how its ambient was set), marker by backend, the paths joined in order of
//! samples (their slope is the convergence rate) and labelled with them, the Pareto front over
//! both families as a staircase, the reference's own noise as a dashed floor, and Whitted's
//! error at the reference's samples (what its model leaves out) as a dashed line.

use std::path::{Path, PathBuf};

use glint_core::Backend;
use glint_io::image_file::write_png_rgb8;
use glint_scene::Integrator;
use plotters::prelude::*;

use super::gi::{Ambient, GiResult, GiRow};
use super::plot::{
    FAMILY, FLOOR_COLOUR, HEIGHT, WIDTH, dashed_level, draw_legend, log_log_chart, log_range, register_font,
};
use crate::cli::units::ms;

const WHITTED_COLOUR: RGBColor = RGBColor(120, 60, 170);
const PATH_COLOUR: RGBColor = RGBColor(30, 140, 70);

/// Whitted's points by how the row's ambient was set: the one the scene writes in the
/// integrator's colour, none in a pale one, the fitted in a dark one (24 rows of one colour
/// hid the fitted ones the text speaks of; a lecturer).
fn whitted_colour(ambient: Option<Ambient>) -> RGBColor {
    match ambient {
        Some(Ambient::AsWritten) | None => WHITTED_COLOUR,
        Some(Ambient::Without) => RGBColor(190, 150, 225),
        Some(Ambient::Fitted) => RGBColor(60, 20, 90),
    }
}

fn draw(g: &GiResult, runs: usize) -> anyhow::Result<Vec<u8>> {
    register_font()?;
    let rows: Vec<&GiRow> = g.rows.iter().filter(|r| r.rmse > 0.0).collect();
    let at = |r: &GiRow| (ms(r.median).max(1e-3), r.rmse);
    let (x0, x1) = log_range(rows.iter().map(|r| at(r).0), 1.3, 1.3);
    let floor = Some(g.reference_noise).filter(|n| *n > 0.0);
    let converged = Some(g.kinds.whitted_rmse).filter(|e| *e > 0.0);
    let (y0, y1) = log_range(rows.iter().map(|r| r.rmse).chain(floor).chain(converged), 1.6, 1.6);
    let y1 = (y1 * (y1 / y0).powf(0.4)).min(f64::MAX);
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE)?;
        let title = format!(
            "{}: Whitted and paths against a path-traced reference ({} spp, depth {})",
            g.scene, g.reference_spp, g.reference_depth
        );
        let x_desc = format!("render time, median of {runs} runs (ms, log)");
        let y_desc = "RMSE against the path-traced reference (linear radiance, log)";
        let mut chart = log_log_chart(&root, title, 20, (x0, x1), (y0, y1), x_desc, y_desc)?;
        if let Some(f) = floor {
            dashed_level(&mut chart, (x0, x1), f, FLOOR_COLOUR, format!("the reference's own noise: RMSE {f:.1e}"))?;
        }
        if let Some(e) = converged {
            let label = format!(
                "whitted at depth {}, {} spp (ambient as written): what it leaves out, RMSE {e:.1e}",
                g.kinds.whitted_depth, g.kinds.whitted_spp
            );
            dashed_level(&mut chart, (x0, x1), e, WHITTED_COLOUR, label)?;
        }
        for backend in [Backend::Cpu, Backend::Gpu] {
            let mut paths: Vec<&&GiRow> =
                rows.iter().filter(|r| r.integrator == Integrator::Path && r.backend == backend).collect();
            paths.sort_by_key(|r| r.spp);
            chart.draw_series(LineSeries::new(paths.iter().map(|r| at(r)), PATH_COLOUR.mix(0.5)))?;
            // Each path point's samples, below it (the line runs down and to the right).
            chart.draw_series(paths.iter().map(|r| {
                EmptyElement::at(at(r)) + Text::new(format!("{} spp", r.spp), (-14, 9), (FAMILY, 12).into_font())
            }))?;
        }
        // Colour says what was rendered, shape on which backend: one legend entry each.
        let kinds = [
            (Integrator::Whitted, Some(Ambient::AsWritten), "whitted, ambient as written"),
            (Integrator::Whitted, Some(Ambient::Without), "whitted, no ambient"),
            (Integrator::Whitted, Some(Ambient::Fitted), "whitted, ambient fitted"),
            (Integrator::Path, None, "paths"),
        ];
        for (integrator, ambient, label) in kinds {
            let colour = match integrator {
                Integrator::Whitted => whitted_colour(ambient),
                Integrator::Path => PATH_COLOUR,
            };
            let of = |backend| {
                rows.iter().filter(move |r| (r.integrator, r.ambient, r.backend) == (integrator, ambient, backend))
            };
            if of(Backend::Cpu).chain(of(Backend::Gpu)).next().is_none() {
                continue;
            }
            chart.draw_series(of(Backend::Cpu).map(|r| Circle::new(at(r), 5, colour.filled())))?;
            chart
                .draw_series(of(Backend::Gpu).map(|r| TriangleMarker::new(at(r), 7, colour.filled())))?
                .label(label)
                .legend(move |(x, y)| Rectangle::new([(x + 6, y - 5), (x + 18, y + 5)], colour.filled()));
        }
        for (backend, name) in [(Backend::Cpu, "on the CPU"), (Backend::Gpu, "on the GPU")] {
            if !rows.iter().any(|r| r.backend == backend) {
                continue;
            }
            let grey = RGBColor(90, 90, 90);
            let series = chart.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?.label(name);
            match backend {
                Backend::Cpu => series.legend(move |(x, y)| Circle::new((x + 12, y), 5, grey.filled())),
                Backend::Gpu => series.legend(move |(x, y)| TriangleMarker::new((x + 12, y), 7, grey.filled())),
            };
        }
        // The Pareto front over both families: the least error reached by each time.
        let mut by_time: Vec<(f64, f64)> = rows.iter().map(|r| at(r)).collect();
        by_time.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs: Vec<(f64, f64)> = Vec::new();
        for (t, e) in by_time {
            if stairs.last().is_none_or(|&(_, best)| e < best) {
                if let Some(&(_, best)) = stairs.last() {
                    stairs.push((t, best));
                }
                stairs.push((t, e));
            }
        }
        if !stairs.is_empty() {
            chart
                .draw_series(LineSeries::new(stairs, BLACK.stroke_width(2)))?
                .label("Pareto front (both integrators)")
                .legend(|(x, y)| PathElement::new([(x, y), (x + 24, y)], BLACK.stroke_width(2)));
        }
        draw_legend(&mut chart)?;
        root.present()?;
    }
    Ok(buf)
}

/// The plot's file name for the scene `scene`.
pub fn file_name(scene: &str) -> String {
    format!("gi_vs_time_{scene}.png")
}

/// Writes `gi_vs_time_SCENE.png` into `dir`.
pub fn write_gi_plot(dir: &Path, g: &GiResult, runs: usize) -> anyhow::Result<PathBuf> {
    let rgb = draw(g, runs)?;
    let path = dir.join(file_name(&g.scene));
    let metadata = vec![
        ("Software".to_string(), format!("glint {}", env!("CARGO_PKG_VERSION"))),
        ("Title".to_string(), format!("{}: Whitted and paths against a path-traced reference", g.scene)),
        ("glint:scene".to_string(), g.scene.clone()),
    ];
    write_png_rgb8(&path, WIDTH, HEIGHT, &rgb, &metadata)?;
    Ok(path)
}
