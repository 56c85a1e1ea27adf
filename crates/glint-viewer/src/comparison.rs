//! GPU against CPU: the same error figures and heat map as `glint render --backend both`,
//! computed on a background thread (FLIP takes a while at full resolution).

use std::sync::mpsc::{Receiver, TryRecvError, channel};

use glint_core::HdrImage;
use glint_core::compare::{ImageErrors, compare_images, diff_heatmap};

#[derive(Clone, Debug)]
pub struct Compared {
    pub revision: u64,
    pub errors: ImageErrors,
    pub width: u32,
    pub height: u32,
    /// The heat map as 8-bit RGB.
    pub heatmap: Vec<u8>,
}

#[derive(Debug, Default)]
pub struct Comparison {
    pending: Option<(u64, Receiver<Compared>)>,
    pub latest: Option<Compared>,
}

impl Comparison {
    /// Starts comparing the two renders of `revision` unless that is done or under way.
    pub fn request(&mut self, revision: u64, cpu: &HdrImage, gpu: &HdrImage, repaint: impl Fn() + Send + 'static) {
        let done = self.latest.as_ref().is_some_and(|c| c.revision == revision);
        let running = self.pending.as_ref().is_some_and(|(r, _)| *r == revision);
        if done || running || (cpu.width, cpu.height) != (gpu.width, gpu.height) {
            return;
        }
        let (tx, rx) = channel();
        let (cpu, gpu) = (cpu.clone(), gpu.clone());
        let spawned = std::thread::Builder::new().name("glint-compare".into()).spawn(move || {
            let errors = compare_images(&cpu, &gpu);
            let heatmap = diff_heatmap(&cpu, &gpu);
            // The receiver may be gone (a newer edit): nothing to do then.
            let _ = tx.send(Compared { revision, errors, width: cpu.width, height: cpu.height, heatmap });
            repaint();
        });
        match spawned {
            Ok(_) => self.pending = Some((revision, rx)),
            Err(e) => log::error!("cannot start the comparison thread: {e}"),
        }
    }

    /// Takes a finished comparison; true when a new one arrived.
    pub fn poll(&mut self) -> bool {
        let Some((_, rx)) = &self.pending else { return false };
        match rx.try_recv() {
            Ok(c) => {
                self.latest = Some(c);
                self.pending = None;
                true
            }
            Err(TryRecvError::Empty) => false,
            Err(TryRecvError::Disconnected) => {
                self.pending = None;
                false
            }
        }
    }

    pub fn is_running(&self) -> bool {
        self.pending.is_some()
    }
}
