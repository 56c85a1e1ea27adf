// Twin of crates/glint-core/src/layout.rs: the flat scene layout shared with the CPU tracer.
// A naga reflection test checks every struct's offsets and size and every constant against
// the Rust definitions, so this file cannot drift from them silently.
#define_import_path glint::scene_data

const LIGHT_POINT: u32 = 0u;
const LIGHT_DIRECTIONAL: u32 = 1u;
const LIGHT_SPOT: u32 = 2u;
const ATTENUATION_POLYNOMIAL: u32 = 0u;
const ATTENUATION_INVERSE_SQUARE: u32 = 1u;
const SPOT_FALLOFF_POWER: u32 = 0u;
const SPOT_FALLOFF_SMOOTH: u32 = 1u;
const LIGHT_CASTS_SHADOWS: u32 = 1u;
// GpuLight::spot_versin_cutoff of a light with no cone (cutoff 180°): 1 − cos 180°.
const NO_CONE_VERSIN: f32 = 2.0;
const CAMERA_ORTHOGRAPHIC: f32 = 1.0;
const SPECULAR_BLINN: u32 = 0u;
const SPECULAR_PHONG: u32 = 1u;
const SPECULAR_COOK_TORRANCE: u32 = 2u;
const FRESNEL_EXACT: u32 = 0u;
const FRESNEL_SCHLICK: u32 = 1u;
const MESH_HAS_NORMALS: u32 = 1u;
const MESH_HAS_UVS: u32 = 2u;
const MESH_HAS_COLOURS: u32 = 4u;
const NO_TEXTURE: u32 = 0xffffffffu;
const WRAP_REPEAT: u32 = 0u;
const WRAP_CLAMP_TO_EDGE: u32 = 1u;
const WRAP_MIRRORED_REPEAT: u32 = 2u;
const FILTER_NEAREST: u32 = 0u;
const FILTER_BILINEAR: u32 = 1u;
const EPS_TMIN: u32 = 0u;
const EPS_NUDGE_RAY: u32 = 1u;
const EPS_NUDGE_NORMAL: u32 = 2u;
const EPS_ROBUST: u32 = 3u;
const EPS_SKIP_CONVEX: u32 = 4u;
const INTEGRATOR_WHITTED: u32 = 0u;
const INTEGRATOR_PATH: u32 = 1u;
// Kinds of light a path brings back (SceneHeader.omit_kinds) and a path's history bits.
const PATH_DIRECT: u32 = 1u;
const PATH_INDIRECT: u32 = 2u;
const PATH_CAUSTIC: u32 = 4u;
const PATH_REST: u32 = 8u;
const HISTORY_NON_DELTA: u32 = 3u;
const HISTORY_DELTA_AFTER: u32 = 4u;
// Where texture coordinates come from (Surface.uv_origin).
const UV_MESH: u32 = 0u;
const UV_ACROSS_X: u32 = 1u;
const UV_ACROSS_Y: u32 = 2u;
const UV_ACROSS_Z: u32 = 3u;
const NO_HIT: u32 = 0xffffffffu;

// The feature bits (SceneHeader.features) are not read here: the host compiles each feature
// in or out as an #ifdef shader def named as in glint_types::layout::feature::NAMES.

// Bits of the per-image status word the shader raises and the host reports.
const STATUS_LOOP_LIMIT: u32 = 1u;
const STATUS_STACK_OVERFLOW: u32 = 2u;
const STATUS_DRIVER_LOOP_CUTOFF: u32 = 4u;
const STATUS_BVH_STACK_OVERFLOW: u32 = 8u;

// Primitive references of the BVH (glint_types::layout; glint_core::bvh builds them): the top
// bit marks a triangle.
const PRIM_REF_TRIANGLE: u32 = 0x80000000u;
const PRIM_REF_INDEX: u32 = 0x7fffffffu;
// The GPU walk carries a node as its first child pair's record or first primitive reference
// << NODE_REF_COUNT_BITS | its leaf count (bvh.wgsl's node_ref).
const NODE_REF_COUNT_BITS: u32 = 3u;
// Bits of QuantizedPair.children below its first index: the two children's leaf counts.
const PAIR_FIRST_SHIFT: u32 = 6u;

