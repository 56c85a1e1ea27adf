// Twin of crates/glint-core/src/cpu/bvh/mod.rs: closest hit and shadow transmittance through the
// BVH (built on the CPU, glint_core::bvh), used instead of intersect.wgsl's brute-force loops
// under the BVH shader def (trace.wgsl and shade.wgsl import from here then: intersect.wgsl
// cannot import this module, which imports its primitive tests).
//
// Never misses a hit brute force finds: the slab test pads each box by a relative margin far
// above f32 rounding; of equal t the smaller (kind, index) in brute force's order wins, so the
// result does not depend on the visiting order. Below the root, a node's box is its parent's
// quantized record of it (glint_types::layout::QuantizedPair), which only ever holds more. The
// stack is fixed (BVH_STACK_SIZE); a traversal that needs more raises
// STATUS_BVH_STACK_OVERFLOW, never silently. Shadow crossings
// are multiplied in visiting order (the CPU sorts them to be bit-identical to its brute force;
// the f32 GPU image is compared within the parity thresholds). A leaf's triangles are read from
// their corners copied in leaf order (bindings.wgsl), as the CPU's are from its own copy.
#define_import_path glint::bvh

#import glint::scene_data::{BvhNode, QuantizedPair, PRIM_REF_TRIANGLE, PRIM_REF_INDEX, NODE_REF_COUNT_BITS, PAIR_FIRST_SHIFT, STATUS_BVH_STACK_OVERFLOW}
#import glint::bindings::{header, planes, spheres, triangles, meshes, bvh_nodes, bvh_leaf_ab, bvh_leaf_c}
#import glint::ray::{Ray, status}
#import glint::primitive::{MaybeT, sphere_roots, intersect_triangle, ray_shear}
#import glint::intersect::{Hit, Leaving, PRIM_NONE, PRIM_SPHERE, PRIM_PLANE, PRIM_TRIANGLE, intersect_sphere_leaving, cross_surface, all_zero, sphere_transmittance, planes_transmittance, bound, replaces}
#ifdef SKIP_LEFT
#import glint::intersect::is_leaving
#endif
#ifdef PLANES
#import glint::intersect::closest_plane
#endif

// Entries of the traversal stack: the scene's tree depth + 1 (glint_gpu::shaders::
// bvh_stack_size), at most 64, deeper than any tree the builder makes for 2^31 primitives with
// balanced splits; a degenerate deeper one raises STATUS_BVH_STACK_OVERFLOW.
const BVH_STACK_SIZE: u32 = #{BVH_STACK_SIZE}u;
// Relative padding of a box against the scale of the box and the ray origin (f32 rounding is
// ~6e-8), and the absolute padding for boxes and origins at 0.
const BOX_PAD: f32 = 1e-5;
const BOX_PAD_ABS: f32 = 1e-30;
// Direction components below this count as zero in the slab test.
const DIR_ZERO: f32 = 1e-30;
// Stand-in for an infinite slab distance.
const SLAB_INF: f32 = 3e38;

// The per-ray part of the slab test, with the padding relative to the origin's magnitude; a box
// adds its own (`enter`). Not the whole scene's, as the CPU's SlabRay::new takes at its 1e-9:
// at this 1e-5, a ground 3e3 wide padded every box of a model 0.3 wide by 0.03, the walk culled
// almost nothing, and lavapipe's loop budget ran out (an off-screen triangle 3e3 away did it).
struct SlabRay {
    origin: vec3<f32>,
    inv: vec3<f32>,
    parallel: vec3<bool>,
    pad: f32,
}

// The CPU's SlabRay::new.
fn slab_ray(ray: Ray) -> SlabRay {
    let parallel = abs(ray.dir) < vec3<f32>(DIR_ZERO);
    let inv = select(vec3<f32>(1.0) / ray.dir, vec3<f32>(0.0), parallel);
    let o = abs(ray.origin);
    return SlabRay(ray.origin, inv, parallel, BOX_PAD * max(o.x, max(o.y, o.z)) + BOX_PAD_ABS);
}

// The padding of the box from lower to upper: relative to the larger of the origin's and the
// box's own magnitude.
fn box_pad(s: SlabRay, lower: vec3<f32>, upper: vec3<f32>) -> f32 {
    let m = max(abs(lower), abs(upper));
    return max(s.pad, BOX_PAD * max(m.x, max(m.y, m.z)) + BOX_PAD_ABS);
}

