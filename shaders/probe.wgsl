// Twin of crates/glint-core/src/cpu/ray_tree.rs: the pixel probe's ray tree (PROBE variant only).
// trace.wgsl's walk calls one probe_* hook where the CPU's trace.rs calls its TreeRecorder,
// and the nodes come out in the CPU's depth-first order.
#define_import_path glint::probe

#import glint::scene_data::{ProbeRecord, PROBE_HIT, PROBE_TIR, NO_HIT, MAX_PROBE_NODES, MAX_PROBE_LIGHTS, RAY_CAMERA, RAY_REFLECTION, RAY_SHADOW, NODE_HIT, NODE_TIR, NODE_CUT_BAILOUT, NODE_CUT_DEPTH, NO_PARENT, TREE_OVERFLOW, TREE_LIGHTS_TRUNCATED}
#import glint::bindings::{header, lights, probe_out, probe_tree}
#import glint::ray::{Ray, ray_counts, probe, probe_active}
#import glint::shade::{Surface, light_sample}

// How a ray of the walk joins the tree (twin of the CPU's RayNode::new arguments): the node
// whose hit spawned it, its kind, NODE_* flags (a cut ray is recorded, not traced) and its own
// factor k.
struct ProbeLink {
    parent: u32,
    kind: u32,
    flags: u32,
    factor: vec3<f32>,
}

// The links beside trace.wgsl's stack of rays (as many entries), and that of the ray shade_hit
// hands back as `next`.
var<private> link_stack: array<ProbeLink, #{STACK_SIZE}u>;
var<private> next_link: ProbeLink;
// The tree node being shaded.
var<private> probe_node: u32;
// NODE_TIR when the hit being shaded reflects totally: its mirror child carries the flag.
var<private> hit_tir: u32;
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

// A node for `ray` (from t_min) joined to the tree by `link`, before its hit is known: the
// CPU's RayNode::new and TreeRecorder::open in one.
fn open(link: ProbeLink, ray: Ray, t_min: f32, depth: u32, weight: vec3<f32>) -> u32 {
    let i = probe_alloc();
    if i < MAX_PROBE_NODES {
        probe_clear(i);
        probe_tree.nodes[i].kind = link.kind;
        probe_tree.nodes[i].flags = link.flags;
        probe_tree.nodes[i].parent = link.parent;
        probe_tree.nodes[i].depth = depth;
        probe_tree.nodes[i].origin = vec4<f32>(ray.origin, t_min);
        probe_tree.nodes[i].dir = vec4<f32>(ray.dir, 0.0);
        probe_tree.nodes[i].weight = vec4<f32>(weight, 0.0);
        probe_tree.nodes[i].factor = vec4<f32>(link.factor, 0.0);
    }
    return i;
}

// The hit of node i and the local terms shade_local recorded in `probe` (its attenuation comes
// from probe_attenuation; the GPU records no radiance).
fn close(i: u32, t: f32) {
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

// The shadow rays of the node being shaded, from its recorded light terms: one node per light a
// shadow ray was traced to, from p along the light sample's L, its factor V_j.
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

// The hooks of trace.wgsl's walk, in the order of the walk.

// main: an empty tree for the pixel's first sample.
fn probe_start() {
    probe_tree.node_count = 0u;
    probe_tree.flags = select(0u, TREE_LIGHTS_TRUNCATED, header.light_count > MAX_PROBE_LIGHTS);
}

// trace_ray: the camera ray is the tree's root.
fn probe_root() {
    next_link = ProbeLink(NO_PARENT, RAY_CAMERA, 0u, vec3<f32>(1.0));
}

// The walk takes up `ray`: its node, opened. True for a cut ray, which is recorded, not traced.
fn probe_enter(ray: Ray, t_min: f32, depth: u32, weight: vec3<f32>) -> bool {
    probe_node = open(next_link, ray, t_min, depth, weight);
    return (next_link.flags & (NODE_CUT_BAILOUT | NODE_CUT_DEPTH)) != 0u;
}

// The global attenuation f_att(t) at the node's hit.
fn probe_attenuation(f: f32) {
    if probe_node < MAX_PROBE_NODES {
        probe_tree.nodes[probe_node].attenuation = f;
    }
}

// Every hit records its terms in `probe` (each writes every field it reads back, but the flags
// it ORs); the first hit's are kept as the breakdown (probe_shade_end).
fn probe_shade_begin() {
    probe.flags = 0u;
    probe_active = true;
}

// shade_hit: the hit after its local shading, and its shadow rays.
fn probe_hit(s: Surface, ns: vec3<f32>, t: f32, depth: u32, weight: vec3<f32>) {
    // Until probe_factors says otherwise (it is not called without TRANSMISSION).
    hit_tir = 0u;
    if probe_active {
        probe.flags |= PROBE_HIT;
        probe.object_id = s.object_id;
        probe.material = s.material;
        probe.t = t;
        probe.point = vec4<f32>(s.p, 1.0);
        probe.normal = vec4<f32>(ns, 0.0);
        record_shadow_rays(s.p, depth, weight);
    }
}

// shade_hit (TRANSMISSION): the hit's k_r and k_t, and whether it reflects totally.
fn probe_factors(kr: vec3<f32>, kt: vec3<f32>, tir: bool) {
    if probe_active {
        if tir {
            probe.flags |= PROBE_TIR;
        }
        probe.kr = vec4<f32>(kr, 0.0);
        probe.kt = vec4<f32>(kt, 0.0);
    }
    hit_tir = select(0u, NODE_TIR, tir);
}

// Whether a child at `depth` whose path weight's largest channel is m is cut (NODE_CUT_*),
// counting bailouts as the tracer does; 0 when it is traced. The probe walks on past the depth
// limit to record the children it cuts.
fn probe_cut(depth: u32, m: f32) -> u32 {
    if depth >= header.max_depth {
        return NODE_CUT_DEPTH;
    }
    if m < header.bailout {
        ray_counts.bailout_saved += 1u;
        return NODE_CUT_BAILOUT;
    }
    return 0u;
}

// The child shade_hit hands back as `next`, traced or `cut`, with its own factor.
fn probe_child(kind: u32, cut: u32, factor: vec3<f32>) {
    next_link = ProbeLink(probe_node, kind, cut | select(0u, hit_tir, kind == RAY_REFLECTION), factor);
}

// push_ray and the walk's pops: the link of the ray at stack index i.
fn probe_push(i: u32) {
    link_stack[i] = next_link;
}

fn probe_pop(i: u32) {
    next_link = link_stack[i];
}

// After shade_hit: the node's hit at t (a camera ray's from the eye) and terms, and the first
// hit's breakdown kept.
fn probe_shade_end(t: f32, first: bool) {
    probe_active = false;
    close(probe_node, t);
    if first {
        probe_first = probe;
        probe_first.t = t;
    }
}

// The radiance a node gathered, summed by the camera hit's child it descends from (branch 1
// the mirror child, 2 the refracted one; the camera ray's own, branch 0, by neither).
fn probe_gathered(branch: u32, gathered: vec3<f32>) {
    if branch == 1u {
        probe_first.mirror_sum += vec4<f32>(gathered, 0.0);
    } else if branch == 2u {
        probe_first.refraction_sum += vec4<f32>(gathered, 0.0);
    }
}

// main: the first hit's breakdown, its total the sample's radiance.
fn probe_finish(radiance: vec3<f32>) {
    probe_first.total = vec4<f32>(radiance, 0.0);
    if (probe_first.flags & PROBE_HIT) == 0u {
        probe_first.object_id = NO_HIT;
    }
    probe_out = probe_first;
}
