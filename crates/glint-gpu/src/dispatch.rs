//! Dispatching the tracer: one submission per tile and sample, sample by sample, so that a
//! caller can follow the render and stop it between submissions.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use glint_core::PixelRect;
use glint_types::layout::{STAT_PIXELS_DONE, TileParams};

use crate::buffers::{SceneBuffers, ZERO_STATS};
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::pipeline::TracerPipeline;
use crate::readback::read_buffer;

/// Tile edge in pixels: one submission renders at most this square, so no single submission
/// runs long enough to trip a desktop GPU's watchdog.
pub const DEFAULT_TILE: u32 = 256;

/// Edge of the shader's workgroup (`@workgroup_size(8, 8, 1)` of trace.wgsl and path.wgsl).
pub const WORKGROUP: u32 = 8;

/// Samples of a pixel the path tracer runs in one batch over a tile: long enough that a
/// workgroup's lanes stay busy while their paths' lengths differ, short enough to show progress.
pub const PATH_BATCH: u32 = 64;

/// Bounce dispatches between two reads of the finished-pixel count.
const PATH_CHUNK: u32 = 8;

/// Checks that a tile of `tile` pixels a side needs no more workgroups than the device
/// dispatches.
pub fn check_tile(ctx: &GpuContext, tile: u32) -> Result<(), GpuError> {
    let groups = tile.max(WORKGROUP).div_ceil(WORKGROUP);
    let limit = ctx.limits.max_compute_workgroups_per_dimension;
    if groups > limit {
        return Err(GpuError::TileTooLarge { tile, groups, limit });
    }
    Ok(())
}

impl SceneBuffers {
    /// Renders the one pixel (x, y) with the probe variant.
    pub fn dispatch_probe(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        bind_group: &wgpu::BindGroup,
        x: u32,
        y: u32,
    ) {
        self.dispatch_tile(ctx, pipeline, bind_group, TileParams::pixel(x, y));
    }

    /// Renders one pixel and clears the statistics again (see `GpuTracer::submit`).
    pub fn prime(&self, ctx: &GpuContext, pipeline: &TracerPipeline, bind_group: &wgpu::BindGroup) {
        self.dispatch_tile(ctx, pipeline, bind_group, TileParams::pixel(0, 0));
        ctx.queue.write_buffer(&self.stats, 0, bytemuck::cast_slice(&ZERO_STATS));
    }

    /// One sample of one tile: Whitted's kernel once, or the path tracer's `start` and then its
    /// bounce kernel max_depth + 1 times, by which every path has ended (the probe and the
    /// pipeline's priming render one pixel this way).
    fn dispatch_tile(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        bind_group: &wgpu::BindGroup,
        params: TileParams,
    ) -> wgpu::SubmissionIndex {
        ctx.queue.write_buffer(&self.tile, 0, bytemuck::bytes_of(&params));
        let groups = (params.width.div_ceil(WORKGROUP), params.height.div_ceil(WORKGROUP));
        match &pipeline.start {
            Some(start) => {
                self.encode(ctx, bind_group, groups, &[(start, 1), (&pipeline.pipeline, self.max_depth + 1)])
            }
            None => self.encode(ctx, bind_group, groups, &[(&pipeline.pipeline, 1)]),
        }
    }

