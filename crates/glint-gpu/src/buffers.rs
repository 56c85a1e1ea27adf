//! Uploading a flat scene: the checks that it fits the device, its GPU buffers, and the bind
//! group a pipeline variant needs from them.

use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use bytemuck::Pod;
use glint_core::FlatScene;
use glint_core::bvh::GPU_MAX_TREE_INDEX;
use glint_core::cpu::emitter::Emitters;
use glint_core::flat::{GeometryId, GpuLeafAb, GpuLeafC, fill_gpu_leaves};
use glint_types::layout::{GpuPathState, ProbeRecord, ProbeTree, STAT_WORDS, TileParams};
use wgpu::util::DeviceExt;

use crate::binding::Binding;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::pipeline::{TracerPipeline, with_error_scopes};
use crate::shaders::{GPU_PRIMITIVE_LIMIT, ShaderKey};

/// A scene's geometry on the GPU (primitives and BVH), for the geometry `id` names. The tracer
/// keeps the last one and the next upload of the same geometry reuses it: the viewer's scenes
/// after a camera or light edit share their geometry (`FlatScene::rebuild`), and uploading a
/// million triangles again for every preview cost more than tracing the preview.
#[derive(Clone, Debug)]
pub struct GeometryBuffers {
    id: GeometryId,
    spheres: wgpu::Buffer,
    planes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    bvh_nodes: wgpu::Buffer,
    bvh_leaf: BvhLeafBuffers,
    vertices: wgpu::Buffer,
    normals: wgpu::Buffer,
    meshes: wgpu::Buffer,
    uvs: wgpu::Buffer,
    colours: wgpu::Buffer,
}

/// The last geometry uploaded, shared by the tracer's renders and probes.
#[derive(Debug, Default)]
pub struct GeometryCache {
    last: Mutex<Option<GeometryBuffers>>,
    /// Geometries uploaded so far (what a reuse saves is seen in it).
    uploads: AtomicU64,
}

impl GeometryCache {
    pub fn uploads(&self) -> u64 {
        self.uploads.load(Ordering::Relaxed)
    }
}

/// The BVH leaves' words (`glint_core::flat::fill_gpu_leaves`), written into the mapped
/// buffers a chunk at a time: no host copy of all their 48 bytes a reference.
#[derive(Clone, Debug)]
struct BvhLeafBuffers {
    ab: wgpu::Buffer,
    c: wgpu::Buffer,
}

/// References filled per chunk (3 MiB of words).
const LEAF_CHUNK: usize = 1 << 16;

impl BvhLeafBuffers {
    fn upload(ctx: &GpuContext, scene: &FlatScene) -> Self {
        // Storage buffers may not be empty: a scene without a tree gets one unused reference.
        let refs = scene.bvh_prims.len().max(1);
        let mapped = |label: &str, item_size: usize| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: (refs * item_size) as u64,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: true,
            })
        };
        let ab = mapped("glint BVH leaf corners a, b", size_of::<GpuLeafAb>());
        let c = mapped("glint BVH leaf corners c", size_of::<GpuLeafC>());
        {
            let mut ab_view = ab.get_mapped_range_mut(..).expect("mapped at creation");
            let mut c_view = c.get_mapped_range_mut(..).expect("mapped at creation");
            let mut ab_words = vec![GpuLeafAb::default(); LEAF_CHUNK];
            let mut c_words = vec![GpuLeafC::default(); LEAF_CHUNK];
            for (k, prims) in scene.bvh_prims.chunks(LEAF_CHUNK).enumerate() {
                let (ab_chunk, c_chunk) = (&mut ab_words[..prims.len()], &mut c_words[..prims.len()]);
                fill_gpu_leaves(&scene.vertices, &scene.triangles, prims, ab_chunk, c_chunk);
                let start = k * LEAF_CHUNK;
                let bytes = |item: usize| start * item..(start + prims.len()) * item;
                ab_view.slice(bytes(size_of::<GpuLeafAb>())).copy_from_slice(bytemuck::cast_slice(ab_chunk));
                c_view.slice(bytes(size_of::<GpuLeafC>())).copy_from_slice(bytemuck::cast_slice(c_chunk));
            }
        }
        ab.unmap();
        c.unmap();
        Self { ab, c }
    }
}

