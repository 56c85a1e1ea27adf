//! The flat, GPU-ready scene layout read by both tracers.
//!
//! Every struct is `#[repr(C)]` + `Pod` and has a WGSL twin in `shaders/layout.wgsl`; a naga
//! reflection test compares offsets, sizes and the constants below, so nothing here is kept in
//! sync by hand. Vectors are `[f32; 4]` (WGSL `vec4<f32>`) to avoid vec3 alignment padding.
//!
//! The scene is stored once in f32. The CPU reference widens those exact values to f64 and does
//! all arithmetic in f64; the GPU uses them as they are. Both tracers therefore see bit-identical
//! input and every difference between their images is arithmetic, never data.

use bytemuck::{Pod, Zeroable};

/// Light kinds (`GpuLight::kind`).
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_DIRECTIONAL: u32 = 1;
pub const LIGHT_SPOT: u32 = 2;

/// Distance attenuation models (`GpuLight::attenuation_model`).
/// f_att = 1 / (c + l·d + q·d²) (OpenGL's).
pub const ATTENUATION_POLYNOMIAL: u32 = 0;
/// f_att = window(d) / d², window 1 or glTF's range window (KHR_lights_punctual).
pub const ATTENUATION_INVERSE_SQUARE: u32 = 1;

/// Spot cone falloffs (`GpuLight::spot_falloff`).
/// S = (L_N·(−L))^s inside a hard cutoff (OpenGL's).
pub const SPOT_FALLOFF_POWER: u32 = 0;
/// S = t², t the cone cosine's place between the outer and inner cone (glTF's).
pub const SPOT_FALLOFF_SMOOTH: u32 = 1;

/// `GpuLight::flags` bits.
pub const LIGHT_CASTS_SHADOWS: u32 = 1;

/// `GpuLight::spot_versin_cutoff` of a light with no cone (cutoff 180°): 1 − cos 180°.
pub const NO_CONE_VERSIN: f32 = 2.0;

/// `GpuCamera::forward`'s w: the projection (a pinhole's is 0).
pub const CAMERA_ORTHOGRAPHIC: f32 = 1.0;

/// Specular models (`GpuMaterial::specular_model`).
pub const SPECULAR_BLINN: u32 = 0;
pub const SPECULAR_PHONG: u32 = 1;
pub const SPECULAR_COOK_TORRANCE: u32 = 2;

/// Fresnel factors of the Cook–Torrance lobe (`GpuMaterial::fresnel`).
pub const FRESNEL_EXACT: u32 = 0;
pub const FRESNEL_SCHLICK: u32 = 1;

/// `GpuMesh::flags` bits.
pub const MESH_HAS_NORMALS: u32 = 1;
pub const MESH_HAS_UVS: u32 = 2;
pub const MESH_HAS_COLOURS: u32 = 4;

/// `GpuMaterial::diffuse_texture` / `emission_texture` of a material without that texture.
pub const NO_TEXTURE: u32 = u32::MAX;

/// Wrap modes (`GpuTexture::wrap_s`, `wrap_t`) and filters (`GpuTexture::filter`).
pub const WRAP_REPEAT: u32 = 0;
pub const WRAP_CLAMP_TO_EDGE: u32 = 1;
pub const WRAP_MIRRORED_REPEAT: u32 = 2;
pub const FILTER_NEAREST: u32 = 0;
pub const FILTER_BILINEAR: u32 = 1;

/// Epsilon strategies (`SceneHeader::epsilon_mode`).
pub const EPS_TMIN: u32 = 0;
pub const EPS_NUDGE_RAY: u32 = 1;
pub const EPS_NUDGE_NORMAL: u32 = 2;
pub const EPS_ROBUST: u32 = 3;
pub const EPS_SKIP_CONVEX: u32 = 4;

/// `SceneHeader::integrator`: Whitted's ray tree, or Monte Carlo paths.
pub const INTEGRATOR_WHITTED: u32 = 0;
pub const INTEGRATOR_PATH: u32 = 1;

