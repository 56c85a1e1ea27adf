//! BVH traversal of the CPU tracer (`crate::bvh` builds the hierarchy): closest hit and shadow
//! transmittance, bit-identical to the brute-force loops of `intersect.rs`.
//!
//! Why identical: the box test is conservative (it never rejects a box holding a primitive the
//! primitive test would report), the primitive tests are the same functions with the same ray
//! shear, and the result does not depend on the order primitives are visited in. Brute force
//! keeps the first of equal t in the order spheres, planes, triangles (each by index); here a
//! hit replaces the best one if its t is smaller, or equal with a smaller (kind, index) in that
//! order. The shadow product's rounding depends on the order of its factors, so crossings are
//! collected and multiplied in brute force's order.
//!
//! The WGSL twin is `shaders/bvh.wgsl` (same functions, except the closure-driven `traverse`
//! and its loop `walk`).

mod wide_slab;

use glam::DVec3;

use self::wide_slab::{Entered, SlabPlanes};
use super::intersect::{
    Hit, Leaving, Prim, all_zero, bound, closest_plane, cross_surface, intersect_sphere_leaving, is_leaving,
    planes_transmittance, replaces, sphere_roots_counted, triangle_corners,
};
use super::primitive::{RayShear, intersect_triangle, ray_shear, sphere_roots};
use super::{Ray, TraceContext, v3};
use crate::bvh::{PrimRef, WIDTH, WideNode};
use crate::flat::Corners;
use glint_types::layout::BvhNode;
use glint_types::layout::feature;

/// Relative padding of a box in the slab test, against the scale of the box and the ray origin:
/// many orders of magnitude above the f64 rounding error of the primitive tests and of the slab
/// arithmetic, so a box is never rejected when a primitive inside it would be hit.
const BOX_PAD: f64 = 1e-9;
/// Absolute padding, for boxes and origins at 0.
const BOX_PAD_ABS: f64 = 1e-280;
/// pbrt's γ(3), by which the far slab distance is enlarged (Ize 2013).
pub(super) const GAMMA3: f64 = 3.0 * (f64::EPSILON * 0.5) / (1.0 - 3.0 * (f64::EPSILON * 0.5));
/// Direction components below this count as zero in the slab test (their reciprocal would
/// overflow); such a ray moves less than 1e-270 along that axis within `FAR`.
const DIR_ZERO: f64 = 1e-300;

/// The per-ray part of the slab test, including the padding: relative to the larger of the
/// origin's and the whole scene's (the root box's) magnitude, so at least the padding any box
/// of the scene needs, computed once per ray instead of once per box.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlabRay {
    pub(super) origin: [f64; 3],
    pub(super) inv: [f64; 3],
    pub(super) parallel: [bool; 3],
    pub(super) pad: f64,
}

/// The largest magnitude of a box's coordinates.
fn box_scale(node: &BvhNode) -> f64 {
    node.min.iter().chain(&node.max).fold(0.0, |m: f64, &x| m.max(f64::from(x).abs()))
}

impl SlabRay {
    pub(super) fn new(ray: &Ray, root: &BvhNode) -> Self {
        let origin = ray.origin.to_array();
        let d = ray.dir.to_array();
        let parallel = d.map(|x| x.abs() < DIR_ZERO);
        let inv = std::array::from_fn(|k| if parallel[k] { 0.0 } else { 1.0 / d[k] });
        let scale = origin.iter().fold(box_scale(root), |m: f64, x| m.max(x.abs()));
        Self { origin, inv, parallel, pad: BOX_PAD * scale + BOX_PAD_ABS }
    }

    /// The margin by which a slab distance may pass the bound t and the box still be entered:
    /// the padding and the rounding of distances up to |t|. Each end of [t_lo, t_hi] gets its
    /// own: a margin taken from t_hi = `FAR` at the near end too would let every box behind the
    /// origin through, and shadow rays to directional lights walk the whole line.
    pub(super) fn slack(&self, t: f64) -> f64 {
        self.pad + GAMMA3 * t.abs().min(1e300)
    }