impl GeometryBuffers {
    fn upload(ctx: &GpuContext, scene: &FlatScene) -> Self {
        Self {
            id: scene.geometry_id(),
            spheres: storage(ctx, "glint spheres", &scene.spheres),
            planes: storage(ctx, "glint planes", &scene.planes),
            triangles: storage(ctx, "glint triangles", &scene.triangles),
            // check_limits has reported a tree without a GPU form to any variant that binds it.
            bvh_nodes: storage(ctx, "glint BVH nodes", scene.bvh_nodes.gpu().unwrap_or_default()),
            bvh_leaf: BvhLeafBuffers::upload(ctx, scene),
            vertices: storage(ctx, "glint vertices", &scene.vertices),
            normals: storage(ctx, "glint normals", &scene.normals),
            meshes: storage(ctx, "glint meshes", &scene.meshes),
            uvs: storage(ctx, "glint texture coordinates", &scene.uvs),
            colours: storage(ctx, "glint vertex colours", &scene.colours),
        }
    }

    /// The cached buffers when they hold `scene`'s geometry, else a new upload, then cached.
    fn of(ctx: &GpuContext, scene: &FlatScene, cache: &GeometryCache) -> Self {
        let mut cached = cache.last.lock().unwrap_or_else(|e| e.into_inner());
        let id = scene.geometry_id();
        if let Some(g) = cached.as_ref().filter(|g| g.id == id) {
            return g.clone();
        }
        // Dropped first: two large geometries need not be on the GPU at once.
        *cached = None;
        let g = Self::upload(ctx, scene);
        cache.uploads.fetch_add(1, Ordering::Relaxed);
        *cached = Some(g.clone());
        g
    }
}

/// The scene's buffers on the GPU.
#[derive(Debug)]
pub struct SceneBuffers {
    header: wgpu::Buffer,
    camera: wgpu::Buffer,
    /// The tile and sample of the next dispatch (see `dispatch.rs`).
    pub(crate) tile: wgpu::Buffer,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    geometry: GeometryBuffers,
    texels: wgpu::Buffer,
    textures: wgpu::Buffer,
    pub output: wgpu::Buffer,
    pub stats: wgpu::Buffer,
    pub probe: wgpu::Buffer,
    pub probe_tree: wgpu::Buffer,
    /// The path tracer's paths (one a pixel of a tile) and emitters (`with_paths`).
    path_states: Option<wgpu::Buffer>,
    emitters: Option<wgpu::Buffer>,
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: u32,
}

/// The zeroed statistics buffer: ray counts and the status word.
pub(crate) const ZERO_STATS: [u32; STAT_WORDS as usize] = [0; STAT_WORDS as usize];

