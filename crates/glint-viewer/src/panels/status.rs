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

fn counts(c: &RayCounts) -> String {
    format!(
        "{} camera, {} shadow, {} reflection, {} refraction; {} saved by bailout",
        c.camera, c.shadow, c.reflection, c.refraction, c.bailout_saved
    )
}

pub fn ui(ui: &mut Ui, s: &Status) {
    ui.horizontal_wrapped(|ui| {
        match &s.adapter {
            Some(a) => ui.label(format!("GPU: {a}")),
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
            ui.label(format!("compiling the shader for {what}… {secs:.0} s (the last image stays)"));
        }
        if let Some((secs, (done, total))) = s.gpu_rendering {
            ui.spinner();
            ui.label(format!("GPU rendering {done}/{total} samples… {secs:.0} s"));
        }
        if let Some((ms, compiled)) = s.gpu_ms {
            ui.label(gpu_time_text(ms, compiled));
        }
        // Renders, not the window's frames: "fps" beside the UI's time read as the window's.
        if let Some(rate) = s.gpu_fps {
            ui.label(format!("{rate:.1} renders/s"));
        }
        ui.label(format!("UI {:.1} ms", s.ui_ms));
        ui.separator();
        if let Some(samples) = &s.samples {
            ui.label(samples_text(samples));
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
                ui.label(format!("CPU done in {:.0} ms", t * 1e3));
            }
            (None, None) => {}
        }
    });
    ui.horizontal_wrapped(|ui| match (&s.errors, s.comparing) {
        (Some(e), _) => {
            ui.label(format!(
                "GPU vs CPU: max abs {:.3e}, mean abs {:.3e}, PSNR {:.1} dB, FLIP mean {:.5}, first-hit mismatch {:.3} %",
                e.max_abs,
                e.mean_abs,
                e.psnr,
                e.flip_mean,
                e.first_hit_mismatch * 100.0
            ));
        }
        (None, true) => {
            ui.spinner();
            ui.label("comparing GPU and CPU…");
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
    });
    match (&s.gpu_counts, &s.cpu_counts) {
        (Some(g), _) => ui.label(format!("Rays (GPU): {}", counts(g))),
        (None, Some(c)) => ui.label(format!("Rays (CPU): {}", counts(c))),
        (None, None) => ui.weak("Rays: no render yet"),
    };
}

#[cfg(test)]
mod tests {
    use super::{Samples, samples_text};

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
