// Twin of crates/glint-core/src/cpu/emitter.rs: the emissive primitives next-event estimation
// samples, each named as path.wgsl reads it from the `emitters` buffer the host fills with
// Emitters::gpu_words (a sphere's index, or a triangle's PRIM_REF_TRIANGLE | index).
#define_import_path glint::emitter

#import glint::scene_data::{PRIM_REF_TRIANGLE, PRIM_REF_INDEX}
#import glint::bindings::{spheres, triangles}
#import glint::intersect::{Hit, PRIM_SPHERE, PRIM_TRIANGLE, triangle_corners}
#import glint::sample::{to_world, cone_versin, uniform_cone, uniform_cone_pdf, uniform_triangle, area_to_solid_angle}

// What of_hit gives for a plane or a miss: nothing next-event estimation samples.
const NO_EMITTER: u32 = 0xffffffffu;

// The emitter a hit is on (a sphere's index, or PRIM_REF_TRIANGLE | a triangle's), if its
// material emits; NO_EMITTER for planes, which are not sampled, and misses.
fn of_hit(hit: Hit) -> u32 {
    if hit.prim == PRIM_SPHERE {
        return hit.index;
    }
    if hit.prim == PRIM_TRIANGLE {
        return PRIM_REF_TRIANGLE | hit.index;
    }
    return NO_EMITTER;
}

// The density per unit solid angle at p with which next-event estimation picks the point q
// (geometric normal ng_q) of emitter e, one of count.
fn emitter_pdf(e: u32, count: u32, p: vec3<f32>, q: vec3<f32>, ng_q: vec3<f32>) -> f32 {
    let pick = 1.0 / f32(count);
#ifdef SPHERES
    if (e & PRIM_REF_TRIANGLE) == 0u {
        let cone = sphere_cone(e, p);
        if !cone.outside {
            return 0.0;
        }
        return pick * uniform_cone_pdf(cone.versin);
    }
#endif
#ifdef TRIANGLES
    let v = triangle_corners(triangles[e & PRIM_REF_INDEX]);
    let area = 0.5 * length(cross(v[1] - v[0], v[2] - v[0]));
    let to_q = q - p;
    let dist = length(to_q);
    // A ray met the emitter where it left (ε = 0 on a triangle's edge): no density.
    if dist == 0.0 {
        return 0.0;
    }
    return pick * area_to_solid_angle(1.0 / area, dist, dot(ng_q, to_q / dist));
#else
    return 0.0;
#endif
}

// A direction from p towards a point of emitter e (xyz), drawn as emitter_pdf says; w is 0
// where there is none (p inside the sphere, or on the triangle's point).
fn sample_emitter(e: u32, p: vec3<f32>, u: vec2<f32>) -> vec4<f32> {
#ifdef SPHERES
    if (e & PRIM_REF_TRIANGLE) == 0u {
        let cone = sphere_cone(e, p);
        if !cone.outside {
            return vec4<f32>(0.0);
        }
        return vec4<f32>(to_world(cone.axis, uniform_cone(u, cone.versin)), 1.0);
    }
#endif
#ifdef TRIANGLES
    let v = triangle_corners(triangles[e & PRIM_REF_INDEX]);
    let bary = uniform_triangle(u);
    let q = v[0] + bary.x * (v[1] - v[0]) + bary.y * (v[2] - v[0]);
    let len = length(q - p);
    if len > 0.0 {
        return vec4<f32>((q - p) / len, 1.0);
    }
#endif
    return vec4<f32>(0.0);
}

// The cone of directions from p that meet sphere i: its unit axis and its versine (1 − cos of
// its half-angle); outside is false where p is inside, or on, the sphere (it sees only back
// faces, which do not emit), and then axis and versin mean nothing.
struct SphereCone {
    axis: vec3<f32>,
    versin: f32,
    outside: bool,
}

#ifdef SPHERES
fn sphere_cone(i: u32, p: vec3<f32>) -> SphereCone {
    let cr = spheres[i].center_radius;
    let to_c = cr.xyz - p;
    let d2 = dot(to_c, to_c);
    if d2 <= cr.w * cr.w {
        return SphereCone(vec3<f32>(0.0), 0.0, false);
    }
    return SphereCone(to_c / sqrt(d2), cone_versin(cr.w * cr.w / d2), true);
}
#endif
