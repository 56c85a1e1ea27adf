//! Display of a GPU render: a compute pass encodes the linear output buffer as sRGB into an
//! rgba8 texture that a UI (the viewer, through egui-wgpu) samples directly.

use std::borrow::Cow;

use crate::context::GpuContext;

/// Format the texture is written in (storage textures cannot be sRGB)…
pub const STORAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
/// …and the format of the view for display, so that samplers decode the sRGB bytes.
pub const VIEW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

#[derive(Debug)]
pub struct Presenter {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    size: wgpu::Buffer,
    texture: wgpu::Texture,
    /// The sRGB view to display: sampling decodes to linear.
    pub view: wgpu::TextureView,
    /// The same sRGB bytes in a plain `Rgba8Unorm` view, for renderers that blend in gamma
    /// space and expect gamma-encoded textures (egui-wgpu's native textures).
    pub gamma_view: wgpu::TextureView,
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
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("glint display"),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: STORAGE_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[VIEW_FORMAT],
        });
        // The sRGB view is for sampling only: sRGB formats cannot be storage-bound, so the view
        // must not inherit the texture's STORAGE_BINDING usage (wgpu rejects it otherwise).
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(VIEW_FORMAT),
            usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
            ..Default::default()
        });
        let gamma_view = texture.create_view(&wgpu::TextureViewDescriptor {
            format: Some(STORAGE_FORMAT),
            usage: Some(wgpu::TextureUsages::TEXTURE_BINDING),
            ..Default::default()
        });
        let size = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("glint present size"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&size, 0, bytemuck::cast_slice(&[width, height, 0, 0]));
        Self { pipeline, layout, size, texture, view, gamma_view, width, height }
    }

    /// Encodes `radiance` (the tracer's output buffer, same size) into the texture.
    pub fn present(&self, ctx: &GpuContext, radiance: &wgpu::Buffer) {
        let storage_view = self.texture.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint present"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: radiance.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&storage_view) },
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
