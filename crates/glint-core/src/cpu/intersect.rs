//! CPU twin of `shaders/intersect.wgsl`: the nearest hit among a scene's primitives and the
//! shadow transmittance, by brute force (`primitive.rs` tests one ray against one primitive).

use glam::DVec3;

use super::primitive::{RayShear, intersect_plane, intersect_sphere, intersect_triangle, ray_shear, sphere_roots};
use super::{Ray, TraceContext, v3};
use crate::FlatScene;
use glint_types::layout::{GpuSphere, GpuTriangle, MESH_HAS_NORMALS, feature};

/// The kind of primitive a hit is on. WGSL stores it as the `PRIM_*` constants (checked by the
/// reflection test); the CPU matches on the enum, exhaustively.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Prim {
    Sphere = 1,
    Plane = 2,
    Triangle = 3,
}

/// No primitive: a miss (the GPU's `Hit::prim`, the ray cast's `HitRecord::prim`).
pub const PRIM_NONE: u32 = 0;
pub const PRIM_SPHERE: u32 = Prim::Sphere as u32;
pub const PRIM_PLANE: u32 = Prim::Plane as u32;
pub const PRIM_TRIANGLE: u32 = Prim::Triangle as u32;

/// The nearest intersection found so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub prim: Prim,
    pub index: u32,
    /// Barycentric weights of vertices b and c (triangles only).
    pub bu: f64,
    pub bv: f64,
}

/// The primitive a secondary ray leaves, under `EpsilonMode::SkipConvex` (the seed's "convex
/// objects do not test intersection if the ray's prior intersection is with that object") and
/// `EpsilonMode::Robust`.
/// A plane or triangle cannot be met again by a ray leaving it, nor a sphere by a ray leaving
/// into its outside: those are not tested at all. A ray entering a sphere meets it once more,
/// at its far side: of that sphere only the far root counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Leaving {
    /// `None` for camera rays and under the other ε strategies.
    pub prim: Option<Prim>,
    pub index: u32,
    /// The ray goes into the sphere it leaves.
    pub inside: bool,
}

impl Leaving {
    /// A ray that leaves no primitive (or whose strategy tests every one).
    pub const NONE: Self = Self { prim: None, index: 0, inside: false };
}

/// Whether (prim, index) is the primitive the ray leaves (only ever under `skip_convex` and
/// `robust`).
#[inline]
pub fn is_leaving(leaving: &Leaving, prim: Prim, index: u32) -> bool {
    leaving.prim == Some(prim) && leaving.index == index
}

/// `intersect_sphere` for sphere `index` of a ray leaving `leaving`: the sphere it leaves into
/// the outside is not tested, the one it enters only by its far root (its near root is the
/// point the ray starts from).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn intersect_sphere_leaving(
    ctx: &TraceContext,
    leaving: &Leaving,
    index: u32,
    center: DVec3,
    radius: f64,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
) -> Option<f64> {
    if ctx.has(feature::SKIP_LEFT) && is_leaving(leaving, Prim::Sphere, index) {
        if !leaving.inside {
            return None;
        }
        let (_, t1) = sphere_roots(center, radius, ray, t_min)?;
        return (t1 > t_min && t1 < t_max).then_some(t1);
    }
    intersect_sphere(center, radius, ray, t_min, t_max)
}

/// The rank of a kind in brute force's order.
pub fn rank(prim: Prim) -> u32 {
    match prim {
        Prim::Sphere => 0,
        Prim::Plane => 1,
        Prim::Triangle => 2,
    }
}

/// The place of a primitive in scene order among its kind: its index for spheres and planes,
/// its `order` for triangles (which the BVH stores in leaf order).
pub fn tie_order(scene: &FlatScene, prim: Prim, index: u32) -> u32 {
    match prim {
        Prim::Sphere | Prim::Plane => index,
        Prim::Triangle => scene.triangles[index as usize].order,
    }
}

/// Whether a hit at t on (prim, index) replaces `best`: the smallest t, and of equal t the
/// first in scene order (spheres, planes, triangles, each in the order of the scene file).
pub fn replaces(scene: &FlatScene, t: f64, prim: Prim, index: u32, best: &Option<Hit>) -> bool {
    match best {
        None => true,
        Some(b) => {
            t < b.t
                || (t == b.t
                    && (rank(prim), tie_order(scene, prim, index)) < (rank(b.prim), tie_order(scene, b.prim, b.index)))
        }
    }
}

