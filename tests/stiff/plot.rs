//! docs/numerics-translation.png: the GPU's FLIP against its own CPU image for case 17's scene
//! translated away from the origin, traced camera-relative (the default) and in world space (as
//! before rebasing), on log-log axes. Written with the tables (`generated.rs`).

use glint_io::image_file::write_png_rgb8;
use plotters::prelude::*;

use crate::case17_translation_and_scale::Sweep;

/// Embedded, as the report's plots, so that the plot is the same without system fonts.
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";
const WIDTH: u32 = 800;
const HEIGHT: u32 = 520;
const EYE: RGBColor = RGBColor(31, 119, 180);
const WORLD: RGBColor = RGBColor(230, 110, 0);

/// Draws the translation sweep; `None` without GPU figures.
pub fn translation_plot(sweep: &Sweep) -> Option<Vec<u8>> {
    let points = |f: fn(&crate::case17_translation_and_scale::Row) -> Option<f64>| -> Option<Vec<(f64, f64)>> {
        sweep.rows.iter().map(|r| f(r).map(|v| (r.magnitude, v.max(1e-5)))).collect()
    };
    let eye = points(|r| r.gpu_flip)?;
    let world = points(|r| r.world_flip)?;
    plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).ok()?;
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).ok()?;
        let mut chart = ChartBuilder::on(&root)
            .caption("Case 17: GPU error against the distance from the world origin", (FAMILY, 20))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(72)
            .build_cartesian_2d((5e1..2e6).log_scale(), (1e-5..1.0).log_scale())
            .ok()?;
        chart
            .configure_mesh()
            .x_desc("translation T of the scene (scene units, log)")
            .y_desc("mean FLIP of GPU against CPU (log)")
            .axis_desc_style((FAMILY, 15))
            .label_style((FAMILY, 13))
            .x_label_formatter(&|v| format!("{v:.0e}"))
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .draw()
            .ok()?;
        for (series, colour, label) in [
            (&world, WORLD, "world space (before rebasing)"),
            (&eye, EYE, "camera frame (rebased where the camera looks)"),
        ] {
            chart.draw_series(LineSeries::new(series.iter().copied(), colour.stroke_width(2))).ok()?;
            chart
                .draw_series(series.iter().map(|&p| Circle::new(p, 5, colour.filled())))
                .ok()?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 12, y), 5, colour.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.3))
            .label_font((FAMILY, 14))
            .draw()
            .ok()?;
        root.present().ok()?;
    }
    Some(buf)
}

/// Writes the plot beside the document (under GLINT_WRITE_NUMERICS=1 only).
pub fn write_translation_plot(sweep: &Sweep) {
    if !crate::generated::writing() {
        return;
    }
    let Some(buf) = translation_plot(sweep) else { return };
    let path = crate::generated::doc_path().with_file_name("numerics-translation.png");
    write_png_rgb8(&path, WIDTH, HEIGHT, &buf, &[]).expect("docs/numerics-translation.png written");
}