/// The kinds of light a path brings back (`SceneHeader::omit_kinds` bits), by its scatters
/// from the camera in Heckbert's notation, S a delta lobe (k_r, k_t) and D a non-delta one:
/// direct E S* D? L (what Whitted computes, less its ambient), indirect diffuse E S* D D+ L
/// (colour bleeding), caustics E S* D S+ L (light that reached a diffuse surface through a
/// mirror or glass), and the rest (a delta scatter between two non-delta ones).
pub const PATH_DIRECT: u32 = 1;
pub const PATH_INDIRECT: u32 = 2;
pub const PATH_CAUSTIC: u32 = 4;
pub const PATH_REST: u32 = 8;

/// A path's history (`PathState::history`): its non-delta scatters so far in the low bits
/// (saturating at 2), and whether a delta scatter came after the first of them.
pub const HISTORY_NON_DELTA: u32 = 3;
pub const HISTORY_DELTA_AFTER: u32 = 4;

/// A stored tag that no kind of the layout has: a flat scene not made by `FlatScene::build`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{value} is not a valid {what}")]
pub struct UnknownTag {
    pub what: &'static str,
    pub value: u32,
}

/// Object id written for camera rays that hit nothing.
pub const NO_HIT: u32 = u32::MAX;

/// Bits of the per-image status word the GPU tracer raises (never silently).
/// A tree walk reached its iteration bound (lavapipe cuts loops silently past 65,535).
pub const STATUS_LOOP_LIMIT: u32 = 1;
/// A ray tree branched deeper than the GPU stack holds; the deepest rays were dropped.
pub const STATUS_STACK_OVERFLOW: u32 = 2;
/// The driver cut the shader's loops short: lavapipe allows 65,535 loop iterations in all per
/// invocation group and then ends every loop after its current iteration, silently. A canary
/// loop at the end of the shader detects it; the image is then missing work.
pub const STATUS_DRIVER_LOOP_CUTOFF: u32 = 4;
/// A BVH traversal needed more than its fixed stack (`shaders/bvh.wgsl`); the deepest subtrees
/// were not visited, so some hits may be missing.
pub const STATUS_BVH_STACK_OVERFLOW: u32 = 8;

/// The top bit of a BVH primitive reference: set for a triangle, clear for a sphere.
pub const PRIM_REF_TRIANGLE: u32 = 1 << 31;
/// The index bits of a primitive reference.
pub const PRIM_REF_INDEX: u32 = PRIM_REF_TRIANGLE - 1;
/// The GPU walk carries a node in one u32, its first child pair's record or first primitive
/// reference shifted past its leaf count (`node_ref` in shaders/bvh.wgsl), so that a child
/// tested is not loaded again when walked.
pub const NODE_REF_COUNT_BITS: u32 = 3;
/// Bits of `QuantizedPair::children` below `first`: both children's leaf counts.
pub const PAIR_FIRST_SHIFT: u32 = 2 * NODE_REF_COUNT_BITS;

/// The world's frame: origin at the world's, scale 1 (`SceneHeader::frame`); the one a scene
/// around the world origin is stored in.
pub const WORLD_FRAME: [f32; 4] = [0.0, 0.0, 0.0, 1.0];

/// Layout of the GPU statistics buffer: (lo, hi) u32 pairs per ray kind, the status word, and
/// the path tracer's count of a tile's pixels that finished their batch of samples.
pub const STAT_CAMERA: u32 = 0;
pub const STAT_SHADOW: u32 = 2;
pub const STAT_REFLECTION: u32 = 4;
pub const STAT_REFRACTION: u32 = 6;
pub const STAT_BAILOUT_SAVED: u32 = 8;
pub const STAT_STATUS: u32 = 10;
pub const STAT_PIXELS_DONE: u32 = 12;
pub const STAT_WORDS: u32 = 14;

