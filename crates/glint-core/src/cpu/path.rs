//! The Monte Carlo path tracer on the CPU (f64), the global-illumination reference the Whitted
//! image is held against (issue 32). A path starts at the camera as the Whitted tree does and
//! at each hit adds:
//!
//! - E_m, when the path meets an emitter's front face (as pbrt-v4 and Mitsuba 3 emit);
//! - every emissive sphere and triangle by next-event estimation (one chosen uniformly, a point
//!   in the cone it fills or on its area), weighed against the paths that meet it by multiple
//!   importance sampling (the power heuristic);
//! - every point, spot and directional light by next-event estimation, with Whitted's own
//!   factors (f_att, the spot factor, S_j as the shadow ray's transmittance): the diffuse part
//!   is exactly Whitted's I_d·k_d·(N·L), the glossy part π·I_s·k_s·f_s·(N·L) with the lobe's
//!   normalised BRDF f_s (`bsdf.rs`);
//! - the background, as a uniform environment, where the path leaves the scene;
//!
//! and continues along one lobe chosen in proportion to its largest k: Lambert's and the glossy
//! lobe (sampled from their mixture, so either may have drawn the direction), or the delta lobes
//! k_r and k_t (Whitted's directions, ior and total internal reflection). Russian roulette from
//! the third bounce on (`ROULETTE_FROM`) keeps it unbiased; `max_depth` bounds the bounces. I_a·k_a and the
//! lights' I_a,j have no place here: they stand in for the indirect light the paths compute.
//!
//! Every random number is a hash of the pixel, the sample, its dimension and the seed, so a
//! pixel's value depends on nothing else (not threads, tiles or order).
//!
//! The lobes and E_m are read from the material, not through Whitted's feature set, which leaves
//! out what Whitted does not compute (a glossy lobe in a scene without specular lights, k_r and
//! k_t at depth 0); the geometry, textures, lights' factors and shadows keep their features.
//!
//! Its twin is `shaders/path.wgsl`, which runs `path_bounce` once a dispatch over a tile's
//! paths (`PathState` kept between dispatches as `GpuPathState`). The scene's features are the
//! path tracer's own (`FlatScene::scene_features`), so that both compile out what a scene's
//! paths do not meet.

use std::f64::consts::PI;

use glam::{DVec2, DVec3, DVec4};

use super::FAR;
use super::bsdf::{glossy_brdf, glossy_pdf, lambert_brdf, sample_glossy};
use super::camera::{camera_ray, sample_offset};
use super::emitter::{Emitter, Emitters, emitter_pdf, sample_emitter};
use super::intersect::Leaving;
use super::offset::{aim_origin, leaving_surface, spawn_ray};
use super::rng::{hash_to_unit, sample_hash};
use super::sample::{cosine_hemisphere, cosine_hemisphere_pdf, frame_x, frame_y, power_heuristic, to_world};
use super::shade::{attenuation_factor, light_sample, light_visibility, material_colours};
use super::surface::{max_channel, reflect_dir, refract_dir, surface_at};
use super::walk::closest_hit;
use super::{Ray, RayCounts, TraceContext, v3};
use glint_types::layout::{
    HISTORY_DELTA_AFTER, HISTORY_NON_DELTA, LIGHT_CASTS_SHADOWS, NO_HIT, PATH_CAUSTIC, PATH_DIRECT, PATH_INDIRECT,
    PATH_REST, feature,
};

/// Random dimensions per bounce: the lobe, the direction's two, Russian roulette, the emitter
/// and the point on it (two), one spare. The camera's jitter takes dimensions 0 and 1.
pub const DIMS_PER_BOUNCE: u32 = 8;
pub const FIRST_PATH_DIM: u32 = 2;

/// Rays of a path traced in full before Russian roulette may end it: the camera's and the first
/// two bounces'; the third bounce on is drawn for.
pub const ROULETTE_FROM: u32 = 3;
/// The most a path survives Russian roulette with, so that a path through white walls ends.
pub const MAX_SURVIVAL: f64 = 0.95;

