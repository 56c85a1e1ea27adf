// Twin of crates/glint-core/src/cpu/trace.rs: the Whitted ray tree and the pixel's samples.
//
// WGSL has no recursion, so the tree is walked with an explicit stack of (ray, path weight,
// depth). Each node adds weight × local shading, where the CPU adds k·I(child) on return:
// the same terms with the same bailout decisions, summed in another order.
#import glint::scene_data::{NO_HIT, STATUS_LOOP_LIMIT, STATUS_STACK_OVERFLOW, STATUS_DRIVER_LOOP_CUTOFF, STAT_STATUS}
#import glint::bindings::{header, camera, tile, materials, spheres, planes, triangles, meshes, output, stats}
#import glint::ray::{Ray, RayCounts, ray_counts, status, driver_cut_loops, flush_counts}
#import glint::camera::{CameraRay, camera_ray, eye, from_eye, sample_offset}
#import glint::ray::FAR
#import glint::intersect::{Hit, Leaving, PRIM_NONE, PRIM_SPHERE, PRIM_PLANE, all_zero}
#ifdef BVH
#import glint::bvh::closest_hit
#else
#import glint::intersect::closest_hit
#endif
#import glint::offset::{spawn_ray, leaving_surface}
#import glint::shade::shade_local
#import glint::surface::{surface_at, reflect_dir, max_channel}
#ifdef TRANSMISSION
#import glint::surface::refract_dir
#endif
#ifdef PROBE
#import glint::scene_data::{RAY_REFLECTION, RAY_REFRACTION}
#import glint::probe::{probe_start, probe_root, probe_enter, probe_attenuation, probe_shade_begin, probe_shade_end, probe_hit, probe_factors, probe_cut, probe_child, probe_push, probe_pop, probe_gathered, probe_finish}
#endif
#ifdef GLOBAL_ATTENUATION
#import glint::shade::attenuation_factor
#endif

struct SampleResult {
    radiance: vec3<f32>,
    object: u32,
}

// Deferred rays the stack holds: a depth-first walk that follows one child at once defers
// at most one ray per level, so max_depth entries suffice.
const STACK_SIZE: u32 = #{STACK_SIZE}u;
// Bound of the tree walk per sample (glint_gpu::shaders::MAX_TREE_NODES, below lavapipe's loop
// budget); reaching it raises STATUS_LOOP_LIMIT.
const MAX_TREE_NODES: u32 = #{MAX_TREE_NODES}u;

struct StackEntry {
    origin: vec3<f32>,
    t_min: f32,
    dir: vec3<f32>,
    depth: u32,
    weight: vec3<f32>,
    // The primitive the ray leaves (skip_convex only).
    leaving: Leaving,
    // Which child of the camera ray's hit this ray descends from: 0 the camera ray itself,
    // 1 the mirror child, 2 the refracted child (the pixel probe sums radiance by branch).
    branch: u32,
}

var<private> stack: array<StackEntry, STACK_SIZE>;
var<private> stack_top: u32;

// A path weight times v (a child's k, a local radiance), where a zero of v stays zero. The CPU
// adds k·I(child) on return, where a zero radiance stays zero; here the weight is carried down,
// and k_r up to 1e9 passes f32's range within 5 bounces: ∞·0 would be NaN. An infinite weight
// times light is infinite, so the image is refused as the CPU's is; a weight held at f32's
// largest value had written a finite, wrong image (k_r = 2 at depth 140; a tester).
fn weigh(weight: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    return select(weight * v, vec3<f32>(0.0), v == vec3<f32>(0.0));
}

#ifdef RECURSION
fn push_ray(entry: StackEntry) {
    if stack_top >= STACK_SIZE {
        status |= STATUS_STACK_OVERFLOW;
        return;
    }
    stack[stack_top] = entry;
#ifdef PROBE
    probe_push(stack_top);
#endif
    stack_top += 1u;
}
#endif

// What shading a hit yields: its weighted local radiance and, when the ray tree goes on, the
// next ray to follow (the other child, if any, waits on the stack).
struct Shaded {
    radiance: vec3<f32>,
    next: StackEntry,
    has_next: bool,
}

