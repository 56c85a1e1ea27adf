//! Uploading a flat scene, dispatching the tracer tile by tile, and reading the image back.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use bytemuck::Pod;
use glint_core::FlatScene;
use glint_core::HdrImage;
use glint_core::cpu::RayCounts;
use glint_core::glam::dvec3;
use glint_core::layout::{
    NO_HIT, ProbeRecord, STAT_BAILOUT_SAVED, STAT_CAMERA, STAT_REFLECTION, STAT_REFRACTION, STAT_SHADOW, STAT_STATUS,
    STAT_WORDS, TileParams,
};
use wgpu::util::DeviceExt;

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::binding::Binding;
use crate::pipeline::{TracerPipeline, create_pipeline, with_error_scopes};
use crate::shaders::{GPU_PRIMITIVE_LIMIT, ShaderKey};

/// Tile edge in pixels: one submission renders at most this square, so no single submission
/// runs long enough to trip a desktop GPU's watchdog.
pub const DEFAULT_TILE: u32 = 256;
const WORKGROUP: u32 = 8;

#[derive(Clone, Copy, Debug)]
pub struct GpuOptions {
    /// Compile only the features the scene needs (default); off, the full shader runs.
    pub specialise: bool,
    pub tile: u32,
}

impl Default for GpuOptions {
    fn default() -> Self {
        Self { specialise: true, tile: DEFAULT_TILE }
    }
}

#[derive(Clone, Debug)]
pub struct GpuRender {
    pub image: HdrImage,
    pub counts: RayCounts,
    /// `STATUS_*` bits the shader raised (0 when every bound held).
    pub status: u32,
    /// From the first submission until the GPU finished the last tile.
    pub render_time: Duration,
    /// Buffer creation and upload.
    pub upload_time: Duration,
    /// Pipeline creation; zero when the variant came from the cache.
    pub pipeline_time: Duration,
    /// Copying the image back to the host.
    pub readback_time: Duration,
    pub key: ShaderKey,
    pub statements: usize,
}

/// The scene's buffers on the GPU.
#[derive(Debug)]
pub struct SceneBuffers {
    header: wgpu::Buffer,
    camera: wgpu::Buffer,
    tile: wgpu::Buffer,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    spheres: wgpu::Buffer,
    planes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    pub output: wgpu::Buffer,
    pub stats: wgpu::Buffer,
    pub probe: wgpu::Buffer,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
}

/// The GPU tracer: a device and a cache of compiled shader variants.
#[derive(Debug)]
pub struct GpuTracer {
    ctx: GpuContext,
    cache: Mutex<HashMap<ShaderKey, Arc<TracerPipeline>>>,
}

fn storage<T: Pod>(ctx: &GpuContext, label: &str, items: &[T], zero: T) -> wgpu::Buffer {
    // Storage buffers may not be empty: an absent kind gets one unused element.
    let one = [zero];
    let data = if items.is_empty() { &one[..] } else { items };
    ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::cast_slice(data),
        usage: wgpu::BufferUsages::STORAGE,
    })
}

fn uniform<T: Pod>(ctx: &GpuContext, label: &str, value: &T) -> wgpu::Buffer {
    ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::bytes_of(value),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    })
}

