//! The status bar: device, timings, progress, and the errors of GPU against CPU.

use egui::Ui;
use glint_core::compare::ImageErrors;
use glint_core::cpu::RayCounts;
use glint_scene::format_rounded;

/// What the status bar says on a software adapter.
pub const SOFTWARE_ADAPTER: &str = "software Vulkan (lavapipe): the GPU tracer runs on the CPU";

/// Everything the status bar shows, gathered by the app.
#[derive(Clone, Debug, Default)]
pub struct Status {
    pub adapter: Option<String>,
    /// The adapter is a software one: the GPU tracer shares the CPU with the reference.
    pub software: bool,
    /// The last render's GPU time, and whether it compiled its shader variant.
    pub gpu_ms: Option<(f64, bool)>,
    /// Seconds the full-resolution GPU render in flight has run, once it runs long, and the
    /// sample passes the GPU has finished of how many.
    pub gpu_rendering: Option<(f64, (u32, u32))>,
    /// A render whose shader variant is new, waiting for its compile: what it adds, and seconds.
    pub gpu_compiling: Option<(String, f64)>,
    /// GPU renders per second (not the window's frames).
    pub gpu_fps: Option<f64>,
    pub ui_ms: f64,
    pub cpu_progress: Option<(usize, usize, f64)>,
    pub cpu_time: Option<f64>,
    pub errors: Option<ImageErrors>,
    pub comparing: bool,
    pub gpu_counts: Option<RayCounts>,
    pub cpu_counts: Option<RayCounts>,
    /// Path mode: the samples a pixel of each tracer's image has.
    pub samples: Option<Samples>,
    /// The document has invalid values: nothing renders until they are mended.
    pub held: bool,
}

/// The last GPU render's time: one whose shader variant was new says its compile is in it
/// (on lavapipe seconds, shown as "14539.8 ms/frame" of a 40 ms render; a lecturer).
fn gpu_time_text(ms: f64, compiled: bool) -> String {
    if compiled {
        format!("GPU {ms:.1} ms/render, its shader's compile included")
    } else {
        format!("GPU {ms:.1} ms/render")
    }
}

/// Path mode's samples: the GPU's mean over its batches, and the CPU reference's.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Samples {
    pub gpu: Option<u32>,
    /// GPU samples a pixel per second of GPU time.
    pub gpu_rate: Option<f64>,
    pub accumulating: bool,
    pub paused: bool,
    pub full: bool,
    pub cpu: Option<u32>,
}

/// "GPU 192 samples (48/s), adding…; CPU 64 samples".
pub fn samples_text(s: &Samples) -> String {
    let samples = |n: u32| if n == 1 { "1 sample".to_string() } else { format!("{n} samples") };
    let gpu = match (s.gpu, s.gpu_rate) {
        // Two digits below 10: a model at 2.7 s a sample showed "(0/s)" while it added them.
        (Some(n), Some(rate)) if rate < 10.0 => format!("GPU {} ({}/s)", samples(n), format_rounded(rate, 2)),
        (Some(n), Some(rate)) => format!("GPU {} ({rate:.0}/s)", samples(n)),
        (Some(n), None) => format!("GPU {}", samples(n)),
        (None, _) => "GPU no samples yet".into(),
    };
    let state = if s.full {
        ", the most it adds"
    } else if s.paused {
        ", paused"
    } else if s.accumulating {
        ", adding…"
    } else {
        ""
    };
    let cpu = s.cpu.map_or("CPU rendering…".to_string(), |n| format!("CPU {}", samples(n)));
    format!("{gpu}{state}; {cpu}")
}

/// One figure of the status bar on one line, however narrow the window: in a wrapping row a
/// label breaks at any space, and at 1024 px "GPU 12.7 ms/render" stood as "GPU 12.7" at the
/// row's end and "ms/render" under it (a lecturer). A figure too long for what is left of its
/// row moves whole to the next.
fn figure(ui: &mut Ui, text: impl Into<egui::WidgetText>) -> egui::Response {
    ui.add(egui::Label::new(text).wrap_mode(egui::TextWrapMode::Extend))
}

