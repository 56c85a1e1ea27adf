//! Dispatching the tracer: one submission per tile and sample.

use glint_core::layout::TileParams;

use crate::buffers::{SceneBuffers, ZERO_STATS};
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::pipeline::TracerPipeline;

/// Tile edge in pixels: one submission renders at most this square, so no single submission
/// runs long enough to trip a desktop GPU's watchdog.
pub const DEFAULT_TILE: u32 = 256;

/// Edge of the shader's workgroup (`@workgroup_size(8, 8, 1)` of trace.wgsl).
pub const WORKGROUP: u32 = 8;

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

    fn dispatch_tile(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        bind_group: &wgpu::BindGroup,
        params: TileParams,
    ) {
        ctx.queue.write_buffer(&self.tile, 0, bytemuck::bytes_of(&params));
        let mut encoder =
            ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("glint tile") });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("glint trace"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&pipeline.pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.dispatch_workgroups(params.width.div_ceil(WORKGROUP), params.height.div_ceil(WORKGROUP), 1);
        }
        ctx.queue.submit([encoder.finish()]);
    }

    /// Dispatches the whole image: one submission per tile and sample, so that no submission
    /// runs long enough to trip a desktop GPU's watchdog and no invocation runs past lavapipe's
    /// loop budget however many samples a pixel takes.
    pub fn dispatch(&self, ctx: &GpuContext, pipeline: &TracerPipeline, bind_group: &wgpu::BindGroup, tile: u32) {
        let tile = tile.max(WORKGROUP);
        for y0 in (0..self.height).step_by(tile as usize) {
            for x0 in (0..self.width).step_by(tile as usize) {
                let (width, height) = (tile.min(self.width - x0), tile.min(self.height - y0));
                for sample_index in 0..self.spp {
                    let params = TileParams::new(x0, y0, width, height, sample_index);
                    self.dispatch_tile(ctx, pipeline, bind_group, params);
                }
            }
        }
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
