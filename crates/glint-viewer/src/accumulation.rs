//! Progressive path tracing on the GPU: in path mode the full-resolution render of a revision
//! is followed by further batches of the same scene with other seeds (independent paths), and
//! their mean is what the GPU view shows, the comparison reads and export writes. An edit
//! starts over; pausing stops submitting batches.

use std::time::Duration;

use glint_core::HdrImage;
use glint_core::cpu::RayCounts;

/// The most samples a pixel accumulates before the GPU goes idle: 2^16, beyond which f64
/// means still move but nothing a viewer shows does.
pub const MAX_SAMPLES: u32 = 1 << 16;

/// The seed of batch `batch` of a scene whose own seed is `seed`: batch 0 is the scene's own
/// (the CPU reference's paths), each later one another stream.
pub fn batch_seed(seed: u32, batch: u32) -> u32 {
    seed.wrapping_add(batch.wrapping_mul(0x9e37_79b9))
}

/// The running mean of a revision's batches.
#[derive(Clone, Debug)]
pub struct Accumulation {
    pub revision: u64,
    pub mean: HdrImage,
    /// Batch 0 alone: the CPU reference's own paths, which the comparison holds it against.
    pub first: HdrImage,
    /// Samples a pixel so far, over every batch.
    pub samples: u32,
    /// Batches added (the next one expected is this index).
    pub batches: u32,
    /// The GPU time of every batch, summed.
    pub gpu_time: Duration,
    pub counts: RayCounts,
}

impl Accumulation {
    /// Starts from a revision's first render (batch 0) of `spp` samples a pixel.
    pub fn new(revision: u64, image: HdrImage, spp: u32, gpu_ms: f64, counts: RayCounts) -> Self {
        Self {
            revision,
            first: image.clone(),
            mean: image,
            samples: spp,
            batches: 1,
            gpu_time: Duration::from_secs_f64(gpu_ms.max(0.0) / 1e3),
            counts,
        }
    }

    /// Adds batch `batch` of `spp` samples a pixel; false (and nothing added) if it is not the
    /// next batch of this revision or has another size.
    pub fn add(
        &mut self,
        revision: u64,
        batch: u32,
        image: &HdrImage,
        spp: u32,
        gpu_ms: f64,
        counts: RayCounts,
    ) -> bool {
        if revision != self.revision
            || batch != self.batches
            || (image.width, image.height) != (self.mean.width, self.mean.height)
        {
            return false;
        }
        let (old, new) = (f64::from(self.samples), f64::from(spp));
        let total = old + new;
        for (m, v) in self.mean.pixels.iter_mut().zip(&image.pixels) {
            *m = (*m * old + *v * new) / total;
        }
        self.samples += spp;
        self.batches += 1;
        self.gpu_time += Duration::from_secs_f64(gpu_ms.max(0.0) / 1e3);
        self.counts += counts;
        true
    }

    /// Samples a pixel per second of GPU time.
    pub fn rate(&self) -> Option<f64> {
        let secs = self.gpu_time.as_secs_f64();
        (secs > 0.0).then(|| f64::from(self.samples) / secs)
    }

    pub fn is_full(&self) -> bool {
        self.samples >= MAX_SAMPLES
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_core::glam::DVec3;

    fn image(v: f64) -> HdrImage {
        let mut i = HdrImage::new(2, 1);
        i.pixels.fill(DVec3::splat(v));
        i
    }

    #[test]
    fn batches_are_weighed_by_their_samples_and_taken_in_order() {
        let mut a = Accumulation::new(7, image(1.0), 4, 10.0, RayCounts::default());
        assert!(a.add(7, 1, &image(4.0), 2, 10.0, RayCounts::default()));
        assert_eq!(a.mean.pixels[0], DVec3::splat(2.0));
        assert_eq!((a.samples, a.batches), (6, 2));
        // Another revision, a batch twice or out of order, another size: not added.
        assert!(!a.add(8, 2, &image(9.0), 2, 10.0, RayCounts::default()));
        assert!(!a.add(7, 1, &image(9.0), 2, 10.0, RayCounts::default()));
        assert!(!a.add(7, 2, &HdrImage::new(1, 1), 2, 10.0, RayCounts::default()));
        assert_eq!(a.mean.pixels[1], DVec3::splat(2.0));
        assert!((a.rate().unwrap() - 300.0).abs() < 1e-9, "{:?}", a.rate());
    }

    #[test]
    fn every_batch_has_a_seed_of_its_own() {
        let seeds: std::collections::HashSet<u32> = (0..1000).map(|b| batch_seed(5, b)).collect();
        assert_eq!(seeds.len(), 1000);
        assert_eq!(batch_seed(5, 0), 5);
    }
}
