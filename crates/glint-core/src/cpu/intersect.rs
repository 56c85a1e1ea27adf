//! CPU twin of `shaders/intersect.wgsl`: ray/primitive intersection, nearest hit and shadow
//! transmittance.

use glam::{DVec3, Vec3Swizzles};

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

/// |n·d| below this counts as parallel to a plane: no division by (almost) zero, on either
/// tracer. A ray this close to parallel would hit the plane ~1e12 units away.
pub const PLANE_PARALLEL_COS: f64 = 1e-12;

/// Largest ray parameter; also the reach of shadow rays towards directional lights. Finite
/// so that the f32 tracer never computes with infinities.
pub const FAR: f64 = 1e30;

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

/// Both roots t0 ≤ t1 of a ray/sphere intersection (`None` when it misses or both roots are
/// behind an origin outside the sphere), after Haines et al., "Precision
/// Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): the discriminant from
/// the perpendicular distance, and the smaller root from c/q so neither loses digits. And c
/// itself as the power of the origin, |C|² − r² + o·(o − 2C), where |f|² − r² would lose far
/// more (an origin near the surface of a sphere much larger than its distance to the origin:
/// f64 rounds f = o − C to ulp(|C|), 1.2e-10 at 1e6, more than the robust offset near the
/// origin, 2^-45 — shadow rays from a planet's ground started inside it, stiff case 18).
// Always inlined, as the sphere tests calling it: called, a DVec3 argument goes through memory
// as three f64 stores read back by 16-byte loads, a store-forwarding stall that cost a fifth
// of a Whitted render.
#[inline(always)]
pub fn sphere_roots(center: DVec3, radius: f64, ray: &Ray, t_min: f64) -> Option<(f64, f64)> {
    let f = ray.origin - center;
    let a = ray.dir.dot(ray.dir);
    let b = -f.dot(ray.dir);
    // The miss test first: most spheres a ray is tested against it misses, and the miss does
    // not need c (the costlier of the two), so c is formed only for a ray that meets the
    // sphere's line. Both tests only return `None`, so their order changes no result.
    let l = f + (b / a) * ray.dir;
    let disc = radius * radius - l.dot(l);
    if disc < 0.0 {
        return None;
    }
    let c = sphere_c(center, radius, ray.origin, f);
    if c > 0.0 && b < 0.0 && t_min >= 0.0 {
        // Origin outside and centre behind it: both roots are negative (product c/a > 0,
        // sum 2b/a < 0), and so are their computed values. Cheaper than the square root. Not
        // for a camera ray, traced from t_min < 0 (the eye behind the anchor's plane).
        return None;
    }
    let q = b + if b >= 0.0 { 1.0 } else { -1.0 } * (a * disc).sqrt();
    if q == 0.0 {
        // Tangent at the origin: the double root is t = 0.
        return Some((0.0, 0.0));
    }
    let t0 = c / q;
    let t1 = q / a;
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// |o − C|² − r² with the smaller error bound (twin of intersect.wgsl's, which also returns
/// the bound for its choice of discriminant): directly, ≈ ε·(|f|² + r²), or as the power |C|² − r² (exact squares of the
/// stored f32 values) plus o·(o − 2C), ≈ ε·(|power| + |o|·|o − 2C|), by FORM_MARGIN.
#[inline(always)]
pub fn sphere_c(center: DVec3, radius: f64, origin: DVec3, f: DVec3) -> f64 {
    let rr = radius * radius;
    let ff = f.dot(f);
    let power = center.dot(center) - rr;
    let o2c = origin - 2.0 * center;
    if FORM_MARGIN * (power.abs() + origin.abs().dot(o2c.abs())) < ff + rr { power + origin.dot(o2c) } else { ff - rr }
}

/// How much better an alternative form's error bound must be before it replaces the usual one
/// (twin of intersect.wgsl's): 16× (4 bits), so that ordinary scenes keep the usual form.
pub const FORM_MARGIN: f64 = 16.0;

/// The hit point `p` moved onto the sphere for the robust offset (twin of intersect.wgsl's):
/// W&B's C + r·n carries the rounding of |C| + r (on a sphere of radius 1e6, 1.2e-10 in f64 —
/// enough to start a shadow ray below the surface, where the offset near the origin is 2^-45);
/// where p − h·n with h = (|C|² − r² + p·(p − 2C)) / (|p − C| + r) carries far less, that. The
/// power |C|² − r² is computed here in f64 from the stored values (the f32 twin reads it
/// precomputed, `GpuSphere::power`).
pub fn sphere_surface_point(p: DVec3, center: DVec3, radius: f64, ng: DVec3) -> DVec3 {
    let power = center.dot(center) - radius * radius;
    let p2c = p - 2.0 * center;
    let err_projection = center.length() + radius;
    let err_height = p.length() + (power.abs() + p.abs().dot(p2c.abs())) / (2.0 * radius);
    if FORM_MARGIN * err_height < err_projection {
        let h = (power + p.dot(p2c)) / ((p - center).length() + radius);
        return p - h * ng;
    }
    center + radius * ng
}

/// Nearest sphere root inside (t_min, t_max).
#[inline(always)]
pub fn intersect_sphere(center: DVec3, radius: f64, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let (t0, t1) = sphere_roots(center, radius, ray, t_min)?;
    if t0 > t_min && t0 < t_max {
        Some(t0)
    } else if t1 > t_min && t1 < t_max {
        Some(t1)
    } else {
        None
    }
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

/// The plane n·x = d; rays (almost) parallel to it miss.
#[inline]
pub fn intersect_plane(n: DVec3, d: f64, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let denom = n.dot(ray.dir);
    if denom.abs() < PLANE_PARALLEL_COS {
        return None;
    }
    let t = (d - n.dot(ray.origin)) / denom;
    (t > t_min && t < t_max).then_some(t)
}

/// Per-ray set-up of the watertight triangle test: the axis permutation and shear that map
/// the ray onto +z.
#[derive(Clone, Copy, Debug)]
pub struct RayShear {
    pub kx: usize,
    pub ky: usize,
    pub kz: usize,
    /// (d_kx / d_kz, d_ky / d_kz, 1 / d_kz).
    pub s: DVec3,
}

pub fn ray_shear(dir: DVec3) -> RayShear {
    let a = dir.abs();
    let kz = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let mut kx = (kz + 1) % 3;
    let mut ky = (kx + 1) % 3;
    if dir[kz] < 0.0 {
        std::mem::swap(&mut kx, &mut ky);
    }
    RayShear { kx, ky, kz, s: DVec3::new(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]) }
}

/// a + b + c, added smallest magnitude first. The sum then does not depend on the order of the
/// terms or on their common sign, so a triangle and a copy of it with its vertices rotated or
/// reversed get bit-identical t (coplanar duplicates tie, and the first one wins).
pub fn sum_by_magnitude(a: f64, b: f64, c: f64) -> f64 {
    let (mut x, mut y, mut z) = (a, b, c);
    if x.abs() > y.abs() {
        std::mem::swap(&mut x, &mut y);
    }
    if y.abs() > z.abs() {
        std::mem::swap(&mut y, &mut z);
    }
    if x.abs() > y.abs() {
        std::mem::swap(&mut x, &mut y);
    }
    (x + y) + z
}

/// Watertight ray/triangle test (Woop, Benthin & Wald, JCGT 2013): edges shared by two
/// triangles are never missed by both. Returns (t, bu, bv); degenerate triangles never hit.
#[inline(always)]
pub fn intersect_triangle(
    va: DVec3,
    vb: DVec3,
    vc: DVec3,
    ray: &Ray,
    shear: &RayShear,
    t_min: f64,
    t_max: f64,
) -> Option<(f64, f64, f64)> {
    let RayShear { kx, ky, kz, s } = *shear;
    let (sx, sy, sz) = (s.x, s.y, s.z);
    // Arrays, not DVec3: indexing a DVec3 by a run-time axis is a branch per access.
    let a = (va - ray.origin).to_array();
    let b = (vb - ray.origin).to_array();
    let c = (vc - ray.origin).to_array();
    let ax = a[kx] - sx * a[kz];
    let ay = a[ky] - sy * a[kz];
    let bx = b[kx] - sx * b[kz];
    let by = b[ky] - sy * b[kz];
    let cx = c[kx] - sx * c[kz];
    let cy = c[ky] - sy * c[kz];
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = sum_by_magnitude(u, v, w);
    if det == 0.0 {
        return None;
    }
    let (du, dv, dw) = (u * (sz * a[kz]), v * (sz * b[kz]), w * (sz * c[kz]));
    let inv = 1.0 / det;
    let mut t = sum_by_magnitude(du, dv, dw) * inv;
    // t sums the corners' depths weighted by the edge functions, which cancel for a triangle
    // far larger than its distance from the ray's origin (a ground quad of half-size 1e8 under
    // an eye 2 above it: t off by ε·1e8). The plane's form is taken where its bound is
    // FORM_MARGIN times smaller; it never is below 2|t|, so it is not even formed unless the
    // watertight bound exceeds that many times |t| (a huge triangle, or a ray meeting a wall at
    // a small t near a corner). The bound is summed as t is, so that a copy with rotated
    // corners makes the same choice.
    let err_watertight = sum_by_magnitude(du.abs(), dv.abs(), dw.abs()) * inv.abs();
    if err_watertight > 2.0 * FORM_MARGIN * t.abs()
        && let Some(t_plane) = plane_t(&triangle_plane(va, vb, vc), ray, err_watertight)
    {
        t = t_plane;
    }
    (t > t_min && t < t_max).then_some((t, v * inv, w * inv))
}

/// A triangle's plane for the forms that replace the watertight t and the barycentric
/// re-projection where those cancel: the corner first in (x, y, z) order, the normal
/// (b − a) × (c − a) of the corners in that order (so that copies of a triangle with its
/// corners rotated or reversed get the same plane, bit for bit) and its error bound per
/// component, over ε.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TrianglePlane {
    pub corner: DVec3,
    pub normal: DVec3,
    pub err_normal: DVec3,
}

