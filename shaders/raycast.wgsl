// Twin of crates/glint-core/src/cpu/raycast.rs: the closest hit of each ray of a buffer
// through the BVH (bvh.wgsl's closest_hit, the tracer's own), nothing else, for
// `glint bench rays`. Composed with the BVH shader def and the scene's primitive kinds.
//
// One ray per invocation. Rays are two vec4<f32> each (origin, t_min; direction, t_max); a hit
// is (prim, index, bitcast t, 0) with prim PRIM_NONE for a miss. The status word gets the
// BVH's stack overflow and lavapipe's loop cut-off (the canary), so that a cut traversal
// fails the benchmark instead of counting as a fast miss.
#import glint::scene_data::{STATUS_DRIVER_LOOP_CUTOFF, STAT_STATUS}
#import glint::bindings::{tile, stats, rays_in, hits_out}
#import glint::ray::{Ray, status, driver_cut_loops}
#import glint::intersect::{Leaving, PRIM_NONE}
#import glint::bvh::closest_hit

// Invocations per workgroup (glint_gpu::raycast::WORKGROUP).
const WORKGROUP: u32 = 64u;

// The closest hit of one ray within its [t_min, t_max], as (prim, index, t bits, 0).
fn cast_ray(origin_t_min: vec4<f32>, dir_t_max: vec4<f32>) -> vec4<u32> {
    let h = closest_hit(Ray(origin_t_min.xyz, dir_t_max.xyz), origin_t_min.w, dir_t_max.w, Leaving(PRIM_NONE, 0u, false));
    // A miss has no t (the CPU's None); 0 rather than t_max, as the CPU's record.
    let t = select(h.t, 0.0, h.prim == PRIM_NONE);
    return vec4<u32>(h.prim, h.index, bitcast<u32>(t), 0u);
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    // Rows of at most 65,535 workgroups (the dispatch limit per dimension) for larger buffers.
    let index = gid.y * groups.x * WORKGROUP + gid.x;
    if index >= arrayLength(&hits_out) {
        return;
    }
    status = 0u;
    hits_out[index] = cast_ray(rays_in[2u * index], rays_in[2u * index + 1u]);
    if driver_cut_loops() {
        status |= STATUS_DRIVER_LOOP_CUTOFF;
    }
    if status != 0u {
        atomicOr(&stats[STAT_STATUS], status);
    }
}
