// Twin of crates/glint-core/src/cpu/trace.rs: the Whitted ray tree and the pixel's samples.
//
// WGSL has no recursion, so the tree is walked with an explicit stack of (ray, path weight,
// depth). Each node adds weight × local shading, where the CPU adds k·I(child) on return:
// the same terms with the same bailout decisions, summed in another order.
#import glint::scene_data::{PROBE_HIT, PROBE_TIR, GpuSphere, GpuPlane, GpuTriangle, NO_HIT, EPS_ROBUST, UV_MESH, STATUS_LOOP_LIMIT, STATUS_STACK_OVERFLOW, STATUS_DRIVER_LOOP_CUTOFF, STAT_STATUS, STAT_CAMERA, STAT_SHADOW, STAT_REFLECTION, STAT_REFRACTION, STAT_BAILOUT_SAVED}
#import glint::bindings::{header, camera, tile, materials, spheres, planes, triangles, meshes, output, stats, probe_out}
#import glint::ray::{Ray, RayCounts, ray_counts, status, probe, probe_active, driver_cut_loops}
#import glint::camera::{camera_ray, sample_offset}
#import glint::intersect::{Hit, Leaving, FAR, PRIM_NONE, PRIM_SPHERE, PRIM_PLANE, PRIM_TRIANGLE, triangle_corners, triangle_shading_normal, all_zero, sphere_surface_point}
#ifdef BVH
#import glint::bvh::closest_hit
#else
#import glint::intersect::closest_hit
#endif
#import glint::offset::{spawn_ray, leaving_surface}
#import glint::shade::{Surface, shade_local}
#ifdef PROBE
#import glint::scene_data::{ProbeRecord, ProbeNode, MAX_PROBE_NODES, MAX_PROBE_LIGHTS, RAY_CAMERA, RAY_REFLECTION, RAY_REFRACTION, RAY_SHADOW, NODE_HIT, NODE_TIR, NODE_CUT_BAILOUT, NODE_CUT_DEPTH, NO_PARENT, TREE_OVERFLOW, TREE_LIGHTS_TRUNCATED}
#import glint::bindings::{probe_tree, lights}
#import glint::shade::light_sample
#endif
#ifdef GLOBAL_ATTENUATION
#import glint::shade::attenuation_factor
#endif
#ifdef TEXTURES
#import glint::texture::{planar_axis, planar_uv}
#ifdef TRIANGLES
#import glint::texture::{triangle_uv, triangle_uv_origin}
#endif
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

#ifdef PROBE
// How a ray of the walk joins the probe's ray tree (twin of the CPU's RayNode::new arguments):
// the node whose hit spawned it, its kind, NODE_* flags (a cut ray is recorded, not traced)
// and its own factor k.
struct ProbeLink {
    parent: u32,
    kind: u32,
    flags: u32,
    factor: vec3<f32>,
}

// The links beside the stack's rays, and that of the ray shade_hit hands back as `next`.
var<private> link_stack: array<ProbeLink, STACK_SIZE>;
var<private> next_link: ProbeLink;
// The tree node being shaded.
var<private> probe_node: u32;
// The first hit's breakdown (ProbeRecord), kept while the later nodes record theirs in `probe`.
var<private> probe_first: ProbeRecord;

// The index of a new tree node; past the buffer's capacity the tree is marked overflowed and
// the node is not written (every writer checks the index).
fn probe_alloc() -> u32 {
    let i = probe_tree.node_count;
    probe_tree.node_count = i + 1u;
    if i >= MAX_PROBE_NODES {
        probe_tree.flags |= TREE_OVERFLOW;
    }
    return i;
}

// Node i with no hit, no terms and no light: a node's fields one by one, never the whole
// struct (with its light array), which lavapipe compiles into thousands of stores.
fn probe_clear(i: u32) {
    probe_tree.nodes[i].object_id = 0u;
    probe_tree.nodes[i].material = 0u;
    probe_tree.nodes[i].light = 0u;
    probe_tree.nodes[i].light_count = 0u;
    probe_tree.nodes[i].t = 0.0;
    probe_tree.nodes[i].attenuation = 1.0;
    probe_tree.nodes[i].point = vec4<f32>(0.0);
    probe_tree.nodes[i].normal = vec4<f32>(0.0);
    probe_tree.nodes[i].emission = vec4<f32>(0.0);
    probe_tree.nodes[i].ambient = vec4<f32>(0.0);
    probe_tree.nodes[i].ka = vec4<f32>(0.0);
    probe_tree.nodes[i].kd = vec4<f32>(0.0);
}