/// Feature bits (`SceneHeader::features`): what the scene uses. Both tracers skip the work of
/// an absent feature, and the GPU tracer removes its code (`#ifdef` shader defs named
/// `NAMES`, chosen in glint-gpu's `shaders.rs`).
pub mod feature {
    pub const POINT_LIGHTS: u32 = 1 << 0;
    pub const DIRECTIONAL_LIGHTS: u32 = 1 << 1;
    pub const SPOT_LIGHTS: u32 = 1 << 2;
    /// Some point or spot light has polynomial attenuation other than (1, 0, 0).
    pub const ATTENUATION: u32 = 1 << 3;
    /// Some light casts shadows (and there is geometry to cast them).
    pub const SHADOWS: u32 = 1 << 4;
    /// Some material has k_t > 0, so shadows are filtered rather than binary.
    pub const FILTERED_SHADOWS: u32 = 1 << 5;
    pub const REFLECTION: u32 = 1 << 6;
    pub const TRANSMISSION: u32 = 1 << 7;
    pub const SPHERES: u32 = 1 << 8;
    pub const PLANES: u32 = 1 << 9;
    pub const TRIANGLES: u32 = 1 << 10;
    /// Some material has a texture (an image, or the checker): texel buffer, texture table and
    /// texture coordinates.
    pub const TEXTURES: u32 = 1 << 11;
    pub const BLINN: u32 = 1 << 12;
    pub const PHONG: u32 = 1 << 13;
    /// Some light has a non-zero own ambient term I_a,j.
    pub const LIGHT_AMBIENT: u32 = 1 << 14;
    /// Some material emits (E_m ≠ 0).
    pub const EMISSION: u32 = 1 << 15;
    /// Some material has k_s > 0.
    pub const SPECULAR: u32 = 1 << 16;
    /// Stratified jitter (spp > 1, or any path render).
    pub const JITTER: u32 = 1 << 17;
    /// Some point or spot light has inverse-square attenuation (with or without a range).
    pub const INVERSE_SQUARE: u32 = 1 << 18;
    /// Some spot light has the smooth (glTF) cone falloff.
    pub const SMOOTH_SPOT: u32 = 1 << 19;
    /// The ε strategy is `skip_convex` or `robust`: secondary rays carry the primitive they
    /// leave, which the primitive loops skip (or, for a sphere the ray enters, test by its far
    /// root only).
    pub const SKIP_LEFT: u32 = 1 << 20;
    /// The world's global attenuation is on (not (1, 0, 0)) and child rays are traced.
    pub const GLOBAL_ATTENUATION: u32 = 1 << 21;
    /// Some material with k_s > 0 has the Cook–Torrance lobe.
    pub const COOK_TORRANCE: u32 = 1 << 22;
    /// Some mesh has vertex colours (they multiply k_a and k_d).
    pub const VERTEX_COLOURS: u32 = 1 << 23;
    /// Every feature: the unspecialised tracer.
    pub const ALL: u32 = (1 << 24) - 1;

    /// Names in bit order, for logs, cache keys and shader defs.
    pub const NAMES: [&str; 24] = [
        "POINT_LIGHTS",
        "DIRECTIONAL_LIGHTS",
        "SPOT_LIGHTS",
        "ATTENUATION",
        "SHADOWS",
        "FILTERED_SHADOWS",
        "REFLECTION",
        "TRANSMISSION",
        "SPHERES",
        "PLANES",
        "TRIANGLES",
        "TEXTURES",
        "BLINN",
        "PHONG",
        "LIGHT_AMBIENT",
        "EMISSION",
        "SPECULAR",
        "JITTER",
        "INVERSE_SQUARE",
        "SMOOTH_SPOT",
        "SKIP_LEFT",
        "GLOBAL_ATTENUATION",
        "COOK_TORRANCE",
        "VERTEX_COLOURS",
    ];

    /// Whether a scene with `features` traces child rays: the one test of "needs a ray tree
    /// (and, on the GPU, a stack)" that both tracers use.
    pub const fn recurses(features: u32) -> bool {
        features & (REFLECTION | TRANSMISSION) != 0
    }
}

