// The scene buffers. Bindings the specialised shader does not use are dropped from the
// composed module, and the host builds its bind group layout from what remains.
#define_import_path glint::bindings

#import glint::scene_data::{SceneHeader, GpuCamera, GpuMaterial, GpuLight, GpuSphere, GpuPlane, GpuTriangle, GpuMesh, GpuTexture, TileParams, ProbeRecord, ProbeTree, GpuPathState}

@group(0) @binding(0) var<uniform> header: SceneHeader;
@group(0) @binding(1) var<uniform> camera: GpuCamera;
@group(0) @binding(2) var<uniform> tile: TileParams;
@group(0) @binding(3) var<storage, read> materials: array<GpuMaterial>;
@group(0) @binding(4) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(5) var<storage, read> spheres: array<GpuSphere>;
@group(0) @binding(6) var<storage, read> planes: array<GpuPlane>;
@group(0) @binding(7) var<storage, read> triangles: array<GpuTriangle>;
// rgb radiance and, in w, the first-hit object id as f32 (exact below 2^24; −1 for none).
@group(0) @binding(8) var<storage, read_write> output: array<vec4<f32>>;
// Ray counts as (lo, hi) u32 pairs and the status word; see STAT_* in scene_data.
@group(0) @binding(9) var<storage, read_write> stats: array<atomic<u32>>;
// The pixel probe's breakdown (only in the PROBE variant).
@group(0) @binding(10) var<storage, read_write> probe_out: ProbeRecord;
// The BVH over spheres and triangles (only with the BVH shader def): nodes, and
// what its leaves point into, per primitive reference in leaf order: its triangle's corners a
// (the reference in w) and b, and in an array of its own corner c, so each binding of a
// 4-million-triangle mesh fits 128 MiB (glint_core::flat::fill_gpu_leaves). Corners copied
// into leaf order are three loads a triangle test instead of seven, dependent ones (reference,
// triangle, vertices), which lavapipe makes lane by lane.
// The nodes are the root (a BvhNode) and then one QuantizedPair per interior node, each read
// as its two 16-byte words (bvh.wgsl's load_node and load_pair): lavapipe fetches a storage
// buffer lane by lane once per load instruction, and two vec4 loads are fewer than the
// fields' four or five.
@group(0) @binding(11) var<storage, read> bvh_nodes: array<array<vec4<u32>, 2>>;
@group(0) @binding(12) var<storage, read> bvh_leaf_ab: array<array<vec4<u32>, 2>>;
// Indexed meshes: vertex positions (w = 1), vertex normals beside them (w = 0; one unused
// element when no mesh has normals), and what a mesh's triangles share.
@group(0) @binding(13) var<storage, read> vertices: array<vec4<f32>>;
@group(0) @binding(14) var<storage, read> normals: array<vec4<f32>>;
@group(0) @binding(15) var<storage, read> meshes: array<GpuMesh>;
// Textures (only with the TEXTURES shader def): texture coordinates beside the vertices (one
// unused element when no mesh has them), every texture's linear RGBA texels, and the texture
// table pointing into them.
@group(0) @binding(16) var<storage, read> uvs: array<vec2<f32>>;
@group(0) @binding(17) var<storage, read> texels: array<vec4<f32>>;
@group(0) @binding(18) var<storage, read> textures: array<GpuTexture>;
// The pixel probe's ray tree (only in the PROBE variant).
@group(0) @binding(19) var<storage, read_write> probe_tree: ProbeTree;
@group(0) @binding(20) var<storage, read> bvh_leaf_c: array<vec4<u32>>;
// Linear vertex colours beside the vertices (rgb, w = 1; white for a mesh without them; one
// unused element when no mesh has them; only with the VERTEX_COLOURS shader def).
@group(0) @binding(21) var<storage, read> colours: array<vec4<f32>>;
// The ray-cast kernel's buffers (raycast.wgsl, `glint bench rays`; numbered after the
// tracer's): two vec4<f32> per ray (origin, t_min; direction, t_max), and per ray its hit as
// (prim, index, bitcast t, 0).
@group(0) @binding(22) var<storage, read> rays_in: array<vec4<f32>>;
@group(0) @binding(23) var<storage, read_write> hits_out: array<vec4<u32>>;
// The path tracer's buffers (path.wgsl; numbered after the ray-cast kernel's): a path per pixel
// of the tile between the bounce dispatches, and what next-event estimation samples: the
// emitters' count, then each emissive sphere's index or triangle's PRIM_REF_TRIANGLE | index.
@group(0) @binding(24) var<storage, read_write> path_states: array<GpuPathState>;
@group(0) @binding(25) var<storage, read> emitters: array<u32>;
