//! The emissive primitives next-event estimation samples: which they are, a direction towards
//! a point of one, and that choice's density. Its twin is `shaders/emitter.wgsl`, which reads
//! the list as the buffer of `Emitters::gpu_words`.

use glam::{DVec2, DVec3};

use super::intersect::{Hit, Prim, triangle_corners};
use super::sample::{area_to_solid_angle, cone_versin, to_world, uniform_cone, uniform_cone_pdf, uniform_triangle};
use super::{TraceContext, v3};
use crate::flat::FlatScene;
use glint_types::layout::PRIM_REF_TRIANGLE;

/// A primitive that emits: what next-event estimation samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Emitter {
    Sphere(u32),
    Triangle(u32),
}

impl Emitter {
    /// The primitive a hit is on, as an emitter if its material emits (every emissive sphere
    /// and triangle is in `Emitters`, so no list needs searching); planes are never sampled.
    pub fn of_hit(hit: &Hit) -> Option<Self> {
        match hit.prim {
            Prim::Sphere => Some(Self::Sphere(hit.index)),
            Prim::Triangle => Some(Self::Triangle(hit.index)),
            Prim::Plane => None,
        }
    }
}

/// The emissive spheres and triangles of a scene. Planes emit to the paths that meet them but
/// are not sampled: they have no finite area.
#[derive(Clone, Debug, Default)]
pub struct Emitters {
    pub list: Vec<Emitter>,
}

impl Emitters {
    pub fn of(ctx: &TraceContext) -> Self {
        Self::of_scene(ctx.scene)
    }

    pub fn of_scene(scene: &FlatScene) -> Self {
        let emits = |material: u32| scene.materials[material as usize].emission[..3].iter().any(|&e| e > 0.0);
        let spheres = (0..scene.spheres.len() as u32).filter(|&i| emits(scene.spheres[i as usize].material));
        let triangles = (0..scene.triangles.len() as u32)
            .filter(|&i| emits(scene.meshes[scene.triangles[i as usize].mesh as usize].material));
        Self { list: spheres.map(Emitter::Sphere).chain(triangles.map(Emitter::Triangle)).collect() }
    }

    /// The GPU's emitter buffer (path.wgsl): the count, then each sphere's index and each
    /// triangle's `PRIM_REF_TRIANGLE | index`.
    pub fn gpu_words(&self) -> Vec<u32> {
        let refs = self.list.iter().map(|e| match *e {
            Emitter::Sphere(i) => i,
            Emitter::Triangle(i) => PRIM_REF_TRIANGLE | i,
        });
        std::iter::once(self.list.len() as u32).chain(refs).collect()
    }
}

/// The density, per unit solid angle at `p`, with which next-event estimation picks the point
/// `q` (geometric normal `ng_q`) of `emitter`: the choice of one of `count`, times the cone's or
/// the area's density. 0 where `p` is inside a sphere (it sees the back faces, which do not emit).
pub fn emitter_pdf(ctx: &TraceContext, emitter: Emitter, count: usize, p: DVec3, q: DVec3, ng_q: DVec3) -> f64 {
    let scene = ctx.scene;
    let pick = 1.0 / count as f64;
    match emitter {
        Emitter::Sphere(i) => sphere_cone(ctx, i, p).map_or(0.0, |(_, versin)| pick * uniform_cone_pdf(versin)),
        Emitter::Triangle(i) => {
            let [a, b, c] = triangle_corners(scene, &scene.triangles[i as usize]);
            let area = 0.5 * (b - a).cross(c - a).length();
            let to_q = q - p;
            let dist = to_q.length();
            // A ray met the emitter where it left (ε = 0 on a triangle's edge): no direction,
            // no density (0/0 would make the sample NaN).
            if dist == 0.0 {
                return 0.0;
            }
            pick * area_to_solid_angle(1.0 / area, dist, ng_q.dot(to_q / dist))
        }
    }
}

/// A direction from `p` towards a point of `emitter`, drawn as `emitter_pdf` says.
pub fn sample_emitter(ctx: &TraceContext, emitter: Emitter, p: DVec3, u: DVec2) -> Option<DVec3> {
    let scene = ctx.scene;
    match emitter {
        Emitter::Sphere(i) => sphere_cone(ctx, i, p).map(|(axis, versin)| to_world(axis, uniform_cone(u, versin))),
        Emitter::Triangle(i) => {
            let [a, b, c] = triangle_corners(scene, &scene.triangles[i as usize]);
            let bary = uniform_triangle(u);
            let q = a + bary.x * (b - a) + bary.y * (c - a);
            (q - p).try_normalize()
        }
    }
}

/// The cone of directions from `p` that meet sphere `i`: its unit axis and its versine
/// (1 − cos of its half-angle). None where `p` is inside, or on, the sphere: it sees only back
/// faces, which do not emit.
pub fn sphere_cone(ctx: &TraceContext, i: u32, p: DVec3) -> Option<(DVec3, f64)> {
    let cr = ctx.scene.spheres[i as usize].center_radius;
    let (c, r) = (v3(cr), f64::from(cr[3]));
    let to_c = c - p;
    let d2 = to_c.length_squared();
    if d2 <= r * r {
        return None;
    }
    Some((to_c / d2.sqrt(), cone_versin(r * r / d2)))
}
