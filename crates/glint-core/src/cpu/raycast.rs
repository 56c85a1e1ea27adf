//! CPU twin of `shaders/raycast.wgsl`: the closest hit of each ray of a buffer through the
//! BVH, nothing else (no shading), for `glint bench rays`. The same `bvh::closest_hit` the
//! tracer uses, so the figures are the tracer's traversal cost.

use rayon::prelude::*;

use bytemuck::{Pod, Zeroable};

use super::intersect::{Hit, Leaving, PRIM_NONE};
use super::{Ray, TraceContext, bvh, v3};

/// Rays a rayon task takes at once: enough to amortise the task, few enough to balance
/// incoherent rays whose cost varies a hundredfold.
const RAYS_PER_TASK: usize = 256;

/// One ray as the GPU reads it: origin and t_min, unit direction and t_max.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct RayRecord {
    pub origin_t_min: [f32; 4],
    pub dir_t_max: [f32; 4],
}

/// The closest hit of one ray as the GPU writes it: the kind (`intersect::Prim` as u32,
/// `PRIM_NONE` = 0 for a miss), the index in that kind's array, and t.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C)]
pub struct HitRecord {
    pub prim: u32,
    pub index: u32,
    pub t: f32,
    pub pad: u32,
}

impl HitRecord {
    /// The record of a CPU hit (t rounded to f32).
    pub fn from_hit(hit: Option<Hit>) -> Self {
        match hit {
            Some(h) => Self { prim: h.prim as u32, index: h.index, t: h.t as f32, pad: 0 },
            None => Self { prim: PRIM_NONE, index: 0, t: 0.0, pad: 0 },
        }
    }

    pub fn is_hit(&self) -> bool {
        self.prim != PRIM_NONE
    }
}

/// The closest hit of one ray within its [t_min, t_max], through the BVH.
pub fn cast_ray(ctx: &TraceContext, ray: &RayRecord) -> HitRecord {
    let r = Ray { origin: v3(ray.origin_t_min), dir: v3(ray.dir_t_max) };
    let (t_min, t_max) = (f64::from(ray.origin_t_min[3]), f64::from(ray.dir_t_max[3]));
    HitRecord::from_hit(bvh::closest_hit(ctx, &r, t_min, t_max, &Leaving::NONE))
}

/// `cast_ray` for every ray, in parallel on the current rayon pool, in ray order.
pub fn cast_rays(ctx: &TraceContext, rays: &[RayRecord]) -> Vec<HitRecord> {
    rays.par_iter().with_min_len(RAYS_PER_TASK).map(|r| cast_ray(ctx, r)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FlatScene;
    use crate::cpu::intersect;
    use crate::rays::RaySet;
    use glint_scene::bumpy::bumpy;

    #[test]
    fn bvh_hits_equal_brute_force_on_both_ray_sets() {
        let desc = bumpy(6);
        let flat = FlatScene::build(&desc, &desc.render);
        let ctx = TraceContext::new(&flat).expect("valid scene");
        for set in RaySet::ALL {
            // Every 97th ray: brute force over 146 triangles is slow in a debug build.
            let rays: Vec<RayRecord> = set.rays().into_iter().step_by(97).collect();
            let hits = cast_rays(&ctx, &rays);
            let mut hit = 0;
            for (r, h) in rays.iter().zip(&hits) {
                let ray = Ray { origin: v3(r.origin_t_min), dir: v3(r.dir_t_max) };
                let brute = intersect::closest_hit(&ctx, &ray, 0.0, f64::from(r.dir_t_max[3]), &Leaving::NONE);
                assert_eq!(*h, HitRecord::from_hit(brute), "{} ray {r:?}", set.name());
                hit += usize::from(h.prim != PRIM_NONE);
            }
            assert!(hit > 0 && hit < rays.len(), "{}: {hit} of {} rays hit", set.name(), rays.len());
        }
    }
}
