//! `error_vs_time_SCENE.png`: RMSE against render time on log-log axes, one series per backend,
//! the Pareto front as a staircase, and the GPU's f32 floor as a dashed line.

use std::path::Path;
use std::sync::OnceLock;

use anyhow::anyhow;
use glint_core::Backend;
use glint_io::image_file::write_png_rgb8;
use glint_scene::Integrator;
use plotters::coord::Shift;
use plotters::coord::combinators::{LogCoord, WithKeyPoints};
use plotters::prelude::*;

use super::sweep::{Row, SceneResult};
use crate::cli::units::ms;

/// Embedded so that plots render the same on a bare CI machine (no system fonts, no
/// fontconfig); see assets/fonts/README.md for its provenance and licence.
static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
pub(super) const FAMILY: &str = "sans-serif";

pub(super) const WIDTH: u32 = 960;
pub(super) const HEIGHT: u32 = 640;
pub(super) const CPU_COLOUR: RGBColor = RGBColor(31, 119, 180);
pub(super) const GPU_COLOUR: RGBColor = RGBColor(230, 110, 0);
pub(super) const FLOOR_COLOUR: RGBColor = RGBColor(200, 30, 40);

pub(super) fn register_font() -> anyhow::Result<()> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok { Ok(()) } else { Err(anyhow!("the embedded plot font could not be loaded")) }
}

/// Rows that a log axis can show: ranked (not the reference) and with a positive error.
fn plotted(scene: &SceneResult) -> Vec<&Row> {
    scene.rows.iter().filter(|r| !r.is_reference() && r.errors.rmse > 0.0).collect()
}

/// Log range covering `values`, padded by the factors `below` and `above`.
pub(super) fn log_range(values: impl Iterator<Item = f64>, below: f64, above: f64) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !(lo > 0.0 && hi.is_finite()) {
        return (0.1, 10.0);
    }
    // Padded within f64's normal numbers: an axis from 0 or to infinity has no decades.
    ((lo / below).max(f64::MIN_POSITIVE), (hi * above).min(f64::MAX))
}

/// Ticks m × 10^k inside [lo, hi] for the mantissas `ms`: plotters' own log ticks leave
/// short ranges unlabelled.
pub(super) fn ticks(lo: f64, hi: f64, ms: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let mut decade = 10f64.powi(lo.log10().floor() as i32);
    // Finite and above 0: past f64's largest decade it would stay infinite, and below its
    // smallest (10^-324) 0, and either ≤ hi forever.
    while decade <= hi && decade.is_finite() && decade > 0.0 {
        out.extend(ms.iter().map(|m| m * decade).filter(|v| *v >= lo && *v <= hi));
        decade *= 10.0;
    }
    out
}

pub(super) const ALL_MANTISSAS: [f64; 9] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];

/// Most labelled decades an axis shows: a damaged shard's error of 1e308 made 312 labels, one
/// over the other.
const MAX_LABELLED_DECADES: f64 = 12.0;

/// Labelled ticks: 1-2-5 per decade when the range is short, decades otherwise, and every k-th
/// decade where more than `MAX_LABELLED_DECADES` would be labelled.
pub(super) fn bold_ticks(lo: f64, hi: f64) -> Vec<f64> {
    // Not (hi / lo).log10(): that ratio overflows across f64's whole range.
    let decades = hi.log10() - lo.log10();
    if decades < 3.0 {
        return ticks(lo, hi, &[1.0, 2.0, 5.0]);
    }
    let every = (decades / MAX_LABELLED_DECADES).ceil().max(1.0) as i64;
    ticks(lo, hi, &[1.0]).into_iter().filter(|v| (v.log10().round() as i64).rem_euclid(every) == 0).collect()
}

/// The lighter grid lines: every mantissa, or only the decades where the labels are thinned.
pub(super) fn light_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if hi.log10() - lo.log10() > MAX_LABELLED_DECADES { ticks(lo, hi, &[1.0]) } else { ticks(lo, hi, &ALL_MANTISSAS) }
}

/// A tick's label as written: `0.001` … `1000000`, and beyond that `1e-5`, `1e12` (not 300 digits).
pub(super) fn tick_label(v: f64) -> String {
    if !(1e-4..1e7).contains(&v) {
        format!("{v:e}")
    } else if v >= 1.0 {
        format!("{v:.0}")
    } else {
        format!("{v}")
    }
}

/// The report's log-log charts: both axes logarithmic over the given ranges, 1-2-5 or decade
/// ticks labelled, the lighter mantissas as grid lines.
pub(super) type LogLog = Cartesian2d<WithKeyPoints<LogCoord<f64>>, WithKeyPoints<LogCoord<f64>>>;