// The margin by which a slab distance may pass the bound t and the box still be entered: a
// padding and the rounding of distances up to |t|. Each end of [t_lo, t_hi] gets its own (the
// CPU's SlabRay::slack says why).
fn slack(pad: f32, t: f32) -> f32 {
    return pad + BOX_PAD * min(abs(t), 1e30);
}

// The entry distance into the padded box from lower to upper if the ray meets it within
// [t_lo, t_hi].
fn enter(s: SlabRay, lower: vec3<f32>, upper: vec3<f32>, t_lo: f32, t_hi: f32) -> MaybeT {
    let pad = box_pad(s, lower, upper);
    let lo = lower - vec3<f32>(pad);
    let hi = upper + vec3<f32>(pad);
    let outside = any(s.parallel & ((s.origin < lo) | (s.origin > hi)));
    let a = (lo - s.origin) * s.inv;
    let b = (hi - s.origin) * s.inv;
    let near = select(min(a, b), vec3<f32>(-SLAB_INF), s.parallel);
    // Enlarged by its magnitude: a camera ray's t may be negative (traced from t_min < 0).
    let exit = max(a, b);
    let far = select(exit + BOX_PAD * abs(exit), vec3<f32>(SLAB_INF), s.parallel);
    let t0 = max(near.x, max(near.y, near.z));
    let t1 = min(far.x, min(far.y, far.z));
    return MaybeT(t0, !outside && t0 <= t1 && t0 <= t_hi + slack(pad, t_hi) && t1 >= t_lo - slack(pad, t_lo));
}

// No node: the walk pops the stack next. Never a node_ref (its count bits would be 7, above
// MAX_LEAF).
const NO_NODE: u32 = 0xffffffffu;

// The nodes a walk comes back to (as node_ref), each with the distance the ray enters it at,
// and how many there are: the CPU walk's Vec<(u32, f64)>. Passed by pointer.
struct NodeStack {
    node: array<u32, BVH_STACK_SIZE>,
    t: array<f32, BVH_STACK_SIZE>,
    len: u32,
}

// The walk's stack, one per invocation for all its walks (they never nest): a function's
// variables are zero-filled on every call (WGSL), a private one once, when the invocation
// starts. Each walk starts by emptying it.
var<private> node_stack: NodeStack;

// The root, record 0, in two vec4 loads (bindings.wgsl says why).
fn load_node(i: u32) -> BvhNode {
    let w = bvh_nodes[i];
    return BvhNode(bitcast<vec3<f32>>(w[0].xyz), w[0].w, bitcast<vec3<f32>>(w[1].xyz), w[1].w);
}

// The children of an interior node, record i >= 1, in two vec4 loads.
fn load_pair(i: u32) -> QuantizedPair {
    let w = bvh_nodes[i];
    return QuantizedPair(bitcast<vec3<f32>>(w[0].xyz), w[0].w, w[1].x, array<u32, 3>(w[1].y, w[1].z, w[1].w));
}

// The pair's boxes dequantized (glint_core::bvh::pair_boxes): the left child's min and max, then the
// right's. Each q · 2^e is exact, so the sum's is the only rounding, as the builder assumed.
fn pair_boxes(p: QuantizedPair) -> array<vec3<f32>, 4> {
    let e = vec3<u32>(p.exponents, p.exponents >> 8u, p.exponents >> 16u) & vec3<u32>(0xffu);
    let step = bitcast<vec3<f32>>(e << vec3<u32>(23u));
    let q = vec3<u32>(p.planes[0], p.planes[1], p.planes[2]);
    let byte = vec3<u32>(0xffu);
    return array<vec3<f32>, 4>(
        p.origin + vec3<f32>(q & byte) * step,
        p.origin + vec3<f32>((q >> vec3<u32>(8u)) & byte) * step,
        p.origin + vec3<f32>((q >> vec3<u32>(16u)) & byte) * step,
        p.origin + vec3<f32>(q >> vec3<u32>(24u)) * step,
    );
}

// The pair's children as node_refs, this being record i (glint_core::bvh::pair_refs;
// glint_types::layout::QuantizedPair says where each child is).
fn pair_refs(p: QuantizedPair, i: u32) -> vec2<u32> {
    let count_mask = (1u << NODE_REF_COUNT_BITS) - 1u;
    let first = p.children >> PAIR_FIRST_SHIFT;
    let left_count = (p.children >> NODE_REF_COUNT_BITS) & count_mask;
    let right_count = p.children & count_mask;
    let left = select(i + 1u, first, left_count > 0u);
    let right = select(select(first, i + 1u, left_count > 0u), first + left_count, right_count > 0u);
    return vec2<u32>((left << NODE_REF_COUNT_BITS) | left_count, (right << NODE_REF_COUNT_BITS) | right_count);
}