    /// The entry distance of the ray into the (padded) box if it meets it within
    /// [t_lo, t_hi], else `None`.
    #[inline]
    pub(super) fn enter(&self, (min, max): ([f32; 3], [f32; 3]), t_lo: f64, t_hi: f64) -> Option<f64> {
        let mut t0 = f64::NEG_INFINITY;
        let mut t1 = f64::INFINITY;
        for k in 0..3 {
            let (l, h) = (f64::from(min[k]) - self.pad, f64::from(max[k]) + self.pad);
            if self.parallel[k] {
                if self.origin[k] < l || self.origin[k] > h {
                    return None;
                }
                continue;
            }
            let a = (l - self.origin[k]) * self.inv[k];
            let b = (h - self.origin[k]) * self.inv[k];
            let (near, far) = if self.inv[k] >= 0.0 { (a, b) } else { (b, a) };
            // Plain comparisons, not f64::max/min: the operands are never NaN here and the
            // NaN-aware forms cost a third of the traversal.
            if near > t0 {
                t0 = near;
            }
            if far < t1 {
                t1 = far;
            }
        }
        // Rounding is monotonic, so enlarging the minimum is enlarging every far distance; by
        // its magnitude, as a camera ray's t may be negative (it is traced from t_min < 0).
        let t1 = t1 + 2.0 * GAMMA3 * t1.abs();
        (t0 <= t1 && t0 <= t_hi + self.slack(t_hi) && t1 >= t_lo - self.slack(t_lo)).then_some(t0)
    }
}

/// The corners of triangle `index`, referenced at `slot` of `bvh_prims`: from the scene's
/// leaf-order copy when the context has it, else from the indexed mesh. The same f32 values
/// either way, and the same the GPU's twin reads from its own leaf-order copy.
#[inline(always)]
fn leaf_triangle(ctx: &TraceContext, slot: usize, index: u32) -> [DVec3; 3] {
    match ctx.leaf_corners {
        Some(c) => c[slot].map(|p| glam::Vec3::from_array(p).as_dvec3()),
        None => triangle_corners(ctx.scene, &ctx.scene.triangles[index as usize]),
    }
}

/// An entry of the walk's stack: a wide node (`count` 0) or a leaf's references, with the
/// distance the ray enters its box at.
#[derive(Clone, Copy, Debug)]
struct Pending {
    first: u32,
    count: u32,
    t: f64,
}

impl Pending {
    /// The wide root, where every walk starts (its distance is never read).
    const ROOT: Self = Self { first: 0, count: 0, t: 0.0 };
}

thread_local! {
    /// Each worker's traversal stack, reused from ray to ray instead of allocated for each.
    static STACK: std::cell::Cell<Vec<Pending>> = const { std::cell::Cell::new(Vec::new()) };
}

/// Calls `visit` on every primitive reference in a leaf whose box the ray meets within
/// [t_min, `limit()`], nearer boxes first, with its slot in `bvh_prims`.
fn traverse(
    ctx: &TraceContext,
    ray: &Ray,
    t_min: f64,
    mut limit: impl FnMut() -> f64,
    mut visit: impl FnMut(usize, u32) -> bool,
) -> bool {
    let nodes = &ctx.scene.bvh_nodes;
    let Some(root) = nodes.first() else { return true };
    let slab = SlabRay::new(ray, root);
    let planes = SlabPlanes::of(&slab);
    // The vector test of the wide root's children rejects a ray that misses the scene, so the
    // root's own box is tested only where there is no vector test.
    if planes.is_none() && slab.enter((root.min, root.max), t_min, limit()).is_none() {
        return true;
    }
    // Taken, not borrowed: a traversal started inside `visit` gets a stack of its own.
    let mut stack = STACK.take();
    stack.clear();
    let walk = Walk {
        slab: &slab,
        planes: planes.as_ref(),
        nodes: nodes.wide(),
        prims: &ctx.scene.bvh_prims,
        corners: ctx.leaf_corners,
    };
    let passed = walk.run(&mut stack, t_min, &mut limit, &mut visit);
    STACK.set(stack);
    passed
}

/// What `traverse`'s loop reads.
struct Walk<'a> {
    slab: &'a SlabRay,
    planes: Option<&'a SlabPlanes>,
    nodes: &'a [WideNode],
    prims: &'a [u32],
    corners: Option<&'a [Corners]>,
}

