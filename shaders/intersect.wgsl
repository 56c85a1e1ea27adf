// Twin of crates/glint-core/src/cpu/intersect.rs: the nearest hit among the scene's
// primitives and the shadow transmittance, by brute force (primitive.wgsl tests one ray
// against one primitive).
#define_import_path glint::intersect

#import glint::scene_data::{GpuTriangle, MESH_HAS_NORMALS}
#import glint::bindings::{header, materials, spheres, planes, triangles, vertices, normals, meshes}
#import glint::ray::Ray
#import glint::primitive::{MaybeT, RayShear, intersect_plane, intersect_sphere, intersect_triangle, ray_shear, sphere_roots}

const PRIM_NONE: u32 = 0u;
const PRIM_SPHERE: u32 = 1u;
const PRIM_PLANE: u32 = 2u;
const PRIM_TRIANGLE: u32 = 3u;

struct Hit {
    t: f32,
    prim: u32,
    index: u32,
    bu: f32,
    bv: f32,
}

// The primitive a secondary ray leaves under skip_convex and robust (PRIM_NONE otherwise): not tested
// again, but for a sphere the ray goes into, whose far root alone counts.
struct Leaving {
    prim: u32,
    index: u32,
    inside: bool,
}

#ifdef SKIP_LEFT
fn is_leaving(leaving: Leaving, prim: u32, index: u32) -> bool {
    return leaving.prim == prim && leaving.index == index;
}

// Which roots of sphere `index` a ray leaving `leaving` may cross: both, none (the sphere it
// leaves into the outside) or the far one (the sphere it enters).
fn sphere_roots_counted(leaving: Leaving, index: u32) -> vec2<bool> {
    if is_leaving(leaving, PRIM_SPHERE, index) {
        return vec2<bool>(false, leaving.inside);
    }
    return vec2<bool>(true, true);
}
#endif

// intersect_sphere for sphere `index` of a ray leaving `leaving` (the CPU's rule).
fn intersect_sphere_leaving(leaving: Leaving, index: u32, center: vec3<f32>, radius: f32, power: f32, ray: Ray, t_min: f32, t_max: f32) -> MaybeT {
#ifdef SKIP_LEFT
    if is_leaving(leaving, PRIM_SPHERE, index) {
        let r = sphere_roots(center, radius, power, ray, t_min);
        return MaybeT(r.t_far, leaving.inside && r.ok && r.t_far > t_min && r.t_far < t_max);
    }
#endif
    return intersect_sphere(center, radius, power, ray, t_min, t_max);
}

// The rank of a kind in brute force's order (spheres, planes, triangles).
fn rank(prim: u32) -> u32 {
    return select(select(2u, 1u, prim == PRIM_PLANE), 0u, prim == PRIM_SPHERE);
}

// The place of a primitive in scene order among its kind: its index for spheres and planes,
// its `order` for triangles (which the BVH stores in leaf order).
fn tie_order(prim: u32, index: u32) -> u32 {
#ifdef TRIANGLES
    if prim == PRIM_TRIANGLE {
        return triangles[index].order;
    }
#endif
    return index;
}

// Whether a hit at t on (prim, index) replaces `best`: the smallest t, and of equal t the
// first in scene order (spheres, planes, triangles, each in the order of the scene file).
fn replaces(t: f32, prim: u32, index: u32, best: Hit) -> bool {
    if best.prim == PRIM_NONE {
        return true;
    }
    if t != best.t {
        return t < best.t;
    }
    let r = rank(prim);
    let br = rank(best.prim);
    return r < br || (r == br && tie_order(prim, index) < tie_order(best.prim, best.index));
}

// The bound passed to the primitive tests: t_max until a hit, then just above the best t, so
// that an equal t gets through their strict `t < t_max` and the tie rule decides.
fn bound(best: Hit, t_max: f32) -> f32 {
    if best.prim == PRIM_NONE {
        return t_max;
    }
    // The next f32 up. A camera ray's t may be negative (it is traced from t_min < 0), where
    // the next value up has the next smaller magnitude; +0 and −0 go to the least normal
    // positive value (a subnormal bound may be flushed to zero and refuse a tie at t = 0, as a
    // camera ray starting on a surface meets it).
    let bits = bitcast<u32>(best.t);
    if best.t > 0.0 {
        return bitcast<f32>(bits + 1u);
    }
    if best.t < 0.0 {
        return bitcast<f32>(bits - 1u);
    }
    return bitcast<f32>(0x00800000u);
}

#ifdef PLANES
// The nearest plane hit in (t_min, t_max) that replaces `best` (the tie rule), or `best`: the
// planes' loop of both walks (planes are unbounded, so the BVH holds none).
fn closest_plane(ray: Ray, t_min: f32, t_max: f32, leaving: Leaving, best_so_far: Hit) -> Hit {
    var best = best_so_far;
    for (var i = 0u; i < header.plane_count; i++) {
#ifdef SKIP_LEFT
        if is_leaving(leaving, PRIM_PLANE, i) {
            continue;
        }
#endif
        let no = planes[i].normal_offset;
        let h = intersect_plane(no.xyz, no.w, ray, t_min, bound(best, t_max));
        if h.ok && replaces(h.t, PRIM_PLANE, i, best) {
            best = Hit(h.t, PRIM_PLANE, i, 0.0, 0.0);
        }
    }
    return best;
}
#endif

