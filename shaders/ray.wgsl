// Twin of crates/glint-core/src/cpu/mod.rs: the ray and the per-invocation ray counts shared
// by all tracer modules.
#define_import_path glint::ray

#import glint::scene_data::{ProbeRecord, STAT_STATUS, STAT_CAMERA, STAT_SHADOW, STAT_REFLECTION, STAT_REFRACTION, STAT_BAILOUT_SAVED}
#import glint::bindings::{tile, stats}

// Largest ray parameter; also the reach of shadow rays towards directional lights.
const FAR: f32 = 1e30;

struct Ray {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

// Rays traced by this invocation, by kind, flushed to the statistics buffer once at the end
// (twin of the CPU's RayCounts).
struct RayCounts {
    camera: u32,
    shadow: u32,
    reflection: u32,
    refraction: u32,
    bailout_saved: u32,
}

var<private> ray_counts: RayCounts;
// Status bits (STATUS_*) raised by this invocation.
var<private> status: u32;

// The pixel probe (PROBE variant only): the breakdown being recorded, and whether the node
// being shaded is the camera ray's first hit.
var<private> probe: ProbeRecord;
var<private> probe_active: bool;

// lavapipe ends every loop after its current iteration once the invocation group has run
// its loop budget (glint_gpu::shaders::LAVAPIPE_LOOP_BUDGET iterations in all), without any
// error. A loop of `tile.canary_laps` (2) laps
// then stops after one: the only way to see that the work before it was cut short. Every
// entry point (trace.wgsl, raycast.wgsl) ends with it.
fn driver_cut_loops() -> bool {
    var laps = 0u;
    loop {
        laps += 1u;
        if laps >= tile.canary_laps {
            break;
        }
    }
    return laps < tile.canary_laps;
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

// This invocation's ray counts and status bits into the statistics buffer, once at its end.
fn flush_counts() {
    add_stat(STAT_CAMERA, ray_counts.camera);
    add_stat(STAT_SHADOW, ray_counts.shadow);
    add_stat(STAT_REFLECTION, ray_counts.reflection);
    add_stat(STAT_REFRACTION, ray_counts.refraction);
    add_stat(STAT_BAILOUT_SAVED, ray_counts.bailout_saved);
    if status != 0u {
        atomicOr(&stats[STAT_STATUS], status);
    }
}