/// Global parameters of one render.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SceneHeader {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    /// Maximum recursion depth from the settings. (When nothing reflects or transmits, the
    /// REFLECTION and TRANSMISSION feature bits are off and no child ray is traced.)
    pub max_depth: u32,
    pub sphere_count: u32,
    pub plane_count: u32,
    pub triangle_count: u32,
    pub light_count: u32,
    pub material_count: u32,
    /// Feature bits of the scene (`feature::*`). An unspecialised run passes `feature::ALL`
    /// beside the scene (CPU) or compiles every feature in (GPU); this field stays the scene's.
    pub features: u32,
    pub epsilon_mode: u32,
    pub seed: u32,
    pub epsilon: f32,
    pub bailout: f32,
    /// Entries of the vertex (and, where a mesh has them, normal) buffer.
    pub vertex_count: u32,
    pub mesh_count: u32,
    /// `INTEGRATOR_*`: what the tracers compute. The feature bits are the ones it needs.
    pub integrator: u32,
    /// Paths follow the non-delta lobes too (1), or only k_r and k_t (0: the transport Whitted
    /// computes, with direct light by next-event estimation). Whitted's tracer does not read it.
    pub indirect: u32,
    /// The kinds of light (`PATH_*` bits) a path-traced image leaves out: 0 for the whole
    /// image; one kind alone is every other bit. Whitted's tracer does not read it.
    pub omit_kinds: u32,
    pub pad_b: u32,
    /// Global ambient I_a (rgb, w unused).
    pub ambient: [f32; 4],
    /// Radiance of missed rays (rgb, w unused).
    pub background: [f32; 4],
    /// (c, l, q, unused) of the attenuation of reflected and transmitted terms by the distance
    /// their ray travelled; (1, 0, 0, 0) when off.
    pub global_attenuation: [f32; 4],
    /// The frame the coordinates are given in: xyz the world point that is the origin (the
    /// storage origin `glint_scene::storage_origin` of the scene both tracers build, 0 for a
    /// scene around the world origin; where the camera looks when the GPU traces camera-relative,
    /// `rebase.rs`), w the length scale of the robust offset near the origin (1, or the
    /// power of two nearest the scene's extent when rebased). Planar texture coordinates are
    /// taken relative to it, from each texture's planar origins (`GpuTexture::planar_u`).
    pub frame: [f32; 4],
}

/// The camera as ray-generation vectors: a pinhole's pixel at normalised device coordinates (x, y)
/// in [−1, 1]² looks along `forward + x·right + y·up` (right and up are pre-scaled by the
/// field of view and aspect ratio) from the eye, `anchor.xyz − anchor.w·forward`. An
/// orthographic camera (`forward.w` = `CAMERA_ORTHOGRAPHIC`) looks along `forward` from the
/// eye's plane, at eye + x·right + y·up (right and up then half the view's width and height).
///
/// The eye is not stored: a camera ray starts on the plane through the anchor, at
/// anchor + w·(x·right + y·up), and reaches back to the eye with t_min = −w·|forward + x·right +
/// y·up| (`camera_ray`). For an eye far from the scene the anchor is the point of the view axis
/// nearest the centre of the scene's bounded geometry (on the GPU, nearest its frame's origin,
/// at the focus), so the pixel's offset is added to
/// small coordinates and an f32 direction's error acts over the scene's depth only, not over the
/// eye's distance: from an eye D away, f32 would point each ray D·6e-8 off and store the eye as
/// far off (stiff case 22). A nearer eye is its own anchor (w = 0: the rays are the eye's).
/// An orthographic ray starts at anchor + x·right + y·up and reaches back to the eye's plane
/// with t_min = −w·|forward|.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuCamera {
    /// xyz the anchor on the view axis, w ≥ 0 its distance from the eye (an f32 value the
    /// anchor was placed from, so that the eye is exact to the anchor's rounding).
    pub anchor: [f32; 4],
    /// xyz the view direction, w the projection (0 a pinhole, or `CAMERA_ORTHOGRAPHIC`).
    pub forward: [f32; 4],
    pub right: [f32; 4],
    pub up: [f32; 4],
}