// Nearest hit in (t_min, t_max); ties go to the first in scene order (`replaces`), as on the CPU.
fn closest_hit(ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> Hit {
    var best = Hit(t_max, PRIM_NONE, 0u, 0.0, 0.0);
#ifdef SPHERES
    for (var i = 0u; i < header.sphere_count; i++) {
        let cr = spheres[i].center_radius;
        let h = intersect_sphere_leaving(leaving, i, cr.xyz, cr.w, spheres[i].power, ray, t_min, best.t);
        if h.ok {
            best = Hit(h.t, PRIM_SPHERE, i, 0.0, 0.0);
        }
    }
#endif
#ifdef PLANES
    best = closest_plane(ray, t_min, t_max, leaving, best);
#endif
#ifdef TRIANGLES
    if header.triangle_count > 0u {
        let sh = ray_shear(ray.dir);
        for (var i = 0u; i < header.triangle_count; i++) {
#ifdef SKIP_LEFT
            if is_leaving(leaving, PRIM_TRIANGLE, i) {
                continue;
            }
#endif
            let v = triangle_corners(triangles[i]);
            let h = intersect_triangle(v[0], v[1], v[2], ray, sh, t_min, bound(best, t_max));
            if h.ok && replaces(h.t, PRIM_TRIANGLE, i, best) {
                best = Hit(h.t, PRIM_TRIANGLE, i, h.bu, h.bv);
            }
        }
    }
#endif
    return best;
}

// Multiplies the transmittance by one crossed surface's k_t (or zeroes it when shadows are
// not filtered).
fn cross_surface(tr: vec3<f32>, material: u32) -> vec3<f32> {
#ifdef FILTERED_SHADOWS
    return tr * materials[material].kt.xyz;
#else
    return vec3<f32>(0.0);
#endif
}

fn all_zero(v: vec3<f32>) -> bool {
    return v.x == 0.0 && v.y == 0.0 && v.z == 0.0;
}

#ifdef SPHERES
// `tr` times the k_t of each surface of sphere i (both roots, or those sphere_roots_counted
// leaves) crossed in (t_min, t_max).
fn sphere_transmittance(tr_in: vec3<f32>, i: u32, ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> vec3<f32> {
    var tr = tr_in;
    let cr = spheres[i].center_radius;
    let r = sphere_roots(cr.xyz, cr.w, spheres[i].power, ray, t_min);
    var counted = vec2<bool>(true, true);
#ifdef SKIP_LEFT
    counted = sphere_roots_counted(leaving, i);
#endif
    if r.ok {
        if counted.x && r.t_near > t_min && r.t_near < t_max {
            tr = cross_surface(tr, spheres[i].material);
            if all_zero(tr) {
                return tr;
            }
        }
        if counted.y && r.t_far > t_min && r.t_far < t_max {
            tr = cross_surface(tr, spheres[i].material);
        }
    }
    return tr;
}
#endif

#ifdef TRIANGLES
// `tr` times triangle i's k_t if the ray crosses it in (t_min, t_max).
fn triangle_transmittance(tr: vec3<f32>, i: u32, ray: Ray, sh: RayShear, t_min: f32, t_max: f32) -> vec3<f32> {
    let tri = triangles[i];
    let v = triangle_corners(tri);
    if intersect_triangle(v[0], v[1], v[2], ray, sh, t_min, t_max).ok {
        return cross_surface(tr, meshes[tri.mesh].material);
    }
    return tr;
}
#endif

#ifdef PLANES
// `tr` times the k_t of every plane crossed in (t_min, t_max), in index order, but the one the
// ray leaves.
fn planes_transmittance(tr_in: vec3<f32>, ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> vec3<f32> {
    var tr = tr_in;
    for (var i = 0u; i < header.plane_count; i++) {
#ifdef SKIP_LEFT
        if is_leaving(leaving, PRIM_PLANE, i) {
            continue;
        }
#endif
        let no = planes[i].normal_offset;
        if intersect_plane(no.xyz, no.w, ray, t_min, t_max).ok {
            tr = cross_surface(tr, planes[i].material);
            if all_zero(tr) {
                return tr;
            }
        }
    }
    return tr;
}
#endif

// Light passing from the ray origin to t_max: 0 behind an opaque occluder, the product of
// k_t over every surface crossed otherwise.
fn shadow_transmittance(ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> vec3<f32> {
    var tr = vec3<f32>(1.0);
#ifdef SPHERES
    for (var i = 0u; i < header.sphere_count; i++) {
        tr = sphere_transmittance(tr, i, ray, t_min, t_max, leaving);
        if all_zero(tr) {
            return tr;
        }
    }
#endif
#ifdef PLANES
    tr = planes_transmittance(tr, ray, t_min, t_max, leaving);
    if all_zero(tr) {
        return tr;
    }
#endif
#ifdef TRIANGLES
    if header.triangle_count > 0u {
        let sh = ray_shear(ray.dir);
        for (var i = 0u; i < header.triangle_count; i++) {
#ifdef SKIP_LEFT
            if is_leaving(leaving, PRIM_TRIANGLE, i) {
                continue;
            }
#endif
            tr = triangle_transmittance(tr, i, ray, sh, t_min, t_max);
            if all_zero(tr) {
                return tr;
            }
        }
    }
#endif
    return tr;
}

#ifdef TRIANGLES
// A triangle's three vertex positions from the shared vertex buffer.
fn triangle_corners(tri: GpuTriangle) -> array<vec3<f32>, 3> {
    return array<vec3<f32>, 3>(vertices[tri.va].xyz, vertices[tri.vb].xyz, vertices[tri.vc].xyz);
}

fn triangle_shading_normal(tri: GpuTriangle, bu: f32, bv: f32, ng: vec3<f32>) -> vec3<f32> {
    if (meshes[tri.mesh].flags & MESH_HAS_NORMALS) == 0u {
        return ng;
    }
    let n = (1.0 - bu - bv) * normals[tri.va].xyz + bu * normals[tri.vb].xyz + bv * normals[tri.vc].xyz;
    let len = length(n);
    if len > 0.0 {
        return n / len;
    }
    return ng;
}
#endif
