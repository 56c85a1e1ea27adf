//! `gi_vs_time_SCENE.png`: Whitted's images and the path tracer's against the path-traced
//! reference on one log-log chart of error against render time, colour by integrator and
//! marker by backend, the paths joined in order of samples (their slope is the convergence
//! rate), the Pareto front over both families as a staircase, and the reference's own noise
//! as a dashed floor.

use std::path::{Path, PathBuf};

use glint_core::Backend;
use glint_io::image_file::write_png_rgb8;
use glint_scene::Integrator;
use plotters::prelude::*;

use super::gi::{GiResult, GiRow};
use super::plot::{FLOOR_COLOUR, HEIGHT, WIDTH, draw_legend, log_log_chart, log_range, register_font};
use crate::cli::units::ms;

const WHITTED_COLOUR: RGBColor = RGBColor(120, 60, 170);
const PATH_COLOUR: RGBColor = RGBColor(30, 140, 70);

fn draw(g: &GiResult, runs: usize) -> anyhow::Result<Vec<u8>> {
    register_font()?;
    let rows: Vec<&GiRow> = g.rows.iter().filter(|r| r.rmse > 0.0).collect();
    let at = |r: &GiRow| (ms(r.median).max(1e-3), r.rmse);
    let (x0, x1) = log_range(rows.iter().map(|r| at(r).0), 1.3, 1.3);
    let floor = Some(g.reference_noise).filter(|n| *n > 0.0);
    let (y0, y1) = log_range(rows.iter().map(|r| r.rmse).chain(floor), 1.6, 1.6);
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
        let y_desc = "RMSE against the path-traced reference (log)";
        let mut chart = log_log_chart(&root, title, 20, (x0, x1), (y0, y1), x_desc, y_desc)?;
        if let Some(f) = floor {
            chart
                .draw_series(DashedLineSeries::new([(x0, f), (x1, f)], 8, 5, FLOOR_COLOUR.stroke_width(2)))?
                .label(format!("the reference's own noise: RMSE {f:.1e}"))
                // Dashed in the legend too, as drawn.
                .legend(|(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new([(0, 0), (9, 0)], FLOOR_COLOUR.stroke_width(2))
                        + PathElement::new([(15, 0), (24, 0)], FLOOR_COLOUR.stroke_width(2))
                });
        }
        for backend in [Backend::Cpu, Backend::Gpu] {
            let mut paths: Vec<&&GiRow> =
                rows.iter().filter(|r| r.integrator == Integrator::Path && r.backend == backend).collect();
            paths.sort_by_key(|r| r.spp);
            chart.draw_series(LineSeries::new(paths.iter().map(|r| at(r)), PATH_COLOUR.mix(0.5)))?;
        }
        for (integrator, colour) in [(Integrator::Whitted, WHITTED_COLOUR), (Integrator::Path, PATH_COLOUR)] {
            for backend in [Backend::Cpu, Backend::Gpu] {
                let points: Vec<(f64, f64)> =
                    rows.iter().filter(|r| r.integrator == integrator && r.backend == backend).map(|r| at(r)).collect();
                if points.is_empty() {
                    continue;
                }
                let label = format!("{} on the {}", integrator.name(), backend.name());
                match backend {
                    Backend::Cpu => {
                        chart
                            .draw_series(points.iter().map(|&p| Circle::new(p, 5, colour.filled())))?
                            .label(label)
                            .legend(move |(x, y)| Circle::new((x + 12, y), 5, colour.filled()));
                    }
                    Backend::Gpu => {
                        chart
                            .draw_series(points.iter().map(|&p| TriangleMarker::new(p, 7, colour.filled())))?
                            .label(label)
                            .legend(move |(x, y)| TriangleMarker::new((x + 12, y), 7, colour.filled()));
                    }
                }
            }
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