impl GpuCamera {
    /// Whether its rays are parallel (`forward.w` = `CAMERA_ORTHOGRAPHIC`), not a pinhole's.
    pub fn is_orthographic(&self) -> bool {
        self.forward[3] == CAMERA_ORTHOGRAPHIC
    }
}

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    pub ka: [f32; 4],
    pub kd: [f32; 4],
    pub ks: [f32; 4],
    pub kr: [f32; 4],
    pub kt: [f32; 4],
    pub emission: [f32; 4],
    pub shininess: f32,
    pub ior: f32,
    /// `SPECULAR_*`: which lobe spec_j is.
    pub specular_model: u32,
    /// Index into the texture table whose colour multiplies k_a and k_d, or `NO_TEXTURE`.
    pub diffuse_texture: u32,
    /// Index into the texture table whose colour multiplies E_m, or `NO_TEXTURE`.
    pub emission_texture: u32,
    /// Beckmann roughness m of the Cook–Torrance lobe.
    pub roughness: f32,
    /// `FRESNEL_*`: the Cook–Torrance lobe's Fresnel factor.
    pub fresnel: u32,
    pub pad: u32,
}

/// One texture of the texture table: where its texels start in the texel buffer (linear RGBA
/// f32, row by row from the top), its size, its sampler, and its UV transform.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuTexture {
    pub offset: u32,
    pub width: u32,
    pub height: u32,
    /// `WRAP_*` along u and along v.
    pub wrap_s: u32,
    pub wrap_t: u32,
    /// `FILTER_*`.
    pub filter_mode: u32,
    pub pad_a: u32,
    pub pad_b: u32,
    /// Rows of the 2×3 UV transform: u' = transform_u · (u, v, 1), v' = transform_v · (u, v, 1)
    /// (w unused).
    pub transform_u: [f32; 4],
    pub transform_v: [f32; 4],
    /// The transformed planar coordinates of the frame's origin, for planar coordinates taken
    /// across the x, y and z axis (`UV_ACROSS_X` …; w unused): u' = transform_u.xy · uv +
    /// planar_u[axis], with uv relative to the frame. Computed in f64 and folded into the wrap
    /// mode's period (`texture_table::planar_origins` for the stored frame, `flat::move_texture_origins` for a rebased one),
    /// so that a scene far from the world origin keeps its texel
    /// edges on the GPU; in world space (frame origin 0) they are transform_u.z and
    /// transform_v.z.
    pub planar_u: [f32; 4],
    pub planar_v: [f32; 4],
}

/// Where texture coordinates come from (`Surface::uv_origin`): a mesh's own UVs, or planar
/// coordinates across the geometric normal's dominant axis, relative to the frame's origin.
pub const UV_MESH: u32 = 0;
pub const UV_ACROSS_X: u32 = 1;
pub const UV_ACROSS_Y: u32 = 2;
pub const UV_ACROSS_Z: u32 = 3;

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// Position (point, spot).
    pub position: [f32; 4],
    /// Unit direction of travel (directional) or unit spot axis L_N (spot).
    pub direction: [f32; 4],
    pub diffuse: [f32; 4],
    pub specular: [f32; 4],
    pub ambient: [f32; 4],
    /// (c, l, q, unused) of the polynomial model; (1, 0, 0, 0) otherwise.
    pub attenuation: [f32; 4],
    pub kind: u32,
    pub flags: u32,
    /// s of the power falloff; 0 for the smooth one.
    pub spot_exponent: f32,
    /// 1 − cos(cutoff) of the power falloff, 2 for cutoff 180 (no cone); 1 − cos(outer cone) of
    /// the smooth one. Versines, not cosines: formed in f64 as 2·sin²(θ/2) and rounded once, so
    /// a cone of a degree keeps f32's relative precision (its cosine would keep 4e-4 of it).
    pub spot_versin_cutoff: f32,
    /// `ATTENUATION_*`: which f_att the light has.
    pub attenuation_model: u32,
    /// `SPOT_FALLOFF_*`: which S a spot light has (power for the other kinds).
    pub spot_falloff: u32,
    /// The inverse-square model's range window; 0 for none (plain 1/d²) and other models.
    pub range: f32,
    /// 1 − cos(inner cone) of the smooth falloff; 0 otherwise.
    pub spot_versin_inner: f32,
}