impl Walk<'_> {
    /// The loop of `traverse`, from the wide root. Of the children a step enters, the nearest
    /// is taken at once and the others pushed, farthest first; an entry popped is skipped when
    /// a hit found since it was pushed is nearer than its box.
    fn run(
        &self,
        stack: &mut Vec<Pending>,
        t_min: f64,
        limit: &mut impl FnMut() -> f64,
        visit: &mut impl FnMut(usize, u32) -> bool,
    ) -> bool {
        let slab = self.slab;
        let lo = t_min - slab.slack(t_min);
        let mut current = Some(Pending::ROOT);
        loop {
            let next = match current.take() {
                Some(p) => p,
                None => match stack.pop() {
                    Some(p) => {
                        let t_hi = limit();
                        if p.t > t_hi + slab.slack(t_hi) {
                            continue;
                        }
                        p
                    }
                    None => return true,
                },
            };
            if next.count > 0 {
                let first = next.first as usize;
                for (slot, &r) in (first..).zip(&self.prims[first..first + next.count as usize]) {
                    if !visit(slot, r) {
                        return false;
                    }
                }
                continue;
            }
            let node = &self.nodes[next.first as usize];
            let t_hi = limit();
            let Entered { t, mask: entered } = match self.planes {
                Some(p) => p.enter(node, lo, t_hi + slab.slack(t_hi)),
                None => Entered::of(std::array::from_fn(|l| {
                    slab.enter(node.child_box(l), t_min, t_hi).unwrap_or(f64::INFINITY)
                })),
            };
            // The nearest entered child taken, the others pushed, farthest first. None, one or
            // several children: bit tests, not `count_ones` (x86_64's baseline has no popcnt).
            let pending = |l: usize| Pending { first: node.first[l], count: node.count[l], t: t[l] };
            if entered == 0 {
                continue;
            }
            if entered & (entered - 1) == 0 {
                let p = pending(entered.trailing_zeros() as usize);
                self.prefetch(&p);
                current = Some(p);
                continue;
            }
            // An insertion sort of at most `WIDTH`.
            let mut sorted = [Pending::ROOT; WIDTH];
            let mut n = 0;
            let mut bits = entered;
            while bits != 0 {
                let p = pending(bits.trailing_zeros() as usize);
                bits &= bits - 1;
                self.prefetch(&p);
                let mut at = n;
                while at > 0 && sorted[at - 1].t > p.t {
                    sorted[at] = sorted[at - 1];
                    at -= 1;
                }
                sorted[at] = p;
                n += 1;
            }
            stack.extend(sorted[1..n].iter().rev());
            current = Some(sorted[0]);
        }
    }

    /// Asks for what the walk reads when it takes `p`, while it still sorts and pushes the
    /// other children: a wide node's lines, or a leaf's references and triangle corners.
    /// Incoherent rays spend most of the walk waiting for memory, and this overlaps the wait
    /// with the work of a step. A hint only: no effect on results, and none at all off x86_64.
    #[inline(always)]
    #[allow(unsafe_code)] // reason: `_mm_prefetch` is `unsafe` only for its target-feature attribute.
    fn prefetch(&self, p: &Pending) {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
            let first = p.first as usize;
            // SAFETY: SSE is part of x86_64; a prefetch never faults and never reads into the
            // program, whatever the address (here ones inside the arrays for a valid tree).
            let prefetch = |p: *const u8| unsafe { _mm_prefetch::<_MM_HINT_T0>(p.cast()) };
            if p.count == 0 {
                // Every line of the node (aligned to them).
                let node = self.nodes.as_ptr().wrapping_add(first).cast::<u8>();
                for offset in (0..size_of::<WideNode>()).step_by(64) {
                    prefetch(node.wrapping_add(offset));
                }
                return;
            }
            prefetch(self.prims.as_ptr().wrapping_add(first).cast());
            if let Some(c) = self.corners {
                // Every line the leaf's corners touch (up to 4 × 36 bytes: three lines).
                let start = c.as_ptr().wrapping_add(first).cast::<u8>();
                let misalign = start as usize & 63;
                let line = start.wrapping_sub(misalign);
                for offset in (0..misalign + p.count as usize * size_of::<Corners>()).step_by(64) {
                    prefetch(line.wrapping_add(offset));
                }
            }
        }
    }
}

