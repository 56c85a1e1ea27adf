//! The GPU's form of the binary hierarchy: the two children of each interior node in one
//! 32-byte record, their boxes quantized to 8 bits a plane against the pair's own box (as
//! compressed wide BVHs do: Ylitie et al. 2017), so a step of the GPU walk loads two 16-byte
//! words instead of two whole nodes' four. On lavapipe every storage-buffer load is a loop over
//! the lanes of a SIMD group, and the binary walk was bound by those loads.
//!
//! Record 0 is the root as a `BvhNode` (its box exact; `left_first` 1 when it is interior).
//! Records are in depth-first order, so an interior left child's pair is the next record, and
//! one index (`first`) says where the other child is. Boxes only grow: each dequantized plane
//! is rounded outward by construction (`plane_below`, `plane_above`), computed in f32 exactly
//! as the shader does, so the walk still never misses a hit brute force finds.

use super::Aabb;
use glint_types::layout::{BvhNode, NODE_REF_COUNT_BITS, PAIR_FIRST_SHIFT, QuantizedPair};

/// Records and leaf references a tree the GPU walks may have at most: `first` must fit the
/// bits above the two counts.
pub const GPU_MAX_TREE_INDEX: u64 = 1 << (32 - PAIR_FIRST_SHIFT);

/// The smallest and largest power-of-two exponent of a quantization step. Below, steps would
/// be subnormal; above, 255 steps could overflow f32 (validated scenes span at most a few
/// 1e9, far below either bound).
const MIN_EXPONENT: i32 = -126;
const MAX_EXPONENT: i32 = 119;

/// Why a node array has no GPU form.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QuantizeError {
    #[error("BVH node {node} names child {child}, past the {len} nodes")]
    ChildOutside { node: usize, child: usize, len: usize },
    #[error("BVH node {node}'s leaf children are not neighbours in the reference array")]
    LeavesApart { node: usize },
    #[error("BVH node {node}'s children are at index {first}, past the GPU's limit of {limit} (GPU_MAX_TREE_INDEX)")]
    IndexTooLarge { node: usize, first: u64, limit: u64 },
    #[error("the BVH has more interior nodes than nodes: it is not a tree")]
    NotATree,
    #[error(
        "BVH node {node}'s box spans {extent:e} on axis {axis}, beyond the {max:e} the GPU's 8-bit child boxes hold"
    )]
    TooWide { node: usize, axis: usize, extent: f64, max: f64 },
}

/// The GPU form of `nodes` (a tree rooted at node 0; none for no nodes).
pub fn quantize(nodes: &[BvhNode]) -> Result<Vec<QuantizedPair>, QuantizeError> {
    let Some(root) = nodes.first() else { return Ok(Vec::new()) };
    let root_record = BvhNode { left_first: if root.count == 0 { 1 } else { root.left_first }, ..*root };
    // A binary tree has one interior node fewer than leaves: about half the nodes.
    let mut out = Vec::with_capacity(nodes.len() / 2 + 1);
    out.push(bytemuck::cast(root_record));
    if root.count > 0 {
        return Ok(out);
    }
    // Depth first, left before right. When both children are interior, the right one's record
    // index is known once its left sibling's subtree is written, so its parent's `first` is
    // patched then; a lone interior child's record is the next one.
    enum Task {
        Pair(usize),
        Right { parent: usize, node: usize },
    }
    let mut tasks = vec![Task::Pair(0)];
    while let Some(task) = tasks.pop() {
        match task {
            Task::Pair(i) => {
                if out.len() > nodes.len() {
                    return Err(QuantizeError::NotATree);
                }
                let node = &nodes[i];
                let [l, r] = [0, 1].map(|k| node.left_first as usize + k);
                let (left, right) = match (nodes.get(l), nodes.get(r)) {
                    (Some(a), Some(b)) => (a, b),
                    _ => return Err(QuantizeError::ChildOutside { node: i, child: r, len: nodes.len() }),
                };
                let record = out.len();
                let first = match (left.count, right.count) {
                    (0, 0) => 0, // patched by the Right task
                    (0, _) => right.left_first,
                    (_, 0) => left.left_first,
                    (cl, _) if right.left_first == left.left_first + cl => left.left_first,
                    _ => return Err(QuantizeError::LeavesApart { node: i }),
                };
                let counts = (left.count << NODE_REF_COUNT_BITS) | right.count;
                let mut pair = quantized_pair(i, Aabb::of_node(left), Aabb::of_node(right))?;
                pair.children = with_first(i, first, counts)?;
                out.push(pair);
                match (left.count, right.count) {
                    (0, 0) => tasks.extend([Task::Right { parent: record, node: r }, Task::Pair(l)]),
                    (0, _) => tasks.push(Task::Pair(l)),
                    (_, 0) => tasks.push(Task::Pair(r)),
                    _ => {}
                }
            }
            Task::Right { parent, node } => {
                let counts = out[parent].children & ((1 << PAIR_FIRST_SHIFT) - 1);
                out[parent].children = with_first(node, out.len() as u32, counts)?;
                tasks.push(Task::Pair(node));
            }
        }
    }
    Ok(out)
}

