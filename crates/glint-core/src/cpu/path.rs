//! The Monte Carlo path tracer on the CPU (f64), the global-illumination reference the Whitted
//! image is held against (issue 32). A path starts at the camera as the Whitted tree does and
//! at each hit adds:
//!
//! - E_m, when the path meets an emitter's front face (as pbrt-v4 and Mitsuba 3 emit);
//! - every point, spot and directional light by next-event estimation, with Whitted's own
//!   factors (f_att, the spot factor, S_j as the shadow ray's transmittance): the diffuse part
//!   is exactly Whitted's I_d·k_d·(N·L), the glossy part π·I_s·k_s·f_s·(N·L) with the lobe's
//!   normalised BRDF f_s (`bsdf.rs`);
//! - the background, as a uniform environment, where the path leaves the scene;
//!
//! and continues along one lobe chosen in proportion to its largest k: Lambert's and the glossy
//! lobe (sampled from their mixture, so either may have drawn the direction), or the delta lobes
//! k_r and k_t (Whitted's directions, ior and total internal reflection). Russian roulette after
//! `ROULETTE_FROM` bounces keeps it unbiased; `max_depth` bounds the bounces. I_a·k_a and the
//! lights' I_a,j have no place here: they stand in for the indirect light the paths compute.
//!
//! Every random number is a hash of the pixel, the sample, its dimension and the seed, so a
//! pixel's value depends on nothing else (not threads, tiles or order).
//!
//! The lobes and E_m are read from the material, not through Whitted's feature set, which leaves
//! out what Whitted does not compute (a glossy lobe in a scene without specular lights, k_r and
//! k_t at depth 0); the geometry, textures, lights' factors and shadows keep their features.
//!
//! Not yet (issue 32): next-event estimation to emissive spheres and triangles with multiple
//! importance sampling, the WGSL twin, its own specialisation, and the `integrator` setting of
//! scenes and commands.

use std::f64::consts::PI;

use glam::{DVec2, DVec3};

use super::bsdf::{
    blinn_brdf, blinn_pdf, cook_torrance_brdf, cook_torrance_pdf, lambert_brdf, phong_brdf, phong_pdf, sample_blinn,
    sample_cook_torrance, sample_phong,
};
use super::camera::{camera_ray, sample_offset};
use super::intersect::{FAR, Leaving};
use super::offset::{leaving_surface, spawn_ray};
use super::rng::{hash_to_unit, sample_hash};
use super::sample::{cosine_hemisphere, cosine_hemisphere_pdf, frame_x, frame_y, to_world};
use super::shade::{attenuation_factor, light_sample, light_visibility, material_colours};
use super::trace::{reflect_dir, refract_dir, surface_at};
use super::walk::closest_hit;
use super::{Ray, RayCounts, TraceContext, v3};
use glint_scene::SpecularModel;
use glint_types::MaterialTags;
use glint_types::layout::{GpuMaterial, LIGHT_CASTS_SHADOWS, feature};

/// Random dimensions per bounce: the lobe, the direction's two, Russian roulette. The camera's
/// jitter takes dimensions 0 and 1.
const DIMS_PER_BOUNCE: u32 = 4;
const FIRST_PATH_DIM: u32 = 2;

/// Bounces traced in full before Russian roulette may end a path.
pub const ROULETTE_FROM: u32 = 3;
/// The most a path survives Russian roulette with, so that a path through white walls ends.
const MAX_SURVIVAL: f64 = 0.95;

fn max_channel(v: DVec3) -> f64 {
    v.x.max(v.y).max(v.z)
}

/// The glossy lobe's BRDF per unit k_s, for the material's specular model.
pub fn glossy_brdf(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, wi: DVec3) -> f64 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => blinn_brdf(wo, wi, n),
        SpecularModel::Phong => phong_brdf(wo, wi, n),
        SpecularModel::CookTorrance => {
            cook_torrance_brdf(wo, wi, f64::from(mat.roughness), f64::from(mat.ior), tags.fresnel)
        }
    }
}

/// A direction from the glossy lobe.
pub fn sample_glossy(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, u: DVec2) -> DVec3 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => sample_blinn(wo, u, n),
        SpecularModel::Phong => sample_phong(wo, u, n),
        SpecularModel::CookTorrance => sample_cook_torrance(wo, u, f64::from(mat.roughness)),
    }
}

/// The density of `sample_glossy` at `wi`.
pub fn glossy_pdf(mat: &GpuMaterial, tags: MaterialTags, wo: DVec3, wi: DVec3) -> f64 {
    let n = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Blinn => blinn_pdf(wo, wi, n),
        SpecularModel::Phong => phong_pdf(wo, wi, n),
        SpecularModel::CookTorrance => cook_torrance_pdf(wo, wi, f64::from(mat.roughness)),
    }
}