// A node as the walk carries it from the test of its box to its visit, so that it is not
// loaded twice: its child pair's record or first primitive reference above the count's
// NODE_REF_COUNT_BITS (buffers.rs checks that every index fits). A leaf when the count bits
// are not 0. Only the root is made here; pair_refs makes the others.
fn node_ref(node: BvhNode) -> u32 {
    return (node.left_first << NODE_REF_COUNT_BITS) | node.count;
}

// The count and the first child or primitive of a node reference.
fn ref_count(r: u32) -> u32 {
    return r & ((1u << NODE_REF_COUNT_BITS) - 1u);
}

fn ref_first(r: u32) -> u32 {
    return r >> NODE_REF_COUNT_BITS;
}

// The root (node 0, as node_ref) if the ray enters its box within [t_min, t_max], else NO_NODE.
fn root_node(slab: SlabRay, root: BvhNode, t_min: f32, t_max: f32) -> u32 {
    return select(NO_NODE, node_ref(root), enter(slab, root.min, root.max, t_min, t_max).ok);
}

// Of the children in record `l`, the one the ray enters first within [t_min, t_hi] (the
// walk's next node, NO_NODE if neither); the farther of two is pushed, as the CPU's walk does.
// A full stack raises STATUS_BVH_STACK_OVERFLOW.
fn nearer_child(
    stack: ptr<private, NodeStack>,
    slab: SlabRay,
    l: u32,
    t_min: f32,
    t_hi: f32,
) -> u32 {
    let pair = load_pair(l);
    let boxes = pair_boxes(pair);
    let refs = pair_refs(pair, l);
    let ra = refs.x;
    let rb = refs.y;
    let tl = enter(slab, boxes[0], boxes[1], t_min, t_hi);
    let tr_ = enter(slab, boxes[2], boxes[3], t_min, t_hi);
    if tl.ok && tr_.ok {
        let left_first = tl.t <= tr_.t;
        let n = (*stack).len;
        if n >= BVH_STACK_SIZE {
            status |= STATUS_BVH_STACK_OVERFLOW;
        } else {
            (*stack).node[n] = select(ra, rb, left_first);
            (*stack).t[n] = select(tl.t, tr_.t, left_first);
            (*stack).len = n + 1u;
        }
        return select(rb, ra, left_first);
    }
    if tl.ok {
        return ra;
    }
    return select(NO_NODE, rb, tr_.ok);
}

// The node on top of the stack, popped; NO_NODE when a hit found since it was pushed (t_hi) is
// nearer than its box, as the CPU's walk skips it (the walk then pops again).
fn pop_node(
    stack: ptr<private, NodeStack>,
    slab: SlabRay,
    t_hi: f32,
) -> u32 {
    let n = (*stack).len - 1u;
    (*stack).len = n;
    // The origin's pad alone, not the box's: t is the entry into the padded box, at or before
    // any hit in it, so a box with a hit within t_hi passes on the rounding of t alone.
    return select(NO_NODE, (*stack).node[n], (*stack).t[n] <= t_hi + slack(slab.pad, t_hi));
}

// The walk's next leaf from `start` (NO_NODE: pop first), NO_NODE when the stack runs out:
// interior nodes are passed by nearer_child and pop_node in the CPU's order. A loop of its own
// ("while-while", Aila and Laine 2009): the lanes of a SIMD group reach their leaves at
// different steps, and the leaf tests then run once for all the lanes that have one instead
// of once per step for each lane that happens to be at a leaf.
fn next_leaf(
    stack: ptr<private, NodeStack>,
    slab: SlabRay,
    start: u32,
    t_min: f32,
    t_hi: f32,
) -> u32 {
    var current = start;
    loop {
        if current != NO_NODE {
            if ref_count(current) > 0u {
                break;
            }
            current = nearer_child(stack, slab, ref_first(current), t_min, t_hi);
        }
        // A step that entered neither child pops in the same iteration.
        if current == NO_NODE {
            if (*stack).len == 0u {
                break;
            }
            current = pop_node(stack, slab, t_hi);
        }
    }
    return current;
}

// The first word of the leaf reference at `slot`: its triangle's corner a, the reference in w.
fn leaf_head(slot: u32) -> vec4<u32> {
    return bvh_leaf_ab[slot][0];
}

