// Twin of crates/glint-core/src/cpu/primitive.rs: one ray against one primitive (sphere,
// plane, triangle), and the hit point moved onto its surface for the robust offset.
#define_import_path glint::primitive

#import glint::ray::{Ray, FAR}

const PLANE_PARALLEL_COS: f32 = 1e-12;

// A root, or none (WGSL has no Option).
struct MaybeT {
    t: f32,
    ok: bool,
}

struct SphereRoots {
    t_near: f32,
    t_far: f32,
    ok: bool,
}

// How much better an alternative form's error bound must be before it replaces the usual one:
// 16× (4 bits), so that only the cases where f32 cancels change, never ordinary scenes.
const FORM_MARGIN: f32 = 16.0;

// c = |o − C|² − r² (x) and its error bound (y). Directly it loses ≈ ε·(|f|² + r²): all of it
// for an origin 1 above a sphere of radius 1e6 (c ≈ 2e6 against |f|² ≈ 1e12). power + o·(o − 2C)
// is the same c and loses ≈ ε·(|power| + |o|·|o − 2C|): little for an origin near the frame's
// origin. The form whose bound is FORM_MARGIN times smaller is taken.
fn sphere_c(center: vec3<f32>, radius: f32, power: f32, origin: vec3<f32>, f: vec3<f32>) -> vec2<f32> {
    let rr = radius * radius;
    let ff = dot(f, f);
    let o2c = origin - 2.0 * center;
    let err_direct = ff + rr;
    let err_power = abs(power) + dot(abs(origin), abs(o2c));
    if FORM_MARGIN * err_power < err_direct {
        return vec2<f32>(power + dot(origin, o2c), err_power);
    }
    return vec2<f32>(ff - rr, err_direct);
}

// Haines et al., Ray Tracing Gems ch. 7: discriminant from the perpendicular distance, the
// smaller root from c/q. Two more forms where f32 would cancel (docs/numerics.md,
// "Cancellation in the f32 twins"): c as the power form, which the f64 twin also chooses by the
// same bound (sphere_c), and b² − a·c for the discriminant, which the f64 twin leaves out (its
// first form loses nothing f64 needs). `power` is the sphere's precomputed |C|² − r² (GpuSphere::power).
fn sphere_roots(center: vec3<f32>, radius: f32, power: f32, ray: Ray, t_min: f32) -> SphereRoots {
    let f = ray.origin - center;
    let a = dot(ray.dir, ray.dir);
    let b = -dot(f, ray.dir);
    let rr = radius * radius;
    let ce = sphere_c(center, radius, power, ray.origin, f);
    let c = ce.x;
    // Both roots behind an origin outside (not for a camera ray, traced from t_min < 0).
    if c > 0.0 && b < 0.0 && t_min >= 0.0 {
        return SphereRoots(0.0, 0.0, false);
    }
    // a·Δ as a·(r² − |l|²), which loses ≈ ε·a·r², or as b² − a·c, which loses ≈ ε·(b² + a·δc):
    // the latter where the ray leaves a point near a huge sphere's surface steeply (b² ≪ r²).
    let l = f + (b / a) * ray.dir;
    let textbook = FORM_MARGIN * (b * b + a * ce.y) < a * rr;
    let ad = select(a * (rr - dot(l, l)), b * b - a * c, textbook);
    if ad < 0.0 {
        return SphereRoots(0.0, 0.0, false);
    }
    let q = b + select(-1.0, 1.0, b >= 0.0) * sqrt(ad);
    if q == 0.0 {
        return SphereRoots(0.0, 0.0, true);
    }
    let t_near = c / q;
    let t_far = q / a;
    return SphereRoots(min(t_near, t_far), max(t_near, t_far), true);
}

fn intersect_sphere(center: vec3<f32>, radius: f32, power: f32, ray: Ray, t_min: f32, t_max: f32) -> MaybeT {
    let r = sphere_roots(center, radius, power, ray, t_min);
    if !r.ok {
        return MaybeT(0.0, false);
    }
    if r.t_near > t_min && r.t_near < t_max {
        return MaybeT(r.t_near, true);
    }
    if r.t_far > t_min && r.t_far < t_max {
        return MaybeT(r.t_far, true);
    }
    return MaybeT(0.0, false);
}

