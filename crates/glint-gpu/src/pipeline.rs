//! Compute pipelines for shader variants, with bind group layouts reflected from the
//! composed module (so a binding removed by specialisation is not declared either).

use std::borrow::Cow;
use std::time::{Duration, Instant};

use crate::binding::Binding;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::shaders::{
    ModuleStats, PATH_WGSL, ShaderKey, TRACE_WGSL, compose_entry, module_stats, undecorated, validate,
};

#[derive(Debug)]
pub struct TracerPipeline {
    pub key: ShaderKey,
    pub pipeline: wgpu::ComputePipeline,
    /// The kernel that starts the paths, in the path tracer's module (its entry point `start`;
    /// `pipeline` is then the bounce).
    pub start: Option<wgpu::ComputePipeline>,
    pub bind_group_layout: wgpu::BindGroupLayout,
    /// The bindings the module uses, ascending.
    pub bindings: Vec<Binding>,
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

/// The bindings `module` declares, ascending, each with its buffer type; a binding that is not
/// in the table is an error naming it.
pub fn reflect_bindings(module: &naga::Module) -> Result<Vec<(Binding, wgpu::BufferBindingType)>, GpuError> {
    let mut bindings = Vec::new();
    for (_, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        let name = var.name.as_deref().map_or("(unnamed)", undecorated);
        let binding = Binding::of_global(rb.group, rb.binding, name)?;
        let ty = match var.space {
            naga::AddressSpace::Uniform => wgpu::BufferBindingType::Uniform,
            naga::AddressSpace::Storage { access } => {
                wgpu::BufferBindingType::Storage { read_only: !access.contains(naga::StorageAccess::STORE) }
            }
            other => return Err(GpuError::Validation(format!("unexpected address space {other:?} of `{name}`"))),
        };
        bindings.push((binding, ty));
    }
    bindings.sort_by_key(|(b, _)| b.number());
    Ok(bindings)
}

/// The tracer's pipeline for `key`: Whitted's (trace.wgsl) or the path tracer's (path.wgsl).
pub fn create_pipeline(ctx: &GpuContext, key: ShaderKey) -> Result<TracerPipeline, GpuError> {
    if key.path {
        create_entry_pipeline(ctx, key, PATH_WGSL, "path tracer")
    } else {
        create_entry_pipeline(ctx, key, TRACE_WGSL, "tracer")
    }
}

/// The pipeline of the entry module `entry` (trace.wgsl, raycast.wgsl) composed for `key`;
/// `what` names it in labels and logs.
pub fn create_entry_pipeline(
    ctx: &GpuContext,
    key: ShaderKey,
    entry: &str,
    what: &str,
) -> Result<TracerPipeline, GpuError> {
    let start = Instant::now();
    let module = compose_entry(&key, entry)?;
    validate(&module)?;
    let stats = module_stats(&module);
    let bindings = reflect_bindings(&module)?;
    let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
        .iter()
        .map(|&(binding, ty)| wgpu::BindGroupLayoutEntry {
            binding: binding.number(),
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
            count: None,
        })
        .collect();
    let bindings = bindings.into_iter().map(|(binding, _)| binding).collect();
    let label = format!("glint {what} [{}]", key.describe());
    let has_start = module.entry_points.iter().any(|e| e.name == "start");
    let (pipeline, start_kernel, bind_group_layout) = with_error_scopes(ctx, || {
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
        let entry = |name: &str| {
            ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&label),
                layout: Some(&layout),
                module: &shader,
                entry_point: Some(name),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        (entry("main"), has_start.then(|| entry("start")), bind_group_layout)
    })?;
    let create_time = start.elapsed();
    log::info!("created {label} in {:.1} ms ({} statements)", create_time.as_secs_f64() * 1e3, stats.statements);
    Ok(TracerPipeline { key, pipeline, start: start_kernel, bind_group_layout, bindings, stats, create_time })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders::compose;

    #[test]
    fn every_binding_of_the_full_probe_shader_is_in_the_table() {
        let module = compose(&ShaderKey { probe: true, ..ShaderKey::full() }).expect("full probe shader composes");
        let found: Vec<Binding> =
            reflect_bindings(&module).expect("known bindings").into_iter().map(|(b, _)| b).collect();
        let tracer: Vec<Binding> = Binding::ALL.into_iter().filter(|b| b.is_tracers()).collect();
        assert_eq!(found, tracer, "the full probe shader uses every binding but the ray-cast kernel's");
    }

    #[test]
    fn an_unknown_binding_in_a_composed_module_is_an_error_naming_it() {
        // An entry module using a binding of bindings.wgsl and one of its own.
        let entry = "#import glint::bindings::header\n\
            @group(0) @binding(42) var<storage, read_write> bogus: array<u32>;\n\
            @compute @workgroup_size(1)\nfn main() {\n    bogus[0] = header.width;\n}\n";
        let module = compose_entry(&ShaderKey::full(), entry).expect("the entry module composes");
        match reflect_bindings(&module) {
            Err(GpuError::UnknownBinding { group: 0, binding: 42, name }) => assert_eq!(name, "bogus"),
            other => panic!("expected the unknown binding `bogus` to be an error, got {other:?}"),
        }
    }
}
