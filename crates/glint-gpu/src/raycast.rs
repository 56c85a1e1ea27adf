//! The ray-cast kernel (`shaders/raycast.wgsl`): the closest hit of every ray of a buffer
//! through the scene's BVH, with the tracer's own WGSL `closest_hit`, for `glint bench rays`
//! and the CPU/GPU hit comparison. No shading, no image.

use std::time::{Duration, Instant};

use glint_core::FlatScene;
use glint_core::cpu::raycast::{HitRecord, RayRecord};
use glint_types::layout::feature;
use wgpu::util::DeviceExt;

use crate::binding::Binding;
use crate::buffers::{GeometryCache, SceneBuffers, ZERO_STATS};
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::pipeline::{TracerPipeline, create_entry_pipeline, with_error_scopes};
use crate::readback::{decode_stats, read_buffer};
use crate::shaders::{RAYCAST_WGSL, ShaderKey, bvh_stack_size};
use crate::status::{StatusContext, messages};

/// Invocations per workgroup (`@workgroup_size(64, 1, 1)` of raycast.wgsl).
pub const WORKGROUP: u32 = 64;

/// A scene uploaded for ray casting, with the kernel compiled for its primitive kinds.
#[derive(Debug)]
pub struct RayCaster {
    pipeline: TracerPipeline,
    scene: SceneBuffers,
}

/// A buffer of rays on the GPU and the buffer their hits go to.
#[derive(Debug)]
pub struct RayBatch {
    hits: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    pub count: u32,
}

/// The shader variant: only the primitive kinds select code in `closest_hit`; the BVH always.
pub fn raycast_key(scene: &FlatScene) -> ShaderKey {
    let kinds = feature::SPHERES | feature::PLANES | feature::TRIANGLES;
    ShaderKey {
        features: scene.header.features & kinds,
        stack_size: 1,
        probe: false,
        bvh: true,
        bvh_stack: bvh_stack_size(scene),
        path: false,
        tree_nodes: crate::shaders::MAX_TREE_NODES,
    }
}

impl RayCaster {
    /// Compiles the kernel for `scene` and uploads the scene (its BVH included) as stored: the
    /// rays it casts are records in the scene's stored coordinates (`glint_core::rays`; world
    /// space for a scene around the world origin, `SceneHeader::frame`), and the hits compared
    /// with the CPU's. Unlike the tracer it is not rebased on a camera (it has none).
    pub fn new(ctx: &GpuContext, scene: &FlatScene) -> Result<Self, GpuError> {
        let pipeline = create_entry_pipeline(ctx, raycast_key(scene), RAYCAST_WGSL, "ray cast")?;
        // A cache of its own: the kernel runs on one scene.
        let scene = SceneBuffers::upload(ctx, scene, raycast_key(scene), &GeometryCache::default())?;
        Ok(Self { pipeline, scene })
    }

    /// Uploads `rays` and makes room for their hits.
    pub fn upload(&self, ctx: &GpuContext, rays: &[RayRecord]) -> Result<RayBatch, GpuError> {
        let count = u32::try_from(rays.len()).map_err(|_| GpuError::TooLarge {
            what: format!("{} rays", rays.len()),
            needed: rays.len() as u64,
            limit: u64::from(u32::MAX),
            limit_name: "u32 ray index",
        })?;
        let hits_size = (rays.len().max(1) * size_of::<HitRecord>()) as u64;
        for (what, needed) in [("the ray buffer", size_of_val(rays) as u64), ("the hit buffer", hits_size)] {
            if needed > ctx.limits.max_storage_buffer_binding_size {
                return Err(GpuError::TooLarge {
                    what: what.into(),
                    needed,
                    limit: ctx.limits.max_storage_buffer_binding_size,
                    limit_name: "max_storage_buffer_binding_size",
                });
            }
        }
        with_error_scopes(ctx, || {
            let one = [RayRecord::default()];
            let rays_buffer = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("glint rays"),
                contents: bytemuck::cast_slice(if rays.is_empty() { &one[..] } else { rays }),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let hits = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint hits"),
                size: hits_size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let bind_group = self.scene.bind_group_with(
                ctx,
                &self.pipeline,
                &[(Binding::RaysIn, &rays_buffer), (Binding::HitsOut, &hits)],
            )?;
            Ok(RayBatch { hits, bind_group, count })
        })?
    }