// The hit point p moved onto the sphere for the robust offset. W&B's C + r·n carries the
// rounding of |C| + r: ulp(1e6) = 0.06 on a sphere of radius 1e6, enough to start a shadow
// ray below its surface. p − h·n with the height h = (power + p·(p − 2C)) / (|p − C| + r)
// carries ≈ ε·(|p| + (|power| + |p|·|p − 2C|)/(2r)) instead: used where that is far smaller.
fn sphere_surface_point(p: vec3<f32>, center: vec3<f32>, radius: f32, power: f32, ng: vec3<f32>) -> vec3<f32> {
    let p2c = p - 2.0 * center;
    let err_projection = length(center) + radius;
    let err_height = length(p) + (abs(power) + dot(abs(p), abs(p2c))) / (2.0 * radius);
    if FORM_MARGIN * err_height < err_projection {
        let h = (power + dot(p, p2c)) / (length(p - center) + radius);
        return p - h * ng;
    }
    return center + radius * ng;
}

fn intersect_plane(n: vec3<f32>, d: f32, ray: Ray, t_min: f32, t_max: f32) -> MaybeT {
    let denom = dot(n, ray.dir);
    if abs(denom) < PLANE_PARALLEL_COS {
        return MaybeT(0.0, false);
    }
    let t = (d - dot(n, ray.origin)) / denom;
    return MaybeT(t, t > t_min && t < t_max);
}

struct RayShear {
    kx: u32,
    ky: u32,
    kz: u32,
    s: vec3<f32>,
}

fn ray_shear(dir: vec3<f32>) -> RayShear {
    let a = abs(dir);
    var kz = 2u;
    if a.x >= a.y && a.x >= a.z {
        kz = 0u;
    } else if a.y >= a.z {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    if dir[kz] < 0.0 {
        let tmp = kx;
        kx = ky;
        ky = tmp;
    }
    return RayShear(kx, ky, kz, vec3<f32>(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]));
}

struct TriangleHit {
    t: f32,
    bu: f32,
    bv: f32,
    ok: bool,
}

// a + b + c, smallest magnitude first: independent of the order and common sign of the terms,
// so a triangle and a copy with its vertices rotated or reversed get bit-identical t.
fn sum_by_magnitude(a: f32, b: f32, c: f32) -> f32 {
    var x = a;
    var y = b;
    var z = c;
    if abs(x) > abs(y) {
        let t = x;
        x = y;
        y = t;
    }
    if abs(y) > abs(z) {
        let t = y;
        y = z;
        z = t;
    }
    if abs(x) > abs(y) {
        let t = x;
        x = y;
        y = t;
    }
    return (x + y) + z;
}

// Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection", JCGT 2013 (without the
// double-precision fallback, which WGSL cannot express; edges stay watertight).
fn intersect_triangle(va: vec3<f32>, vb: vec3<f32>, vc: vec3<f32>, ray: Ray, sh: RayShear, t_min: f32, t_max: f32) -> TriangleHit {
    let miss = TriangleHit(0.0, 0.0, 0.0, false);
    let a = va - ray.origin;
    let b = vb - ray.origin;
    let c = vc - ray.origin;
    let ax = a[sh.kx] - sh.s.x * a[sh.kz];
    let ay = a[sh.ky] - sh.s.y * a[sh.kz];
    let bx = b[sh.kx] - sh.s.x * b[sh.kz];
    let by = b[sh.ky] - sh.s.y * b[sh.kz];
    let cx = c[sh.kx] - sh.s.x * c[sh.kz];
    let cy = c[sh.ky] - sh.s.y * c[sh.kz];
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return miss;
    }
    let det = sum_by_magnitude(u, v, w);
    if det == 0.0 {
        return miss;
    }
    let du = u * (sh.s.z * a[sh.kz]);
    let dv = v * (sh.s.z * b[sh.kz]);
    let dw = w * (sh.s.z * c[sh.kz]);
    let inv = 1.0 / det;
    var t = sum_by_magnitude(du, dv, dw) * inv;
    // The corners' depths cancel for a triangle far larger than its distance from the origin
    // (the CPU twin says more): the plane's form where its bound is FORM_MARGIN times smaller.
    let err_watertight = sum_by_magnitude(abs(du), abs(dv), abs(dw)) * abs(inv);
    if err_watertight > 2.0 * FORM_MARGIN * abs(t) {
        let plane = plane_t(triangle_plane(va, vb, vc), ray, err_watertight);
        if plane.ok {
            t = plane.t;
        }
    }
    if !(t > t_min && t < t_max) {
        return miss;
    }
    return TriangleHit(t, v * inv, w * inv, true);
}