/// Whether `p` comes before `q` in (x, y, z) order.
fn lex_less(p: DVec3, q: DVec3) -> bool {
    p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && p.z < q.z)))
}

pub fn triangle_plane(va: DVec3, vb: DVec3, vc: DVec3) -> TrianglePlane {
    let (mut a, mut b, mut c) = (va, vb, vc);
    if lex_less(b, a) {
        (a, b) = (b, a);
    }
    if lex_less(c, b) {
        (b, c) = (c, b);
    }
    if lex_less(b, a) {
        (a, b) = (b, a);
    }
    let (e1, e2) = (b - a, c - a);
    // The edges' rounding and the cross product's: each product's size, three times.
    let sizes = (e1.yzx() * e2.zxy()).abs() + (e1.zxy() * e2.yzx()).abs();
    TrianglePlane { corner: a, normal: e1.cross(e2), err_normal: 3.0 * sizes }
}

/// t where `ray` meets `plane`, n·(a − o) / n·d, where its error bound is FORM_MARGIN times
/// below `err_watertight` (the watertight t's, over ε): it loses what the normal does (none of
/// an axis-aligned ground's) and the rounding of a − o along it, not along the triangle.
pub fn plane_t(plane: &TrianglePlane, ray: &Ray, err_watertight: f64) -> Option<f64> {
    let a = plane.corner - ray.origin;
    let n = plane.normal;
    let (num, den) = (n.dot(a), n.dot(ray.dir));
    let err_num = a.abs().dot(plane.err_normal) + 2.0 * n.abs().dot(a.abs());
    let err_den = ray.dir.abs().dot(plane.err_normal) + 2.0 * n.abs().dot(ray.dir.abs());
    // Taken only where den's sign is sure (its bound, in units of the precision's ε, below it)
    // and t = num/den stays below FAR: judged before dividing, so that no infinity or NaN is
    // ever formed, which the f32 twin cannot compare with (WGSL promises nothing of them).
    if !(err_den * f64::EPSILON < den.abs() && num.abs() * (1.0 / FAR) < den.abs()) {
        return None;
    }
    let t = num / den;
    let err = err_num / den.abs() + t.abs() * (err_den / den.abs());
    (FORM_MARGIN * err < err_watertight).then_some(t)
}