/// `intersect::closest_hit` through the BVH: the same hit, bit for bit.
pub fn closest_hit(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> Option<Hit> {
    let scene = ctx.scene;
    let spheres_on = ctx.has(feature::SPHERES);
    let triangles_on = ctx.has(feature::TRIANGLES);
    let skip = ctx.has(feature::SKIP_LEFT);
    let shear: RayShear = ray_shear(ray.dir);
    let best = std::cell::Cell::new(None::<Hit>);
    traverse(
        ctx,
        ray,
        t_min,
        || bound(&best.get(), t_max),
        |slot, r| {
            let b = best.get();
            let limit = bound(&b, t_max);
            match PrimRef::decode(r) {
                PrimRef::Sphere(i) if spheres_on => {
                    let cr = scene.spheres[i as usize].center_radius;
                    if let Some(t) =
                        intersect_sphere_leaving(ctx, leaving, i, v3(cr), f64::from(cr[3]), ray, t_min, limit)
                        && replaces(scene, t, Prim::Sphere, i, &b)
                    {
                        best.set(Some(Hit { t, prim: Prim::Sphere, index: i, bu: 0.0, bv: 0.0 }));
                    }
                }
                PrimRef::Triangle(i) if triangles_on && !(skip && is_leaving(leaving, Prim::Triangle, i)) => {
                    let [a, b0, c] = leaf_triangle(ctx, slot, i);
                    if let Some((t, bu, bv)) = intersect_triangle(a, b0, c, ray, &shear, t_min, limit)
                        && replaces(scene, t, Prim::Triangle, i, &b)
                    {
                        best.set(Some(Hit { t, prim: Prim::Triangle, index: i, bu, bv }));
                    }
                }
                PrimRef::Sphere(_) | PrimRef::Triangle(_) => {}
            }
            true
        },
    );
    let best = best.get();
    if ctx.has(feature::PLANES) {
        return closest_plane(ctx, ray, t_min, t_max, leaving, best);
    }
    best
}

/// A surface a shadow ray crosses: its place in brute force's order (kind, index, root) and
/// its material.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    key: (PrimRef, u32),
    material: u32,
}

/// `intersect::shadow_transmittance` through the BVH: the same product, bit for bit.
pub fn shadow_transmittance(ctx: &TraceContext, ray: &Ray, t_min: f64, t_max: f64, leaving: &Leaving) -> DVec3 {
    let scene = ctx.scene;
    let spheres_on = ctx.has(feature::SPHERES);
    let triangles_on = ctx.has(feature::TRIANGLES);
    let skip = ctx.has(feature::SKIP_LEFT);
    let shear = ray_shear(ray.dir);
    // A surface whose k_t is zero (or any surface, without filtered shadows) makes the product
    // zero whatever the order: return at once, as brute force would at the end.
    let opaque = |material: u32| all_zero(cross_surface(ctx, DVec3::ONE, material));
    let mut crossings: Vec<Crossing> = Vec::new();
    let passed = traverse(
        ctx,
        ray,
        t_min,
        || t_max,
        |slot, r| {
            let p = PrimRef::decode(r);
            match p {
                PrimRef::Sphere(i) if spheres_on => {
                    let s = &scene.spheres[i as usize];
                    let cr = s.center_radius;
                    let counted = sphere_roots_counted(ctx, leaving, i);
                    if let Some((t0, t1)) = sphere_roots(v3(cr), f64::from(cr[3]), ray, t_min) {
                        for (root, (t, counted)) in [t0, t1].into_iter().zip(counted).enumerate() {
                            if counted && t > t_min && t < t_max {
                                if opaque(s.material) {
                                    return false;
                                }
                                crossings.push(Crossing { key: (p, root as u32), material: s.material });
                            }
                        }
                    }
                }
                PrimRef::Triangle(i) if triangles_on && !(skip && is_leaving(leaving, Prim::Triangle, i)) => {
                    let [a, b, c] = leaf_triangle(ctx, slot, i);
                    if intersect_triangle(a, b, c, ray, &shear, t_min, t_max).is_some() {
                        let tri = &scene.triangles[i as usize];
                        let material = scene.meshes[tri.mesh as usize].material;
                        if opaque(material) {
                            return false;
                        }
                        crossings.push(Crossing { key: (p, 0), material });
                    }
                }
                PrimRef::Sphere(_) | PrimRef::Triangle(_) => {}
            }
            true
        },
    );
    if !passed {
        return DVec3::ZERO;
    }
    crossings.sort_unstable_by_key(|c| c.key);
    let first_triangle = crossings.partition_point(|c| matches!(c.key.0, PrimRef::Sphere(_)));
    let mut tr = DVec3::ONE;
    for c in &crossings[..first_triangle] {
        tr = cross_surface(ctx, tr, c.material);
        if all_zero(tr) {
            return tr;
        }
    }
    if ctx.has(feature::PLANES) {
        tr = planes_transmittance(ctx, tr, ray, t_min, t_max, leaving);
        if all_zero(tr) {
            return tr;
        }
    }
    for c in &crossings[first_triangle..] {
        tr = cross_surface(ctx, tr, c.material);
        if all_zero(tr) {
            return tr;
        }
    }
    tr
}