// A triangle's plane: the corner first in (x, y, z) order, the normal of the corners in that
// order (the same for copies with rotated or reversed corners) and its error bound over ε.
struct TrianglePlane {
    corner: vec3<f32>,
    normal: vec3<f32>,
    err_normal: vec3<f32>,
}

fn lex_less(p: vec3<f32>, q: vec3<f32>) -> bool {
    return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && p.z < q.z)));
}

fn triangle_plane(va: vec3<f32>, vb: vec3<f32>, vc: vec3<f32>) -> TrianglePlane {
    var a = va;
    var b = vb;
    var c = vc;
    if lex_less(b, a) {
        let x = a;
        a = b;
        b = x;
    }
    if lex_less(c, b) {
        let x = b;
        b = c;
        c = x;
    }
    if lex_less(b, a) {
        let x = a;
        a = b;
        b = x;
    }
    let e1 = b - a;
    let e2 = c - a;
    let sizes = abs(e1.yzx * e2.zxy) + abs(e1.zxy * e2.yzx);
    return TrianglePlane(a, cross(e1, e2), 3.0 * sizes);
}

// t where the ray meets the plane, where its bound is FORM_MARGIN times below err_watertight.
fn plane_t(plane: TrianglePlane, ray: Ray, err_watertight: f32) -> MaybeT {
    let a = plane.corner - ray.origin;
    let n = plane.normal;
    let num = dot(n, a);
    let den = dot(n, ray.dir);
    let err_num = dot(abs(a), plane.err_normal) + 2.0 * dot(abs(n), abs(a));
    let err_den = dot(abs(ray.dir), plane.err_normal) + 2.0 * dot(abs(n), abs(ray.dir));
    // Only where den's sign is sure and t stays below FAR, judged before dividing: WGSL
    // promises nothing of infinities or NaN (the CPU twin says more).
    if !(err_den * F32_EPSILON < abs(den) && abs(num) * (1.0 / FAR) < abs(den)) {
        return MaybeT(0.0, false);
    }
    let t = num / den;
    let err = err_num / abs(den) + abs(t) * (err_den / abs(den));
    return MaybeT(t, FORM_MARGIN * err < err_watertight);
}

// f32's machine epsilon, 2^-23: the unit of the error bounds above.
const F32_EPSILON: f32 = 1.1920929e-7;

// The hit point p moved onto the triangle for the robust offset: the corners interpolated at
// (bu, bv), or where that carries their rounding (ε·|v|: 6 units on a quad of half-size 1e8)
// and p's height above the plane far less, p moved along the normal by it.
fn triangle_surface_point(p: vec3<f32>, va: vec3<f32>, vb: vec3<f32>, vc: vec3<f32>, bu: f32, bv: f32) -> vec3<f32> {
    let bw = 1.0 - bu - bv;
    let ones = vec3<f32>(1.0);
    let err_barycentric = dot(abs(bw) * abs(va) + abs(bu) * abs(vb) + abs(bv) * abs(vc), ones);
    let err_p = dot(abs(p), ones);
    if err_barycentric > FORM_MARGIN * err_p {
        let plane = triangle_plane(va, vb, vc);
        // Scaled by its largest component: |n|² of a triangle 1e9 wide would overflow f32.
        let m = abs(plane.normal);
        let scale = max(m.x, max(m.y, m.z));
        let n = plane.normal / scale;
        let err_n = plane.err_normal / scale;
        let f = p - plane.corner;
        let nn = dot(n, n);
        let err_height = (dot(abs(f), err_n) + 2.0 * dot(abs(n), abs(f))) / sqrt(nn);
        if scale > 0.0 && FORM_MARGIN * (err_height + err_p) < err_barycentric {
            return p - (dot(n, f) / nn) * n;
        }
    }
    return bw * va + bu * vb + bv * vc;
}