/// The radiance one camera sample of pixel (x, y) brings back along its path.
pub fn path_sample(ctx: &TraceContext, x: u32, y: u32, sample: u32, counts: &mut RayCounts) -> DVec3 {
    let scene = ctx.scene;
    let h = &scene.header;
    let pixel = y * h.width + x;
    let uniform = |dim: u32| hash_to_unit(sample_hash(pixel, sample, dim, h.seed));
    let (ox, oy) = sample_offset(pixel, sample, h.spp, h.seed, ctx.has(feature::JITTER));
    let mut ray = camera_ray(&scene.camera, h.width, h.height, x, y, ox, oy);
    counts.camera += 1;
    let (mut t_min, mut leaving) = (0.0, Leaving::NONE);
    let (mut beta, mut radiance) = (DVec3::ONE, DVec3::ZERO);
    for depth in 0..=ctx.max_depth {
        let Some(hit) = closest_hit(ctx, &ray, t_min, FAR, &leaving) else {
            radiance += beta * v3(h.background);
            break;
        };
        // As Whitted's child rays: a bounce's share times f_att(t); the camera ray's is not.
        if depth > 0 && ctx.has(feature::GLOBAL_ATTENUATION) {
            beta *= attenuation_factor(h.global_attenuation, hit.t);
        }
        let s = surface_at(ctx, &ray, &hit);
        let front = ray.dir.dot(s.ng) < 0.0;
        let (ng, ns) = if front { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
        let mat = &scene.materials[s.material as usize];
        let tags = ctx.material_tags[s.material as usize];
        let c = material_colours(ctx, mat, s.uv, s.uv_origin);
        if front {
            radiance += beta * c.emission;
        }
        let (fx, fy) = (frame_x(ns), frame_y(ns));
        let to_local = |d: DVec3| DVec3::new(d.dot(fx), d.dot(fy), d.dot(ns));
        let wo = to_local(-ray.dir);
        let ks = v3(mat.ks);

        for (light, &light_tags) in scene.lights.iter().zip(&ctx.light_tags) {
            let ls = light_sample(ctx, light, light_tags, s.p);
            let scale = ls.f_att * ls.spot;
            let n_dot_l = ns.dot(ls.l);
            if scale == 0.0 || n_dot_l <= 0.0 {
                continue;
            }
            let visibility = if ctx.has(feature::SHADOWS) && light.flags & LIGHT_CASTS_SHADOWS != 0 {
                light_visibility(ctx, light, light_tags.kind, &s, ng, &ls, counts)
            } else {
                DVec3::ONE
            };
            let diffuse = v3(light.diffuse) * c.kd * n_dot_l;
            let glossy = if ks == DVec3::ZERO {
                DVec3::ZERO
            } else {
                PI * v3(light.specular) * ks * glossy_brdf(mat, tags, wo, to_local(ls.l)) * n_dot_l
            };
            radiance += beta * scale * (visibility * (diffuse + glossy));
        }

        if depth == ctx.max_depth {
            break;
        }
        let kr = v3(mat.kr);
        let kt = v3(mat.kt);
        let weights = [max_channel(c.kd), max_channel(ks), max_channel(kr), max_channel(kt)];
        let total: f64 = weights.iter().sum();
        if total <= 0.0 {
            break;
        }
        let dim = FIRST_PATH_DIM + depth * DIMS_PER_BOUNCE;
        let pick = uniform(dim) * total;
        let u = DVec2::new(uniform(dim + 1), uniform(dim + 2));
        let (dir, transmitted) = if pick < weights[0] + weights[1] {
            // Lambert's and the glossy lobe as one mixture: the direction's density is the
            // mixture's, whichever lobe drew it.
            let wi = if pick < weights[0] { cosine_hemisphere(u) } else { sample_glossy(mat, tags, wo, u) };
            if wi.z <= 0.0 {
                break;
            }
            let pdf = (weights[0] * cosine_hemisphere_pdf(wi.z) + weights[1] * glossy_pdf(mat, tags, wo, wi)) / total;
            if pdf <= 0.0 {
                break;
            }
            let f = c.kd * lambert_brdf(wo, wi) + ks * glossy_brdf(mat, tags, wo, wi);
            beta *= f * (wi.z / pdf);
            counts.reflection += 1;
            (to_world(ns, wi), false)
        } else if pick < weights[0] + weights[1] + weights[2] {
            beta *= kr * (total / weights[2]);
            counts.reflection += 1;
            (reflect_dir(ray.dir, ns), false)
        } else {
            beta *= kt * (total / weights[3]);
            let ior = f64::from(mat.ior);
            let eta = if front { 1.0 / ior } else { ior };
            match refract_dir(ray.dir, ns, eta) {
                Some(d) => {
                    counts.refraction += 1;
                    (d, true)
                }
                // Total internal reflection: k_t's share follows the mirror direction.
                None => {
                    counts.reflection += 1;
                    (reflect_dir(ray.dir, ns), false)
                }
            }
        };
        // Leave on the side the lobe sends the path to; a shading normal can point a drawn
        // direction into the surface, where the path ends rather than leak.
        let side = if transmitted { -ng } else { ng };
        if dir.dot(side) <= 0.0 {
            break;
        }
        if depth + 1 >= ROULETTE_FROM {
            let survival = max_channel(beta).min(MAX_SURVIVAL);
            if uniform(dim + 3) >= survival {
                break;
            }
            beta /= survival;
        }
        let sp = spawn_ray(ctx, s.p, s.p_surface, side, dir, leaving_surface(s.prim, s.index, s.ng, side));
        ray = Ray { origin: sp.origin, dir };
        (t_min, leaving) = (sp.t_min, sp.leaving);
    }
    radiance
}

/// The mean of `spp` path samples of pixel (x, y).
pub fn path_pixel(ctx: &TraceContext, x: u32, y: u32, spp: u32, counts: &mut RayCounts) -> DVec3 {
    let mut sum = DVec3::ZERO;
    for sample in 0..spp {
        sum += path_sample(ctx, x, y, sample, counts);
    }
    sum / f64::from(spp.max(1))
}
