//! The Whitted against GI view's images: the scene's Whitted image, rendered on the CPU in the
//! background while the view is shown, and its signed difference from the path-traced image on
//! screen (the GPU's mean over its batches, else the CPU's), made again as the paths converge.

use glint_core::compare::SignedDifference;
use glint_core::{CpuOptions, FlatScene, HdrImage, RenderControl};

use crate::images::CpuTexture;
use crate::worker::Worker;

/// Why the integrator cannot be switched to Whitted while the view is shown: its GI side is the
/// scene's own path render (Whitted there showed Whitted's image on both sides, labelled
/// "GI (paths)", and a difference of 0; a lecturer).
pub const PATHS_HELD: &str = "Whitted vs GI holds Whitted's image against the paths, so the integrator stays Paths \
     while this view is shown. Choose another view to render the scene with Whitted's integrator alone.";

/// The signed difference of a revision's Whitted image from its paths of `samples` a pixel.
#[derive(Clone, Debug)]
pub struct GiDifference {
    pub revision: u64,
    pub samples: u32,
    /// Whether the paths were the GPU's (else the CPU's): the image shown beside Whitted.
    pub from_gpu: bool,
    pub diff: SignedDifference,
}

/// The paths a difference is taken from: their image, samples a pixel, and whether the GPU's.
pub type Paths<'a> = (&'a HdrImage, u32, bool);

#[derive(Debug)]
pub struct WhittedVsGi {
    whitted_worker: Worker<Result<HdrImage, String>>,
    diff_worker: Worker<GiDifference>,
    /// The Whitted image of a revision.
    pub whitted: Option<(u64, HdrImage)>,
    pub difference: Option<GiDifference>,
    pub error: Option<String>,
    pub whitted_texture: CpuTexture,
    pub diff_texture: CpuTexture,
}

impl WhittedVsGi {
    pub fn new(repaint: egui::Context) -> Self {
        Self {
            whitted_worker: Worker::new("glint-whitted", "Whitted render", Some(repaint.clone())),
            diff_worker: Worker::new("glint-gi-difference", "Whitted − GI difference", Some(repaint)),
            whitted: None,
            difference: None,
            error: None,
            whitted_texture: CpuTexture::default(),
            diff_texture: CpuTexture::default(),
        }
    }

    /// The Whitted image of `revision`, if it is there.
    pub fn whitted_of(&self, revision: u64) -> Option<&HdrImage> {
        self.whitted.as_ref().filter(|(r, _)| *r == revision).map(|(_, i)| i)
    }

    /// Whether `revision`'s Whitted image is neither there nor being rendered.
    pub fn needs_whitted(&self, revision: u64) -> bool {
        self.whitted_of(revision).is_none() && self.whitted_worker.running_revision() != Some(revision)
    }

    pub fn difference_of(&self, revision: u64) -> Option<&GiDifference> {
        self.difference.as_ref().filter(|d| d.revision == revision)
    }

    /// Starts what `revision` still needs: its Whitted image (`whitted`, the scene with
    /// Whitted's integrator), then the difference from `gi` (the paths of `samples` a pixel),
    /// again each time the paths have twice the samples of the last difference.
    pub fn request(&mut self, revision: u64, whitted: Option<FlatScene>, gi: Option<Paths<'_>>) {
        if self.needs_whitted(revision) {
            let Some(scene) = whitted else { return };
            let started = self.whitted_worker.start(revision, move |handle| {
                let control = RenderControl { cancel: Some(handle.cancel_flag()), ..RenderControl::default() };
                glint_core::render_cpu(&scene, &CpuOptions::default(), control)
                    .map(|r| r.image)
                    .map_err(|e| e.to_string())
            });
            if let Err(e) = started {
                self.error = Some(e.to_string());
            }
            return;
        }
        // Still rendering: nothing to hold against the paths yet.
        let (Some(w), Some((gi, samples, from_gpu))) = (self.whitted_of(revision), gi) else { return };
        let current = self.difference_of(revision).map(|d| d.samples);
        let due = current.is_none_or(|n| samples >= 2 * n);
        if !due || self.diff_worker.is_running() || (w.width, w.height) != (gi.width, gi.height) {
            return;
        }
        let (w, gi) = (w.clone(), gi.clone());
        let started = self.diff_worker.start(revision, move |_| GiDifference {
            revision,
            samples,
            from_gpu,
            diff: SignedDifference::new(&w, &gi),
        });
        if let Err(e) = started {
            self.error = Some(e.to_string());
        }
    }

    /// Collects finished jobs into the textures.
    pub fn poll(&mut self, ctx: &egui::Context) {
        match self.whitted_worker.poll() {
            Some((revision, Ok(Ok(image)))) => {
                let rgba: Vec<u8> = image.to_srgb8().chunks_exact(3).flat_map(|p| [p[0], p[1], p[2], 255]).collect();
                self.whitted_texture.set_rgba(ctx, "whitted", image.width, image.height, &rgba);
                self.whitted = Some((revision, image));
                self.error = None;
            }
            Some((_, Ok(Err(e)))) => self.error = Some(e),
            Some((_, Err(e))) => self.error = Some(e.to_string()),
            None => {}
        }
        match self.diff_worker.poll() {
            Some((_, Ok(d))) => {
                self.diff_texture.set_rgb(ctx, "whitted − gi", d.diff.width, d.diff.height, &d.diff.rgb);
                self.difference = Some(d);
            }
            Some((_, Err(e))) => self.error = Some(e.to_string()),
            None => {}
        }
    }

    pub fn is_running(&self) -> bool {
        self.whitted_worker.is_running() || self.diff_worker.is_running()
    }
}