#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuSphere {
    /// (centre xyz, radius).
    pub center_radius: [f32; 4],
    pub material: u32,
    pub object_id: u32,
    /// The power of the frame's origin with respect to the sphere, |C|² − r², computed in f64
    /// from the stored centre and radius and rounded once (`origin_power`). The f32 tracer
    /// takes c = |o − C|² − r² for a ray origin o near the frame's origin as
    /// power + o·(o − 2C) where that has fewer digits to lose (see docs/numerics.md).
    pub power: f32,
    pub pad: u32,
}

/// The distance between adjacent f32 values at |x| (at least the smallest normal's): how
/// finely the layout stores a coordinate of that size.
pub fn f32_spacing(x: f64) -> f64 {
    let exponent = ((x.abs() as f32).max(f32::MIN_POSITIVE).to_bits() >> 23) as i32 - 127;
    2f64.powi(exponent - 23)
}

/// |C|² − r² of a stored (centre, radius) in f64 (the f32 squares are exact), rounded to f32.
pub fn origin_power(center_radius: [f32; 4]) -> f32 {
    let [x, y, z, r] = center_radius.map(f64::from);
    ((x * x + y * y + z * z) - r * r) as f32
}

/// The plane n·x = d with unit normal n.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuPlane {
    /// (n xyz, d).
    pub normal_offset: [f32; 4],
    pub material: u32,
    pub object_id: u32,
    pub pad: [u32; 2],
}

/// One triangle of an indexed mesh: three indices into the vertex buffer (positions, and
/// normals where its mesh has them), the index of its mesh, and its place in scene order.
/// 20 bytes; the vertices are shared with the neighbouring triangles.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuTriangle {
    pub va: u32,
    pub vb: u32,
    pub vc: u32,
    pub mesh: u32,
    /// Its index among the scene's triangles before the BVH put them in leaf order: of two
    /// hits at equal t the smaller wins, so the result does not depend on the stored order.
    pub order: u32,
}

/// What the triangles of one mesh share: material, object and whether vertex normals exist.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuMesh {
    pub material: u32,
    pub object_id: u32,
    pub flags: u32,
    pub pad: u32,
}

/// The pixel rectangle one GPU dispatch renders.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct TileParams {
    pub origin_x: u32,
    pub origin_y: u32,
    pub width: u32,
    pub height: u32,
    /// The sample this dispatch adds: samples go in separate dispatches so that one
    /// invocation's loop iterations stay within the driver's budget whatever the spp.
    pub sample_index: u32,
    /// Iterations of the canary loop (always `LOOP_CANARY_LAPS`; a uniform so that no
    /// compiler can unroll it).
    pub canary_laps: u32,
    /// The path tracer's batch ends before this sample: each pixel runs its samples from
    /// `sample_index` up to it, one after the other (`sample_index + 1` for Whitted's).
    pub sample_end: u32,
    pub pad_b: u32,
}

/// Laps of the canary loop that tells whether the driver's loop budget ran out.
pub const LOOP_CANARY_LAPS: u32 = 2;

impl TileParams {
    /// Sample `sample_index` of the `width`×`height` pixels from (x, y).
    pub fn new(x: u32, y: u32, width: u32, height: u32, sample_index: u32) -> Self {
        Self {
            origin_x: x,
            origin_y: y,
            width,
            height,
            sample_index,
            canary_laps: LOOP_CANARY_LAPS,
            sample_end: sample_index + 1,
            pad_b: 0,
        }
    }

    /// The one pixel (x, y), first sample.
    pub fn pixel(x: u32, y: u32) -> Self {
        Self::new(x, y, 1, 1, 0)
    }
}

