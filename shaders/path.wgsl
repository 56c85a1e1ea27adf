// Twin of crates/glint-core/src/cpu/path.rs: the Monte Carlo path tracer, in f32, one bounce a
// dispatch over the tile's paths (a wavefront). `start` makes each pixel's camera path for the
// sample `tile.sample_index`; `main` then runs until every pixel has run its samples up to
// `tile.sample_end`, each invocation taking its pixel's path one bounce on. No invocation loops
// over a path's bounces, so lavapipe's loop budget holds at any depth: a bounce's loops are one
// ray's walk, the lights and a shadow ray each. A path that ends adds its radiance to the
// output as accumulate_sample does (samples in order, divided by spp at the last), and its
// pixel's next sample starts in its place at once (path regeneration, Novák et al. 2010), so
// that the lanes of a workgroup stay busy while their paths' lengths differ. A pixel done with
// the batch counts itself in STAT_PIXELS_DONE, which the host reads to know when to stop.
#import glint::scene_data::{GpuPathState, NO_HIT, PATH_DIRECT, PATH_INDIRECT, PATH_CAUSTIC, PATH_REST, HISTORY_NON_DELTA, HISTORY_DELTA_AFTER, LIGHT_CASTS_SHADOWS, STATUS_DRIVER_LOOP_CUTOFF, STAT_PIXELS_DONE}
#import glint::bindings::{header, camera, tile, materials, lights, output, stats, path_states, emitters}
#import glint::ray::{Ray, RayCounts, ray_counts, status, driver_cut_loops, flush_counts}
#import glint::rng::{sample_hash, hash_to_unit}
#import glint::camera::{camera_ray, sample_offset}
#import glint::ray::FAR
#import glint::intersect::{Leaving, PRIM_NONE, all_zero}
#ifdef BVH
#import glint::bvh::closest_hit
#else
#import glint::intersect::closest_hit
#endif
#import glint::offset::{spawn_ray, leaving_surface, aim_origin}
#import glint::shade::{Surface, light_sample, material_colours}
#ifdef SHADOWS
#import glint::shade::light_visibility
#endif
#ifdef GLOBAL_ATTENUATION
#import glint::shade::attenuation_factor
#endif
#import glint::surface::{surface_at, reflect_dir, max_channel}
#ifdef TRANSMISSION
#import glint::surface::refract_dir
#endif
#import glint::sample::{PI, frame_x, frame_y, to_world, cosine_hemisphere, cosine_hemisphere_pdf, power_heuristic}
#import glint::bsdf::lambert_brdf
#ifdef SPECULAR
#import glint::bsdf::{glossy_brdf, sample_glossy, glossy_pdf}
#endif
#import glint::emitter::{NO_EMITTER, of_hit, emitter_pdf, sample_emitter}

// Random dimensions per bounce, and the camera's two before them (cpu::path's).
const DIMS_PER_BOUNCE: u32 = 8u;
const FIRST_PATH_DIM: u32 = 2u;
// Rays traced in full before Russian roulette (the camera's and two bounces'), and the most a path survives it with.
const ROULETTE_FROM: u32 = 3u;
const MAX_SURVIVAL: f32 = 0.95;

// A path between bounces (cpu::path::PathState); GpuPathState is its stored form.
struct PathState {
    ray: Ray,
    t_min: f32,
    leaving: Leaving,
    beta: vec3<f32>,
    radiance: vec3<f32>,
    scattered_from: vec3<f32>,
    scattered_pdf: f32,
    depth: u32,
    first_object: u32,
    pixel: u32,
    sample: u32,
    history: u32,
}

// The history of a path after it scatters off a delta lobe (k_r, k_t) or a non-delta one.
fn scattered(history: u32, delta: bool) -> u32 {
    let non_delta = history & HISTORY_NON_DELTA;
    if delta {
        return select(history, history | HISTORY_DELTA_AFTER, non_delta > 0u);
    }
    return (history & HISTORY_DELTA_AFTER) | min(non_delta + 1u, 2u);
}