/// The children word: `first` above the counts, if it fits.
fn with_first(node: usize, first: u32, counts: u32) -> Result<u32, QuantizeError> {
    if u64::from(first) >= GPU_MAX_TREE_INDEX {
        return Err(QuantizeError::IndexTooLarge { node, first: first.into(), limit: GPU_MAX_TREE_INDEX });
    }
    Ok(first << PAIR_FIRST_SHIFT | counts)
}

/// 2^e as an f32.
fn step(e: i32) -> f32 {
    f32::from_bits(((e + 127) as u32) << 23)
}

/// The smallest e with 2^e ≥ x, for a finite x ≥ 0 (MIN_EXPONENT for 0 and subnormals): read
/// off the f64's bits, as `log2().ceil()` would give it, several times faster.
fn exponent_above(x: f64) -> i32 {
    let bits = x.to_bits();
    let biased = (bits >> 52) as i32 & 0x7ff;
    if biased == 0 {
        return MIN_EXPONENT;
    }
    biased - 1023 + i32::from(bits & ((1 << 52) - 1) != 0)
}

/// A plane at `origin + q · step`, as the shader computes it.
fn plane(origin: f32, q: u32, step: f32) -> f32 {
    origin + q as f32 * step
}

/// (c − origin) / step, exactly (step is a power of two) but for the f64 subtraction's rounding:
/// where the plane search starts.
fn steps_to(origin: f32, c: f32, step: f32) -> f64 {
    (f64::from(c) - f64::from(origin)) * f64::from(step.recip())
}

/// The largest q ≤ 255 whose plane is at or below `c` (0 always is: origin ≤ c).
fn plane_below(origin: f32, c: f32, step: f32) -> u32 {
    let guess = steps_to(origin, c, step).floor().clamp(0.0, 255.0) as u32;
    let mut q = guess;
    while q > 0 && plane(origin, q, step) > c {
        q -= 1;
    }
    while q < 255 && plane(origin, q + 1, step) <= c {
        q += 1;
    }
    q
}

/// The smallest q ≤ 255 whose plane is at or above `c`, if there is one.
fn plane_above(origin: f32, c: f32, step: f32) -> Option<u32> {
    let guess = steps_to(origin, c, step).ceil().clamp(0.0, 255.0) as u32;
    let mut q = guess;
    while q < 255 && plane(origin, q, step) < c {
        q += 1;
    }
    while q > 0 && plane(origin, q - 1, step) >= c {
        q -= 1;
    }
    (plane(origin, q, step) >= c).then_some(q)
}

