//! CPU twin of `shaders/offset.wgsl`: where secondary rays start, so that they do not hit the
//! surface they leave (self-intersection, "acne").
//!
//! The seed lists three remedies (reject small t, nudge along the ray, nudge off the surface);
//! `robust` is the scale-aware offset of Wächter & Binder, "A Fast and Robust Method for
//! Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6), applied to the hit point after it is
//! re-projected onto the surface. `skip_convex` is the seed's fourth remedy: the ray starts at
//! the hit point and does not test the primitive it leaves (`intersect::Leaving`).

use glam::DVec3;

use super::TraceContext;
use super::intersect::{Leaving, Prim};
use glint_scene::EpsilonMode;

/// Below this magnitude a coordinate gets a fixed offset (integer ULP steps are too small
/// near zero). Same value as Wächter & Binder.
pub const ORIGIN: f64 = 1.0 / 32.0;
/// The fixed offset near zero. W&B use 2^-16 for f32 hit points; the f64 reference uses
/// 2^-45, keeping the same ratio to its 29 extra mantissa bits.
pub const FLOAT_SCALE: f64 = 1.0 / 35_184_372_088_832.0;
/// Offset in units in the last place, as W&B.
pub const INT_SCALE: f64 = 256.0;
/// Relative amount by which robust shadow rays stop short of the light: INT_SCALE ULPs.
pub const SHADOW_REL: f64 = INT_SCALE * f64::EPSILON;

/// Moves `p` off the surface along `n` (the normal on the side the new ray leaves into).
/// `scale` is the length scale of the fixed offset near the origin (the header's `frame.w`: 1
/// in world space, the scene's extent in a rebased frame, so that a small scene near the
/// camera is not offset by W&B's unit-scene constants).
pub fn offset_ray(p: DVec3, n: DVec3, scale: f64) -> DVec3 {
    let step = |x: f64, nc: f64| -> f64 {
        if x.abs() < ORIGIN * scale {
            return x + (FLOAT_SCALE * scale) * nc;
        }
        let of_i = (INT_SCALE * nc) as i64;
        let bits = x.to_bits() as i64;
        f64::from_bits((bits + if x < 0.0 { -of_i } else { of_i }) as u64)
    };
    DVec3::new(step(p.x, n.x), step(p.y, n.y), step(p.z, n.z))
}

/// Where a secondary ray starts, from which t it looks for hits, and the primitive it leaves
/// (`Leaving::NONE` but under `skip_convex` and `robust`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spawn {
    pub origin: DVec3,
    pub t_min: f64,
    pub leaving: Leaving,
}

/// Primitive `index` of kind `prim`, as a ray leaving it to the side of `n_side` sees it: into a
/// sphere's inside when `n_side` points against the sphere's outward normal `ng` (as stored).
pub fn leaving_surface(prim: Prim, index: u32, ng: DVec3, n_side: DVec3) -> Leaving {
    let inside = match prim {
        Prim::Sphere => n_side.dot(ng) < 0.0,
        Prim::Plane | Prim::Triangle => false,
    };
    Leaving { prim: Some(prim), index, inside }
}

/// The secondary ray leaving the hit at `p` in direction `dir`; `p_surface` is the hit point
/// re-projected onto the surface (see `surface_at`), `n_side` the unit geometric normal turned
/// to the side `dir` goes to, and `leaving` the primitive hit (`leaving_surface`), which
/// `skip_convex` and `robust` keep: the offset covers the hit point's rounding, but the next
/// test's own rounding grows with the primitive's size, not the point's coordinates (a large
/// triangle through a coordinate plane), and a primitive left cannot be met again there.
pub fn spawn_ray(ctx: &TraceContext, p: DVec3, p_surface: DVec3, n_side: DVec3, dir: DVec3, leaving: Leaving) -> Spawn {
    let eps = ctx.epsilon;
    let none = Leaving::NONE;
    match ctx.epsilon_mode {
        EpsilonMode::Tmin => Spawn { origin: p, t_min: eps, leaving: none },
        EpsilonMode::NudgeRay => Spawn { origin: p + eps * dir, t_min: 0.0, leaving: none },
        EpsilonMode::NudgeNormal => Spawn { origin: p + eps * n_side, t_min: 0.0, leaving: none },
        EpsilonMode::SkipConvex => Spawn { origin: p, t_min: eps, leaving },
        EpsilonMode::Robust => {
            let origin = offset_ray(p_surface, n_side, f64::from(ctx.scene.header.frame[3])) + eps * n_side;
            // A direction bent by a shading normal below the surface it leaves (a grazing
            // reflection off an interpolated mesh) crosses that surface at once: it meets it
            // again, as it did before the skip.
            Spawn { origin, t_min: 0.0, leaving: if dir.dot(n_side) > 0.0 { leaving } else { none } }
        }
    }
}

/// Where a ray leaving `p` to `n_side`'s side starts, for aiming it at a point: the spawned
/// origin where it moves off the surface whatever the direction (robust, nudge_normal), else
/// `p`, whose line the origin stays on (tmin, skip_convex; nudge_ray moves along the direction).
/// A direction drawn towards an emitter from `p` and traced from 2^-16 away (the GPU's robust
/// offset) passed beside a lamp 1e-5 wide: 62 % of a Cornell box's light was lost.
pub fn aim_origin(ctx: &TraceContext, p: DVec3, p_surface: DVec3, n_side: DVec3) -> DVec3 {
    match ctx.epsilon_mode {
        EpsilonMode::Robust | EpsilonMode::NudgeNormal => {
            spawn_ray(ctx, p, p_surface, n_side, n_side, Leaving::NONE).origin
        }
        EpsilonMode::Tmin | EpsilonMode::NudgeRay | EpsilonMode::SkipConvex => p,
    }
}

/// How far a shadow ray of length `dist` may look for occluders: it stops short of the light
/// by the same rule that moved its origin.
pub fn shadow_t_max(ctx: &TraceContext, dist: f64) -> f64 {
    match ctx.epsilon_mode {
        EpsilonMode::Robust => dist * (1.0 - SHADOW_REL) - ctx.epsilon,
        EpsilonMode::Tmin | EpsilonMode::NudgeRay | EpsilonMode::NudgeNormal | EpsilonMode::SkipConvex => {
            dist - ctx.epsilon
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_every_coordinate_to_the_normal_side() {
        for p in [DVec3::new(1e6, -3.0, 0.0), DVec3::new(-1e-3, 5e3, -2.5)] {
            let n = DVec3::new(0.6, 0.0, 0.8);
            let q = offset_ray(p, n, 1.0);
            assert!(q.x > p.x && q.z > p.z && q.y == p.y, "{p} -> {q}");
            // Scale-aware: the step is a few hundred ULPs of the coordinate, not a fixed size.
            assert!((q.x - p.x) / p.x.abs().max(ORIGIN) < 1e-12);
        }
    }
}
