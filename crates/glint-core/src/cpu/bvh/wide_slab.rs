//! The CPU walk's test of a wide node's boxes (`cpu::bvh` walks the nodes): `SlabRay::enter`'s
//! f64 arithmetic on all `WIDTH` columns at once, in SSE2 on x86_64, with the scalar form as
//! its reference. CPU only: the GPU walks the binary nodes, one `enter` per box.

use super::{GAMMA3, SlabRay};
use crate::bvh::{WIDTH, WideNode};

/// Pairs of columns of a wide node: the f64 vectors of SSE2 hold two.
const PAIRS: usize = WIDTH / 2;
const _: () = assert!(WIDTH.is_multiple_of(4), "the vector slab test reads a row four columns at a time");

/// `SlabRay` in the form the inner loop wants, for a ray with no direction component below
/// `DIR_ZERO` of `cpu::bvh` (almost every ray; the others take `SlabRay::enter`): per axis, which row of a
/// wide node's bounds is the near and which the far plane (so no branch on the direction's sign
/// per box), and the points the padded planes are measured from. fl(min − fl(o + pad)) differs
/// from `SlabRay::enter`'s fl(fl(min − pad) − o) by one rounding of o + pad, ≤ ε·(|o| + pad), which
/// the padding (1e-9 of the scale, > 10^6 ε) absorbs exactly as it absorbs `enter`'s rounding
/// of min − pad; the subtraction and the product are the two roundings γ(3) covers in both.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlabPlanes {
    /// Rows of `WideNode::bounds` (`min` at 0..3, `max` at 3..6).
    near: [usize; 3],
    far: [usize; 3],
    /// o + pad where the near (far) plane is a min plane, o − pad where it is a max plane.
    o_near: [f64; 3],
    o_far: [f64; 3],
    inv: [f64; 3],
}

impl SlabPlanes {
    pub(super) fn of(slab: &SlabRay) -> Option<Self> {
        if slab.parallel.iter().any(|&p| p) {
            return None;
        }
        let forward = slab.inv.map(|i| i >= 0.0);
        let (lo, hi) = (slab.origin.map(|o| o + slab.pad), slab.origin.map(|o| o - slab.pad));
        Some(Self {
            near: std::array::from_fn(|k| if forward[k] { k } else { k + 3 }),
            far: std::array::from_fn(|k| if forward[k] { k + 3 } else { k }),
            o_near: std::array::from_fn(|k| if forward[k] { lo[k] } else { hi[k] }),
            o_far: std::array::from_fn(|k| if forward[k] { hi[k] } else { lo[k] }),
            inv: slab.inv,
        })
    }

    /// `SlabRay::enter` on every column of `node` at once, with its bounds already widened by
    /// the slack: per column, the entry distance if the ray meets the padded box with t0 ≤ `hi`
    /// and t1 ≥ `lo`, else +∞ (an unused column's empty box is never met), and the entered
    /// columns as bits (read off the comparison, not the distances). The arithmetic of
    /// `enter` lane by lane; on x86_64 in SSE2 vectors (x86_64's baseline), which give the
    /// same values as the scalar form (`enter_scalar`, tested against it): the same IEEE
    /// operations per lane, and max/min that differ from the comparisons only in the sign of a
    /// zero, which no comparison sees.
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    #[allow(unsafe_code)] // reason: SSE2 intrinsics are `unsafe` only for their target-feature attribute.
    pub(super) fn enter(&self, node: &WideNode, lo: f64, hi: f64) -> Entered {
        use std::arch::x86_64::{
            __m128, __m128d, _mm_add_pd, _mm_and_pd, _mm_andnot_pd, _mm_cmple_pd, _mm_cvtps_pd, _mm_max_pd, _mm_min_pd,
            _mm_movehl_ps, _mm_movemask_pd, _mm_mul_pd, _mm_or_pd, _mm_set1_pd, _mm_sub_pd,
        };
        // SAFETY: SSE2 is part of x86_64's baseline, and these intrinsics touch no memory.
        unsafe {
            // A bounds row, widened to f64, two columns a vector.
            let row = |r: usize| -> [__m128d; PAIRS] {
                let row = &node.bounds[r.min(5)];
                std::array::from_fn(|p| {
                    let c = p / 2 * 4;
                    let four: __m128 = bytemuck::cast([row[c], row[c + 1], row[c + 2], row[c + 3]]);
                    if p % 2 == 0 { _mm_cvtps_pd(four) } else { _mm_cvtps_pd(_mm_movehl_ps(four, four)) }
                })
            };
            let mut t0 = [_mm_set1_pd(f64::NEG_INFINITY); PAIRS];
            let mut t1 = [_mm_set1_pd(f64::INFINITY); PAIRS];
            for k in 0..3 {
                let (near, far) = (row(self.near[k]), row(self.far[k]));
                let (o_near, o_far, inv) =
                    (_mm_set1_pd(self.o_near[k]), _mm_set1_pd(self.o_far[k]), _mm_set1_pd(self.inv[k]));
                for p in 0..PAIRS {
                    t0[p] = _mm_max_pd(t0[p], _mm_mul_pd(_mm_sub_pd(near[p], o_near), inv));
                    t1[p] = _mm_min_pd(t1[p], _mm_mul_pd(_mm_sub_pd(far[p], o_far), inv));
                }
            }
            let (lo, hi, grow, none, sign) = (
                _mm_set1_pd(lo),
                _mm_set1_pd(hi),
                _mm_set1_pd(2.0 * GAMMA3),
                _mm_set1_pd(f64::INFINITY),
                _mm_set1_pd(-0.0),
            );
            let mut out = Entered { t: [f64::INFINITY; WIDTH], mask: 0 };
            for p in 0..PAIRS {
                // t1 + 2γ₃·|t1| (the scalar form's).
                let t1 = _mm_add_pd(t1[p], _mm_mul_pd(_mm_andnot_pd(sign, t1[p]), grow));
                let entered =
                    _mm_and_pd(_mm_and_pd(_mm_cmple_pd(t0[p], t1), _mm_cmple_pd(t0[p], hi)), _mm_cmple_pd(lo, t1));
                let t = _mm_or_pd(_mm_and_pd(entered, t0[p]), _mm_andnot_pd(entered, none));
                [out.t[2 * p], out.t[2 * p + 1]] = bytemuck::cast::<__m128d, [f64; 2]>(t);
                out.mask |= (_mm_movemask_pd(entered) as u32) << (2 * p);
            }
            out
        }
    }

