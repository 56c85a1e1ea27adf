//! CPU twin of `shaders/primitive.wgsl`: one ray against one primitive (sphere, plane,
//! triangle), and the hit point moved onto its surface for the robust offset.

use glam::{DVec3, Vec3Swizzles};

use super::{FAR, Ray};

/// |n·d| below this counts as parallel to a plane: no division by (almost) zero, on either
/// tracer. A ray this close to parallel would hit the plane ~1e12 units away.
pub const PLANE_PARALLEL_COS: f64 = 1e-12;

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

/// |o − C|² − r² with the smaller error bound (twin of primitive.wgsl's, which also returns
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
/// (twin of primitive.wgsl's): 16× (4 bits), so that ordinary scenes keep the usual form.
pub const FORM_MARGIN: f64 = 16.0;

/// The hit point `p` moved onto the sphere for the robust offset (twin of primitive.wgsl's):
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