// A node for the ray `e` joined to the tree by `link`, before its hit is known.
fn probe_open(link: ProbeLink, e: StackEntry) -> u32 {
    let i = probe_alloc();
    if i < MAX_PROBE_NODES {
        probe_clear(i);
        probe_tree.nodes[i].kind = link.kind;
        probe_tree.nodes[i].flags = link.flags;
        probe_tree.nodes[i].parent = link.parent;
        probe_tree.nodes[i].depth = e.depth;
        probe_tree.nodes[i].origin = vec4<f32>(e.origin, e.t_min);
        probe_tree.nodes[i].dir = vec4<f32>(e.dir, 0.0);
        probe_tree.nodes[i].weight = vec4<f32>(e.weight, 0.0);
        probe_tree.nodes[i].factor = vec4<f32>(link.factor, 0.0);
    }
    return i;
}

// The hit of node i and the local terms shade_local recorded in `probe`.
fn probe_close(i: u32, t: f32) {
    if i >= MAX_PROBE_NODES {
        return;
    }
    probe_tree.nodes[i].flags |= NODE_HIT;
    probe_tree.nodes[i].t = t;
    probe_tree.nodes[i].object_id = probe.object_id;
    probe_tree.nodes[i].material = probe.material;
    probe_tree.nodes[i].light_count = probe.light_count;
    probe_tree.nodes[i].point = probe.point;
    probe_tree.nodes[i].normal = probe.normal;
    probe_tree.nodes[i].emission = probe.emission;
    probe_tree.nodes[i].ambient = probe.ambient;
    probe_tree.nodes[i].ka = probe.ka;
    probe_tree.nodes[i].kd = probe.kd;
    for (var j = 0u; j < probe.light_count; j++) {
        probe_tree.nodes[i].lights[j] = probe.lights[j];
    }
}

// The shadow rays of the node being shaded, from its recorded light terms (twin of
// glint_core::ray_tree::record_shadow_rays): one node per light a shadow ray was traced to,
// from p along the light sample's L, its factor V_j.
fn record_shadow_rays(p: vec3<f32>, depth: u32, weight: vec3<f32>) {
    for (var j = 0u; j < min(header.light_count, MAX_PROBE_LIGHTS); j++) {
        if probe.lights[j].shadow_ray == 0u {
            continue;
        }
        let ls = light_sample(lights[j], p);
        let i = probe_alloc();
        if i < MAX_PROBE_NODES {
            probe_clear(i);
            probe_tree.nodes[i].kind = RAY_SHADOW;
            probe_tree.nodes[i].parent = probe_node;
            probe_tree.nodes[i].depth = depth + 1u;
            probe_tree.nodes[i].light = j;
            probe_tree.nodes[i].t = ls.dist;
            probe_tree.nodes[i].origin = vec4<f32>(p, 0.0);
            probe_tree.nodes[i].dir = vec4<f32>(ls.l, 0.0);
            probe_tree.nodes[i].weight = vec4<f32>(weight, 0.0);
            probe_tree.nodes[i].factor = probe.lights[j].visibility;
        }
    }
}

#ifdef RECURSION
// Whether a child of path weight w at `depth` is cut (NODE_CUT_*), counting bailouts as the
// tracer does; 0 when it is traced.
fn probe_cut(depth: u32, w: vec3<f32>) -> u32 {
    if depth >= header.max_depth {
        return NODE_CUT_DEPTH;
    }
    if max_channel(w) < header.bailout {
        ray_counts.bailout_saved += 1u;
        return NODE_CUT_BAILOUT;
    }
    return 0u;
}
#endif
#endif

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
        return Surface(p, p_surface, ng, ng, uv, uv_origin, s.material, s.object_id, PRIM_SPHERE, hit.index);
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
        return Surface(p, p_surface, ng, ng, uv, uv_origin, pl.material, pl.object_id, PRIM_PLANE, hit.index);
    }
#endif
#ifdef TRIANGLES
    let tri = triangles[hit.index];
    let v = triangle_corners(tri);
    let ng = normalize(cross(v[1] - v[0], v[2] - v[0]));
    let ns = triangle_shading_normal(tri, hit.bu, hit.bv, ng);
    let p_surface = select(p, (1.0 - hit.bu - hit.bv) * v[0] + hit.bu * v[1] + hit.bv * v[2], robust);
    var uv = vec2<f32>(0.0);
    var uv_origin = UV_MESH;