/// The bound passed to the primitive tests: `t_max` until a hit, then just above the best t,
/// so that an equal t gets through their strict `t < t_max` and the tie rule decides.
pub fn bound(best: &Option<Hit>, t_max: f64) -> f64 {
    best.map_or(t_max, |b| b.t.next_up())
}

/// The nearest plane hit in (t_min, t_max) that replaces `best` (the tie rule), or `best`:
/// the planes' loop of both walks (planes are unbounded, so the BVH holds none).
pub fn closest_plane(
    ctx: &TraceContext,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    leaving: &Leaving,
    best: Option<Hit>,
) -> Option<Hit> {
    let scene = ctx.scene;
    let skip = ctx.has(feature::SKIP_LEFT);
    let mut best = best;
    for (i, p) in scene.planes.iter().enumerate() {
        let no = p.normal_offset;
        let i = i as u32;
        if skip && is_leaving(leaving, Prim::Plane, i) {
            continue;
        }
        if let Some(t) = intersect_plane(v3(no), f64::from(no[3]), ray, t_min, bound(&best, t_max))
            && replaces(scene, t, Prim::Plane, i, &best)
        {
            best = Some(Hit { t, prim: Prim::Plane, index: i, bu: 0.0, bv: 0.0 });
        }
    }
    best
}