/// A path between bounces: the ray it follows next and what it carries. The GPU keeps one per
/// pixel in a buffer between its per-bounce dispatches (`GpuPathState`, path.wgsl's
/// `load_path` and `store_path`).
#[derive(Clone, Copy, Debug)]
pub struct PathState {
    pub ray: Ray,
    pub t_min: f64,
    /// The primitive the ray leaves (skip_convex only).
    pub leaving: Leaving,
    /// The throughput: the product of BRDF·cos/pdf, lobe weights, f_att and 1/survival so far.
    pub beta: DVec3,
    pub radiance: DVec3,
    /// Where the path last scattered off a non-delta lobe, and the density it drew the
    /// direction with (0 after the camera and delta lobes): what an emitter it meets is weighed by.
    pub scattered_from: DVec3,
    pub scattered_pdf: f64,
    /// Bounces so far: 0 for the camera ray.
    pub depth: u32,
    /// The first object hit (`NO_HIT` for none).
    pub first_object: u32,
    pub pixel: u32,
    pub sample: u32,
    /// Its scatters so far, as the kind of light it brings back needs them (`HISTORY_*`).
    pub history: u32,
}

/// The history of a path after it scatters off a delta lobe (k_r, k_t) or a non-delta one.
pub fn scattered(history: u32, delta: bool) -> u32 {
    let non_delta = history & HISTORY_NON_DELTA;
    if delta {
        if non_delta > 0 { history | HISTORY_DELTA_AFTER } else { history }
    } else {
        (history & HISTORY_DELTA_AFTER) | (non_delta + 1).min(2)
    }
}

/// The kind (`PATH_*`) of the light a path of `history` meets: an emitter or the background.
pub fn met_kind(history: u32) -> u32 {
    let non_delta = history & HISTORY_NON_DELTA;
    let delta_after = history & HISTORY_DELTA_AFTER != 0;
    if non_delta == 0 || (non_delta == 1 && !delta_after) {
        PATH_DIRECT
    } else if non_delta == 1 {
        PATH_CAUSTIC
    } else if !delta_after {
        PATH_INDIRECT
    } else {
        PATH_REST
    }
}

/// The kind of the light next-event estimation draws at a hit of a path of `history`: what
/// the path would meet after scattering there off a non-delta lobe.
pub fn sampled_kind(history: u32) -> u32 {
    met_kind(scattered(history, false))
}

/// Whether the image counts light of `kind` (`TraceContext::omit_kinds`).
pub fn counts_kind(ctx: &TraceContext, kind: u32) -> bool {
    ctx.omit_kinds & kind == 0
}

/// The path's random number in dimension `dim`: a hash of its pixel, sample, `dim` and the seed.
pub fn path_uniform(ctx: &TraceContext, path: &PathState, dim: u32) -> f64 {
    hash_to_unit(sample_hash(path.pixel, path.sample, dim, ctx.scene.header.seed))
}

/// The lobes of a surface a path scatters off, in its shading frame (`fx`, `fy`, `ns`), seen
/// from `wo` (local): Lambert's `kd` and the glossy lobe's `ks` give the BRDF; `weights` are
/// the max channels of k_d, k_s, k_r, k_t, which a bounce chooses a lobe by.
#[derive(Clone, Copy, Debug)]
pub struct Lobes {
    pub fx: DVec3,
    pub fy: DVec3,
    pub ns: DVec3,
    pub wo: DVec3,
    pub kd: DVec3,
    pub ks: DVec3,
    pub weights: DVec4,
    pub material: u32,
}

/// `d` in the lobes' shading frame.
pub fn to_local(l: &Lobes, d: DVec3) -> DVec3 {
    DVec3::new(d.dot(l.fx), d.dot(l.fy), d.dot(l.ns))
}

/// The BRDF of Lambert's and the glossy lobe at the local direction `wi` (the glossy lobe's
/// pow and exp2 skipped where k_s is 0).
pub fn lobes_brdf(ctx: &TraceContext, l: &Lobes, wi: DVec3) -> DVec3 {
    let glossy = if l.ks == DVec3::ZERO {
        DVec3::ZERO
    } else {
        let m = l.material as usize;
        l.ks * glossy_brdf(&ctx.scene.materials[m], ctx.material_tags[m], l.wo, wi)
    };
    l.kd * lambert_brdf(l.wo, wi) + glossy
}

