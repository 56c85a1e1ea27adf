//! Reading results back from the GPU: buffer copies to the host, polled once per frame or
//! waited for, and the decoding of the image and the statistics.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glint_core::HdrImage;
use glint_core::cpu::RayCounts;
use glint_core::glam::dvec3;
use glint_types::layout::{
    NO_HIT, STAT_BAILOUT_SAVED, STAT_CAMERA, STAT_REFLECTION, STAT_REFRACTION, STAT_SHADOW, STAT_STATUS,
};

use crate::buffers::SceneBuffers;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::shaders::ShaderKey;

/// A copy of a GPU buffer on its way to the host.
#[derive(Debug)]
pub struct PendingCopy {
    staging: wgpu::Buffer,
    result: Arc<Mutex<Option<Result<(), wgpu::BufferAsyncError>>>>,
}

impl PendingCopy {
    /// Queues the copy of `source` and the mapping of its staging buffer.
    pub fn start(ctx: &GpuContext, source: &wgpu::Buffer) -> Self {
        let size = source.size();
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glint readback"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder =
            ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
        encoder.copy_buffer_to_buffer(source, 0, &staging, 0, size);
        ctx.queue.submit([encoder.finish()]);
        let result = Arc::new(Mutex::new(None));
        let slot = result.clone();
        staging.map_async(wgpu::MapMode::Read, .., move |r| {
            *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(r);
        });
        Self { staging, result }
    }

    /// The bytes, once the copy has landed (`None` while it is in flight).
    pub fn try_take(&self) -> Option<Result<Vec<u8>, GpuError>> {
        let state = self.result.lock().unwrap_or_else(|e| e.into_inner()).take()?;
        Some(state.map_err(|e| GpuError::Readback(e.to_string())).and_then(|()| {
            let view = self.staging.get_mapped_range(..).map_err(|e| GpuError::Readback(e.to_string()))?;
            let bytes = view.to_vec();
            drop(view);
            self.staging.unmap();
            Ok(bytes)
        }))
    }
}

/// Waits for the GPU until `ready` yields a result.
fn wait_for<T>(ctx: &GpuContext, mut ready: impl FnMut() -> Option<Result<T, GpuError>>) -> Result<T, GpuError> {
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Readback(e.to_string()))?;
        if ctx.is_lost() {
            return Err(GpuError::DeviceLost);
        }
        if let Some(result) = ready() {
            return result;
        }
        // The copy is done, but when several threads share the device, another thread's poll
        // may be running this mapping's callback right now: wait for it.
        if Instant::now() > deadline {
            return Err(GpuError::Readback("the mapping did not complete".into()));
        }
        std::thread::yield_now();
    }
}

/// Copies `source` to the host, waiting for it.
pub fn read_buffer(ctx: &GpuContext, source: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let copy = PendingCopy::start(ctx, source);
    wait_for(ctx, || copy.try_take())
}

/// A finished readback: image, ray counts and the status word.
pub type ReadbackResult = (HdrImage, RayCounts, u32);

/// The image and statistics of a job, arriving without blocking the caller.
#[derive(Debug)]
pub struct JobReadback {
    image: PendingCopy,
    stats: PendingCopy,
    width: u32,
    height: u32,
    key: ShaderKey,
    image_bytes: Option<Vec<u8>>,
}

impl JobReadback {
    /// Starts copying the image and the statistics of a job rendered by variant `key`.
    pub(crate) fn start(ctx: &GpuContext, buffers: &SceneBuffers, key: ShaderKey) -> Self {
        Self {
            image: PendingCopy::start(ctx, &buffers.output),
            stats: PendingCopy::start(ctx, &buffers.stats),
            width: buffers.width,
            height: buffers.height,
            key,
            image_bytes: None,
        }
    }

    /// The shader variant that rendered the job (its stack size words a status message).
    pub fn key(&self) -> ShaderKey {
        self.key
    }

    /// Polls the device once; returns the result when both copies have landed.
    pub fn poll(&mut self, ctx: &GpuContext) -> Option<Result<ReadbackResult, GpuError>> {
        if let Err(e) = ctx.device.poll(wgpu::PollType::Poll) {
            return Some(Err(GpuError::Wgpu(e.to_string())));
        }
        self.try_take()
    }

    /// Waits for both copies.
    pub fn wait(mut self, ctx: &GpuContext) -> Result<ReadbackResult, GpuError> {
        wait_for(ctx, || self.try_take())
    }

    /// The result, once both copies have landed.
    fn try_take(&mut self) -> Option<Result<ReadbackResult, GpuError>> {
        if self.image_bytes.is_none() {
            match self.image.try_take()? {
                Ok(bytes) => self.image_bytes = Some(bytes),
                Err(e) => return Some(Err(e)),
            }
        }
        let stats = match self.stats.try_take()? {
            Ok(bytes) => bytes,
            Err(e) => return Some(Err(e)),
        };
        let image = decode_output(self.width, self.height, self.image_bytes.as_deref().unwrap_or_default());
        let (counts, status) = decode_stats(&stats);
        Some(Ok((image, counts, status)))
    }
}

/// rgb radiance and the first-hit id stored as f32 in w (−1 for none).
pub fn decode_output(width: u32, height: u32, bytes: &[u8]) -> HdrImage {
    let texels: &[[f32; 4]] = bytemuck::cast_slice(bytes);
    let mut image = HdrImage::new(width, height);
    for (i, t) in texels.iter().enumerate().take(image.pixels.len()) {
        image.pixels[i] = dvec3(f64::from(t[0]), f64::from(t[1]), f64::from(t[2]));
        image.first_hit[i] = if t[3] < 0.0 { NO_HIT } else { t[3] as u32 };
    }
    image
}

/// The ray counts and the status word of the statistics buffer.
pub fn decode_stats(bytes: &[u8]) -> (RayCounts, u32) {
    let words: &[u32] = bytemuck::cast_slice(bytes);
    let pair = |i: u32| u64::from(words[i as usize]) | (u64::from(words[i as usize + 1]) << 32);
    let counts = RayCounts {
        camera: pair(STAT_CAMERA),
        shadow: pair(STAT_SHADOW),
        reflection: pair(STAT_REFLECTION),
        refraction: pair(STAT_REFRACTION),
        bailout_saved: pair(STAT_BAILOUT_SAVED),
        // The GPU bounds a tree by its walk stack instead: a status flag.
        capped_samples: 0,
    };
    (counts, words[STAT_STATUS as usize])
}