#ifdef TEXTURES
    uv = triangle_uv(tri, hit.bu, hit.bv, p, ng);
    uv_origin = triangle_uv_origin(tri, ng);
#endif
    let mesh = meshes[tri.mesh];
    return Surface(p, p_surface, ng, ns, uv, uv_origin, mesh.material, mesh.object_id, PRIM_TRIANGLE, hit.index);
#else
    return Surface(p, p, vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec2<f32>(0.0), UV_MESH, 0u, NO_HIT, PRIM_NONE, 0u);
#endif
}

#ifdef RECURSION
#ifdef TRANSMISSION
fn refract_dir(d: vec3<f32>, n: vec3<f32>, eta: f32) -> vec4<f32> {
    // xyz: direction; w: 1 if refracted, 0 under total internal reflection.
    let cos_i = -dot(d, n);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if k < 0.0 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(normalize(eta * d + (eta * cos_i - sqrt(k)) * n), 1.0);
}

#endif

fn reflect_dir(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return normalize(d - 2.0 * dot(d, n) * n);
}

fn max_channel(v: vec3<f32>) -> f32 {
    return max(max(v.x, v.y), v.z);
}

fn push_ray(entry: StackEntry) {
    if stack_top >= STACK_SIZE {
        status |= STATUS_STACK_OVERFLOW;
        return;
    }
    stack[stack_top] = entry;
#ifdef PROBE
    link_stack[stack_top] = next_link;
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
    var out = Shaded(weight * shade_local(s, ns, ng, v), no_ray, false);
#ifdef PROBE
    if probe_active {
        probe.flags |= PROBE_HIT;
        probe.object_id = s.object_id;
        probe.material = s.material;
        probe.t = hit.t;
        probe.point = vec4<f32>(s.p, 1.0);
        probe.normal = vec4<f32>(ns, 0.0);
        record_shadow_rays(s.p, depth, weight);
    }
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
#ifdef PROBE
    var tir = 0u;
#endif
#ifdef TRANSMISSION
    if !all_zero(kt) {
        let eta = select(mat.ior, 1.0 / mat.ior, front);
        refracted = refract_dir(ray.dir, ns, eta);
        if refracted.w == 0.0 {
            k_mirror += kt;
#ifdef PROBE
            if probe_active {
                probe.flags |= PROBE_TIR;
            }
            tir = NODE_TIR;
#endif
        }
    }
#ifdef PROBE
    if probe_active {
        probe.kr = vec4<f32>(kr, 0.0);
        probe.kt = vec4<f32>(kt, 0.0);
    }
#endif
    if refracted.w != 0.0 {
        let w = weight * kt;
#ifdef PROBE
        // A cut child goes down the walk like a traced one, so that it is recorded in the
        // CPU's order (after the mirror child's subtree), but is not traced.
        let cut = probe_cut(depth, w);
        if cut != 0u {
            out.next = StackEntry(s.p, 0.0, refracted.xyz, depth + 1u, w, no_ray.leaving, branch);
            next_link = ProbeLink(probe_node, RAY_REFRACTION, cut, kt);
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
#ifdef PROBE
            next_link = ProbeLink(probe_node, RAY_REFRACTION, 0u, kt);
#endif
        }
    }
#endif
    if !all_zero(k_mirror) {
        let w = weight * k_mirror;
#ifdef PROBE
        let cut = probe_cut(depth, w);
        if cut != 0u {
            if out.has_next {
                push_ray(out.next);
            }
            out.next = StackEntry(s.p, 0.0, reflect_dir(ray.dir, ns), depth + 1u, w, no_ray.leaving, branch);
            next_link = ProbeLink(probe_node, RAY_REFLECTION, cut | tir, k_mirror);
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
#ifdef PROBE
            next_link = ProbeLink(probe_node, RAY_REFLECTION, tir, k_mirror);
#endif
        }
    }
#endif
    return out;
}