/// A log-log chart on `root` with the report's title, mesh and axis descriptions.
pub(super) fn log_log_chart<'a, 'b>(
    root: &'a DrawingArea<BitMapBackend<'b>, Shift>,
    title: String,
    title_size: u32,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    x_desc: String,
    y_desc: &str,
) -> anyhow::Result<ChartContext<'a, BitMapBackend<'b>, LogLog>> {
    let x_axis = (x0..x1).log_scale().with_key_points(bold_ticks(x0, x1)).with_light_points(light_ticks(x0, x1));
    let y_axis = (y0..y1).log_scale().with_key_points(bold_ticks(y0, y1)).with_light_points(light_ticks(y0, y1));
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FAMILY, title_size))
        .margin(16)
        .x_label_area_size(52)
        .y_label_area_size(80)
        .build_cartesian_2d(x_axis, y_axis)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style((FAMILY, 16))
        .label_style((FAMILY, 14))
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()?;
    Ok(chart)
}

/// A dashed horizontal line at `y` across the chart, dashed in the legend too, as drawn.
pub(super) fn dashed_level<'a, 'b: 'a>(
    chart: &mut ChartContext<'a, BitMapBackend<'b>, LogLog>,
    (x0, x1): (f64, f64),
    y: f64,
    colour: RGBColor,
    label: String,
) -> anyhow::Result<()> {
    chart.draw_series(DashedLineSeries::new([(x0, y), (x1, y)], 8, 5, colour.stroke_width(2)))?.label(label).legend(
        move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new([(0, 0), (9, 0)], colour.stroke_width(2))
                + PathElement::new([(15, 0), (24, 0)], colour.stroke_width(2))
        },
    );
    Ok(())
}

/// The series' legend in the upper right corner, over a nearly opaque white.
pub(super) fn draw_legend<'a, 'b: 'a>(chart: &mut ChartContext<'a, BitMapBackend<'b>, LogLog>) -> anyhow::Result<()> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(RGBColor(120, 120, 120))
        .label_font((FAMILY, 14))
        .draw()?;
    Ok(())
}

/// Draws the plot of one scene into an RGB buffer.
fn draw(scene: &SceneResult, runs: usize) -> anyhow::Result<Vec<u8>> {
    register_font()?;
    let rows = plotted(scene);
    let gpu_reference = scene.rows.iter().find(|r| r.is_reference() && r.config.backend == Backend::Gpu);
    // A path-traced scene's dashed line is its reference's own noise: the GPU at the reference
    // settings is held against an independent reference there, its error noise like any row's.
    let (floor, floor_label) = match &scene.reference_stats {
        Some(stats) => (Some(stats.noise_rmse), "the reference's own noise (its square is in each row's MSE)"),
        // Where the GPU dropped rays at the reference settings its error there is not rounding.
        None if gpu_reference.is_some_and(Row::dropped_work) => {
            (gpu_reference.map(|r| r.errors.rmse), "GPU at the reference settings: it dropped rays, not an f32 floor")
        }
        None if scene.settings.integrator == Integrator::Path => {
            (gpu_reference.map(|r| r.errors.rmse), "GPU at the reference settings: its paths part: noise, not a floor")
        }
        None => (gpu_reference.map(|r| r.errors.rmse), "GPU at the reference settings: its f32 floor"),
    };
    let (x0, x1) = log_range(rows.iter().flat_map(|r| [ms(r.times[0]), ms(r.times[r.times.len() - 1])]), 1.3, 1.3);
    let errors = rows.iter().flat_map(|r| [Some(r.errors.rmse), r.twin_rmse]).flatten().chain(floor);
    let (y0, y1) = log_range(errors.filter(|e| *e > 0.0), 1.6, 1.6);
    // Head room above the data, a third of the height, keeps the legend off the points.
    let y1 = (y1 * (y1 / y0).powf(0.4)).min(f64::MAX);
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE)?;
        let title = format!(
            "{}: error against render time ({}×{}, reference CPU f64 {} spp)",
            scene.name, scene.settings.width, scene.settings.height, scene.reference.spp
        );
        let x_desc = format!("render time, median of {runs} runs (ms, log)");
        let mut chart = log_log_chart(
            &root,
            title,
            22,
            (x0, x1),
            (y0, y1),
            x_desc,
            "RMSE against the reference (linear radiance, log)",
        )?;
        if let Some(f) = floor.filter(|f| *f > 0.0) {
            let label = format!("{floor_label}: RMSE {f:.1e}");
            dashed_level(&mut chart, (x0, x1), f, FLOOR_COLOUR, label)?;
        }
        // Min–max of the timed runs: how much to trust a time difference.
        for (backend, colour) in [(Backend::Cpu, CPU_COLOUR), (Backend::Gpu, GPU_COLOUR)] {
            chart.draw_series(rows.iter().filter(|r| r.config.backend == backend).map(|r| {
                let e = r.errors.rmse;
                PathElement::new([(ms(r.times[0]), e), (ms(r.times[r.times.len() - 1]), e)], colour.mix(0.5))
            }))?;
        }
        let cpu = rows.iter().filter(|r| r.config.backend == Backend::Cpu);
        if cpu.clone().next().is_some() {
            chart
                .draw_series(cpu.map(|r| Circle::new((r.median_ms(), r.errors.rmse), 5, CPU_COLOUR.filled())))?
                .label("CPU (f64)")
                .legend(|(x, y)| Circle::new((x + 12, y), 5, CPU_COLOUR.filled()));
        }
        let gpu = rows.iter().filter(|r| r.config.backend == Backend::Gpu);
        if gpu.clone().next().is_some() {
            chart
                .draw_series(gpu.map(|r| TriangleMarker::new((r.median_ms(), r.errors.rmse), 7, GPU_COLOUR.filled())))?
                .label("GPU (f32)")
                .legend(|(x, y)| TriangleMarker::new((x + 12, y), 7, GPU_COLOUR.filled()));
        }

        // The arithmetic error alone, at the same time: how far below the sampling and depth
        // error the f32 floor lies at each configuration.
        let twins: Vec<(f64, f64)> =
            rows.iter().filter_map(|r| r.twin_rmse.filter(|e| *e > 0.0).map(|e| (r.median_ms(), e))).collect();
        if !twins.is_empty() {
            chart
                .draw_series(twins.iter().map(|&at| Cross::new(at, 4, GPU_COLOUR.stroke_width(2))))?
                .label("GPU against the CPU at the same settings (f32 error alone)")
                .legend(|(x, y)| Cross::new((x + 12, y), 4, GPU_COLOUR.stroke_width(2)));
        }

        let mut front: Vec<&Row> = rows.iter().copied().filter(|r| r.pareto_all).collect();
        front.sort_by_key(|r| r.median());
        // A staircase: each front point holds its error until the next, faster-converging one.
        let mut stairs = Vec::new();
        for (i, r) in front.iter().enumerate() {
            if i > 0 {
                stairs.push((r.median_ms(), front[i - 1].errors.rmse));
            }
            stairs.push((r.median_ms(), r.errors.rmse));
        }
        if !stairs.is_empty() {
            chart
                .draw_series(LineSeries::new(stairs, BLACK.stroke_width(2)))?
                .label("Pareto front (all configurations)")
                .legend(|(x, y)| PathElement::new([(x, y), (x + 24, y)], BLACK.stroke_width(2)));
        }
        // Label the front's points where a label fits: clustered points keep the first one.
        let (x_px, _) = chart.plotting_area().get_pixel_range();
        let mut placed: Vec<(i32, i32, i32, i32)> = Vec::new();
        let mut labels = Vec::new();
        for r in &front {
            let at = (r.median_ms(), r.errors.rmse);
            let text = format!("{} {}", r.config.backend.name(), r.config.short(scene.settings.integrator));
            let (px, py) = chart.backend_coord(&at);
            let w = 8 * text.chars().count() as i32;
            // Right of the point, where the staircase runs horizontally; left near the edge.
            let dx = if px + 8 + w < x_px.end { 8 } else { -8 - w };
            let rect = (px + dx, py + 2, px + dx + w, py + 18);
            if placed.iter().any(|p| rect.0 < p.2 && p.0 < rect.2 && rect.1 < p.3 && p.1 < rect.3) {
                continue;
            }
            placed.push(rect);
            labels.push(EmptyElement::at(at) + Text::new(text, (dx, 3), (FAMILY, 13).into_font()));
        }
        chart.draw_series(labels)?;

        draw_legend(&mut chart)?;
        root.present()?;
    }
    Ok(buf)
}

