//! Compute pipelines for shader variants, with bind group layouts reflected from the
//! composed module (so a binding removed by specialisation is not declared either).

use std::borrow::Cow;
use std::time::{Duration, Instant};

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::shaders::{ModuleStats, ShaderKey, compose, module_stats, validate};

/// Binding numbers of `shaders/bindings.wgsl`.
pub mod binding {
    pub const HEADER: u32 = 0;
    pub const CAMERA: u32 = 1;
    pub const TILE: u32 = 2;
    pub const MATERIALS: u32 = 3;
    pub const LIGHTS: u32 = 4;
    pub const SPHERES: u32 = 5;
    pub const PLANES: u32 = 6;
    pub const TRIANGLES: u32 = 7;
    pub const OUTPUT: u32 = 8;
    pub const STATS: u32 = 9;
    pub const PROBE: u32 = 10;
}

#[derive(Debug)]
pub struct TracerPipeline {
    pub key: ShaderKey,
    pub pipeline: wgpu::ComputePipeline,
    pub bind_group_layout: wgpu::BindGroupLayout,
    /// The bindings the module uses, ascending.
    pub bindings: Vec<u32>,
    pub stats: ModuleStats,
    /// Composition, validation and pipeline creation.
    pub create_time: Duration,
}

/// Runs `f` inside validation and out-of-memory error scopes and turns what they caught into
/// a `GpuError`.
pub(crate) fn with_error_scopes<T>(ctx: &GpuContext, f: impl FnOnce() -> T) -> Result<T, GpuError> {
    let validation = ctx.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let oom = ctx.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let value = f();
    let oom_error = pollster::block_on(oom.pop());
    let validation_error = pollster::block_on(validation.pop());
    if ctx.is_lost() {
        return Err(GpuError::DeviceLost);
    }
    if let Some(e) = oom_error {
        return Err(GpuError::OutOfMemory(e.to_string()));
    }
    if let Some(e) = validation_error {
        return Err(GpuError::Wgpu(e.to_string()));
    }
    Ok(value)
}

pub fn create_pipeline(ctx: &GpuContext, key: ShaderKey) -> Result<TracerPipeline, GpuError> {
    let start = Instant::now();
    let module = compose(&key)?;
    validate(&module)?;
    let stats = module_stats(&module);
    let mut entries = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let ty = match var.space {
            naga::AddressSpace::Uniform => wgpu::BufferBindingType::Uniform,
            naga::AddressSpace::Storage { access } => {
                wgpu::BufferBindingType::Storage { read_only: !access.contains(naga::StorageAccess::STORE) }
            }
            other => return Err(GpuError::Validation(format!("unexpected address space {other:?} of a binding"))),
        };
        entries.push(wgpu::BindGroupLayoutEntry {
            binding: rb.binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        });
    }
    entries.sort_by_key(|e| e.binding);
    let bindings = entries.iter().map(|e| e.binding).collect();
    let label = format!("glint tracer [{}]", key.describe());
    let (pipeline, bind_group_layout) = with_error_scopes(ctx, || {
        let shader = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&label),
            source: wgpu::ShaderSource::Naga(Cow::Owned(module)),
        });
        let bind_group_layout = ctx
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(&label), entries: &entries });
        let layout = ctx.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(&label),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(&label),
            layout: Some(&layout),
            module: &shader,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        (pipeline, bind_group_layout)
    })?;
    let create_time = start.elapsed();
    log::info!("created {label} in {:.1} ms ({} statements)", create_time.as_secs_f64() * 1e3, stats.statements);
    Ok(TracerPipeline { key, pipeline, bind_group_layout, bindings, stats, create_time })
}