/// The pair of boxes `left` and `right` (children of node `node`), each quantized outward;
/// `children` is left 0.
fn quantized_pair(node: usize, left: Aabb, right: Aabb) -> Result<QuantizedPair, QuantizeError> {
    let mut pair = QuantizedPair::default();
    for k in 0..3 {
        let origin = left.min[k].min(right.min[k]);
        let top = left.max[k].max(right.max[k]);
        let extent = f64::from(top) - f64::from(origin);
        let too_wide = || QuantizeError::TooWide { node, axis: k, extent, max: 255.0 * f64::from(step(MAX_EXPONENT)) };
        if !extent.is_finite() {
            return Err(too_wide());
        }
        // The smallest step whose 255 multiples span the box; one more if rounding says so.
        let mut e = exponent_above(extent / 255.0).clamp(MIN_EXPONENT, MAX_EXPONENT);
        let planes = loop {
            let s = step(e);
            let found = [
                Some(plane_below(origin, left.min[k], s)),
                plane_above(origin, left.max[k], s),
                Some(plane_below(origin, right.min[k], s)),
                plane_above(origin, right.max[k], s),
            ];
            if let [Some(a), Some(b), Some(c), Some(d)] = found {
                break a | b << 8 | c << 16 | d << 24;
            }
            if e == MAX_EXPONENT {
                return Err(too_wide());
            }
            e += 1;
        };
        pair.origin[k] = origin;
        pair.exponents |= ((e + 127) as u32) << (8 * k);
        pair.planes[k] = planes;
    }
    Ok(pair)
}

/// The two children's boxes, dequantized as the shader does (bvh.wgsl's `pair_boxes`).
pub fn pair_boxes(pair: &QuantizedPair) -> [Aabb; 2] {
    let plane_of = |k: usize, byte: u32| {
        let e = (pair.exponents >> (8 * k) & 0xff) as i32 - 127;
        plane(pair.origin[k], pair.planes[k] >> (8 * byte) & 0xff, step(e))
    };
    [0, 2].map(|b| Aabb {
        min: std::array::from_fn(|k| plane_of(k, b)),
        max: std::array::from_fn(|k| plane_of(k, b + 1)),
    })
}

/// The two children as the GPU walk carries them (`first << NODE_REF_COUNT_BITS | count`,
/// count 0 for a pair's record index), this being record `index` (bvh.wgsl's `pair_refs`).
pub fn pair_refs(pair: &QuantizedPair, index: u32) -> [u32; 2] {
    let count_mask = (1 << NODE_REF_COUNT_BITS) - 1;
    let first = pair.children >> PAIR_FIRST_SHIFT;
    let left_count = pair.children >> NODE_REF_COUNT_BITS & count_mask;
    let right_count = pair.children & count_mask;
    let left = if left_count > 0 { first } else { index + 1 };
    let right = match (left_count, right_count) {
        (_, 1..) => first + left_count,
        (1.., 0) => index + 1,
        (0, 0) => first,
    };
    [left << NODE_REF_COUNT_BITS | left_count, right << NODE_REF_COUNT_BITS | right_count]
}

#[cfg(test)]
mod tests {
    use super::super::tests::built_tree;
    use super::super::{f32_down, f32_up};
    use super::*;

    /// Walks the records beside the binary tree: each record's children are the node's
    /// children (the same leaves, the same order), each dequantized box holds its child's box,
    /// and every record is reached once.
    fn check_against(nodes: &[BvhNode]) {
        let records = quantize(nodes).expect("a GPU form");
        let root: BvhNode = bytemuck::cast(records[0]);
        assert_eq!((root.min, root.max, root.count), (nodes[0].min, nodes[0].max, nodes[0].count));
        if nodes[0].count > 0 {
            assert_eq!((records.len(), root.left_first), (1, nodes[0].left_first));
            return;
        }
        assert_eq!(root.left_first, 1);
        let mut reached = vec![false; records.len()];
        let mut stack = vec![(0usize, 1u32)];
        while let Some((node, record)) = stack.pop() {
            assert!(!std::mem::replace(&mut reached[record as usize], true), "record {record} reached twice");
            let pair = records[record as usize];
            let first = nodes[node].left_first as usize;
            for ((child, r), b) in
                [&nodes[first], &nodes[first + 1]].into_iter().zip(pair_refs(&pair, record)).zip(pair_boxes(&pair))
            {
                assert!(b.contains(&Aabb::of_node(child)), "record {record}: {b:?} does not hold {child:?}");
                let (at, count) = (r >> NODE_REF_COUNT_BITS, r & ((1 << NODE_REF_COUNT_BITS) - 1));
                assert_eq!(count, child.count);
                if count > 0 {
                    assert_eq!(at, child.left_first);
                } else {
                    let index = nodes.iter().position(|n| std::ptr::eq(n, child)).expect("a child");
                    stack.push((index, at));
                }
            }
        }
        assert!(reached[1..].iter().all(|&r| r), "records no walk reaches");
        // Index 1 is the builder's unused node.
        let interior = nodes.iter().enumerate().filter(|&(i, n)| n.count == 0 && i != 1).count();
        assert_eq!(records.len(), interior + 1);
    }