/// The nearest hit in (t_min, t_max), testing every primitive. Ties go to the first in scene
/// order (`replaces`; spheres and planes are tested in that order, triangles are stored in the
/// BVH's), the same on both tracers. `cpu::bvh::closest_hit` finds the same hit through the
/// BVH; `cpu::walk` chooses.
pub fn closest_hit(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> Option<Hit> {
    let scene = ctx.scene;
    let mut best: Option<Hit> = None;
    let mut t_far = t_max;
    if ctx.has(feature::SPHERES) {
        for (i, s) in scene.spheres.iter().enumerate() {
            let cr = s.center_radius;
            let i = i as u32;
            if let Some(t) = intersect_sphere_leaving(ctx, leaving, i, v3(cr), f64::from(cr[3]), ray, t_min, t_far) {
                t_far = t;
                best = Some(Hit { t, prim: Prim::Sphere, index: i, bu: 0.0, bv: 0.0 });
            }
        }
    }
    let skip = ctx.has(feature::SKIP_LEFT);
    if ctx.has(feature::PLANES) {
        best = closest_plane(ctx, ray, t_min, t_max, leaving, best);
    }
    if ctx.has(feature::TRIANGLES) && !scene.triangles.is_empty() {
        let shear = ray_shear(ray.dir);
        for (i, tri) in scene.triangles.iter().enumerate() {
            let i = i as u32;
            if skip && is_leaving(leaving, Prim::Triangle, i) {
                continue;
            }
            let [a, b, c] = triangle_corners(scene, tri);
            if let Some((t, bu, bv)) = intersect_triangle(a, b, c, ray, &shear, t_min, bound(&best, t_max))
                && replaces(scene, t, Prim::Triangle, i, &best)
            {
                best = Some(Hit { t, prim: Prim::Triangle, index: i, bu, bv });
            }
        }
    }
    best
}

/// Whether every channel is zero.
pub fn all_zero(v: DVec3) -> bool {
    v == DVec3::ZERO
}

/// Multiplies the transmittance by one crossed surface's k_t (or zeroes it when shadows are
/// not filtered).
pub fn cross_surface(ctx: &TraceContext, tr: DVec3, material: u32) -> DVec3 {
    if ctx.has(feature::FILTERED_SHADOWS) { tr * v3(ctx.scene.materials[material as usize].kt) } else { DVec3::ZERO }
}

/// Which roots of sphere `index` a ray leaving `leaving` may cross: both, none (the sphere it
/// leaves into the outside) or the far one (the sphere it enters).
pub fn sphere_roots_counted(ctx: &TraceContext, leaving: &Leaving, index: u32) -> [bool; 2] {
    if ctx.has(feature::SKIP_LEFT) && is_leaving(leaving, Prim::Sphere, index) {
        [false, leaving.inside]
    } else {
        [true, true]
    }
}

/// `tr` times the k_t of each surface of sphere `index` (both roots, or those
/// `sphere_roots_counted` leaves) crossed in (t_min, t_max).
#[allow(clippy::too_many_arguments)]
pub fn sphere_transmittance(
    ctx: &TraceContext,
    tr: DVec3,
    index: u32,
    s: &GpuSphere,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    leaving: &Leaving,
) -> DVec3 {
    let cr = s.center_radius;
    let mut tr = tr;
    let counted = sphere_roots_counted(ctx, leaving, index);
    if let Some((t0, t1)) = sphere_roots(v3(cr), f64::from(cr[3]), ray, t_min) {
        for (t, counted) in [t0, t1].into_iter().zip(counted) {
            if counted && t > t_min && t < t_max {
                tr = cross_surface(ctx, tr, s.material);
                if all_zero(tr) {
                    return tr;
                }
            }
        }
    }
    tr
}

/// `tr` times the triangle's k_t if the ray crosses it in (t_min, t_max).
pub fn triangle_transmittance(
    ctx: &TraceContext,
    tr: DVec3,
    tri: &GpuTriangle,
    ray: &Ray,
    shear: &RayShear,
    t_min: f64,
    t_max: f64,
) -> DVec3 {
    let [a, b, c] = triangle_corners(ctx.scene, tri);
    match intersect_triangle(a, b, c, ray, shear, t_min, t_max) {
        Some(_) => cross_surface(ctx, tr, ctx.scene.meshes[tri.mesh as usize].material),
        None => tr,
    }
}

/// `tr` times the k_t of every plane crossed in (t_min, t_max), in index order, but the one the
/// ray leaves.
pub fn planes_transmittance(
    ctx: &TraceContext,
    tr: DVec3,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    leaving: &Leaving,
) -> DVec3 {
    let mut tr = tr;
    let skip = ctx.has(feature::SKIP_LEFT);
    for (i, p) in ctx.scene.planes.iter().enumerate() {
        if skip && is_leaving(leaving, Prim::Plane, i as u32) {
            continue;
        }
        let no = p.normal_offset;
        if intersect_plane(v3(no), f64::from(no[3]), ray, t_min, t_max).is_some() {
            tr = cross_surface(ctx, tr, p.material);
            if all_zero(tr) {
                return tr;
            }
        }
    }
    tr
}

/// Fraction of light that passes from the ray origin to t_max: 0 behind an opaque occluder,
/// the product of k_t over every surface crossed otherwise (a glass sphere is crossed twice),
/// testing every primitive. `cpu::bvh::shadow_transmittance` computes the same product through
/// the BVH; `cpu::walk` chooses.
pub fn shadow_transmittance(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> DVec3 {
    let scene = ctx.scene;
    let mut tr = DVec3::ONE;
    if ctx.has(feature::SPHERES) {
        for (i, s) in scene.spheres.iter().enumerate() {
            tr = sphere_transmittance(ctx, tr, i as u32, s, ray, t_min, t_max, leaving);
            if all_zero(tr) {
                return tr;
            }
        }
    }
    if ctx.has(feature::PLANES) {
        tr = planes_transmittance(ctx, tr, ray, t_min, t_max, leaving);
        if all_zero(tr) {
            return tr;
        }
    }
    if ctx.has(feature::TRIANGLES) && !scene.triangles.is_empty() {
        let shear = ray_shear(ray.dir);
        let skip = ctx.has(feature::SKIP_LEFT);
        for (i, tri) in scene.triangles.iter().enumerate() {
            if skip && is_leaving(leaving, Prim::Triangle, i as u32) {
                continue;
            }
            tr = triangle_transmittance(ctx, tr, tri, ray, &shear, t_min, t_max);
            if all_zero(tr) {
                return tr;
            }
        }
    }
    tr
}

/// A triangle's three vertex positions, widened from the shared f32 vertex buffer.
pub fn triangle_corners(scene: &FlatScene, tri: &GpuTriangle) -> [DVec3; 3] {
    [tri.va, tri.vb, tri.vc].map(|i| v3(scene.vertices[i as usize]))
}

/// Unit shading normal of a triangle hit: interpolated vertex normals where the mesh has them
/// (falling back to the geometric normal if they cancel), else the geometric normal.
pub fn triangle_shading_normal(scene: &FlatScene, tri: &GpuTriangle, bu: f64, bv: f64, ng: DVec3) -> DVec3 {
    if scene.meshes[tri.mesh as usize].flags & MESH_HAS_NORMALS == 0 {
        return ng;
    }
    let [na, nb, nc] = [tri.va, tri.vb, tri.vc].map(|i| v3(scene.normals[i as usize]));
    let n = (1.0 - bu - bv) * na + bu * nb + bv * nc;
    let len = n.length();
    if len > 0.0 { n / len } else { ng }
}