// The kind (PATH_*) of the light a path of `history` meets: an emitter or the background.
fn met_kind(history: u32) -> u32 {
    let non_delta = history & HISTORY_NON_DELTA;
    let delta_after = (history & HISTORY_DELTA_AFTER) != 0u;
    if non_delta == 0u || (non_delta == 1u && !delta_after) {
        return PATH_DIRECT;
    } else if non_delta == 1u {
        return PATH_CAUSTIC;
    } else if !delta_after {
        return PATH_INDIRECT;
    }
    return PATH_REST;
}

// The kind of the light next-event estimation draws at a hit of a path of `history`.
fn sampled_kind(history: u32) -> u32 {
    return met_kind(scattered(history, false));
}

// Whether the image counts light of `kind` (header.omit_kinds).
fn counts_kind(kind: u32) -> bool {
    return (header.omit_kinds & kind) == 0u;
}

// The lobes of a surface in its shading frame, seen from wo (local).
struct Lobes {
    fx: vec3<f32>,
    fy: vec3<f32>,
    ns: vec3<f32>,
    wo: vec3<f32>,
    kd: vec3<f32>,
    ks: vec3<f32>,
    weights: vec4<f32>,
    material: u32,
}

// The path's random number in dimension dim.
fn path_uniform(path: PathState, dim: u32) -> f32 {
    return hash_to_unit(sample_hash(path.pixel, path.sample, dim, header.seed));
}

fn to_local(l: Lobes, d: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(d, l.fx), dot(d, l.fy), dot(d, l.ns));
}

// The BRDF of Lambert's and the glossy lobe at the local direction wi.
fn lobes_brdf(l: Lobes, wi: vec3<f32>) -> vec3<f32> {
    var glossy = vec3<f32>(0.0);
#ifdef SPECULAR
    if !all_zero(l.ks) {
        glossy = l.ks * glossy_brdf(materials[l.material], l.wo, wi);
    }
#endif
    return l.kd * lambert_brdf(l.wo, wi) + glossy;
}

// The density with which the non-delta lobes draw wi, as a bounce's own choice does.
fn lobes_pdf(l: Lobes, wi: vec3<f32>) -> f32 {
    var glossy = 0.0;
#ifdef SPECULAR
    if !all_zero(l.ks) {
        glossy = glossy_pdf(materials[l.material], l.wo, wi);
    }
#endif
    let w = l.weights;
    return (w.x * cosine_hemisphere_pdf(wi.z) + w.y * glossy) / (w.x + w.y + w.z + w.w);
}

fn start_path(x: u32, y: u32, sample_index: u32) -> PathState {
    let pixel = y * header.width + x;
    // A path's one sample is jittered over the pixel too (its mean is over the pixel's area).
    let offset = sample_offset(pixel, sample_index, header.spp, header.seed, true);
    ray_counts.camera += 1u;
    let zero = vec3<f32>(0.0);
    let c = camera_ray(camera, header.width, header.height, x, y, offset);
    return PathState(
        c.ray,
        c.t_min,
        Leaving(PRIM_NONE, 0u, false),
        vec3<f32>(1.0),
        zero,
        zero,
        0.0,
        0u,
        NO_HIT,
        pixel,
        sample_index,
        0u,
    );
}

// radiance plus beta times every point, spot and directional light's direct light at s, by
// Whitted's factors, light by light.
fn lights_light(l: Lobes, s: Surface, ng: vec3<f32>, beta: vec3<f32>, radiance: vec3<f32>) -> vec3<f32> {
    var sum = radiance;
    for (var i = 0u; i < header.light_count; i++) {
        let light = lights[i];
        let ls = light_sample(light, s.p);
        let scale = ls.f_att * ls.spot;
        let n_dot_l = dot(l.ns, ls.l);
        if scale == 0.0 || n_dot_l <= 0.0 {
            continue;
        }
        var visibility = vec3<f32>(1.0);
#ifdef SHADOWS
        if (light.flags & LIGHT_CASTS_SHADOWS) != 0u {
            visibility = light_visibility(light, s, ng, ls);
        }
#endif
        let diffuse = light.diffuse.xyz * l.kd * n_dot_l;
        var glossy = vec3<f32>(0.0);
#ifdef SPECULAR
        if !all_zero(l.ks) {
            glossy = PI * light.specular.xyz * l.ks * glossy_brdf(materials[l.material], l.wo, to_local(l, ls.l)) * n_dot_l;
        }
#endif
        sum += beta * scale * (visibility * (diffuse + glossy));
    }
    return sum;
}

