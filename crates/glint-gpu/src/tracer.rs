//! The GPU tracer: a device and a cache of compiled shader variants; renders a flat scene by
//! uploading it, dispatching it tile by tile and reading the image back.

use std::borrow::Cow;
use std::collections::HashMap;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glint_core::HdrImage;
use glint_core::cpu::RayCounts;
use glint_core::cpu::ray_tree::RayTree;
use glint_core::cpu::shade::Breakdown;
use glint_core::flat::GeometryId;
use glint_core::rebase::{Frame, rebased, rebased_with_geometry};
use glint_core::{Accel, FlatScene, PixelRect};
use glint_types::layout::{PROBE_HIT, ProbeRecord};

use crate::buffers::{GeometryCache, SceneBuffers};
use crate::context::GpuContext;
use crate::dispatch::{DEFAULT_TILE, DispatchControl, check_tile};
use crate::error::GpuError;
use crate::job::GpuJob;
use crate::pipeline::{TracerPipeline, create_pipeline, with_error_scopes};
use crate::readback::{decode_stats, read_buffer};
use crate::shaders::ShaderKey;

#[derive(Clone, Copy, Debug)]
pub struct GpuOptions {
    /// Compile only the features the scene needs (default); off, the full shader runs.
    pub specialise: bool,
    pub tile: u32,
    /// How rays find primitives: through the BVH (default) or by testing every one, as the
    /// CPU's `CpuOptions::accel`.
    pub accel: Accel,
    /// Where the coordinates the GPU computes in have their origin: near the camera (default) or
    /// world space (`glint_core::rebase`).
    pub frame: Frame,
    /// The pixels to render (the whole image by default); `render` gives back an image of
    /// this rectangle only, as `glint_core::render_cpu_region` does.
    pub region: Option<PixelRect>,
    /// The most nodes a sample's ray-tree walk visits before it stops and raises
    /// `STATUS_LOOP_LIMIT` (`MAX_TREE_NODES`, below lavapipe's loop budget, by default). A
    /// smaller one lets a test reach the bound on lavapipe, whose budget cuts a larger walk first.
    pub tree_nodes: u32,
}

impl Default for GpuOptions {
    fn default() -> Self {
        Self {
            specialise: true,
            tile: DEFAULT_TILE,
            accel: Accel::default(),
            frame: Frame::default(),
            region: None,
            tree_nodes: crate::shaders::MAX_TREE_NODES,
        }
    }
}

/// The last geometry rebased: the source's identity, the frame, and the rebased scene whose
/// geometry the next render of the same geometry with the same frame origin reuses (the
/// length scale moves no position) — so that the
/// viewer's camera and light edits (which share their geometry, `FlatScene::rebuild`, and
/// rarely move the frame, `rebase::camera_frame`) neither rebase nor upload a mesh again.
#[derive(Debug, Default)]
struct RebasedCache {
    last: Mutex<Option<(GeometryId, [f32; 4], FlatScene)>>,
}

impl RebasedCache {
    /// `scene` in `frame`: itself when stored in that frame, else rebased, reusing the last
    /// rebased geometry when it is this one's in this frame.
    fn in_frame<'a>(&self, scene: &'a FlatScene, frame: Frame) -> Cow<'a, FlatScene> {
        let Some(frame) = frame.rebased_into(scene) else {
            return Cow::Borrowed(scene);
        };
        let id = scene.geometry_id();
        let mut last = self.last.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, _, geometry)) = last.as_ref().filter(|(i, f, _)| *i == id && f[..3] == frame[..3]) {
            return Cow::Owned(rebased_with_geometry(scene, frame, geometry));
        }
        // Dropped first: two rebased copies of a large geometry need not be alive at once.
        *last = None;
        let start = Instant::now();
        let r = rebased(scene, frame);
        log::debug!("geometry rebased to the frame {frame:?} in {:.1} ms", start.elapsed().as_secs_f64() * 1e3);
        *last = Some((id, frame, r.clone()));
        Cow::Owned(r)
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

/// What the probe variant records for one pixel's first sample.
#[derive(Clone, Debug)]
pub struct PixelProbe {
    /// The breakdown of the first hit (`probe::breakdown`), its point in world space in f64 as
    /// the CPU's probe reports it: rounded to f32 in the frame the GPU traced in, a point 5e6
    /// from the world origin would be off by 1/4.
    pub breakdown: Breakdown,
    /// The whole ray tree, in the CPU's node order.
    pub tree: RayTree,
    /// The status word (`status::describe` turns it into messages).
    pub status: u32,
}

/// The GPU tracer: a device and a cache of compiled shader variants.
#[derive(Debug)]
pub struct GpuTracer {
    ctx: GpuContext,
    cache: Mutex<HashMap<ShaderKey, Arc<TracerPipeline>>>,
    geometry: GeometryCache,
    rebased: RebasedCache,
}

/// Waits until the GPU has finished all submitted work.
fn wait_idle(ctx: &GpuContext) -> Result<(), GpuError> {
    ctx.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| GpuError::Wgpu(e.to_string()))?;
    Ok(())
}