fn storage<T: Pod>(ctx: &GpuContext, label: &str, items: &[T]) -> wgpu::Buffer {
    // Storage buffers may not be empty: an absent kind gets one unused element.
    let one = [bytemuck::Zeroable::zeroed()];
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

/// Checks what the GPU tracer cannot take: non-finite data, more primitives of a kind than its
/// loops walk (with the BVH only planes are walked one by one), buffers larger than the device
/// binds. Returns the output buffer's size.
fn check_limits(ctx: &GpuContext, scene: &FlatScene, bvh: bool) -> Result<u64, GpuError> {
    if let Some(field) = scene.first_non_finite() {
        return Err(GpuError::NonFinite { field });
    }
    scene.check_tags()?;
    let h = &scene.header;
    for (what, count) in [("spheres", h.sphere_count), ("planes", h.plane_count), ("triangles", h.triangle_count)] {
        if count > GPU_PRIMITIVE_LIMIT && !(bvh && what != "planes") {
            return Err(GpuError::TooManyPrimitives { what, count, limit: GPU_PRIMITIVE_LIMIT });
        }
    }
    if bvh {
        check_tree_indices(scene.bvh_nodes.len(), scene.bvh_prims.len())?;
        scene.bvh_nodes.gpu()?;
    }
    let output_size = scene.pixel_count() as u64 * 16;
    let limits = &ctx.limits;
    let check = |what: &str, needed: u64| -> Result<(), GpuError> {
        for (limit, limit_name) in [
            (limits.max_storage_buffer_binding_size, "max_storage_buffer_binding_size"),
            (limits.max_buffer_size, "max_buffer_size"),
        ] {
            if needed > limit {
                return Err(GpuError::TooLarge { what: what.into(), needed, limit, limit_name });
            }
        }
        Ok(())
    };
    check(&format!("the {}x{} output image", h.width, h.height), output_size)?;
    for (what, bytes) in storage_sizes(scene) {
        check(what, bytes)?;
    }
    Ok(output_size)
}

/// The bytes of each of a scene's storage buffers whose size grows with the scene, by name.
pub fn storage_sizes(scene: &FlatScene) -> [(&'static str, u64); 11] {
    let bytes = |n: usize, item: usize| (n * item) as u64;
    let refs = scene.bvh_prims.len();
    [
        ("the triangle buffer", size_of_val(&scene.triangles[..]) as u64),
        ("the vertex buffer", size_of_val(&scene.vertices[..]) as u64),
        ("the normal buffer", size_of_val(&scene.normals[..]) as u64),
        ("the sphere buffer", size_of_val(&scene.spheres[..]) as u64),
        ("the BVH node buffer", scene.bvh_nodes.gpu().map_or(0, |n| size_of_val(n) as u64)),
        ("the BVH leaf buffer of corners a and b", bytes(refs, size_of::<GpuLeafAb>())),
        ("the BVH leaf buffer of corners c", bytes(refs, size_of::<GpuLeafC>())),
        ("the texture coordinate buffer", size_of_val(&scene.uvs[..]) as u64),
        ("the vertex colour buffer", size_of_val(&scene.colours[..]) as u64),
        ("the texel buffer", size_of_val(scene.texels.as_slice()) as u64),
        ("the texture table", size_of_val(scene.textures.as_slice()) as u64),
    ]
}

/// Checks that every node and leaf reference of a tree fits the GPU walk's node reference.
fn check_tree_indices(nodes: usize, prims: usize) -> Result<(), GpuError> {
    for (what, count) in [("nodes", nodes as u64), ("leaf references", prims as u64)] {
        if count > GPU_MAX_TREE_INDEX {
            return Err(GpuError::TreeTooLarge { what, count, limit: GPU_MAX_TREE_INDEX });
        }
    }
    Ok(())
}

impl SceneBuffers {
    /// Checks the scene (every float finite) and the device limits, for the shader variant
    /// `key` (walking the BVH or every primitive), then uploads it; its geometry only if
    /// `cache` does not hold it already.
    pub fn upload(
        ctx: &GpuContext,
        scene: &FlatScene,
        key: ShaderKey,
        cache: &GeometryCache,
    ) -> Result<Self, GpuError> {
        let output_size = check_limits(ctx, scene, key.bvh)?;
        // Only the probe variant binds the ray tree (446 KB): other variants get a stand-in.
        let tree_size = if key.probe { size_of::<ProbeTree>() as u64 } else { 16 };
        let h = &scene.header;
        with_error_scopes(ctx, || Self {
            header: uniform(ctx, "glint header", &scene.header),
            camera: uniform(ctx, "glint camera", &scene.camera),
            tile: uniform(ctx, "glint tile", &TileParams::pixel(0, 0)),
            materials: storage(ctx, "glint materials", &scene.materials),
            lights: storage(ctx, "glint lights", &scene.lights),
            geometry: GeometryBuffers::of(ctx, scene, cache),
            texels: storage(ctx, "glint texels", &scene.texels),
            textures: storage(ctx, "glint textures", &scene.textures),
            output: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint output"),
                size: output_size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            stats: ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("glint stats"),
                contents: bytemuck::cast_slice(&ZERO_STATS),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            }),
            probe: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint probe"),
                size: size_of::<ProbeRecord>() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            probe_tree: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint probe tree"),
                size: tree_size,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            path_states: None,
            emitters: None,
            width: h.width,
            height: h.height,
            spp: h.spp.max(1),
            max_depth: h.max_depth,
        })
    }

    /// The path tracer's buffers beside the scene's: a path for each pixel of a `tile`-pixel
    /// square (the most one dispatch covers) and the scene's emitters.
    pub fn with_paths(mut self, ctx: &GpuContext, scene: &FlatScene, tile: u32) -> Result<Self, GpuError> {
        let slots = u64::from(tile.min(self.width)) * u64::from(tile.min(self.height));
        let needed = slots * size_of::<GpuPathState>() as u64;
        if needed > ctx.limits.max_storage_buffer_binding_size {
            return Err(GpuError::TooLarge {
                what: format!("the paths of a {tile}-pixel tile"),
                needed,
                limit: ctx.limits.max_storage_buffer_binding_size,
                limit_name: "max_storage_buffer_binding_size",
            });
        }
        let words = Emitters::of_scene(scene).gpu_words();
        with_error_scopes(ctx, || {
            self.path_states = Some(ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("glint paths"),
                size: needed,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }));
            self.emitters = Some(storage(ctx, "glint emitters", &words));
        })?;
        Ok(self)
    }

    /// The buffer behind `binding`; `None` for the ray-cast kernel's, which are not the scene's.
    fn buffer(&self, binding: Binding) -> Option<&wgpu::Buffer> {
        Some(match binding {
            Binding::Header => &self.header,
            Binding::Camera => &self.camera,
            Binding::Tile => &self.tile,
            Binding::Materials => &self.materials,
            Binding::Lights => &self.lights,
            Binding::Spheres => &self.geometry.spheres,
            Binding::Planes => &self.geometry.planes,
            Binding::Triangles => &self.geometry.triangles,
            Binding::Output => &self.output,
            Binding::Stats => &self.stats,
            Binding::Probe => &self.probe,
            Binding::ProbeTree => &self.probe_tree,
            Binding::BvhNodes => &self.geometry.bvh_nodes,
            Binding::BvhLeafAb => &self.geometry.bvh_leaf.ab,
            Binding::BvhLeafC => &self.geometry.bvh_leaf.c,
            Binding::Vertices => &self.geometry.vertices,
            Binding::Normals => &self.geometry.normals,
            Binding::Meshes => &self.geometry.meshes,
            Binding::Uvs => &self.geometry.uvs,
            Binding::Colours => &self.geometry.colours,
            Binding::Texels => &self.texels,
            Binding::Textures => &self.textures,
            Binding::PathStates => return self.path_states.as_ref(),
            Binding::Emitters => return self.emitters.as_ref(),
            Binding::RaysIn | Binding::HitsOut => return None,
        })
    }

    /// The bind group for `pipeline`, with exactly the bindings its module declares.
    pub fn bind_group(&self, ctx: &GpuContext, pipeline: &TracerPipeline) -> Result<wgpu::BindGroup, GpuError> {
        self.bind_group_with(ctx, pipeline, &[])
    }

    /// `bind_group`, with `extra` buffers for bindings that are not the scene's (the ray-cast
    /// kernel's rays and hits); a binding neither provides is an error naming it.
    pub fn bind_group_with(
        &self,
        ctx: &GpuContext,
        pipeline: &TracerPipeline,
        extra: &[(Binding, &wgpu::Buffer)],
    ) -> Result<wgpu::BindGroup, GpuError> {
        let mut entries = Vec::with_capacity(pipeline.bindings.len());
        for &b in &pipeline.bindings {
            let buffer = extra
                .iter()
                .find(|(e, _)| *e == b)
                .map(|(_, buffer)| *buffer)
                .or_else(|| self.buffer(b))
                .ok_or(GpuError::Unbound { name: b.wgsl_name() })?;
            entries.push(wgpu::BindGroupEntry { binding: b.number(), resource: buffer.as_entire_binding() });
        }
        Ok(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("glint scene"),
            layout: &pipeline.bind_group_layout,
            entries: &entries,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tree_is_refused_only_past_the_node_reference_bits() {
        assert!(check_tree_indices(1 << 26, 1 << 26).is_ok());
        let err = check_tree_indices(1 << 26, (1 << 26) + 1).expect_err("one leaf reference too many");
        assert!(err.to_string().contains("67108865 leaf references"), "{err}");
        assert!(matches!(check_tree_indices((1 << 26) + 1, 4), Err(GpuError::TreeTooLarge { what: "nodes", .. })));
    }
}