/// The plot's file name for the scene `scene`.
pub fn file_name(scene: &str) -> String {
    format!("error_vs_time_{scene}.png")
}

/// Writes `error_vs_time_SCENE.png` into `dir` (atomically, via glint-io's PNG writer).
pub fn write_plot(dir: &Path, scene: &SceneResult, runs: usize) -> anyhow::Result<std::path::PathBuf> {
    let rgb = draw(scene, runs)?;
    let path = dir.join(file_name(&scene.name));
    let metadata = vec![
        ("Software".to_string(), format!("glint {}", env!("CARGO_PKG_VERSION"))),
        ("Title".to_string(), format!("{}: RMSE against render time", scene.name)),
        ("glint:scene".to_string(), scene.name.clone()),
    ];
    write_png_rgb8(&path, WIDTH, HEIGHT, &rgb, &metadata)?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_end_at_the_largest_decade_of_an_absurd_range() {
        // A damaged shard's error of 1e308, padded: the decades ran past f64 into infinity,
        // which is ≤ an infinite bound, and the ticks grew until memory ran out.
        let (lo, hi) = log_range([1e-3, 1e308].into_iter(), 1.5, 1.5);
        assert!(hi.is_finite(), "{hi}");
        // Labelled every 27th decade (312 decades, at most 12 labels), written short.
        let labelled = bold_ticks(lo, hi);
        assert!((11..=12).contains(&labelled.len()), "{labelled:?}");
        assert_eq!(tick_label(1e297), "1e297");
        assert_eq!(
            (tick_label(0.001), tick_label(1e-5), tick_label(50.0)),
            ("0.001".into(), "1e-5".into(), "50".into())
        );
        assert!(ticks(1.0, f64::INFINITY, &ALL_MANTISSAS).len() < 9 * 310);
        // And the smallest: 10^-324 is 0, which stayed 0.
        assert!(ticks(5e-324, 1.0, &[1.0]).len() < 330);
        let (lo, _) = log_range([5e-324, 1.0].into_iter(), 1.5, 1.5);
        assert!(lo >= f64::MIN_POSITIVE, "{lo}");
    }
}