// weight × local shading at a hit, and the children whose path weight passes the bailout:
// the mirror child continues at once, a refracted child is pushed (or continues, when there is
// no mirror child). Keeping one child out of the stack spares most scratch-memory traffic.
fn shade_hit(ray: Ray, hit: Hit, depth: u32, weight: vec3<f32>, branch: u32) -> Shaded {
    let s = surface_at(ray, hit);
    let front = dot(ray.dir, s.ng) < 0.0;
    let ng = select(-s.ng, s.ng, front);
    let ns = select(-s.ns, s.ns, front);
    let v = -ray.dir;
    let no_ray = StackEntry(vec3<f32>(0.0), 0.0, vec3<f32>(0.0), 0u, vec3<f32>(0.0), Leaving(PRIM_NONE, 0u, false), 0u);
    var out = Shaded(weigh(weight, shade_local(s, ns, ng, v)), no_ray, false);
#ifdef PROBE
    probe_hit(s, ns, hit.t, depth, weight);
#endif
#ifdef RECURSION
#ifndef PROBE
    // (The probe walks on past the depth limit to record the children it cuts: probe_cut.)
    if depth >= header.max_depth {
        return out;
    }
#endif
    let mat = materials[s.material];
    let kr = mat.kr.xyz;
    let kt = mat.kt.xyz;
    var k_mirror = kr;
    var refracted = vec4<f32>(0.0);
#ifdef TRANSMISSION
    if !all_zero(kt) {
        let eta = select(mat.ior, 1.0 / mat.ior, front);
        refracted = refract_dir(ray.dir, ns, eta);
        if refracted.w == 0.0 {
            k_mirror += kt;
        }
    }
#ifdef PROBE
    probe_factors(kr, kt, !all_zero(kt) && refracted.w == 0.0);
#endif
    if refracted.w != 0.0 {
        let w = weigh(weight, kt);
#ifdef PROBE
        // A cut child goes down the walk like a traced one, so that it is recorded in the
        // CPU's order (after the mirror child's subtree), but is not traced.
        let cut = probe_cut(depth, max_channel(w));
        if cut != 0u {
            out.next = StackEntry(s.p, 0.0, refracted.xyz, depth + 1u, w, no_ray.leaving, branch);
            out.has_next = true;
        } else {
#else
        if max_channel(w) < header.bailout {
            ray_counts.bailout_saved += 1u;
        } else {
#endif
            ray_counts.refraction += 1u;
            let sp = spawn_ray(s.p, s.p_surface, -ng, refracted.xyz, leaving_surface(s.prim, s.index, s.ng, -ng));
            out.next = StackEntry(sp.origin, sp.t_min, refracted.xyz, depth + 1u, w, sp.leaving, select(branch, 2u, branch == 0u));
            out.has_next = true;
        }
#ifdef PROBE
        probe_child(RAY_REFRACTION, cut, kt);
#endif
    }
#endif
    if !all_zero(k_mirror) {
        let w = weigh(weight, k_mirror);
#ifdef PROBE
        let cut = probe_cut(depth, max_channel(w));
        if cut != 0u {
            if out.has_next {
                push_ray(out.next);
            }
            out.next = StackEntry(s.p, 0.0, reflect_dir(ray.dir, ns), depth + 1u, w, no_ray.leaving, branch);
            out.has_next = true;
        } else {
#else
        if max_channel(w) < header.bailout {
            ray_counts.bailout_saved += 1u;
        } else {
#endif
            ray_counts.reflection += 1u;
            let dir = reflect_dir(ray.dir, ns);
            let sp = spawn_ray(s.p, s.p_surface, ng, dir, leaving_surface(s.prim, s.index, s.ng, ng));
            if out.has_next {
                push_ray(out.next);
            }
            out.next = StackEntry(sp.origin, sp.t_min, dir, depth + 1u, w, sp.leaving, select(branch, 1u, branch == 0u));
            out.has_next = true;
        }
#ifdef PROBE
        probe_child(RAY_REFLECTION, cut, k_mirror);
#endif
    }
#endif
    return out;
}

// Radiance along a camera ray: its whole tree, walked depth first. Returns the radiance and
// the id of the first object hit.
fn trace_ray(primary: CameraRay) -> SampleResult {
    var result = SampleResult(vec3<f32>(0.0), NO_HIT);
    var e = StackEntry(primary.ray.origin, primary.t_min, primary.ray.dir, 0u, vec3<f32>(1.0), Leaving(PRIM_NONE, 0u, false), 0u);
    stack_top = 0u;
#ifdef PROBE
    probe_root();
#endif
    // Declared outside the loop: a driver that cuts the loop short (lavapipe's budget) leaves
    // it below the bound, and that is STATUS_DRIVER_LOOP_CUTOFF's to say, not the bound's.
    var n = 0u;
    for (; n < MAX_TREE_NODES; n++) {
        let r = Ray(e.origin, e.dir);
        let branch_of_node = e.branch;
#ifdef PROBE
        // The camera ray recorded from the eye, where it leaves (traced from the anchor's plane).
        let camera_node = n == 0u;
        if probe_enter(Ray(select(r.origin, eye(primary), camera_node), r.dir), select(e.t_min, 0.0, camera_node), e.depth, e.weight) {
            // Recorded, not traced.
            if stack_top == 0u {
                return result;
            }
            stack_top -= 1u;
            e = stack[stack_top];
            probe_pop(stack_top);
            continue;
        }
#endif
        let hit = closest_hit(r, e.t_min, FAR, e.leaving);
        var has_next = false;
        var gathered = vec3<f32>(0.0);
        if hit.prim == PRIM_NONE {
            gathered = weigh(e.weight, header.background.xyz);
        } else {
            if n == 0u {
                result.object = object_id(hit);
            }
#ifdef GLOBAL_ATTENUATION
            // A child ray's whole share, and its children's path weight, times f_att(t) (the
            // CPU's trace_ray); the camera ray (depth 0) and the background are not attenuated.
            if e.depth > 0u {
                let f = attenuation_factor(header.global_attenuation, hit.t);
                e.weight = weigh(e.weight, vec3<f32>(f));
#ifdef PROBE
                probe_attenuation(f);
#endif
            }
#endif
#ifdef PROBE
            probe_shade_begin();
#endif
            let shaded = shade_hit(r, hit, e.depth, e.weight, e.branch);
#ifdef PROBE
            probe_shade_end(select(hit.t, from_eye(primary, hit.t), n == 0u), n == 0u);
#endif
            gathered = shaded.radiance;
            e = shaded.next;
            has_next = shaded.has_next;
        }
#ifdef PROBE
        // `e` may already be the next ray: the branch is that of the ray just shaded.
        probe_gathered(branch_of_node, gathered);
#endif
        result.radiance += gathered;
        if !has_next {
            if stack_top == 0u {
                return result;
            }
            stack_top -= 1u;
            e = stack[stack_top];
#ifdef PROBE
            probe_pop(stack_top);
#endif
        }
    }
    if n >= MAX_TREE_NODES {
        status |= STATUS_LOOP_LIMIT;
    }
    return result;
}

fn object_id(hit: Hit) -> u32 {
#ifdef SPHERES
    if hit.prim == PRIM_SPHERE {
        return spheres[hit.index].object_id;
    }
#endif
#ifdef PLANES
    if hit.prim == PRIM_PLANE {
        return planes[hit.index].object_id;
    }
#endif
#ifdef TRIANGLES
    return meshes[triangles[hit.index].mesh].object_id;
#else
    return NO_HIT;
#endif
}

fn render_sample(x: u32, y: u32, sample_index: u32) -> SampleResult {
    let pixel = y * header.width + x;
    // Whitted's one sample is the pixel's centre, also in the shader with every feature on.
    let offset = sample_offset(pixel, sample_index, header.spp, header.seed, header.spp > 1u);
    ray_counts.camera += 1u;
    return trace_ray(camera_ray(camera, header.width, header.height, x, y, offset));
}

// Adds sample `tile.sample_index` of pixel (x, y) to the output. The samples of a pixel come in
// separate dispatches, in order, so the sum is formed as the CPU forms it: s0 + s1 + … then / spp.
fn accumulate_sample(x: u32, y: u32) {
    let index = y * header.width + x;
    let sample = render_sample(x, y, tile.sample_index);
    if tile.sample_index == 0u {
        var id = -1.0;
        if sample.object != NO_HIT {
            id = f32(sample.object);
        }
        output[index] = vec4<f32>(sample.radiance, id);
    } else {
        output[index] = vec4<f32>(output[index].xyz + sample.radiance, output[index].w);
    }
    if tile.sample_index + 1u == header.spp && header.spp > 1u {
        output[index] = vec4<f32>(output[index].xyz / f32(header.spp), output[index].w);
    }
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= tile.width || gid.y >= tile.height {
        return;
    }
    let x = tile.origin_x + gid.x;
    let y = tile.origin_y + gid.y;
    ray_counts = RayCounts(0u, 0u, 0u, 0u, 0u);
    status = 0u;
#ifdef PROBE
    // The probe variant renders one pixel's first sample and writes its breakdown and its
    // ray tree.
    probe_start();
    probe_finish(render_sample(x, y, 0u).radiance);
    if driver_cut_loops() {
        status |= STATUS_DRIVER_LOOP_CUTOFF;
    }
    if status != 0u {
        atomicOr(&stats[STAT_STATUS], status);
    }
    return;
#endif
    accumulate_sample(x, y);
    if driver_cut_loops() {
        status |= STATUS_DRIVER_LOOP_CUTOFF;
    }
    flush_counts();
}