    /// Casts every ray of `batch` and waits until the GPU has finished: the time from the
    /// submission until the queue is done (the upload is not in it). A status bit the kernel
    /// raised (BVH stack overflow, lavapipe's loop cut-off) is an error.
    pub fn cast(&self, ctx: &GpuContext, batch: &RayBatch) -> Result<Duration, GpuError> {
        let groups = batch.count.div_ceil(WORKGROUP).max(1);
        let limit = ctx.limits.max_compute_workgroups_per_dimension;
        let (x, y) = (groups.min(limit), groups.div_ceil(limit));
        ctx.queue.write_buffer(&self.scene.stats, 0, bytemuck::cast_slice(&ZERO_STATS));
        // Everything before (stats reset, uploads) is finished before the clock starts.
        wait_idle(ctx)?;
        let start = Instant::now();
        with_error_scopes(ctx, || {
            let mut encoder =
                ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("glint ray cast") });
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("glint ray cast"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline.pipeline);
                pass.set_bind_group(0, &batch.bind_group, &[]);
                pass.dispatch_workgroups(x, y, 1);
            }
            ctx.queue.submit([encoder.finish()]);
        })?;
        wait_idle(ctx)?;
        let elapsed = start.elapsed();
        if ctx.is_lost() {
            return Err(GpuError::DeviceLost);
        }
        let (_, status) = decode_stats(&read_buffer(ctx, &self.scene.stats)?);
        if status != 0 {
            return Err(GpuError::RaycastStatus {
                status,
                messages: messages(status, &StatusContext::CAMERA_RAYS).join("; "),
            });
        }
        Ok(elapsed)
    }

    /// The hits of the last `cast` of `batch`, in ray order.
    pub fn hits(&self, ctx: &GpuContext, batch: &RayBatch) -> Result<Vec<HitRecord>, GpuError> {
        let bytes = read_buffer(ctx, &batch.hits)?;
        let hits: &[HitRecord] = bytemuck::cast_slice(&bytes);
        Ok(hits[..batch.count as usize].to_vec())
    }

    /// The compiled kernel (its creation time, variant and size).
    pub fn pipeline(&self) -> &TracerPipeline {
        &self.pipeline
    }
}

fn wait_idle(ctx: &GpuContext) -> Result<(), GpuError> {
    ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Wgpu(e.to_string()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shaders::{compose_entry, validate};

    #[test]
    fn kernel_composes_for_every_primitive_mix_and_binds_the_ray_buffers() {
        // Every mix of primitive kinds `raycast_key` can give (the other features it masks off).
        let kinds = [feature::SPHERES, feature::PLANES, feature::TRIANGLES];
        for mix in 1..8u32 {
            let features = (0..3).filter(|k| mix & (1 << k) != 0).fold(0, |f, k| f | kinds[k]);
            let key = ShaderKey { features, stack_size: 1, bvh_stack: 16, ..ShaderKey::full() };
            let module = compose_entry(&key, RAYCAST_WGSL).expect("raycast.wgsl composes");
            validate(&module).unwrap_or_else(|e| panic!("[{}]: {e}", key.describe()));
            let main = module.entry_points.iter().find(|e| e.name == "main").expect("entry point main");
            assert_eq!(main.workgroup_size, [WORKGROUP, 1, 1]);
            let bindings: Vec<Binding> = crate::pipeline::reflect_bindings(&module)
                .expect("known bindings")
                .into_iter()
                .map(|(b, _)| b)
                .collect();
            for b in Binding::RAYCAST.into_iter().chain([Binding::BvhNodes, Binding::BvhLeafAb, Binding::Stats]) {
                assert!(bindings.contains(&b), "[{}] lacks {b:?}: {bindings:?}", key.describe());
            }
            // A triangle's third corner only where there are triangles.
            let triangles = features & feature::TRIANGLES != 0;
            assert_eq!(bindings.contains(&Binding::BvhLeafC), triangles, "[{}]: {bindings:?}", key.describe());
            // No shading: the kernel reads no materials, lights or camera.
            for b in [Binding::Materials, Binding::Lights, Binding::Camera, Binding::Output] {
                assert!(!bindings.contains(&b), "[{}] binds {b:?}", key.describe());
            }
        }
    }
}