/// The density with which the non-delta lobes draw `wi`, as a bounce's own choice does.
pub fn lobes_pdf(ctx: &TraceContext, l: &Lobes, wi: DVec3) -> f64 {
    let glossy = if l.ks == DVec3::ZERO {
        0.0
    } else {
        let m = l.material as usize;
        glossy_pdf(&ctx.scene.materials[m], ctx.material_tags[m], l.wo, wi)
    };
    let w = l.weights;
    (w.x * cosine_hemisphere_pdf(wi.z) + w.y * glossy) / (w.x + w.y + w.z + w.w)
}

/// A path from the camera through pixel (x, y), for its sample `sample`.
pub fn start_path(ctx: &TraceContext, x: u32, y: u32, sample: u32, counts: &mut RayCounts) -> PathState {
    let h = &ctx.scene.header;
    let pixel = y * h.width + x;
    let (ox, oy) = sample_offset(pixel, sample, h.spp, h.seed, ctx.has(feature::JITTER));
    counts.camera += 1;
    let camera = camera_ray(&ctx.scene.camera, h.width, h.height, x, y, ox, oy);
    PathState {
        ray: camera.ray,
        t_min: camera.t_min,
        leaving: Leaving::NONE,
        beta: DVec3::ONE,
        radiance: DVec3::ZERO,
        scattered_from: DVec3::ZERO,
        scattered_pdf: 0.0,
        depth: 0,
        first_object: NO_HIT,
        pixel,
        sample,
        history: 0,
    }
}