    #[test]
    fn the_gpu_form_is_the_same_tree_with_boxes_that_hold_the_children() {
        for n in [1, 4, 5, 9, 100, 12_345] {
            let nodes = built_tree(n);
            check_against(&nodes);
            // Far from the origin, where the planes' sums round in f32.
            let shifted: Vec<BvhNode> = nodes
                .iter()
                .map(|nd| BvhNode {
                    min: nd.min.map(|x| f32_down(f64::from(x) + 1e6)),
                    max: nd.max.map(|x| f32_up(f64::from(x) * 1e-3 + 1e6)).map(|x| x.max(f32_up(1e6 + 10.0))),
                    ..*nd
                })
                .collect();
            check_against(&shifted);
        }
    }

    #[test]
    fn malformed_trees_are_errors_not_panics() {
        let leaf = |first| BvhNode { left_first: first, count: 2, ..BvhNode::default() };
        let inner = |first| BvhNode { left_first: first, count: 0, ..BvhNode::default() };
        assert_eq!(quantize(&[]), Ok(Vec::new()));
        assert!(matches!(quantize(&[inner(2), BvhNode::default(), leaf(0)]), Err(QuantizeError::ChildOutside { .. })));
        assert!(matches!(
            quantize(&[inner(2), BvhNode::default(), leaf(0), leaf(3)]),
            Err(QuantizeError::LeavesApart { node: 0 })
        ));
        assert_eq!(quantize(&[inner(0), inner(0)]), Err(QuantizeError::NotATree));
        let far = [inner(2), BvhNode::default(), leaf(0), leaf(1 << 27)];
        assert!(matches!(quantize(&far), Err(QuantizeError::LeavesApart { .. })));
        let big = [inner(2), BvhNode::default(), inner(4), leaf(1 << 26), leaf(0), leaf(2)];
        assert!(matches!(quantize(&big), Err(QuantizeError::IndexTooLarge { .. })), "{:?}", quantize(&big));
    }

    #[test]
    fn a_plane_is_rounded_outward_even_where_f32_rounds_the_sum() {
        // Far from 0 the sum origin + q·step rounds; the chosen planes still hold c.
        for (origin, c) in [(1000.0f32, 1000.0001f32), (-3.0, 2.9999), (1e9, 1e9 + 64.0), (0.0, 1e-30), (-1e-3, 0.0)] {
            for e in [-40, -20, -10, 0, 10] {
                let s = step(e);
                let lo = plane_below(origin, c, s);
                assert!(plane(origin, lo, s) <= c, "{origin} {c} {e}");
                if let Some(hi) = plane_above(origin, c, s) {
                    assert!(plane(origin, hi, s) >= c, "{origin} {c} {e}");
                    assert!(hi == 0 || plane(origin, hi - 1, s) < c, "the smallest such q");
                }
            }
        }
    }

    #[test]
    fn exponent_above_is_log2_rounded_up() {
        for x in [1.0, 1.5, 2.0, 3.0, 255.0, 256.0, 1e-30, 3.7e-9, 1e30, 0.75, 2f64.powi(-1000)] {
            assert_eq!(exponent_above(x).max(MIN_EXPONENT), (x.log2().ceil() as i32).max(MIN_EXPONENT), "{x}");
        }
        assert_eq!(exponent_above(0.0), MIN_EXPONENT);
    }

    #[test]
    fn a_pair_too_wide_for_the_largest_step_is_an_error() {
        let wide = Aabb { min: [-3e38; 3], max: [3e38; 3] };
        let err = quantized_pair(7, wide, wide).expect_err("beyond 255 · 2^119");
        assert!(err.to_string().contains("BVH node 7's box spans"), "{err}");
    }
}