// Layout of the statistics buffer: (lo, hi) u32 pairs per ray kind, then the status word.
const STAT_CAMERA: u32 = 0u;
const STAT_SHADOW: u32 = 2u;
const STAT_REFLECTION: u32 = 4u;
const STAT_REFRACTION: u32 = 6u;
const STAT_BAILOUT_SAVED: u32 = 8u;
const STAT_STATUS: u32 = 10u;
const STAT_PIXELS_DONE: u32 = 12u;
const STAT_WORDS: u32 = 14u;

struct SceneHeader {
    width: u32,
    height: u32,
    spp: u32,
    max_depth: u32,
    sphere_count: u32,
    plane_count: u32,
    triangle_count: u32,
    light_count: u32,
    material_count: u32,
    features: u32,
    epsilon_mode: u32,
    seed: u32,
    epsilon: f32,
    bailout: f32,
    vertex_count: u32,
    mesh_count: u32,
    integrator: u32,
    indirect: u32,
    omit_kinds: u32,
    pad_b: u32,
    ambient: vec4<f32>,
    background: vec4<f32>,
    global_attenuation: vec4<f32>,
    frame: vec4<f32>,
}

struct GpuCamera {
    // xyz a point of the view axis, w its distance from the eye (layout.rs says why).
    anchor: vec4<f32>,
    // xyz the view direction, w the projection (0 a pinhole, or CAMERA_ORTHOGRAPHIC).
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
}

struct GpuMaterial {
    ka: vec4<f32>,
    kd: vec4<f32>,
    ks: vec4<f32>,
    kr: vec4<f32>,
    kt: vec4<f32>,
    emission: vec4<f32>,
    shininess: f32,
    ior: f32,
    specular_model: u32,
    diffuse_texture: u32,
    emission_texture: u32,
    roughness: f32,
    fresnel: u32,
    pad: u32,
}

// One entry of the texture table: texels offset .. offset + width·height of the texel buffer
// (linear RGBA, rows from the top), its sampler, and the rows of its 2×3 UV transform.
struct GpuTexture {
    offset: u32,
    width: u32,
    height: u32,
    wrap_s: u32,
    wrap_t: u32,
    filter_mode: u32,
    pad_a: u32,
    pad_b: u32,
    transform_u: vec4<f32>,
    transform_v: vec4<f32>,
    planar_u: vec4<f32>,
    planar_v: vec4<f32>,
}

struct GpuLight {
    position: vec4<f32>,
    direction: vec4<f32>,
    diffuse: vec4<f32>,
    specular: vec4<f32>,
    ambient: vec4<f32>,
    attenuation: vec4<f32>,
    kind: u32,
    flags: u32,
    spot_exponent: f32,
    spot_versin_cutoff: f32,
    attenuation_model: u32,
    spot_falloff: u32,
    range: f32,
    spot_versin_inner: f32,
}

struct GpuSphere {
    center_radius: vec4<f32>,
    material: u32,
    object_id: u32,
    power: f32,
    pad: u32,
}

struct GpuPlane {
    normal_offset: vec4<f32>,
    material: u32,
    object_id: u32,
    pad: vec2<u32>,
}

struct GpuTriangle {
    va: u32,
    vb: u32,
    vc: u32,
    mesh: u32,
    order: u32,
}

struct GpuMesh {
    material: u32,
    object_id: u32,
    flags: u32,
    pad: u32,
}

// A path between the path tracer's per-bounce dispatches (glint_types::layout::GpuPathState):
// seven vector words, u32 fields as the bits of a w.
struct GpuPathState {
    origin: vec4<f32>,
    dir: vec4<f32>,
    beta: vec4<f32>,
    radiance: vec4<f32>,
    scattered_from: vec4<f32>,
    leaving_pixel: vec4<u32>,
    sample: vec4<u32>,
}