    /// The scalar form of `enter`: the walk's on other targets, and the reference the vector
    /// form is tested against.
    #[cfg_attr(target_arch = "x86_64", allow(dead_code, reason = "the x86_64 walk's test reference"))]
    #[inline(always)]
    fn enter_scalar(&self, node: &WideNode, lo: f64, hi: f64) -> Entered {
        let mut t0 = [f64::NEG_INFINITY; WIDTH];
        let mut t1 = [f64::INFINITY; WIDTH];
        for k in 0..3 {
            let (near, far) = (&node.bounds[self.near[k].min(5)], &node.bounds[self.far[k].min(5)]);
            for l in 0..WIDTH {
                let n = (f64::from(near[l]) - self.o_near[k]) * self.inv[k];
                let f = (f64::from(far[l]) - self.o_far[k]) * self.inv[k];
                // Plain comparisons, not f64::max/min: the operands are never NaN (inv is
                // finite and non-zero here, an empty column's planes are ±∞).
                if n > t0[l] {
                    t0[l] = n;
                }
                if f < t1[l] {
                    t1[l] = f;
                }
            }
        }
        Entered::of(std::array::from_fn(|l| {
            let t1 = t1[l] + 2.0 * GAMMA3 * t1[l].abs();
            if t0[l] <= t1 && t0[l] <= hi && t1 >= lo { t0[l] } else { f64::INFINITY }
        }))
    }

    #[cfg(not(target_arch = "x86_64"))]
    #[inline(always)]
    pub(super) fn enter(&self, node: &WideNode, lo: f64, hi: f64) -> Entered {
        self.enter_scalar(node, lo, hi)
    }
}

/// What a step's slab test gives for the columns of a wide node: the entry distances (+∞ for
/// a column not entered) and the entered columns as bits, the walk's least predictable value,
/// so it branches on their number rather than column by column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Entered {
    pub(super) t: [f64; WIDTH],
    pub(super) mask: u32,
}