#ifdef EMISSION
// What emitter e sends back along dir from s, drawn by next-event estimation and weighed
// against the paths that meet it (mis), or alone.
fn emitter_light(e: u32, count: u32, l: Lobes, s: Surface, ng: vec3<f32>, aim: vec3<f32>, dir: vec3<f32>, mis: bool) -> vec3<f32> {
    let wi = to_local(l, dir);
    if wi.z <= 0.0 || dot(dir, ng) <= 0.0 {
        return vec3<f32>(0.0);
    }
    let sp = spawn_ray(s.p, s.p_surface, ng, dir, leaving_surface(s.prim, s.index, s.ng, ng));
    let shadow = Ray(sp.origin, dir);
    ray_counts.shadow += 1u;
    // Seen if it is what the ray meets first, on its front face.
    let hit = closest_hit(shadow, sp.t_min, FAR, sp.leaving);
    if hit.prim == PRIM_NONE || of_hit(hit) != e {
        return vec3<f32>(0.0);
    }
    let q = surface_at(shadow, hit);
    let light_pdf = emitter_pdf(e, count, aim, q.p, q.ng);
    if dot(dir, q.ng) >= 0.0 || light_pdf <= 0.0 {
        return vec3<f32>(0.0);
    }
    var emission = material_colours(materials[q.material], q).emission;
#ifdef GLOBAL_ATTENUATION
    emission *= attenuation_factor(header.global_attenuation, hit.t);
#endif
    let f = lobes_brdf(l, wi);
    var weight = 1.0;
    if mis {
        weight = power_heuristic(light_pdf, lobes_pdf(l, wi));
    }
    return f * emission * (wi.z * weight / light_pdf);
}
#endif

