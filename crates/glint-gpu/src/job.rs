//! A render in flight: its buffers, what produced it, and when the GPU finished it.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::buffers::SceneBuffers;
use crate::context::GpuContext;
use crate::pipeline::TracerPipeline;
use crate::readback::JobReadback;
use crate::shaders::ShaderKey;

/// A render submitted to the GPU: its buffers stay alive until it is read back or dropped.
#[derive(Debug)]
pub struct GpuJob {
    pub buffers: SceneBuffers,
    pub key: ShaderKey,
    pub statements: usize,
    pub pipeline_time: Duration,
    pub upload_time: Duration,
    pub(crate) submitted: Instant,
    done: Arc<Mutex<Option<Instant>>>,
}

impl GpuJob {
    /// A job of `pipeline` whose dispatches were all submitted since `submitted`: records when
    /// the GPU finishes the work queued so far.
    pub(crate) fn new(
        ctx: &GpuContext,
        buffers: SceneBuffers,
        pipeline: &TracerPipeline,
        pipeline_time: Duration,
        upload_time: Duration,
        submitted: Instant,
    ) -> Self {
        let done = Arc::new(Mutex::new(None));
        let slot = done.clone();
        ctx.queue.on_submitted_work_done(move || {
            *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(Instant::now());
        });
        let (key, statements) = (pipeline.key, pipeline.stats.statements);
        Self { buffers, key, statements, pipeline_time, upload_time, submitted, done }
    }

    /// GPU time from submission to completion, once the GPU has finished.
    pub fn gpu_time(&self) -> Option<Duration> {
        self.done.lock().unwrap_or_else(|e| e.into_inner()).map(|t| t.duration_since(self.submitted))
    }

    /// Starts copying the image and the statistics to the host.
    pub fn start_readback(&self, ctx: &GpuContext) -> JobReadback {
        JobReadback::start(ctx, &self.buffers, self.key)
    }
}