#ifdef TRIANGLES
// The corners of the triangle referenced at `slot`, whose first word is `head`: from the
// leaf-order copy (bindings.wgsl), the same f32 values as the indexed mesh.
fn leaf_triangle(head: vec4<u32>, slot: u32) -> array<vec3<f32>, 3> {
    return array<vec3<f32>, 3>(
        bitcast<vec3<f32>>(head.xyz),
        bitcast<vec3<f32>>(bvh_leaf_ab[slot][1].xyz),
        bitcast<vec3<f32>>(bvh_leaf_c[slot].xyz),
    );
}
#endif

// intersect.wgsl's closest_hit through the BVH: the same hit (the tie rule makes it independent of the
// visiting order).
fn closest_hit(ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> Hit {
    var best = Hit(t_max, PRIM_NONE, 0u, 0.0, 0.0);
    let root = load_node(0u);
    let slab = slab_ray(ray);
#ifdef TRIANGLES
    let sh = ray_shear(ray.dir);
#endif
    node_stack.len = 0u;
    // One call of next_leaf, so that the walk is compiled once (the first descent and the later
    // ones share it).
    var start = root_node(slab, root, t_min, t_max);
    loop {
        let leaf = next_leaf(&node_stack, slab, start, t_min, bound(best, t_max));
        if leaf == NO_NODE {
            break;
        }
        start = NO_NODE;
        let count = ref_count(leaf);
        let first = ref_first(leaf);
        for (var k = 0u; k < count; k++) {
            let slot = first + k;
            let head = leaf_head(slot);
            let r = head.w;
            let i = r & PRIM_REF_INDEX;
            if (r & PRIM_REF_TRIANGLE) != 0u {
#ifdef TRIANGLES
#ifdef SKIP_LEFT
                if is_leaving(leaving, PRIM_TRIANGLE, i) {
                    continue;
                }
#endif
                let v = leaf_triangle(head, slot);
                let h = intersect_triangle(v[0], v[1], v[2], ray, sh, t_min, bound(best, t_max));
                if h.ok && replaces(h.t, PRIM_TRIANGLE, i, best) {
                    best = Hit(h.t, PRIM_TRIANGLE, i, h.bu, h.bv);
                }
#endif
            } else {
#ifdef SPHERES
                let cr = spheres[i].center_radius;
                let h = intersect_sphere_leaving(leaving, i, cr.xyz, cr.w, spheres[i].power, ray, t_min, bound(best, t_max));
                if h.ok && replaces(h.t, PRIM_SPHERE, i, best) {
                    best = Hit(h.t, PRIM_SPHERE, i, 0.0, 0.0);
                }
#endif
            }
        }
    }
#ifdef PLANES
    best = closest_plane(ray, t_min, t_max, leaving, best);
#endif
    return best;
}

// intersect.wgsl's shadow_transmittance through the BVH: 0 at the first opaque occluder, else
// the product of k_t over every surface crossed (in visiting order).
fn shadow_transmittance(ray: Ray, t_min: f32, t_max: f32, leaving: Leaving) -> vec3<f32> {
    var tr = vec3<f32>(1.0);
    let root = load_node(0u);
    let slab = slab_ray(ray);
#ifdef TRIANGLES
    let sh = ray_shear(ray.dir);
#endif
    node_stack.len = 0u;
    // One call of next_leaf, so that the walk is compiled once (the first descent and the later
    // ones share it).
    var start = root_node(slab, root, t_min, t_max);
    loop {
        let leaf = next_leaf(&node_stack, slab, start, t_min, t_max);
        if leaf == NO_NODE {
            break;
        }
        start = NO_NODE;
        let count = ref_count(leaf);
        let first = ref_first(leaf);
        for (var k = 0u; k < count; k++) {
            let slot = first + k;
            let head = leaf_head(slot);
            let r = head.w;
            let i = r & PRIM_REF_INDEX;
            if (r & PRIM_REF_TRIANGLE) != 0u {
#ifdef TRIANGLES
#ifdef SKIP_LEFT
                if is_leaving(leaving, PRIM_TRIANGLE, i) {
                    continue;
                }
#endif
                let v = leaf_triangle(head, slot);
                if intersect_triangle(v[0], v[1], v[2], ray, sh, t_min, t_max).ok {
                    tr = cross_surface(tr, meshes[triangles[i].mesh].material);
                }
                if all_zero(tr) {
                    return tr;
                }
#endif
            } else {
#ifdef SPHERES
                tr = sphere_transmittance(tr, i, ray, t_min, t_max, leaving);
                if all_zero(tr) {
                    return tr;
                }
#endif
            }
        }
    }
#ifdef PLANES
    tr = planes_transmittance(tr, ray, t_min, t_max, leaving);
#endif
    return tr;
}