// One bounce of the path: what its ray meets adds its emission, the lights' and one emitter's
// direct light; then the path goes on along one lobe (true) or ends (false).
fn path_bounce(path: ptr<function, PathState>) -> bool {
    let depth = (*path).depth;
    let ray = (*path).ray;
    let hit = closest_hit(ray, (*path).t_min, FAR, (*path).leaving);
    if hit.prim == PRIM_NONE {
        if counts_kind(met_kind((*path).history)) {
            (*path).radiance += (*path).beta * header.background.xyz;
        }
        return false;
    }
#ifdef GLOBAL_ATTENUATION
    if depth > 0u {
        (*path).beta *= attenuation_factor(header.global_attenuation, hit.t);
    }
#endif
    let s = surface_at(ray, hit);
    if depth == 0u {
        (*path).first_object = s.object_id;
    }
    let front = dot(ray.dir, s.ng) < 0.0;
    let ng = select(-s.ng, s.ng, front);
    let ns = select(-s.ns, s.ns, front);
    let mat = materials[s.material];
    let c = material_colours(mat, s);
#ifdef EMISSION
    if front && !all_zero(c.emission) && counts_kind(met_kind((*path).history)) {
        var weight = 1.0;
        let e = of_hit(hit);
        if e != NO_EMITTER && (*path).scattered_pdf > 0.0 {
            weight = power_heuristic((*path).scattered_pdf, emitter_pdf(e, emitters[0], (*path).scattered_from, s.p, s.ng));
        }
        (*path).radiance += (*path).beta * c.emission * weight;
    }
#endif
    let fx = frame_x(ns);
    let fy = frame_y(ns);
    var ks = vec3<f32>(0.0);
#ifdef SPECULAR
    ks = mat.ks.xyz;
#endif
    var kr = vec3<f32>(0.0);
#ifdef REFLECTION
    kr = mat.kr.xyz;
#endif
    var kt = vec3<f32>(0.0);
#ifdef TRANSMISSION
    kt = mat.kt.xyz;
#endif
    let l = Lobes(
        fx,
        fy,
        ns,
        vec3<f32>(dot(-ray.dir, fx), dot(-ray.dir, fy), dot(-ray.dir, ns)),
        c.kd,
        ks,
        vec4<f32>(max_channel(c.kd), max_channel(ks), max_channel(kr), max_channel(kt)),
        s.material,
    );
    let sampled = counts_kind(sampled_kind((*path).history));
    if sampled {
        (*path).radiance = lights_light(l, s, ng, (*path).beta, (*path).radiance);
    }

    let weights = l.weights;
    let dim = FIRST_PATH_DIM + depth * DIMS_PER_BOUNCE;
    // Where a ray leaving to the front starts: the light sample and a lobe's emitter density
    // are both taken from it (the CPU twin says why).
    let aim = aim_origin(s.p, s.p_surface, ng);
#ifdef EMISSION
    let count = emitters[0];
    if sampled && count > 0u && weights.x + weights.y > 0.0 {
        let pick = min(u32(path_uniform(*path, dim + 4u) * f32(count)), count - 1u);
        let e = emitters[1u + pick];
        let u = vec2<f32>(path_uniform(*path, dim + 5u), path_uniform(*path, dim + 6u));
        // Drawn from where the shadow ray will start, so that it meets what it was aimed at.
        let dir = sample_emitter(e, aim, u);
        if dir.w != 0.0 {
            // At the last bounce no path goes on to meet the emitter: its light sample alone
            // counts it, unweighted.
            (*path).radiance += (*path).beta * emitter_light(e, count, l, s, ng, aim, dir.xyz, depth < header.max_depth);
        }
    }
#endif

    // Without indirect light only k_r and k_t go on: Whitted's transport.
    let choice = select(vec4<f32>(0.0, 0.0, weights.z, weights.w), weights, header.indirect != 0u);
    let total = choice.x + choice.y + choice.z + choice.w;
    if depth == header.max_depth || total <= 0.0 {
        return false;
    }
    let pick = path_uniform(*path, dim) * total;
    let u = vec2<f32>(path_uniform(*path, dim + 1u), path_uniform(*path, dim + 2u));
    var dir = vec3<f32>(0.0);
    var transmitted = false;
    if pick < choice.x + choice.y {
        // Lambert's and the glossy lobe as one mixture.
        var wi = cosine_hemisphere(u);
#ifdef SPECULAR
        if pick >= choice.x {
            wi = sample_glossy(mat, l.wo, u);
        }
#endif
        if wi.z <= 0.0 {
            return false;
        }
        let pdf = lobes_pdf(l, wi);
        if pdf <= 0.0 {
            return false;
        }
        (*path).beta *= lobes_brdf(l, wi) * (wi.z / pdf);
        ray_counts.reflection += 1u;
        (*path).scattered_from = aim;
        (*path).scattered_pdf = pdf;
        (*path).history = scattered((*path).history, false);
        dir = to_world(ns, wi);
    } else if pick < choice.x + choice.y + choice.z {
        (*path).beta *= kr * (total / choice.z);
        ray_counts.reflection += 1u;
        (*path).scattered_pdf = 0.0;
        (*path).history = scattered((*path).history, true);
        dir = reflect_dir(ray.dir, ns);
    } else {
#ifdef TRANSMISSION
        (*path).beta *= kt * (total / choice.w);
        (*path).scattered_pdf = 0.0;
        (*path).history = scattered((*path).history, true);
        let eta = select(mat.ior, 1.0 / mat.ior, front);
        let refracted = refract_dir(ray.dir, ns, eta);
        if refracted.w != 0.0 {
            ray_counts.refraction += 1u;
            dir = refracted.xyz;
            transmitted = true;
        } else {
            // Total internal reflection: k_t's share follows the mirror direction.
            ray_counts.reflection += 1u;
            dir = reflect_dir(ray.dir, ns);
        }
#else
        return false;
#endif
    }
    // Leave on the side the lobe sends the path to; a drawn direction into the surface ends it.
    let side = select(ng, -ng, transmitted);
    if dot(dir, side) <= 0.0 {
        return false;
    }
    if depth + 1u >= ROULETTE_FROM {
        let survival = min(max_channel((*path).beta), MAX_SURVIVAL);
        if path_uniform(*path, dim + 3u) >= survival {
            return false;
        }
        (*path).beta /= survival;
    }
    let sp = spawn_ray(s.p, s.p_surface, side, dir, leaving_surface(s.prim, s.index, s.ng, side));
    (*path).ray = Ray(sp.origin, dir);
    (*path).t_min = sp.t_min;
    (*path).leaving = sp.leaving;
    (*path).depth += 1u;
    return true;
}