impl SceneBuffers {
    /// Checks the scene (every float finite) and the device limits, then uploads it.
    pub fn upload(ctx: &GpuContext, scene: &FlatScene) -> Result<Self, GpuError> {
        if let Some(field) = scene.first_non_finite() {
            return Err(GpuError::NonFinite { field });
        }
        let h = &scene.header;
        for (what, count) in [("spheres", h.sphere_count), ("planes", h.plane_count), ("triangles", h.triangle_count)] {
            if count > GPU_PRIMITIVE_LIMIT {
                return Err(GpuError::TooManyPrimitives { what, count, limit: GPU_PRIMITIVE_LIMIT });
            }
        }
        let output_size = scene.pixel_count() as u64 * 16;
        let limits = &ctx.limits;
        let check = |what: &str, needed: u64| -> Result<(), GpuError> {
            let binding_limit = limits.max_storage_buffer_binding_size;
            if needed > binding_limit {
                return Err(GpuError::TooLarge {
                    what: what.into(),
                    needed,
                    limit: binding_limit,
                    limit_name: "max_storage_buffer_binding_size",
                });
            }
            if needed > limits.max_buffer_size {
                return Err(GpuError::TooLarge {
                    what: what.into(),
                    needed,
                    limit: limits.max_buffer_size,
                    limit_name: "max_buffer_size",
                });
            }
            Ok(())
        };
        check(&format!("the {}x{} output image", h.width, h.height), output_size)?;
        check("the triangle buffer", size_of_val(scene.triangles.as_slice()) as u64)?;
        with_error_scopes(ctx, || Self {
            header: uniform(ctx, "glint header", &scene.header),
            camera: uniform(ctx, "glint camera", &scene.camera),
            tile: uniform(ctx, "glint tile", &TileParams::pixel(0, 0)),
            materials: storage(ctx, "glint materials", &scene.materials, bytemuck::Zeroable::zeroed()),
            lights: storage(ctx, "glint lights", &scene.lights, bytemuck::Zeroable::zeroed()),
            spheres: storage(ctx, "glint spheres", &scene.spheres, bytemuck::Zeroable::zeroed()),
            planes: storage(ctx, "glint planes", &scene.planes, bytemuck::Zeroable::zeroed()),
            triangles: storage(ctx, "glint triangles", &scene.triangles, bytemuck::Zeroable::zeroed()),
            output: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint output"),
                size: output_size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            stats: ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("glint stats"),
                contents: bytemuck::cast_slice(&[0u32; STAT_WORDS as usize]),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            }),
            probe: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint probe"),
                size: size_of::<ProbeRecord>() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            width: h.width,
            height: h.height,
            spp: h.spp.max(1),
        })
    }

    /// The bind group for `pipeline`, with exactly the bindings its module declares.
    pub fn bind_group(&self, ctx: &GpuContext, pipeline: &TracerPipeline) -> wgpu::BindGroup {
        let buffer = |b: Binding| match b {
            Binding::Header => &self.header,
            Binding::Camera => &self.camera,
            Binding::Tile => &self.tile,
            Binding::Materials => &self.materials,
            Binding::Lights => &self.lights,
            Binding::Spheres => &self.spheres,
            Binding::Planes => &self.planes,
            Binding::Triangles => &self.triangles,
            Binding::Output => &self.output,
            Binding::Stats => &self.stats,
            Binding::Probe => &self.probe,
        };
        let entries: Vec<wgpu::BindGroupEntry> = pipeline
            .bindings
            .iter()
            .map(|&b| wgpu::BindGroupEntry { binding: b.number(), resource: buffer(b).as_entire_binding() })
            .collect();
        ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint scene"),
            layout: &pipeline.bind_group_layout,
            entries: &entries,
        })
    }

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

    /// Renders one pixel and clears the statistics again (see `GpuTracer::render`).
    pub fn prime(&self, ctx: &GpuContext, pipeline: &TracerPipeline, bind_group: &wgpu::BindGroup) {
        self.dispatch_tile(ctx, pipeline, bind_group, TileParams::pixel(0, 0));
        ctx.queue.write_buffer(&self.stats, 0, bytemuck::cast_slice(&[0u32; STAT_WORDS as usize]));
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

/// Copies `source` to the host, waiting for it.
pub fn read_buffer(ctx: &GpuContext, source: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let copy = PendingCopy::start(ctx, source);
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Readback(e.to_string()))?;
        if ctx.is_lost() {
            return Err(GpuError::DeviceLost);
        }
        if let Some(result) = copy.try_take() {
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

/// A render submitted to the GPU: its buffers stay alive until it is read back or dropped.
#[derive(Debug)]
pub struct GpuJob {
    pub buffers: SceneBuffers,
    pub key: ShaderKey,
    pub statements: usize,
    pub pipeline_time: Duration,
    pub upload_time: Duration,
    submitted: Instant,
    done: Arc<Mutex<Option<Instant>>>,
}

impl GpuJob {
    /// GPU time from submission to completion, once the GPU has finished.
    pub fn gpu_time(&self) -> Option<Duration> {
        self.done.lock().unwrap_or_else(|e| e.into_inner()).map(|t| t.duration_since(self.submitted))
    }

    /// Starts copying the image and the statistics to the host.
    pub fn start_readback(&self, ctx: &GpuContext) -> JobReadback {
        JobReadback {
            image: PendingCopy::start(ctx, &self.buffers.output),
            stats: PendingCopy::start(ctx, &self.buffers.stats),
            width: self.buffers.width,
            height: self.buffers.height,
            image_bytes: None,
        }
    }
}

/// The image and statistics of a job, arriving without blocking the caller.
#[derive(Debug)]
pub struct JobReadback {
    image: PendingCopy,
    stats: PendingCopy,
    width: u32,
    height: u32,
    image_bytes: Option<Vec<u8>>,
}

/// A finished readback: image, ray counts and the status word.
pub type ReadbackResult = (HdrImage, RayCounts, u32);

impl JobReadback {
    /// Polls the device once; returns the result when both copies have landed.
    pub fn poll(&mut self, ctx: &GpuContext) -> Option<Result<ReadbackResult, GpuError>> {
        if let Err(e) = ctx.device.poll(wgpu::PollType::Poll) {
            return Some(Err(GpuError::Wgpu(e.to_string())));
        }
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

impl GpuTracer {
    pub fn new(ctx: GpuContext) -> Self {
        Self { ctx, cache: Mutex::new(HashMap::new()) }
    }

    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// The pipeline for `key`, from the cache or newly created (then with its creation time).
    pub fn pipeline(&self, key: ShaderKey) -> Result<(Arc<TracerPipeline>, Duration), GpuError> {
        if let Some(p) = self.cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            return Ok((p.clone(), Duration::ZERO));
        }
        let p = Arc::new(create_pipeline(&self.ctx, key)?);
        let time = p.create_time;
        self.cache.lock().unwrap_or_else(|e| e.into_inner()).insert(key, p.clone());
        Ok((p, time))
    }

    /// Uploads `scene` and dispatches every tile without waiting for the GPU. Unspecialised,
    /// the full shader runs on the same buffers: it reads no feature bits from the scene.
    pub fn submit(&self, scene: &FlatScene, options: &GpuOptions) -> Result<GpuJob, GpuError> {
        let groups = options.tile.max(WORKGROUP).div_ceil(WORKGROUP);
        let group_limit = self.ctx.limits.max_compute_workgroups_per_dimension;
        if groups > group_limit {
            return Err(GpuError::TileTooLarge { tile: options.tile, groups, limit: group_limit });
        }
        let key = ShaderKey::for_scene(scene, options.specialise);
        let (pipeline, mut pipeline_time) = self.pipeline(key)?;
        let upload_start = Instant::now();
        let buffers = SceneBuffers::upload(&self.ctx, scene)?;
        let bind_group = with_error_scopes(&self.ctx, || buffers.bind_group(&self.ctx, &pipeline))?;
        let upload_time = upload_start.elapsed();
        if !pipeline_time.is_zero() {
            // Drivers such as lavapipe compile the shader at its first dispatch: run one pixel
            // so that the compilation counts as pipeline creation, not as render time.
            let prime_start = Instant::now();
            with_error_scopes(&self.ctx, || buffers.prime(&self.ctx, &pipeline, &bind_group))?;
            self.ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Wgpu(e.to_string()))?;
            pipeline_time += prime_start.elapsed();
        }
        let submitted = Instant::now();
        with_error_scopes(&self.ctx, || buffers.dispatch(&self.ctx, &pipeline, &bind_group, options.tile))?;
        let done = Arc::new(Mutex::new(None));
        let slot = done.clone();
        self.ctx.queue.on_submitted_work_done(move || {
            *slot.lock().unwrap_or_else(|e| e.into_inner()) = Some(Instant::now());
        });
        Ok(GpuJob { buffers, key, statements: pipeline.stats.statements, pipeline_time, upload_time, submitted, done })
    }

    /// The breakdown of the first sample of pixel (x, y) into the terms of the model, computed
    /// by the probe variant of the same shader (the GPU twin of `glint_core::probe_pixel`).
    pub fn probe_pixel(&self, scene: &FlatScene, x: u32, y: u32) -> Result<(ProbeRecord, u32), GpuError> {
        let key = ShaderKey { probe: true, ..ShaderKey::for_scene(scene, true) };
        let (pipeline, _) = self.pipeline(key)?;
        // The scene's own spp: sample 0 is then jittered in its stratum exactly as the CPU's.
        let buffers = SceneBuffers::upload(&self.ctx, scene)?;
        let bind_group = with_error_scopes(&self.ctx, || buffers.bind_group(&self.ctx, &pipeline))?;
        with_error_scopes(&self.ctx, || buffers.dispatch_probe(&self.ctx, &pipeline, &bind_group, x, y))?;
        let bytes = read_buffer(&self.ctx, &buffers.probe)?;
        let stats = read_buffer(&self.ctx, &buffers.stats)?;
        Ok((bytemuck::pod_read_unaligned(&bytes), decode_stats(&stats).1))
    }

    /// Renders `scene` and reads the image back, waiting for both.
    pub fn render(&self, scene: &FlatScene, options: &GpuOptions) -> Result<GpuRender, GpuError> {
        let job = self.submit(scene, options)?;
        self.ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Wgpu(e.to_string()))?;
        if self.ctx.is_lost() {
            return Err(GpuError::DeviceLost);
        }
        let render_time = job.submitted.elapsed();
        let readback_start = Instant::now();
        let pixels = read_buffer(&self.ctx, &job.buffers.output)?;
        let stats = read_buffer(&self.ctx, &job.buffers.stats)?;
        let readback_time = readback_start.elapsed();
        let image = decode_output(job.buffers.width, job.buffers.height, &pixels);
        let (counts, status) = decode_stats(&stats);
        Ok(GpuRender {
            image,
            counts,
            status,
            render_time,
            upload_time: job.upload_time,
            pipeline_time: job.pipeline_time,
            readback_time,
            key: job.key,
            statements: job.statements,
        })
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

pub fn decode_stats(bytes: &[u8]) -> (RayCounts, u32) {
    let words: &[u32] = bytemuck::cast_slice(bytes);
    let pair = |i: u32| u64::from(words[i as usize]) | (u64::from(words[i as usize + 1]) << 32);
    let counts = RayCounts {
        camera: pair(STAT_CAMERA),
        shadow: pair(STAT_SHADOW),
        reflection: pair(STAT_REFLECTION),
        refraction: pair(STAT_REFRACTION),
        bailout_saved: pair(STAT_BAILOUT_SAVED),
    };
    (counts, words[STAT_STATUS as usize])
}