impl GpuTracer {
    pub fn new(ctx: GpuContext) -> Self {
        Self {
            ctx,
            cache: Mutex::new(HashMap::new()),
            geometry: GeometryCache::default(),
            rebased: RebasedCache::default(),
        }
    }

    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// How many scene geometries this tracer has uploaded: a scene sharing the last one's
    /// geometry (`FlatScene::rebuild`) reuses its buffers.
    pub fn geometry_uploads(&self) -> u64 {
        self.geometry.uploads()
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

    /// Uploads `scene` and dispatches every tile and sample, returning once the last is
    /// submitted (not finished). Unspecialised, the full shader runs on the same buffers: it
    /// reads no feature bits from the scene.
    pub fn submit(
        &self,
        scene: &FlatScene,
        options: &GpuOptions,
        control: DispatchControl<'_>,
    ) -> Result<GpuJob, GpuError> {
        check_tile(&self.ctx, options.tile)?;
        // Checked before any upload or compilation.
        let region = options.region.unwrap_or(PixelRect::full(scene.header.width, scene.header.height));
        if !region.within(scene.header.width, scene.header.height) {
            return Err(GpuError::Region {
                region: region.to_string(),
                width: scene.header.width,
                height: scene.header.height,
            });
        }
        let key = ShaderKey {
            tree_nodes: options.tree_nodes,
            ..ShaderKey::for_scene(scene, options.specialise).with_accel(scene, options.accel)
        }
        .check_storage_limit(self.ctx.limits.max_storage_buffers_per_shader_stage)?;
        let (pipeline, mut pipeline_time) = self.pipeline(key)?;
        let upload_start = Instant::now();
        let scene = self.rebased.in_frame(scene, options.frame);
        let mut buffers = SceneBuffers::upload(&self.ctx, &scene, key, &self.geometry)?;
        if key.path {
            buffers = buffers.with_paths(&self.ctx, &scene, options.tile.max(crate::dispatch::WORKGROUP))?;
        }
        let bind_group = with_error_scopes(&self.ctx, || buffers.bind_group(&self.ctx, &pipeline))??;
        let upload_time = upload_start.elapsed();
        if !pipeline_time.is_zero() {
            // Drivers such as lavapipe compile the shader at its first dispatch: run one pixel
            // so that the compilation counts as pipeline creation, not as render time.
            let prime_start = Instant::now();
            with_error_scopes(&self.ctx, || buffers.prime(&self.ctx, &pipeline, &bind_group))?;
            wait_idle(&self.ctx)?;
            pipeline_time += prime_start.elapsed();
        }
        let submitted = Instant::now();
        with_error_scopes(&self.ctx, || {
            buffers.dispatch(&self.ctx, &pipeline, &bind_group, options.tile, region, control)
        })??;
        Ok(GpuJob::new(&self.ctx, buffers, &pipeline, pipeline_time, upload_time, submitted))
    }

    /// The breakdown of the first sample of pixel (x, y) into the terms of the model, computed
    /// by the probe variant of the same shader (the GPU twin of `glint_core::probe_pixel`), in
    /// the default frame (near the camera) as `render`, with the status word; the hit point is
    /// given back in world space.
    pub fn probe_pixel(&self, scene: &FlatScene, x: u32, y: u32) -> Result<(Breakdown, u32), GpuError> {
        self.probe(scene, x, y).map(|p| (p.breakdown, p.status))
    }

    /// The probe of pixel (x, y) with its whole ray tree, recorded by the same dispatch of the
    /// probe variant (the GPU twin of `glint_core::probe_tree`).
    pub fn probe(&self, scene: &FlatScene, x: u32, y: u32) -> Result<PixelProbe, GpuError> {
        // The probe records Whitted's terms, whatever the scene's integrator.
        let key = ShaderKey {
            probe: true,
            path: false,
            ..ShaderKey::for_scene(scene, true).with_accel(scene, Accel::default())
        }
        .check_storage_limit(self.ctx.limits.max_storage_buffers_per_shader_stage)?;
        let (pipeline, _) = self.pipeline(key)?;
        // The scene's own spp: sample 0 is then jittered in its stratum exactly as the CPU's.
        let scene = self.rebased.in_frame(scene, Frame::default());
        let buffers = SceneBuffers::upload(&self.ctx, &scene, key, &self.geometry)?;
        let bind_group = with_error_scopes(&self.ctx, || buffers.bind_group(&self.ctx, &pipeline))??;
        with_error_scopes(&self.ctx, || buffers.dispatch_probe(&self.ctx, &pipeline, &bind_group, x, y))?;
        let bytes = read_buffer(&self.ctx, &buffers.probe)?;
        let tree = read_buffer(&self.ctx, &buffers.probe_tree)?;
        let stats = read_buffer(&self.ctx, &buffers.stats)?;
        let record: ProbeRecord = bytemuck::pod_read_unaligned(&bytes);
        let mut tree = crate::probe::ray_tree(&tree)?;
        // Points back in world space (in f64), as the CPU's probe reports them.
        let origin = scene.frame_origin();
        let mut breakdown = crate::probe::breakdown(&record)?;
        if record.flags & PROBE_HIT != 0 {
            breakdown.point = glint_core::cpu::v3(record.point) + origin;
        }
        tree.translate(origin);
        Ok(PixelProbe { breakdown, tree, status: decode_stats(&stats).1 })
    }

    /// Renders `scene` and reads the image back, waiting for both: `submit`, then the job's
    /// readback as the viewer polls it, waited for.
    pub fn render(&self, scene: &FlatScene, options: &GpuOptions) -> Result<GpuRender, GpuError> {
        self.render_with(scene, options, DispatchControl::default())
    }

    /// `render`, followed and stoppable through `control`.
    pub fn render_with(
        &self,
        scene: &FlatScene,
        options: &GpuOptions,
        control: DispatchControl<'_>,
    ) -> Result<GpuRender, GpuError> {
        let job = self.submit(scene, options, control)?;
        wait_idle(&self.ctx)?;
        if self.ctx.is_lost() {
            return Err(GpuError::DeviceLost);
        }
        let render_time = job.submitted.elapsed();
        let readback_start = Instant::now();
        let (image, counts, status) = job.start_readback(&self.ctx).wait(&self.ctx)?;
        let image = match options.region {
            Some(r) => image.cropped(r),
            None => image,
        };
        let readback_time = readback_start.elapsed();
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
