//! Display of a GPU render: a compute pass encodes the linear output buffer as 8-bit sRGB
//! RGBA pixels, which a UI reads back (a quarter of the radiance's bytes) and draws.

use std::borrow::Cow;

use crate::context::GpuContext;
use crate::readback::PendingCopy;

#[derive(Debug)]
pub struct Presenter {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    size: wgpu::Buffer,
    /// One u32 a pixel: bytes R, G, B, A (sRGB), rows top to bottom.
    pixels: wgpu::Buffer,
    pub width: u32,
    pub height: u32,
}

impl Presenter {
    pub fn new(ctx: &GpuContext, width: u32, height: u32) -> Self {
        let device = &ctx.device;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("glint present"),
            source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(include_str!("../../../shaders/present.wgsl"))),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("glint present"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let layout = pipeline.get_bind_group_layout(0);
        let pixels = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glint display pixels"),
            size: (u64::from(width) * u64::from(height) * 4).max(4),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let size = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glint display size"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&size, 0, bytemuck::cast_slice(&[width, height, 0u32, 0u32]));
        Self { pipeline, layout, size, pixels, width, height }
    }

    /// Encodes `radiance` (the tracer's output buffer, same size) as sRGB pixels and starts
    /// copying them to the host; queued after what was submitted before, so a finished render's
    /// image is what arrives.
    pub fn present(&self, ctx: &GpuContext, radiance: &wgpu::Buffer) -> PendingPixels {
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint present"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: radiance.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: self.pixels.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: self.size.as_entire_binding() },
            ],
        });
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("present") });
        {
            let mut pass = encoder
                .begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("present"), timestamp_writes: None });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(self.width.div_ceil(8), self.height.div_ceil(8), 1);
        }
        ctx.queue.submit([encoder.finish()]);
        PendingPixels { copy: PendingCopy::start(ctx, &self.pixels), width: self.width, height: self.height }
    }
}

/// A presented image on its way to the host.
#[derive(Debug)]
pub struct PendingPixels {
    copy: PendingCopy,
    pub width: u32,
    pub height: u32,
}

impl PendingPixels {
    /// The RGBA8 (sRGB) bytes once they have landed; polls the device once.
    pub fn poll(&self, ctx: &GpuContext) -> Option<Result<Vec<u8>, crate::GpuError>> {
        if let Err(e) = ctx.device.poll(wgpu::PollType::Poll) {
            return Some(Err(crate::GpuError::Wgpu(e.to_string())));
        }
        self.copy.try_take().map(|r| {
            r.map(|mut bytes| {
                bytes.truncate(self.width as usize * self.height as usize * 4);
                bytes
            })
        })
    }
}

#[cfg(test)]
mod tests {
    /// The presenter's shader is not composed by naga_oil: parse and validate it here, so a
    /// broken edit fails a test without a GPU instead of the viewer at run time.
    #[test]
    fn present_shader_validates() {
        let source = include_str!("../../../shaders/present.wgsl");
        let module = naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
        if let Err(e) = crate::shaders::validate(&module) {
            panic!("present.wgsl is invalid:\n{e}");
        }
    }
}