// The pixel rectangle one dispatch renders.
struct TileParams {
    origin_x: u32,
    origin_y: u32,
    width: u32,
    height: u32,
    sample_index: u32,
    canary_laps: u32,
    sample_end: u32,
    pad_b: u32,
}

const MAX_PROBE_LIGHTS: u32 = 16u;
const PROBE_HIT: u32 = 1u;
const PROBE_TIR: u32 = 2u;

struct ProbeLight {
    f_att: f32,
    spot: f32,
    shadow_ray: u32,
    n_dot_l: f32,
    visibility: vec4<f32>,
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    specular: vec4<f32>,
    contribution: vec4<f32>,
    lobe_cosine: f32,
    lobe: f32,
    lobe_model: u32,
    pad_b: f32,
}

struct ProbeRecord {
    object_id: u32,
    material: u32,
    light_count: u32,
    flags: u32,
    t: f32,
    pad_a: f32,
    pad_b: f32,
    pad_c: f32,
    point: vec4<f32>,
    normal: vec4<f32>,
    emission: vec4<f32>,
    ambient: vec4<f32>,
    ka: vec4<f32>,
    kd: vec4<f32>,
    kr: vec4<f32>,
    kt: vec4<f32>,
    mirror_sum: vec4<f32>,
    refraction_sum: vec4<f32>,
    total: vec4<f32>,
    lights: array<ProbeLight, MAX_PROBE_LIGHTS>,
}

const MAX_PROBE_NODES: u32 = 256u;
const RAY_CAMERA: u32 = 0u;
const RAY_REFLECTION: u32 = 1u;
const RAY_REFRACTION: u32 = 2u;
const RAY_SHADOW: u32 = 3u;
const NODE_HIT: u32 = 1u;
const NODE_TIR: u32 = 2u;
const NODE_CUT_BAILOUT: u32 = 4u;
const NODE_CUT_DEPTH: u32 = 8u;
const NO_PARENT: u32 = 0xffffffffu;
const TREE_OVERFLOW: u32 = 1u;
const TREE_LIGHTS_TRUNCATED: u32 = 2u;

struct ProbeNode {
    kind: u32,
    flags: u32,
    parent: u32,
    depth: u32,
    object_id: u32,
    material: u32,
    light: u32,
    light_count: u32,
    t: f32,
    attenuation: f32,
    pad_a: f32,
    pad_b: f32,
    origin: vec4<f32>,
    dir: vec4<f32>,
    weight: vec4<f32>,
    factor: vec4<f32>,
    point: vec4<f32>,
    normal: vec4<f32>,
    emission: vec4<f32>,
    ambient: vec4<f32>,
    ka: vec4<f32>,
    kd: vec4<f32>,
    lights: array<ProbeLight, MAX_PROBE_LIGHTS>,
}

struct ProbeTree {
    node_count: u32,
    flags: u32,
    pad_a: u32,
    pad_b: u32,
    nodes: array<ProbeNode, MAX_PROBE_NODES>,
}

// A BVH node (glint_types::layout::BvhNode): a leaf when count > 0 (primitive references
// left_first .. left_first + count), else its children are the pair at record left_first.
// Only the root is stored so, as record 0.
struct BvhNode {
    min: vec3<f32>,
    left_first: u32,
    max: vec3<f32>,
    count: u32,
}

// The two children of an interior node (glint_types::layout::QuantizedPair, which says how
// children encodes where they are): each plane of a child's box is origin + q * 2^e on its
// axis, q the byte of planes (left min, left max, right min, right max) and e the axis's byte
// of exponents (biased as an f32's).
struct QuantizedPair {
    origin: vec3<f32>,
    exponents: u32,
    children: u32,
    planes: array<u32, 3>,
}
