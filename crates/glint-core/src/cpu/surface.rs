//! CPU twin of `shaders/surface.wgsl`: the surface a ray hits, and the directions a mirror and
//! a refracting surface send it on in. Whitted's tree (`trace.rs`) and the paths (`path.rs`)
//! share them.

use glam::{DVec2, DVec3};

use super::intersect::{Hit, Prim, triangle_corners, triangle_shading_normal};
use super::primitive::{sphere_surface_point, triangle_surface_point};
use super::shade::Surface;
use super::texture::{planar_axis, planar_uv, triangle_uv, triangle_uv_origin};
use super::{Ray, TraceContext, v3};
use glint_scene::EpsilonMode;
use glint_types::layout::{GpuTriangle, MESH_HAS_COLOURS, UV_MESH, feature};

/// The vertex colour at a triangle hit, interpolated with the barycentrics of the shading
/// normal; exactly white for a mesh without vertex colours.
pub fn triangle_colour(ctx: &TraceContext, tri: &GpuTriangle, bu: f64, bv: f64) -> DVec3 {
    let scene = ctx.scene;
    if scene.meshes[tri.mesh as usize].flags & MESH_HAS_COLOURS == 0 {
        return DVec3::ONE;
    }
    let [a, b, c] = [tri.va, tri.vb, tri.vc].map(|i| v3(scene.colours[i as usize]));
    (1.0 - bu - bv) * a + bu * b + bv * c
}

/// The surface at a hit. Texture coordinates are computed only when some material has a
/// texture (`feature::TEXTURES`), else they are zero; vertex colours only when some mesh has
/// them (`feature::VERTEX_COLOURS`), else white.
pub fn surface_at(ctx: &TraceContext, ray: &Ray, hit: &Hit) -> Surface {
    let scene = ctx.scene;
    let p = ray.origin + hit.t * ray.dir;
    let robust = ctx.epsilon_mode == EpsilonMode::Robust;
    let textures = ctx.has(feature::TEXTURES);
    // Planar texture coordinates relative to the frame's origin, whose own are each
    // texture's `planar_u`/`planar_v` (placed in f64 where the scene is stored, `texture_table::planar_origins`, and moved by a rebase).
    let uv_origin_at = |ng: DVec3| if textures { planar_axis(ng) } else { UV_MESH };
    // What the primitives differ in; the point and the primitive are the hit's.
    let surface = |p_surface, ng, ns, uv, uv_origin, colour, (material, object_id)| Surface {
        p,
        p_surface,
        ng,
        ns,
        uv,
        uv_origin,
        colour,
        material,
        object_id,
        prim: hit.prim,
        index: hit.index,
    };
    match hit.prim {
        Prim::Sphere => {
            let s = &scene.spheres[hit.index as usize];
            let c = v3(s.center_radius);
            let ng = (p - c).normalize();
            let p_surface = if robust { sphere_surface_point(p, c, f64::from(s.center_radius[3]), ng) } else { p };
            let uv = if textures { planar_uv(p, ng) } else { DVec2::ZERO };
            surface(p_surface, ng, ng, uv, uv_origin_at(ng), DVec3::ONE, (s.material, s.object_id))
        }
        Prim::Plane => {
            let pl = &scene.planes[hit.index as usize];
            let ng = v3(pl.normal_offset);
            let p_surface = if robust { p - (ng.dot(p) - f64::from(pl.normal_offset[3])) * ng } else { p };
            let uv = if textures { planar_uv(p, ng) } else { DVec2::ZERO };
            surface(p_surface, ng, ng, uv, uv_origin_at(ng), DVec3::ONE, (pl.material, pl.object_id))
        }
        Prim::Triangle => {
            let tri = &scene.triangles[hit.index as usize];
            let [v0, v1, v2] = triangle_corners(scene, tri);
            let ng = (v1 - v0).cross(v2 - v0).normalize();
            let ns = triangle_shading_normal(scene, tri, hit.bu, hit.bv, ng);
            let p_surface = if robust { triangle_surface_point(p, v0, v1, v2, hit.bu, hit.bv) } else { p };
            let uv = if textures { triangle_uv(scene, tri, hit.bu, hit.bv, p, ng) } else { DVec2::ZERO };
            let uv_origin = if textures { triangle_uv_origin(scene, tri, ng) } else { UV_MESH };
            let colour =
                if ctx.has(feature::VERTEX_COLOURS) { triangle_colour(ctx, tri, hit.bu, hit.bv) } else { DVec3::ONE };
            let mesh = &scene.meshes[tri.mesh as usize];
            surface(p_surface, ng, ns, uv, uv_origin, colour, (mesh.material, mesh.object_id))
        }
    }
}

/// Refraction direction by Snell's law for unit `d` and unit `n` facing the incoming ray,
/// with η = n_from / n_to; `None` under total internal reflection.
pub fn refract_dir(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return None;
    }
    Some((eta * d + (eta * cos_i - k.sqrt()) * n).normalize())
}

/// Mirror direction R = D − 2(D·N)N.
pub fn reflect_dir(d: DVec3, n: DVec3) -> DVec3 {
    (d - 2.0 * d.dot(n) * n).normalize()
}

/// The largest channel of a path weight or colour: what the bailout and Russian roulette judge.
pub fn max_channel(v: DVec3) -> f64 {
    v.x.max(v.y).max(v.z)
}