fn load_path(slot: u32) -> PathState {
    let g = path_states[slot];
    let leaving = Leaving(g.leaving_pixel.x, g.leaving_pixel.y, g.leaving_pixel.z != 0u);
    return PathState(
        Ray(g.origin.xyz, g.dir.xyz),
        g.origin.w,
        leaving,
        g.beta.xyz,
        g.radiance.xyz,
        g.scattered_from.xyz,
        g.beta.w,
        bitcast<u32>(g.dir.w),
        bitcast<u32>(g.radiance.w),
        g.leaving_pixel.w,
        g.sample.x,
        g.sample.y,
    );
}

fn store_path(slot: u32, p: PathState, alive: bool) {
    path_states[slot] = GpuPathState(
        vec4<f32>(p.ray.origin, p.t_min),
        vec4<f32>(p.ray.dir, bitcast<f32>(p.depth)),
        vec4<f32>(p.beta, p.scattered_pdf),
        vec4<f32>(p.radiance, bitcast<f32>(p.first_object)),
        vec4<f32>(p.scattered_from, bitcast<f32>(u32(alive))),
        vec4<u32>(p.leaving.prim, p.leaving.index, u32(p.leaving.inside), p.pixel),
        vec4<u32>(p.sample, p.history, 0u, 0u),
    );
}

// Whether the path in `slot` goes on (its pixel's batch not done).
fn path_alive(slot: u32) -> bool {
    return bitcast<u32>(path_states[slot].scattered_from.w) != 0u;
}

// The ended path's radiance into its pixel: sample 0 writes it (with the first hit), later
// samples add theirs, the last divides by spp.
fn finish_path(p: PathState) {
    let index = p.pixel;
    if p.sample == 0u {
        output[index] = vec4<f32>(p.radiance, select(f32(p.first_object), -1.0, p.first_object == NO_HIT));
    } else {
        output[index] = vec4<f32>(output[index].xyz + p.radiance, output[index].w);
    }
    if p.sample + 1u == header.spp && header.spp > 1u {
        output[index] = vec4<f32>(output[index].xyz / f32(header.spp), output[index].w);
    }
}

@compute @workgroup_size(8, 8, 1)
fn start(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= tile.width || gid.y >= tile.height {
        return;
    }
    ray_counts = RayCounts(0u, 0u, 0u, 0u, 0u);
    status = 0u;
    let path = start_path(tile.origin_x + gid.x, tile.origin_y + gid.y, tile.sample_index);
    store_path(gid.y * tile.width + gid.x, path, true);
    if driver_cut_loops() {
        status |= STATUS_DRIVER_LOOP_CUTOFF;
    }
    flush_counts();
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= tile.width || gid.y >= tile.height {
        return;
    }
    let slot = gid.y * tile.width + gid.x;
    if !path_alive(slot) {
        return;
    }
    ray_counts = RayCounts(0u, 0u, 0u, 0u, 0u);
    status = 0u;
    var path = load_path(slot);
    if path_bounce(&path) {
        store_path(slot, path, true);
    } else {
        finish_path(path);
        if path.sample + 1u < tile.sample_end {
            store_path(slot, start_path(tile.origin_x + gid.x, tile.origin_y + gid.y, path.sample + 1u), true);
        } else {
            path_states[slot].scattered_from.w = bitcast<f32>(0u);
            atomicAdd(&stats[STAT_PIXELS_DONE], 1u);
        }
    }
    if driver_cut_loops() {
        status |= STATUS_DRIVER_LOOP_CUTOFF;
    }
    flush_counts();
}