/// The hit point `p` moved onto the triangle for the robust offset (barycentrics `bu`, `bv`):
/// W&B's interpolation of the corners carries their rounding, ε·|v| (6 units on a quad of
/// half-size 1e8, which starts shadow rays far off the point); where p moved along the
/// plane's normal by its height above it carries far less, that.
pub fn triangle_surface_point(p: DVec3, va: DVec3, vb: DVec3, vc: DVec3, bu: f64, bv: f64) -> DVec3 {
    let bw = 1.0 - bu - bv;
    let err_barycentric = (bw.abs() * va.abs() + bu.abs() * vb.abs() + bv.abs() * vc.abs()).element_sum();
    // The plane's bound is never below |p|: only a larger barycentric one is worth the plane.
    if err_barycentric > FORM_MARGIN * p.abs().element_sum() {
        let plane = triangle_plane(va, vb, vc);
        // Scaled by its largest component: |n|² of a triangle 1e9 wide would overflow f32.
        let scale = plane.normal.abs().max_element();
        let (n, err_n, f) = (plane.normal / scale, plane.err_normal / scale, p - plane.corner);
        let nn = n.dot(n);
        let err_height = (f.abs().dot(err_n) + 2.0 * n.abs().dot(f.abs())) / nn.sqrt();
        if scale > 0.0 && FORM_MARGIN * (err_height + p.abs().element_sum()) < err_barycentric {
            return p - (n.dot(f) / nn) * n;
        }
    }
    bw * va + bu * vb + bv * vc
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

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray { origin: DVec3::from(o), dir: DVec3::from(d).normalize() }
    }

    #[test]
    fn unit_sphere_a_million_units_away_is_found() {
        let r = ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let t = intersect_sphere(DVec3::new(0.0, 0.0, 1e6), 1.0, &r, 0.0, FAR).unwrap();
        assert_eq!(t, 1e6 - 1.0);
    }

    #[test]
    fn sphere_behind_the_ray_and_from_inside() {
        let r = ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        assert!(intersect_sphere(DVec3::new(0.0, 0.0, -5.0), 1.0, &r, 0.0, FAR).is_none());
        let t = intersect_sphere(DVec3::ZERO, 2.0, &r, 0.0, FAR).unwrap();
        assert!((t - 2.0).abs() < 1e-15);
    }

    #[test]
    fn plane_parallel_ray_misses_without_dividing() {
        let r = ray([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
        assert!(intersect_plane(DVec3::Y, 0.0, &r, 0.0, FAR).is_none());
        let down = ray([0.0, 1.0, 0.0], [0.0, -1.0, 0.0]);
        assert_eq!(intersect_plane(DVec3::Y, 0.0, &down, 0.0, FAR), Some(1.0));
    }

    #[test]
    fn triangle_barycentrics_and_shared_edge() {
        let (a, b, c, d) = (
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        );
        // A ray exactly through the shared diagonal a–c must hit at least one of the two.
        for k in 0..=20 {
            let s = -1.0 + 0.1 * f64::from(k);
            let r = ray([s, s, -1.0], [0.0, 0.0, 1.0]);
            let sh = ray_shear(r.dir);
            let h1 = intersect_triangle(a, b, c, &r, &sh, 0.0, FAR);
            let h2 = intersect_triangle(a, c, d, &r, &sh, 0.0, FAR);
            assert!(h1.is_some() || h2.is_some(), "hole at s = {s}");
        }
        let r = ray([0.5, -0.5, -1.0], [0.0, 0.0, 1.0]);
        let (t, bu, bv) = intersect_triangle(a, b, c, &r, &ray_shear(r.dir), 0.0, FAR).unwrap();
        assert_eq!(t, 1.0);
        let p = (1.0 - bu - bv) * a + bu * b + bv * c;
        assert!((p - DVec3::new(0.5, -0.5, 0.0)).length() < 1e-15);
    }

    #[test]
    fn degenerate_triangles_never_hit() {
        let r = ray([0.0, 0.0, -1.0], [0.0, 0.0, 1.0]);
        let sh = ray_shear(r.dir);
        let p = DVec3::ZERO;
        let cases = [
            (p, p, p),
            (DVec3::new(-1.0, 0.0, 0.0), DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0)),
            (DVec3::new(-1.0, 0.0, 0.0), DVec3::new(-1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 0.0)),
        ];
        for (a, b, c) in cases {
            assert!(intersect_triangle(a, b, c, &r, &sh, 0.0, FAR).is_none());
        }
    }
}