/// `parts` as one sentence (a space between them) whose lines break only between parts, each
/// line as high as a label's (not a button's, as a row's lines are).
fn sentence(ui: &mut Ui, parts: &[String]) {
    ui.scope(|ui| {
        ui.spacing_mut().interact_size.y = 0.0;
        ui.horizontal_wrapped(|ui| {
            let space = ui.fonts_mut(|f| f.glyph_width(&egui::TextStyle::Body.resolve(ui.style()), ' '));
            ui.spacing_mut().item_spacing.x = space;
            for p in parts {
                figure(ui, p);
            }
        });
    });
}

/// The figures of a comparison, each whole: "GPU vs CPU: max abs 2.955e-2," … "PSNR 69.0 dB,".
fn error_parts(e: &ImageErrors) -> Vec<String> {
    vec![
        format!("GPU vs CPU: max abs {:.3e},", e.max_abs),
        format!("mean abs {:.3e},", e.mean_abs),
        format!("PSNR {:.1} dB,", e.psnr),
        format!("FLIP mean {:.5},", e.flip_mean),
        format!("first-hit mismatch {:.3} %", e.first_hit_mismatch * 100.0),
    ]
}

/// The rays by kind, each count with its kind: "Rays (GPU): 76800 camera," … "10825 saved by bailout".
fn count_parts(tracer: &str, c: &RayCounts) -> Vec<String> {
    vec![
        format!("Rays ({tracer}): {} camera,", c.camera),
        format!("{} shadow,", c.shadow),
        format!("{} reflection,", c.reflection),
        format!("{} refraction;", c.refraction),
        format!("{} saved by bailout", c.bailout_saved),
    ]
}

