//! "Fit ambient" (issue 33): in the background, a path-traced image of the current scene and
//! view, and the global I_a per channel that brings Whitted's image closest to it
//! (`glint_core::ambient_fit`), shown with the error before and after and applied on click.

use glint_core::ambient_fit::{AmbientFit, fit_ambient};
use glint_core::{CpuOptions, FlatScene, RenderControl, render_cpu};
use glint_scene::{Integrator, RenderSettings};

use crate::document::Document;
use crate::worker::Worker;

/// Paths a pixel of the reference at least: fewer leave its noise above the error being fitted.
pub const MIN_REFERENCE_SPP: u32 = 64;

#[derive(Debug)]
pub struct AmbientFitter {
    worker: Worker<Result<(AmbientFit, f64), String>>,
    /// The last fit, with the paths' indirect light (their mean less that of their direct
    /// light), and the revision it was made for.
    pub result: Option<(u64, AmbientFit, f64)>,
    pub error: Option<String>,
}

impl AmbientFitter {
    pub fn new(repaint: Option<egui::Context>) -> Self {
        Self { worker: Worker::new("glint-ambient-fit", "ambient fit", repaint), result: None, error: None }
    }

    pub fn is_running(&self) -> bool {
        self.worker.is_running()
    }

    /// Starts fitting the document's scene as it is now (replacing a fit still running).
    pub fn start(&mut self, doc: &Document) {
        let desc = doc.desc.clone();
        let settings = doc.desc.render.clone();
        let started = self.worker.start(doc.revision, move |handle| {
            let paths = RenderSettings {
                integrator: Integrator::Path,
                indirect: true,
                spp: settings.spp.max(MIN_REFERENCE_SPP),
                ..settings.clone()
            };
            let control = RenderControl { cancel: Some(handle.cancel_flag()), ..RenderControl::default() };
            let options = CpuOptions::default();
            let reference = render_cpu(&FlatScene::build(&desc, &paths), &options, control)
                .map_err(|e| format!("the path-traced image: {e}"))?
                .image;
            // Paths without indirect light follow only k_r and k_t: their expectation is the
            // direct kind of light (E S* D? L), at a fraction of the cost.
            let direct = RenderSettings { indirect: false, ..paths };
            let control = RenderControl { cancel: Some(handle.cancel_flag()), ..RenderControl::default() };
            let direct = render_cpu(&FlatScene::build(&desc, &direct), &options, control)
                .map_err(|e| format!("the paths' direct light: {e}"))?
                .image;
            let fit =
                fit_ambient(&desc, &settings, &reference, &options).map_err(|e| format!("Whitted's images: {e}"))?;
            Ok((fit, reference.mean() - direct.mean()))
        });
        if let Err(e) = started {
            self.error = Some(e.to_string());
        }
    }

    /// Takes a finished fit, if one arrived.
    pub fn poll(&mut self) {
        if let Some((revision, result)) = self.worker.poll() {
            match result.map_err(|e| e.to_string()).and_then(|r| r) {
                Ok((fit, indirect)) => (self.result, self.error) = (Some((revision, fit, indirect)), None),
                Err(e) => self.error = Some(e),
            }
        }
    }
}

/// The World section's Fit ambient row; true when the fitted I_a was applied.
pub fn ui(ui: &mut egui::Ui, doc: &mut Document, fitter: &mut AmbientFitter) -> bool {
    fitter.poll();
    let mut applied = false;
    ui.horizontal_wrapped(|ui| {
        let button = ui.add_enabled(!fitter.is_running(), egui::Button::new("Fit ambient to paths"));
        if crate::help::hint(button, "Fit ambient to paths").clicked() {
            fitter.start(doc);
        }
        if fitter.is_running() {
            ui.spinner();
            ui.label("rendering paths…");
        }
    });
    if let Some(e) = &fitter.error {
        ui.colored_label(ui.visuals().warn_fg_color, e);
    }
    if let Some((revision, fit, _)) = fitter.result
        && !fit.determined
    {
        ui.label("I_a changes no pixel here (no material in view has k_a), so no value fits better than another.");
        if revision < doc.fit_revision {
            ui.weak("(fitted to an earlier edit of the scene)");
        }
    } else if let Some((revision, fit, indirect)) = fitter.result {
        let [r, g, b] = fit.ambient;
        // The I_a written now, applied or typed since the fit: the fit does not depend on it,
        // and its figures follow from the fit's moments (the image is affine in I_a).
        let (rmse_as_written, adds_as_written) = fit.at(doc.desc.world.ambient.0);
        ui.label(format!("Fitted I_a = ({r:.3}, {g:.3}, {b:.3})"));
        ui.label(format!(
            "RMSE against the paths: {rmse_as_written:.4} as written, {:.4} without, {:.4} fitted",
            fit.rmse_without, fit.rmse_fitted
        ));
        ui.label(format!(
            "I_a·k_a adds {:.4} to the mean as written, {:.4} fitted; without it Whitted's image is {:.4} below \
             the paths', of which {indirect:.4} is their indirect light (the paths' less their direct light) \
             and the rest direct light Whitted's model does not compute here (an area emitter's)",
            adds_as_written, fit.adds_fitted, fit.below_reference
        ));
        if revision < doc.fit_revision {
            ui.weak("(fitted to an earlier edit of the scene)");
        }
        if doc.desc.world.ambient.0 == fit.ambient {
            ui.weak("I_a is the fitted value.");
        } else if ui.button("Apply the fitted I_a").clicked() {
            doc.desc.world.ambient = glint_scene::Rgb(fit.ambient);
            applied = true;
        }
    }
    applied
}