/// One bounce of `path`: what its ray meets adds its emission, the lights' and one emitter's
/// direct light; then the path goes on along one lobe (true) or ends (false).
pub fn path_bounce(ctx: &TraceContext, emitters: &Emitters, path: &mut PathState, counts: &mut RayCounts) -> bool {
    let scene = ctx.scene;
    let h = &scene.header;
    let depth = path.depth;
    let Some(hit) = closest_hit(ctx, &path.ray, path.t_min, FAR, &path.leaving) else {
        if counts_kind(ctx, met_kind(path.history)) {
            path.radiance += path.beta * v3(h.background);
        }
        return false;
    };
    // As Whitted's child rays: a bounce's share times f_att(t); the camera ray's is not.
    if depth > 0 && ctx.has(feature::GLOBAL_ATTENUATION) {
        path.beta *= attenuation_factor(h.global_attenuation, hit.t);
    }
    let ray = path.ray;
    let s = surface_at(ctx, &ray, &hit);
    if depth == 0 {
        path.first_object = s.object_id;
    }
    let front = ray.dir.dot(s.ng) < 0.0;
    let (ng, ns) = if front { (s.ng, s.ns) } else { (-s.ng, -s.ns) };
    let mat = &scene.materials[s.material as usize];
    let c = material_colours(ctx, mat, &s);
    // Emission here means the material emits, so a sphere or triangle is in `emitters`.
    if front && c.emission != DVec3::ZERO && counts_kind(ctx, met_kind(path.history)) {
        let weight = match Emitter::of_hit(&hit) {
            Some(e) if path.scattered_pdf > 0.0 => power_heuristic(
                path.scattered_pdf,
                emitter_pdf(ctx, e, emitters.list.len(), path.scattered_from, s.p, s.ng),
            ),
            Some(_) | None => 1.0,
        };
        path.radiance += path.beta * c.emission * weight;
    }
    let (fx, fy) = (frame_x(ns), frame_y(ns));
    let ks = v3(mat.ks);
    let (kr, kt) = (v3(mat.kr), v3(mat.kt));
    let l = Lobes {
        fx,
        fy,
        ns,
        wo: DVec3::new((-ray.dir).dot(fx), (-ray.dir).dot(fy), (-ray.dir).dot(ns)),
        kd: c.kd,
        ks,
        weights: DVec4::new(max_channel(c.kd), max_channel(ks), max_channel(kr), max_channel(kt)),
        material: s.material,
    };
    let sampled = counts_kind(ctx, sampled_kind(path.history));
    if sampled {
        path.radiance = lights_light(ctx, &l, &s, ng, path.beta, path.radiance, counts);
    }

    let weights = l.weights;
    let dim = FIRST_PATH_DIM + depth * DIMS_PER_BOUNCE;
    // Where a ray leaving to the front starts: the light sample is drawn from it, and a lobe's
    // ray that meets an emitter has the emitter's density taken from it too, so that the two
    // weights of one direction add to 1 (taken from the surface point, they did not, and with
    // robust ε = 0.01 a lamp 0.02 above a floor lit it 0.9 % too dark).
    let aim = aim_origin(ctx, s.p, s.p_surface, ng);
    if sampled && !emitters.list.is_empty() && weights.x + weights.y > 0.0 {
        let pick =
            ((path_uniform(ctx, path, dim + 4) * emitters.list.len() as f64) as usize).min(emitters.list.len() - 1);
        let e = emitters.list[pick];
        let u = DVec2::new(path_uniform(ctx, path, dim + 5), path_uniform(ctx, path, dim + 6));
        // Drawn from where the shadow ray will start, so that it meets what it was aimed at.
        if let Some(dir) = sample_emitter(ctx, e, aim, u) {
            // At the last bounce no path goes on to meet the emitter: its light sample alone
            // counts it, unweighted.
            let mis = depth < ctx.max_depth;
            path.radiance += path.beta * emitter_light(ctx, emitters, e, &l, &s, ng, aim, dir, mis, counts);
        }
    }

    // Without indirect light only k_r and k_t go on: Whitted's transport.
    let choice = if ctx.indirect { weights } else { DVec4::new(0.0, 0.0, weights.z, weights.w) };
    let total = choice.x + choice.y + choice.z + choice.w;
    if depth == ctx.max_depth || total <= 0.0 {
        return false;
    }
    let pick = path_uniform(ctx, path, dim) * total;
    let u = DVec2::new(path_uniform(ctx, path, dim + 1), path_uniform(ctx, path, dim + 2));
    let (dir, transmitted) = if pick < choice.x + choice.y {
        // Lambert's and the glossy lobe as one mixture: the direction's density is the
        // mixture's, whichever lobe drew it.
        let wi = if pick < choice.x {
            cosine_hemisphere(u)
        } else {
            sample_glossy(mat, ctx.material_tags[s.material as usize], l.wo, u)
        };
        if wi.z <= 0.0 {
            return false;
        }
        let pdf = lobes_pdf(ctx, &l, wi);
        if pdf <= 0.0 {
            return false;
        }
        path.beta *= lobes_brdf(ctx, &l, wi) * (wi.z / pdf);
        counts.reflection += 1;
        (path.scattered_from, path.scattered_pdf) = (aim, pdf);
        path.history = scattered(path.history, false);
        (to_world(ns, wi), false)
    } else if pick < choice.x + choice.y + choice.z {
        path.beta *= kr * (total / choice.z);
        counts.reflection += 1;
        path.scattered_pdf = 0.0;
        path.history = scattered(path.history, true);
        (reflect_dir(ray.dir, ns), false)
    } else {
        path.beta *= kt * (total / choice.w);
        path.scattered_pdf = 0.0;
        path.history = scattered(path.history, true);
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
        return false;
    }
    if depth + 1 >= ROULETTE_FROM {
        let survival = max_channel(path.beta).min(MAX_SURVIVAL);
        if path_uniform(ctx, path, dim + 3) >= survival {
            return false;
        }
        path.beta /= survival;
    }
    let sp = spawn_ray(ctx, s.p, s.p_surface, side, dir, leaving_surface(s.prim, s.index, s.ng, side));
    path.ray = Ray { origin: sp.origin, dir };
    (path.t_min, path.leaving) = (sp.t_min, sp.leaving);
    path.depth += 1;
    true
}

/// `radiance` plus `beta` times the direct light of every point, spot and directional light at
/// `s` (normal `ng` turned to the incoming ray), by Whitted's factors: the diffuse part exactly
/// Whitted's I_d·k_d·(N·L), the glossy part π·I_s·k_s·f_s·(N·L). Added light by light.
pub fn lights_light(
    ctx: &TraceContext,
    l: &Lobes,
    s: &super::shade::Surface,
    ng: DVec3,
    beta: DVec3,
    radiance: DVec3,
    counts: &mut RayCounts,
) -> DVec3 {
    let scene = ctx.scene;
    let mut sum = radiance;
    for (light, &light_tags) in scene.lights.iter().zip(&ctx.light_tags) {
        let ls = light_sample(ctx, light, light_tags, s.p);
        let scale = ls.f_att * ls.spot;
        let n_dot_l = l.ns.dot(ls.l);
        if scale == 0.0 || n_dot_l <= 0.0 {
            continue;
        }
        let visibility = if ctx.has(feature::SHADOWS) && light.flags & LIGHT_CASTS_SHADOWS != 0 {
            light_visibility(ctx, light, light_tags.kind, s, ng, &ls, counts)
        } else {
            DVec3::ONE
        };
        let diffuse = v3(light.diffuse) * l.kd * n_dot_l;
        let glossy = if l.ks == DVec3::ZERO {
            DVec3::ZERO
        } else {
            let m = l.material as usize;
            PI * v3(light.specular)
                * l.ks
                * glossy_brdf(&scene.materials[m], ctx.material_tags[m], l.wo, to_local(l, ls.l))
                * n_dot_l
        };
        sum += beta * scale * (visibility * (diffuse + glossy));
    }
    sum
}