/// A path between the GPU path tracer's per-bounce dispatches (path.wgsl's `load_path` and
/// `store_path`; the f32 form of `cpu::path::PathState`), one per pixel of a tile. Seven
/// 16-byte words, u32 fields as their bits in a w: lavapipe loads a storage buffer lane by lane
/// once per load instruction, and seven vector loads are fewer than eighteen scalar ones.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuPathState {
    /// xyz the ray's origin, w its t_min.
    pub origin: [f32; 4],
    /// xyz the ray's direction, w the bounces so far (a u32's bits).
    pub dir: [f32; 4],
    /// xyz the throughput, w the density of the last non-delta scatter (0 after a delta lobe).
    pub beta: [f32; 4],
    /// xyz the radiance so far, w the first object hit (a u32's bits).
    pub radiance: [f32; 4],
    /// xyz where the path last scattered off a non-delta lobe, w 1 while the path goes on and
    /// 0 once its pixel's batch is done (a u32's bits).
    pub scattered_from: [f32; 4],
    /// The primitive the ray leaves (`Leaving`: prim, index, inside as 0 or 1) and the pixel.
    pub leaving_pixel: [u32; 4],
    /// x the sample, y the history (`HISTORY_*`); z, w unused.
    pub sample: [u32; 4],
}

/// Lights whose terms the GPU pixel probe records (the CPU probe records all).
pub const MAX_PROBE_LIGHTS: u32 = 16;

/// `ProbeRecord::flags` bits.
pub const PROBE_HIT: u32 = 1;
/// The probed hit reflected totally: its k_t share followed the mirror ray.
pub const PROBE_TIR: u32 = 2;

/// One light's terms at the probed hit (GPU twin of `cpu::shade::LightTerm`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ProbeLight {
    pub f_att: f32,
    pub spot: f32,
    /// 1 when a shadow ray was traced towards the light, else 0.
    pub shadow_ray: u32,
    /// N·L before it is clamped (`cpu::shade::LightAngles`, as are the lobe's three).
    pub n_dot_l: f32,
    pub visibility: [f32; 4],
    pub ambient: [f32; 4],
    pub diffuse: [f32; 4],
    pub specular: [f32; 4],
    pub contribution: [f32; 4],
    pub lobe_cosine: f32,
    pub lobe: f32,
    /// The `SPECULAR_*` lobe evaluated.
    pub lobe_model: u32,
    pub pad_b: f32,
}

/// The breakdown of one camera sample, as the GPU probe writes it (twin of
/// `cpu::shade::Breakdown`; the host splits the mirror subtree into k_r and k_t parts).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ProbeRecord {
    pub object_id: u32,
    pub material: u32,
    pub light_count: u32,
    pub flags: u32,
    pub t: f32,
    pub pad_a: f32,
    pub pad_b: f32,
    pub pad_c: f32,
    pub point: [f32; 4],
    pub normal: [f32; 4],
    pub emission: [f32; 4],
    pub ambient: [f32; 4],
    /// k_a and k_d at the hit, after the texture and the vertex colour (the material's own without them).
    pub ka: [f32; 4],
    pub kd: [f32; 4],
    pub kr: [f32; 4],
    pub kt: [f32; 4],
    /// Radiance gathered by the mirror child's subtree (weights included).
    pub mirror_sum: [f32; 4],
    /// Radiance gathered by the refracted child's subtree.
    pub refraction_sum: [f32; 4],
    pub total: [f32; 4],
    pub lights: [ProbeLight; MAX_PROBE_LIGHTS as usize],
}

/// Nodes of the ray tree the GPU probe records (`ProbeTree`); a larger tree sets
/// `TREE_OVERFLOW` and keeps its first nodes. A depth-5 tree through glass with shadow rays to
/// three lights and the cut children of the last level has about 250.
pub const MAX_PROBE_NODES: u32 = 256;

/// `ProbeNode::kind`: the ray kinds of a Whitted tree (`ray_tree::RayKind`).
pub const RAY_CAMERA: u32 = 0;
pub const RAY_REFLECTION: u32 = 1;
pub const RAY_REFRACTION: u32 = 2;
pub const RAY_SHADOW: u32 = 3;

/// `ProbeNode::flags` bits.
pub const NODE_HIT: u32 = 1;
/// A mirror ray that also carries the k_t share (total internal reflection at its parent).
pub const NODE_TIR: u32 = 2;
/// Not traced: its path weight fell below the bailout.
pub const NODE_CUT_BAILOUT: u32 = 4;
/// Not traced: its parent was at the maximum depth.
pub const NODE_CUT_DEPTH: u32 = 8;
/// `ProbeNode::parent` of the camera ray.
pub const NO_PARENT: u32 = u32::MAX;

