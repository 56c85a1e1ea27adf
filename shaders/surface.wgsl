// Twin of crates/glint-core/src/cpu/surface.rs: the surface a ray hits, and the directions a
// mirror and a refracting surface send it on in. Whitted's tree (trace.wgsl) and the paths
// (path.wgsl) share them.
#define_import_path glint::surface

#import glint::scene_data::{NO_HIT, EPS_ROBUST, UV_MESH, GpuTriangle, MESH_HAS_COLOURS}
#import glint::bindings::{header, spheres, planes, triangles, meshes, colours}
#import glint::ray::Ray
#import glint::intersect::{Hit, PRIM_NONE, PRIM_SPHERE, PRIM_PLANE, PRIM_TRIANGLE, triangle_corners, triangle_shading_normal}
#import glint::primitive::{sphere_surface_point, triangle_surface_point}
#import glint::shade::Surface
#ifdef TEXTURES
#import glint::texture::{planar_axis, planar_uv}
#ifdef TRIANGLES
#import glint::texture::{triangle_uv, triangle_uv_origin}
#endif
#endif

#ifdef VERTEX_COLOURS
// Interpolated with the barycentrics of the shading normal; exactly white for a mesh without
// vertex colours.
fn triangle_colour(tri: GpuTriangle, bu: f32, bv: f32) -> vec3<f32> {
    if (meshes[tri.mesh].flags & MESH_HAS_COLOURS) == 0u {
        return vec3<f32>(1.0);
    }
    return (1.0 - bu - bv) * colours[tri.va].xyz + bu * colours[tri.vb].xyz + bv * colours[tri.vc].xyz;
}
#endif

// The surface at a hit. Texture coordinates are computed only under TEXTURES, else zero;
// vertex colours only under VERTEX_COLOURS, else white.
fn surface_at(ray: Ray, hit: Hit) -> Surface {
    let p = ray.origin + hit.t * ray.dir;
    let robust = header.epsilon_mode == EPS_ROBUST;
#ifdef SPHERES
    if hit.prim == PRIM_SPHERE {
        let s = spheres[hit.index];
        let c = s.center_radius.xyz;
        let ng = normalize(p - c);
        let p_surface = select(p, sphere_surface_point(p, c, s.center_radius.w, s.power, ng), robust);
        var uv = vec2<f32>(0.0);
        var uv_origin = UV_MESH;
#ifdef TEXTURES
        uv = planar_uv(p, ng);
        uv_origin = planar_axis(ng);
#endif
        return Surface(p, p_surface, ng, ng, uv, uv_origin, vec3<f32>(1.0), s.material, s.object_id, PRIM_SPHERE, hit.index);
    }
#endif
#ifdef PLANES
    if hit.prim == PRIM_PLANE {
        let pl = planes[hit.index];
        let ng = pl.normal_offset.xyz;
        let p_surface = select(p, p - (dot(ng, p) - pl.normal_offset.w) * ng, robust);
        var uv = vec2<f32>(0.0);
        var uv_origin = UV_MESH;
#ifdef TEXTURES
        uv = planar_uv(p, ng);
        uv_origin = planar_axis(ng);
#endif
        return Surface(p, p_surface, ng, ng, uv, uv_origin, vec3<f32>(1.0), pl.material, pl.object_id, PRIM_PLANE, hit.index);
    }
#endif
#ifdef TRIANGLES
    let tri = triangles[hit.index];
    let v = triangle_corners(tri);
    let ng = normalize(cross(v[1] - v[0], v[2] - v[0]));
    let ns = triangle_shading_normal(tri, hit.bu, hit.bv, ng);
    var p_surface = p;
    if robust {
        p_surface = triangle_surface_point(p, v[0], v[1], v[2], hit.bu, hit.bv);
    }
    var uv = vec2<f32>(0.0);
    var uv_origin = UV_MESH;
#ifdef TEXTURES
    uv = triangle_uv(tri, hit.bu, hit.bv, p, ng);
    uv_origin = triangle_uv_origin(tri, ng);
#endif
    var colour = vec3<f32>(1.0);
#ifdef VERTEX_COLOURS
    colour = triangle_colour(tri, hit.bu, hit.bv);
#endif
    let mesh = meshes[tri.mesh];
    return Surface(p, p_surface, ng, ns, uv, uv_origin, colour, mesh.material, mesh.object_id, PRIM_TRIANGLE, hit.index);
#else
    return Surface(p, p, vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec2<f32>(0.0), UV_MESH, vec3<f32>(1.0), 0u, NO_HIT, PRIM_NONE, 0u);
#endif
}

// Refraction direction by Snell's law for unit d and unit n facing the incoming ray, with
// eta = n_from / n_to. xyz: the direction; w: 1 if refracted, 0 under total internal
// reflection (WGSL has no Option).
fn refract_dir(d: vec3<f32>, n: vec3<f32>, eta: f32) -> vec4<f32> {
    let cos_i = -dot(d, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(normalize(eta * d + (eta * cos_i - sqrt(k)) * n), 1.0);
}

// Mirror direction R = D − 2(D·N)N.
fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return normalize(d - 2.0 * dot(d, n) * n);
}

// The largest channel of a path weight or colour: what the bailout and Russian roulette judge.
fn max_channel(v: vec3<f32>) -> f32 {
    return max(max(v.x, v.y), v.z);
}