impl Entered {
    /// From the distances alone.
    #[inline(always)]
    pub(super) fn of(t: [f64; WIDTH]) -> Self {
        let mask = t.iter().enumerate().fold(0u32, |m, (l, &t)| m | (u32::from(t < f64::INFINITY) << l));
        Self { t, mask }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::cpu::FAR;
    use crate::cpu::Ray;
    use glint_types::layout::BvhNode;

    fn node(min: [f32; 3], max: [f32; 3]) -> BvhNode {
        BvhNode { min, left_first: 0, max, count: 1 }
    }

    /// With t_hi = FAR (a shadow ray to a directional light, a ray before its first hit) a box
    /// behind the origin is culled, one around or ahead of it entered, in both slab tests; an
    /// unused column of a wide node is never entered.
    #[test]
    fn a_box_behind_the_origin_is_culled_even_when_the_ray_reaches_far() {
        let ray = Ray { origin: DVec3::new(0.0, 0.0, 0.0), dir: DVec3::new(0.48, 0.6, 0.64) };
        let root = node([-10.0; 3], [10.0; 3]);
        let slab = SlabRay::new(&ray, &root);
        let planes = SlabPlanes::of(&slab).expect("no axis is parallel to the ray");
        let behind = node([-2.0; 3], [-1.0; 3]);
        let around = node([-1.0; 3], [1.0; 3]);
        let ahead = node([1.0; 3], [2.0; 3]);
        let t_min = 1e-9;
        let (lo, hi) = (t_min - slab.slack(t_min), FAR + slab.slack(FAR));
        let wide = WideNode::over(&[behind, around, ahead]);
        let t = planes.enter(&wide, lo, hi);
        for (lane, (name, entered)) in [("behind", false), ("around", true), ("ahead", true)].into_iter().enumerate() {
            assert_eq!(slab.enter(wide.child_box(lane), t_min, FAR).is_some(), entered, "{name}: SlabRay::enter");
            assert_eq!(t.t[lane] < f64::INFINITY, entered, "{name}: SlabPlanes::enter");
            assert_eq!(t.mask & (1 << lane) != 0, entered, "{name}: SlabPlanes::enter's mask");
        }
        assert_eq!(t.t[3], f64::INFINITY, "an unused column was entered");
        assert_eq!(t.mask, 0b110, "the mask is not the entered columns");
        assert!(slab.enter(wide.child_box(3), t_min, FAR).is_none(), "an unused column was entered");
        // A box whose far face the ray leaves exactly at t_min is still entered (conservative).
        let ends_at_origin = node([-1.0; 3], [0.0; 3]);
        assert!(slab.enter((ends_at_origin.min, ends_at_origin.max), 0.0, FAR).is_some());
        assert_eq!(planes.enter(&WideNode::over(&[ends_at_origin]), -slab.slack(0.0), hi).mask, 1);
    }

    /// The vector slab test gives the scalar one's distances (equal as f64: a zero's sign may
    /// differ) on random wide nodes, with empty and flat boxes, boxes behind, around and ahead of
    /// the origin, and both ends of the interval near and far.
    #[test]
    fn the_vector_slab_test_equals_the_scalar_one() {
        let mut state = 0x9e37_79b9_u32;
        let mut rnd = move |scale: f32| {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state as f32 / u32::MAX as f32 * 2.0 - 1.0) * scale
        };
        let root = node([-8.0; 3], [8.0; 3]);
        let (mut entered, mut checked) = (0, 0);
        for _ in 0..2000 {
            let dir = DVec3::new(f64::from(rnd(1.0)), f64::from(rnd(1.0)), f64::from(rnd(1.0)));
            if dir.length() < 1e-3 {
                continue;
            }
            let ray = Ray { origin: DVec3::new(f64::from(rnd(4.0)), f64::from(rnd(4.0)), 0.5), dir: dir.normalize() };
            let slab = SlabRay::new(&ray, &root);
            let Some(planes) = SlabPlanes::of(&slab) else { continue };
            // Boxes around a point of the ray (those at the interval's ends or behind the origin
            // are the cases), some flat in z (a triangle in an axis plane).
            let boxes: Vec<BvhNode> = (0..rnd(2.0).abs() as usize + 2)
                .map(|_| {
                    let p = (ray.origin + ray.dir * f64::from(rnd(6.0))).as_vec3().to_array();
                    let flat = rnd(1.0) > 0.5;
                    let min: [f32; 3] =
                        std::array::from_fn(|k| if k == 2 && flat { p[k] } else { p[k] - rnd(1.0).abs() });
                    let max: [f32; 3] =
                        std::array::from_fn(|k| if k == 2 && flat { p[k] } else { p[k] + rnd(1.0).abs() });
                    node(min, max)
                })
                .collect();
            let wide = WideNode::over(&boxes);
            for (t_min, t_hi) in [(1e-9, FAR), (0.0, 2.0), (3.0, 5.0)] {
                let (lo, hi) = (t_min - slab.slack(t_min), t_hi + slab.slack(t_hi));
                let (v, s) = (planes.enter(&wide, lo, hi), planes.enter_scalar(&wide, lo, hi));
                assert_eq!(v, s, "ray {ray:?} boxes {boxes:?} [{t_min}, {t_hi}]");
                assert_eq!(v, Entered::of(v.t), "the mask is not the entered columns: {v:?}");
                entered += v.t.iter().filter(|t| **t < f64::INFINITY).count();
                checked += boxes.len();
            }
        }
        assert!(entered > checked / 10 && entered < checked * 9 / 10, "{entered} of {checked} boxes entered");
    }
}