/// `ProbeTree::flags` bits.
/// The tree had more than `MAX_PROBE_NODES` nodes: only the first were recorded.
pub const TREE_OVERFLOW: u32 = 1;
/// The scene has more than `MAX_PROBE_LIGHTS` lights: the terms and shadow rays of the
/// others are missing.
pub const TREE_LIGHTS_TRUNCATED: u32 = 2;

/// One ray of the tree the GPU probe records, in the CPU's depth-first order (twin of
/// `ray_tree::RayNode`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ProbeNode {
    pub kind: u32,
    pub flags: u32,
    pub parent: u32,
    pub depth: u32,
    pub object_id: u32,
    pub material: u32,
    /// The light a shadow ray goes to.
    pub light: u32,
    pub light_count: u32,
    /// Distance to the hit (to the light for a shadow ray).
    pub t: f32,
    /// The world's global attenuation f_att(t) at the hit (1 without it).
    pub attenuation: f32,
    pub pad_a: f32,
    pub pad_b: f32,
    pub origin: [f32; 4],
    pub dir: [f32; 4],
    /// The product of k along the path, this ray's own factor included.
    pub weight: [f32; 4],
    /// This ray's own factor: k_r, k_t, k_r + k_t under total internal reflection, V for a
    /// shadow ray, 1 for the camera ray.
    pub factor: [f32; 4],
    pub point: [f32; 4],
    pub normal: [f32; 4],
    pub emission: [f32; 4],
    pub ambient: [f32; 4],
    pub ka: [f32; 4],
    pub kd: [f32; 4],
    pub lights: [ProbeLight; MAX_PROBE_LIGHTS as usize],
}

/// The GPU probe's ray tree: `node_count` nodes were met (more than were kept when
/// `TREE_OVERFLOW` is set).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ProbeTree {
    pub node_count: u32,
    pub flags: u32,
    pub pad_a: u32,
    pub pad_b: u32,
    pub nodes: [ProbeNode; MAX_PROBE_NODES as usize],
}

/// One BVH node (glint-core builds them): a leaf when `count > 0` (primitive references
/// `left_first .. left_first + count`), else an interior node whose children are `left_first`
/// and `left_first + 1`. The GPU reads only the root so, as record 0 of its node buffer.
///
/// Aligned to its size, so that a pair of siblings stored from an even index is one 64-byte
/// cache line.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BvhNode {
    pub min: [f32; 3],
    pub left_first: u32,
    pub max: [f32; 3],
    pub count: u32,
}

const _: () = assert!(size_of::<BvhNode>() == 32);

/// The children of one interior node, as the GPU walks them (glint-core's `bvh::quantized`
/// builds and reads them). Each plane of a child's box is `origin + q · 2^e` on its axis, for
/// an 8-bit q and the axis's e: the product is exact in f32, so the one rounding is the sum's,
/// and a fused multiply-add gives the same value.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct QuantizedPair {
    /// The lower corner of the pair's box.
    pub origin: [f32; 3],
    /// The biased f32 exponent of each axis's step 2^e, in bytes 0, 1, 2 (byte 3 is 0).
    pub exponents: u32,
    /// Where the children are: `first` above PAIR_FIRST_SHIFT, then the left and the right
    /// child's leaf counts (NODE_REF_COUNT_BITS each; 0 for an interior node). A leaf left
    /// child holds references `first ..`, and a leaf right child follows it (or starts at
    /// `first` when the left child is interior); an interior left child's pair is the next
    /// record, and an interior right child's is the next record if the left child is a leaf,
    /// else `first`.
    pub children: u32,
    /// Per axis, the q of the left child's lower and upper plane, then the right child's, in
    /// bytes 0 to 3.
    pub planes: [u32; 3],
}

const _: () = assert!(size_of::<QuantizedPair>() == size_of::<BvhNode>());
