// Twin of crates/glint-core/src/cpu/offset.rs: where secondary rays start.
#define_import_path glint::offset

#import glint::scene_data::{EPS_TMIN, EPS_NUDGE_RAY, EPS_NUDGE_NORMAL, EPS_ROBUST, EPS_SKIP_CONVEX}
#import glint::bindings::header
#import glint::intersect::{Leaving, PRIM_NONE, PRIM_SPHERE}

// Wächter & Binder, Ray Tracing Gems ch. 6, with their f32 constants (the f64 twin scales
// FLOAT_SCALE to its precision).
const ORIGIN: f32 = 0.03125;
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
const INT_SCALE: f32 = 256.0;
// INT_SCALE ULPs, relative (f32 epsilon 2^-23).
const SHADOW_REL: f32 = 256.0 * 1.1920929e-7;

struct Spawn {
    origin: vec3<f32>,
    t_min: f32,
    leaving: Leaving,
}

// `scale`: the length scale of the fixed offset near the origin (header.frame.w).
fn offset_ray(p: vec3<f32>, n: vec3<f32>, scale: f32) -> vec3<f32> {
    let of_i = vec3<i32>(INT_SCALE * n);
    let p_i = bitcast<vec3<f32>>(bitcast<vec3<i32>>(p) + select(of_i, -of_i, p < vec3<f32>(0.0)));
    return select(p_i, p + (FLOAT_SCALE * scale) * n, abs(p) < vec3<f32>(ORIGIN * scale));
}

// Primitive `index` of kind `prim` as a ray leaving it to the side of n_side sees it: into a
// sphere's inside when n_side points against its outward normal ng.
fn leaving_surface(prim: u32, index: u32, ng: vec3<f32>, n_side: vec3<f32>) -> Leaving {
    return Leaving(prim, index, prim == PRIM_SPHERE && dot(n_side, ng) < 0.0);
}

fn spawn_ray(p: vec3<f32>, p_surface: vec3<f32>, n_side: vec3<f32>, dir: vec3<f32>, leaving: Leaving) -> Spawn {
    let eps = header.epsilon;
    let none = Leaving(PRIM_NONE, 0u, false);
    switch header.epsilon_mode {
        case EPS_TMIN: {
            return Spawn(p, eps, none);
        }
        case EPS_NUDGE_RAY: {
            return Spawn(p + eps * dir, 0.0, none);
        }
        case EPS_NUDGE_NORMAL: {
            return Spawn(p + eps * n_side, 0.0, none);
        }
        case EPS_SKIP_CONVEX: {
            return Spawn(p, eps, leaving);
        }
        // EPS_ROBUST; the host refuses any other stored value (FlatScene::check_tags).
        default: {
            let origin = offset_ray(p_surface, n_side, header.frame.w) + eps * n_side;
            // A direction bent below the surface it leaves meets it again (the CPU twin says why).
            if dot(dir, n_side) > 0.0 {
                return Spawn(origin, 0.0, leaving);
            }
            return Spawn(origin, 0.0, none);
        }
    }
}

// Where a ray leaving p to n_side's side starts, for aiming it at a point (the CPU twin says why):
// the spawned origin where it moves off the surface whatever the direction, else p.
fn aim_origin(p: vec3<f32>, p_surface: vec3<f32>, n_side: vec3<f32>) -> vec3<f32> {
    if header.epsilon_mode == EPS_ROBUST || header.epsilon_mode == EPS_NUDGE_NORMAL {
        return spawn_ray(p, p_surface, n_side, n_side, Leaving(PRIM_NONE, 0u, false)).origin;
    }
    return p;
}

fn shadow_t_max(dist: f32) -> f32 {
    if header.epsilon_mode == EPS_ROBUST {
        return dist * (1.0 - SHADOW_REL) - header.epsilon;
    }
    return dist - header.epsilon;
}