/// The radiance one camera sample of pixel (x, y) brings back along its path, and the id of
/// the first object hit (`NO_HIT` for none), as Whitted's `render_sample` gives them.
pub fn path_sample(
    ctx: &TraceContext,
    emitters: &Emitters,
    x: u32,
    y: u32,
    sample: u32,
    counts: &mut RayCounts,
) -> (DVec3, u32) {
    let mut path = start_path(ctx, x, y, sample, counts);
    while path_bounce(ctx, emitters, &mut path, counts) {}
    (path.radiance, path.first_object)
}

/// What an emitter sends back along `dir` from the surface `s` (its normal `ng` turned to the
/// incoming ray), `dir` drawn from `aim` (`aim_origin`) by next-event estimation: E_m over the
/// density the point was drawn with,
/// times the lobes' BRDF and cosine, weighed against the paths' own chance to meet it; without
/// `mis` the light sample is the only way the emitter is counted from here.
pub fn emitter_light(
    ctx: &TraceContext,
    emitters: &Emitters,
    e: Emitter,
    l: &Lobes,
    s: &super::shade::Surface,
    ng: DVec3,
    aim: DVec3,
    dir: DVec3,
    mis: bool,
    counts: &mut RayCounts,
) -> DVec3 {
    let wi = to_local(l, dir);
    if wi.z <= 0.0 || dir.dot(ng) <= 0.0 {
        return DVec3::ZERO;
    }
    let sp = spawn_ray(ctx, s.p, s.p_surface, ng, dir, leaving_surface(s.prim, s.index, s.ng, ng));
    let shadow = Ray { origin: sp.origin, dir };
    counts.shadow += 1;
    // The emitter is seen if it is what the ray meets first, on its front face.
    let Some(hit) = closest_hit(ctx, &shadow, sp.t_min, FAR, &sp.leaving) else { return DVec3::ZERO };
    if Emitter::of_hit(&hit) != Some(e) {
        return DVec3::ZERO;
    }
    let q = surface_at(ctx, &shadow, &hit);
    let light_pdf = emitter_pdf(ctx, e, emitters.list.len(), aim, q.p, q.ng);
    if dir.dot(q.ng) >= 0.0 || light_pdf <= 0.0 {
        return DVec3::ZERO;
    }
    let mut emission = material_colours(ctx, &ctx.scene.materials[q.material as usize], &q).emission;
    // As the paths that meet it: f_att(t) over the segment.
    if ctx.has(feature::GLOBAL_ATTENUATION) {
        emission *= attenuation_factor(ctx.scene.header.global_attenuation, hit.t);
    }
    let (f, bsdf_pdf) = (lobes_brdf(ctx, l, wi), lobes_pdf(ctx, l, wi));
    let weight = if mis { power_heuristic(light_pdf, bsdf_pdf) } else { 1.0 };
    f * emission * (wi.z * weight / light_pdf)
}

/// The mean of `spp` path samples of pixel (x, y), and the first sample's first-hit object.
pub fn path_pixel(
    ctx: &TraceContext,
    emitters: &Emitters,
    x: u32,
    y: u32,
    spp: u32,
    counts: &mut RayCounts,
) -> (DVec3, u32) {
    let (mut sum, first) = path_sample(ctx, emitters, x, y, 0, counts);
    for sample in 1..spp {
        sum += path_sample(ctx, emitters, x, y, sample, counts).0;
    }
    (sum / f64::from(spp.max(1)), first)
}
