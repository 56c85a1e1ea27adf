//! The limits the viewer's wgpu device is opened with.

use std::sync::Arc;

use egui_wgpu::WgpuSetup;

/// `setup` with a device that binds as many storage buffers, and buffers as large, as the
/// adapter allows: egui asks for wgpu's defaults (8 storage buffers per stage, 128 MiB
/// bindings), and the tracer's BVH and mesh variants need more than 8 buffers and big scenes
/// larger bindings; and textures as large as it allows, since a render may be 16384 a side
/// (egui asks for 8192). Everything else egui asks for is kept.
pub fn with_tracer_limits(setup: WgpuSetup) -> WgpuSetup {
    match setup {
        WgpuSetup::CreateNew(mut new) => {
            let base = new.device_descriptor.clone();
            new.device_descriptor = Arc::new(move |adapter| {
                let mut descriptor = base(adapter);
                let available = adapter.limits();
                let limits = &mut descriptor.required_limits;
                limits.max_storage_buffers_per_shader_stage = available.max_storage_buffers_per_shader_stage;
                limits.max_storage_buffer_binding_size = available.max_storage_buffer_binding_size;
                limits.max_buffer_size = available.max_buffer_size;
                limits.max_texture_dimension_2d = available.max_texture_dimension_2d;
                descriptor
            });
            WgpuSetup::CreateNew(new)
        }
        // A device made elsewhere comes with its own limits.
        existing @ WgpuSetup::Existing(_) => existing,
    }
}
