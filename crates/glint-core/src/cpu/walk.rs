//! Where the CPU chooses how rays find what they hit, as the WGSL does where `trace.wgsl` and
//! `shade.wgsl` import `glint::bvh` or `glint::intersect` (shader def `BVH`): through the BVH,
//! or by testing every primitive (`TraceContext::traversal`, the same rule). Both give the same
//! hit and the same transmittance bit for bit. CPU-only: the WGSL chooses at compile time.

use glam::DVec3;

use super::intersect::{Hit, Leaving};
use super::{Ray, TraceContext, Traversal, bvh, intersect};

/// The nearest hit in (t_min, t_max) (`intersect::closest_hit`, `bvh::closest_hit`).
pub fn closest_hit(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> Option<Hit> {
    match ctx.traversal {
        Traversal::Bvh => bvh::closest_hit(ctx, ray, t_min, t_max, leaving),
        Traversal::BruteForce => intersect::closest_hit(ctx, ray, t_min, t_max, leaving),
    }
}

/// The fraction of light that passes from the ray's origin to t_max
/// (`intersect::shadow_transmittance`, `bvh::shadow_transmittance`).
pub fn shadow_transmittance(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> DVec3 {
    match ctx.traversal {
        Traversal::Bvh => bvh::shadow_transmittance(ctx, ray, t_min, t_max, leaving),
        Traversal::BruteForce => intersect::shadow_transmittance(ctx, ray, t_min, t_max, leaving),
    }
}