pub fn ui(ui: &mut Ui, s: &Status) {
    ui.horizontal_wrapped(|ui| {
        match &s.adapter {
            Some(a) => figure(ui, format!("GPU: {a}")),
            None => ui.label("GPU: none"),
        };
        if s.software {
            ui.colored_label(ui.visuals().warn_fg_color, SOFTWARE_ADAPTER).on_hover_text(
                "A software Vulkan driver (Mesa's lavapipe here) runs the WGSL tracer on the CPU cores, \
                 beside the CPU reference: expect it to be several times slower than the reference. \
                 A hardware GPU runs it on the GPU.",
            );
        }
        ui.separator();
        if let Some((what, secs)) = &s.gpu_compiling {
            ui.spinner();
            // A non-breaking space keeps the seconds with their unit in this long, wrapping line.
            ui.label(format!("compiling the shader for {what}… {secs:.0}\u{a0}s (the last image stays)"));
        }
        if let Some((secs, (done, total))) = s.gpu_rendering {
            ui.spinner();
            figure(ui, format!("GPU rendering {done}/{total} samples… {secs:.0} s"));
        }
        if let Some((ms, compiled)) = s.gpu_ms {
            figure(ui, gpu_time_text(ms, compiled));
        }
        // Renders, not the window's frames: "fps" beside the UI's time read as the window's.
        if let Some(rate) = s.gpu_fps {
            figure(ui, format!("{rate:.1} renders/s"));
        }
        figure(ui, format!("UI {:.1} ms", s.ui_ms));
        ui.separator();
        if let Some(samples) = &s.samples {
            figure(ui, samples_text(samples));
            ui.separator();
        }
        match (s.cpu_progress, s.cpu_time) {
            (Some((done, total, secs)), _) => {
                let f = done as f32 / total.max(1) as f32;
                ui.add(
                    egui::ProgressBar::new(f).desired_width(120.0).text(format!("CPU {:.0} % {secs:.1} s", f * 100.0)),
                );
            }
            (None, Some(t)) => {
                figure(ui, format!("CPU done in {:.0} ms", t * 1e3));
            }
            (None, None) => {}
        }
    });
    match (&s.errors, s.comparing) {
        (Some(e), _) => sentence(ui, &error_parts(e)),
        (None, true) => {
            ui.horizontal_wrapped(|ui| {
                ui.spinner();
                ui.label("comparing GPU and CPU…");
            });
        }
        (None, false) if s.adapter.is_none() => {
            ui.weak("GPU vs CPU: no GPU to compare");
        }
        (None, false) if s.held => {
            ui.weak("GPU vs CPU: held while a value is invalid (listed in the side panel)");
        }
        (None, false) => {
            ui.weak("GPU vs CPU: waiting for both renders");
        }
    }
    match (&s.gpu_counts, &s.cpu_counts) {
        (Some(g), _) => sentence(ui, &count_parts("GPU", g)),
        (None, Some(c)) => sentence(ui, &count_parts("CPU", c)),
        (None, None) => {
            ui.weak("Rays: no render yet");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{ImageErrors, RayCounts, Samples, Status, samples_text};

    /// The lines of text the status bar draws for `s` in a window `width` points wide, with
    /// how far right each reaches.
    fn drawn_rows(s: &Status, width: f32) -> Vec<(String, f32)> {
        let ctx = egui::Context::default();
        let input = || egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(width, 400.0))),
            ..egui::RawInput::default()
        };
        let show = |ui: &mut egui::Ui| {
            egui::Panel::bottom("status").show(ui, |ui| super::ui(ui, s));
        };
        // The second pass lays out with the sizes the first one measured.
        ctx.run_ui(input(), show).drop_without_applying_deltas();
        let output = ctx.run_ui(input(), show);
        let mut rows = Vec::new();
        for clipped in &output.shapes {
            let egui::Shape::Text(t) = &clipped.shape else { continue };
            for row in &t.galley.rows {
                rows.push((row.text(), t.pos.x + row.rect().right()));
            }
        }
        output.drop_without_applying_deltas();
        rows
    }

    #[test]
    fn a_figure_is_never_parted_from_its_unit_however_narrow_the_window() {
        // What a lecturer's status bar showed under Xvfb; at 1024 px "GPU 12.7" ended a line
        // and "ms/render" began the next.
        let status = Status {
            adapter: Some(
                "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu), driver llvmpipe Mesa 22.3.6 (LLVM 15.0.6)".into(),
            ),
            software: true,
            gpu_ms: Some((12.7, false)),
            gpu_rendering: Some((3.0, (4, 16))),
            gpu_compiling: Some(("spot lights, Phong highlights".into(), 12.0)),
            gpu_fps: Some(8.4),
            ui_ms: 1.2,
            cpu_time: Some(0.092),
            errors: Some(ImageErrors { max_abs: 2.955e-2, mean_abs: 1.055e-5, psnr: 69.0, ..ImageErrors::default() }),
            gpu_counts: Some(RayCounts { camera: 76800, shadow: 96507, reflection: 40266, ..RayCounts::default() }),
            ..Status::default()
        };
        for width in (700..=1600).step_by(4).map(|w| w as f32) {
            let rows = drawn_rows(&status, width);
            assert!(rows.iter().any(|(r, _)| r.contains("12.7 ms/render")), "{width}: {rows:?}");
            for (row, right) in &rows {
                // A row that ends in a digit has left the figure's unit to the next.
                let ends_in_figure = row.trim_end().ends_with(|c: char| c.is_ascii_digit());
                assert!(!ends_in_figure || row.contains("(LLVM 15.0.6)"), "at {width} px a row ends {row:?}");
                assert!(*right <= width + 0.5, "at {width} px {row:?} reaches {right}");
            }
        }
    }

    #[test]
    fn a_slow_rate_is_not_written_as_zero() {
        let s = |n, rate| Samples {
            gpu: Some(n),
            gpu_rate: rate,
            accumulating: true,
            paused: false,
            full: false,
            cpu: Some(1),
        };
        assert_eq!(samples_text(&s(10, Some(0.37))), "GPU 10 samples (0.37/s), adding…; CPU 1 sample");
        assert_eq!(samples_text(&s(192, Some(48.4))), "GPU 192 samples (48/s), adding…; CPU 1 sample");
        assert_eq!(samples_text(&s(1, None)), "GPU 1 sample, adding…; CPU 1 sample");
    }
}