    /// One submission of `steps` (each kernel dispatched so many times, in order, over `groups`
    /// workgroups): wgpu orders the dispatches of a pass, each seeing what the last wrote.
    fn encode(
        &self,
        ctx: &GpuContext,
        bind_group: &wgpu::BindGroup,
        groups: (u32, u32),
        steps: &[(&wgpu::ComputePipeline, u32)],
    ) -> wgpu::SubmissionIndex {
        let mut encoder =
            ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("glint tile") });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("glint trace"),
                timestamp_writes: None,
            });
            pass.set_bind_group(0, bind_group, &[]);
            for &(kernel, times) in steps {
                pass.set_pipeline(kernel);
                for _ in 0..times {
                    pass.dispatch_workgroups(groups.0, groups.1, 1);
                }
            }
        }
        ctx.queue.submit([encoder.finish()])
    }

    /// The path tracer's image: batches of `PATH_BATCH` samples, each over every tile. A tile's
    /// pixels each run the batch's samples one after the other (path.wgsl); the bounce kernel
    /// is dispatched in chunks until the finished-pixel count says all are done, which takes
    /// at most (samples × (max_depth + 1)) dispatches. A cancel stops between chunks; the
    /// progress counts the batches' samples, a batch's share of them as its tiles finish (a
    /// batch of 64 on lavapipe said 0/64 for minutes, then all of them).
    fn dispatch_paths(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        start: &wgpu::ComputePipeline,
        bind_group: &wgpu::BindGroup,
        tile: u32,
        region: PixelRect,
        control: DispatchControl<'_>,
    ) -> Result<(), GpuError> {
        let cancelled = || control.cancel.is_some_and(|c| c.load(Ordering::Relaxed));
        if let Some(p) = control.progress {
            p.start(self.spp);
        }
        for first in (0..self.spp).step_by(PATH_BATCH as usize) {
            let end = (first + PATH_BATCH).min(self.spp);
            // Every path ends within max_depth + 1 bounces; every sample takes at least one.
            let most = (end - first) * (self.max_depth + 1);
            let tiles = tiles_of(region, tile).count() as u64;
            for (k, (x0, y0, width, height)) in tiles_of(region, tile).enumerate() {
                {
                    if cancelled() {
                        return Err(GpuError::Cancelled);
                    }
                    let params = TileParams { sample_end: end, ..TileParams::new(x0, y0, width, height, first) };
                    ctx.queue.write_buffer(&self.tile, 0, bytemuck::bytes_of(&params));
                    let done_word = u64::from(STAT_PIXELS_DONE) * 4;
                    ctx.queue.write_buffer(&self.stats, done_word, bytemuck::bytes_of(&0u32));
                    let groups = (width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP));
                    let mut dispatched = (end - first).max(PATH_CHUNK).min(most);
                    self.encode(ctx, bind_group, groups, &[(start, 1), (&pipeline.pipeline, dispatched)]);
                    while self.pixels_done(ctx)? < width * height && dispatched < most {
                        if cancelled() {
                            return Err(GpuError::Cancelled);
                        }
                        let chunk = PATH_CHUNK.min(most - dispatched);
                        self.encode(ctx, bind_group, groups, &[(&pipeline.pipeline, chunk)]);
                        dispatched += chunk;
                    }
                }
                if let Some(p) = control.progress {
                    let share = u64::from(end - first) * (k as u64 + 1) / tiles;
                    p.finished(first + share as u32);
                }
            }
        }
        Ok(())
    }

    /// How many pixels of the tile have finished their batch (waits for the GPU).
    fn pixels_done(&self, ctx: &GpuContext) -> Result<u32, GpuError> {
        let words = read_buffer(ctx, &self.stats)?;
        Ok(bytemuck::cast_slice::<u8, u32>(&words)[STAT_PIXELS_DONE as usize])
    }

    /// Dispatches the whole image: one submission per tile and sample, so that no submission
    /// runs long enough to trip a desktop GPU's watchdog and no invocation runs past lavapipe's
    /// loop budget however many samples a pixel takes. Sample after sample over the whole image
    /// (each pixel still adds its samples in order, so the image is the same as tile after
    /// tile): the finished passes are the progress, and a cancel stops at the next submission.
    /// At most one pass is queued ahead of the one running, so that a cancel takes effect
    /// within about a pass on a GPU whose `submit` does not wait (lavapipe's does).
    pub fn dispatch(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        bind_group: &wgpu::BindGroup,
        tile: u32,
        region: PixelRect,
        control: DispatchControl<'_>,
    ) -> Result<(), GpuError> {
        let tile = tile.max(WORKGROUP);
        if let Some(start) = &pipeline.start {
            return self.dispatch_paths(ctx, pipeline, start, bind_group, tile, region, control);
        }
        if let Some(p) = control.progress {
            p.start(self.spp);
        }
        let mut previous_pass = None;
        for sample_index in 0..self.spp {
            let mut last = None;
            for (x0, y0, width, height) in tiles_of(region, tile) {
                {
                    if control.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                        return Err(GpuError::Cancelled);
                    }
                    let params = TileParams::new(x0, y0, width, height, sample_index);
                    last = Some(self.dispatch_tile(ctx, pipeline, bind_group, params));
                }
            }
            if let Some(p) = control.progress {
                let p = p.clone();
                ctx.queue.on_submitted_work_done(move || p.finished(sample_index + 1));
            }
            if let Some(index) = previous_pass.replace(last) {
                let wait = wgpu::PollType::Wait { submission_index: index, timeout: None };
                ctx.device.poll(wait).map_err(|e| GpuError::Wgpu(e.to_string()))?;
            }
        }
        Ok(())
    }
}

/// The `tile`-pixel squares of `region` as (x0, y0, width, height), row by row.
fn tiles_of(region: PixelRect, tile: u32) -> impl Iterator<Item = (u32, u32, u32, u32)> {
    let (x_end, y_end) = (region.x0 + region.width, region.y0 + region.height);
    (region.y0..y_end).step_by(tile as usize).flat_map(move |y0| {
        (region.x0..x_end).step_by(tile as usize).map(move |x0| (x0, y0, tile.min(x_end - x0), tile.min(y_end - y0)))
    })
}

/// What the caller of a render may do while it is dispatched.
#[derive(Clone, Copy, Debug, Default)]
pub struct DispatchControl<'a> {
    /// Checked before every submission; once set, the render stops with `GpuError::Cancelled`.
    pub cancel: Option<&'a AtomicBool>,
    /// Sample passes the GPU has finished, of how many.
    pub progress: Option<&'a Arc<SampleProgress>>,
}

/// How many of a render's sample passes the GPU has finished (each pass is the whole image at
/// one sample), updated as the GPU reports submitted work done.
#[derive(Debug, Default)]
pub struct SampleProgress {
    done: AtomicU32,
    total: AtomicU32,
}

impl SampleProgress {
    /// The progress of a render of `total` passes, none finished.
    pub fn new(total: u32) -> Self {
        Self { done: AtomicU32::new(0), total: AtomicU32::new(total) }
    }

    fn start(&self, total: u32) {
        self.done.store(0, Ordering::Relaxed);
        self.total.store(total, Ordering::Relaxed);
    }

    fn finished(&self, passes: u32) {
        self.done.fetch_max(passes, Ordering::Relaxed);
    }

    /// (finished passes, all passes).
    pub fn get(&self) -> (u32, u32) {
        (self.done.load(Ordering::Relaxed), self.total.load(Ordering::Relaxed))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders::{ShaderKey, compose};

    #[test]
    fn workgroup_matches_the_entry_point() {
        let module = compose(&ShaderKey::full()).expect("full shader composes");
        let main = module.entry_points.iter().find(|e| e.name == "main").expect("entry point main");
        assert_eq!(main.workgroup_size, [WORKGROUP, WORKGROUP, 1]);
    }
}