// Radiance along a camera ray: its whole tree, walked depth first. Returns the radiance and
// the id of the first object hit.
fn trace_ray(ray: Ray) -> SampleResult {
    var result = SampleResult(vec3<f32>(0.0), NO_HIT);
    var e = StackEntry(ray.origin, 0.0, ray.dir, 0u, vec3<f32>(1.0), Leaving(PRIM_NONE, 0u, false), 0u);
    stack_top = 0u;
#ifdef PROBE
    next_link = ProbeLink(NO_PARENT, RAY_CAMERA, 0u, vec3<f32>(1.0));
#endif
    for (var n = 0u; n < MAX_TREE_NODES; n++) {
        let r = Ray(e.origin, e.dir);
        let branch_of_node = e.branch;
#ifdef PROBE
        let link = next_link;
        probe_node = probe_open(link, e);
        if (link.flags & (NODE_CUT_BAILOUT | NODE_CUT_DEPTH)) != 0u {
            // Recorded, not traced.
            if stack_top == 0u {
                return result;
            }
            stack_top -= 1u;
            e = stack[stack_top];
            next_link = link_stack[stack_top];
            continue;
        }
#endif
        let hit = closest_hit(r, e.t_min, FAR, e.leaving);
        var has_next = false;
        var gathered = vec3<f32>(0.0);
        if hit.prim == PRIM_NONE {
            gathered = e.weight * header.background.xyz;
        } else {
            if n == 0u {
                result.object = object_id(hit);
            }
#ifdef GLOBAL_ATTENUATION
            // A child ray's whole share, and its children's path weight, times f_att(t) (the
            // CPU's trace_ray); the camera ray (depth 0) and the background are not attenuated.
            if e.depth > 0u {
                let f = attenuation_factor(header.global_attenuation, hit.t);
                e.weight *= f;
#ifdef PROBE
                if probe_node < MAX_PROBE_NODES {
                    probe_tree.nodes[probe_node].attenuation = f;
                }
#endif
            }
#endif
#ifdef PROBE
            // Every hit records its terms in `probe` (each writes every field it reads back, but
            // the flags it ORs); the first hit's are kept as the breakdown.
            probe.flags = 0u;
            probe_active = true;
#endif
            let shaded = shade_hit(r, hit, e.depth, e.weight, e.branch);
#ifdef PROBE
            probe_active = false;
            probe_close(probe_node, hit.t);
            if n == 0u {
                probe_first = probe;
            }
#endif
            gathered = shaded.radiance;
            e = shaded.next;
            has_next = shaded.has_next;
        }
#ifdef PROBE
        if n > 0u {
            // `e` may already be the next ray: the branch is that of the ray just shaded.
            if branch_of_node == 1u {
                probe_first.mirror_sum += vec4<f32>(gathered, 0.0);
            } else if branch_of_node == 2u {
                probe_first.refraction_sum += vec4<f32>(gathered, 0.0);
            }
        }
#endif
        result.radiance += gathered;
        if !has_next {
            if stack_top == 0u {
                return result;
            }
            stack_top -= 1u;
            e = stack[stack_top];
#ifdef PROBE
            next_link = link_stack[stack_top];
#endif
        }
    }
    status |= STATUS_LOOP_LIMIT;
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
    let offset = sample_offset(pixel, sample_index, header.spp, header.seed);
    let ray = camera_ray(camera, header.width, header.height, x, y, offset);
    ray_counts.camera += 1u;
    return trace_ray(ray);
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

// Adds a count to a (lo, hi) pair of the statistics buffer with carry, so that counts past
// 2^32 stay exact.
fn add_stat(index: u32, value: u32) {
    if value == 0u {
        return;
    }
    let old = atomicAdd(&stats[index], value);
    if old + value < old {
        atomicAdd(&stats[index + 1u], 1u);
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
    probe_tree.node_count = 0u;
    probe_tree.flags = select(0u, TREE_LIGHTS_TRUNCATED, header.light_count > MAX_PROBE_LIGHTS);
    let sampled = render_sample(x, y, 0u);
    probe_first.total = vec4<f32>(sampled.radiance, 0.0);
    if (probe_first.flags & PROBE_HIT) == 0u {
        probe_first.object_id = NO_HIT;
    }
    probe_out = probe_first;
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
    add_stat(STAT_CAMERA, ray_counts.camera);
    add_stat(STAT_SHADOW, ray_counts.shadow);
    add_stat(STAT_REFLECTION, ray_counts.reflection);
    add_stat(STAT_REFRACTION, ray_counts.refraction);
    add_stat(STAT_BAILOUT_SAVED, ray_counts.bailout_saved);
    if status != 0u {
        atomicOr(&stats[STAT_STATUS], status);
    }
}
