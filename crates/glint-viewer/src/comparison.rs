//! GPU against CPU: the same error figures and heat map as `glint render --backend both`,
//! computed on a background thread (FLIP takes a while at full resolution).

use glint_core::HdrImage;
use glint_core::compare::{DiffBin, ImageErrors, PixelDiffs, compare_images, diff_heatmap};

use crate::worker::Worker;

#[derive(Clone, Debug)]
pub struct Compared {
    pub revision: u64,
    pub errors: ImageErrors,
    pub width: u32,
    pub height: u32,
    /// The heat map as 8-bit RGB.
    pub heatmap: Vec<u8>,
    /// Per-pixel |GPU − CPU| and first-hit disagreement (read under the cursor, worst pixel).
    pub diffs: PixelDiffs,
    pub histogram: Vec<DiffBin>,
}

#[derive(Debug)]
pub struct Comparison {
    worker: Worker<Compared>,
    pub latest: Option<Compared>,
}

impl Comparison {
    /// Comparisons that wake the UI of `repaint` when they are done.
    pub fn new(repaint: egui::Context) -> Self {
        Self { worker: Worker::new("glint-compare", "comparison", Some(repaint)), latest: None }
    }

    /// Starts comparing the two renders of `revision` unless that is done or under way.
    pub fn request(&mut self, revision: u64, cpu: &HdrImage, gpu: &HdrImage) {
        let done = self.latest.as_ref().is_some_and(|c| c.revision == revision);
        let running = self.worker.running_revision() == Some(revision);
        if done || running || (cpu.width, cpu.height) != (gpu.width, gpu.height) {
            return;
        }
        // The CPU's image as a file stores it, so that what is identical in the saved images
        // shows black.
        let (cpu, gpu) = (cpu.as_stored(), gpu.clone());
        let started = self.worker.start(revision, move |_| {
            let errors = compare_images(&cpu, &gpu);
            let heatmap = diff_heatmap(&cpu, &gpu);
            let diffs = PixelDiffs::new(&cpu, &gpu);
            let histogram = diffs.histogram();
            Compared { revision, errors, width: cpu.width, height: cpu.height, heatmap, diffs, histogram }
        });
        if let Err(e) = started {
            log::error!("{e}");
        }
    }

    /// Takes a finished comparison; true when a new one arrived.
    pub fn poll(&mut self) -> bool {
        match self.worker.poll() {
            Some((_, Ok(c))) => {
                self.latest = Some(c);
                true
            }
            Some((_, Err(e))) => {
                log::error!("{e}");
                false
            }
            None => false,
        }
    }

    pub fn is_running(&self) -> bool {
        self.worker.is_running()
    }
}
