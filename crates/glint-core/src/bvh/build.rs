//! The binned-SAH builder of `Bvh` (storage and boxes are in the parent module).

use rayon::prelude::*;

use super::{Aabb, Bounded, Bvh, MAX_LEAF, PrimRef};
use glint_types::layout::{BvhNode, PRIM_REF_INDEX};

/// SAH bins per axis.
const BINS: usize = 16;
/// Nodes with more primitives than this build their children in parallel.
const PARALLEL_THRESHOLD: usize = 4096;
/// Nodes with more primitives than this also bin them in parallel, in chunks of this many
/// (near the root, where there are fewer subtrees than threads).
const PARALLEL_CHUNK: usize = 16384;

/// A primitive during the build: its reference, box and centroid.
#[derive(Clone, Copy, Debug)]
struct Item {
    r: u32,
    bounds: Aabb,
    centroid: [f64; 3],
}

/// Builds the hierarchy over every sphere and triangle.
pub fn build(prims: &Bounded) -> Bvh {
    assert!(prims.triangles.len() <= PRIM_REF_INDEX as usize, "too many triangles for a primitive reference");
    let refs: Vec<u32> = (0..prims.spheres.len() as u32)
        .map(|i| PrimRef::Sphere(i).encode())
        .chain((0..prims.triangles.len() as u32).map(|i| PrimRef::Triangle(i).encode()))
        .collect();
    let mut items: Vec<Item> = refs
        .par_iter()
        .with_min_len(PARALLEL_CHUNK)
        .map(|&r| {
            let bounds = prims.prim_box(r);
            let centroid = std::array::from_fn(|k| 0.5 * (f64::from(bounds.min[k]) + f64::from(bounds.max[k])));
            Item { r, bounds, centroid }
        })
        .collect();
    if items.is_empty() {
        return Bvh::default();
    }
    if items.len() <= MAX_LEAF {
        let root = build_node(&mut items, 0, &mut Vec::new());
        return Bvh { nodes: vec![root], prims: items.iter().map(|i| i.r).collect() };
    }
    // The root, then an unused node, so that every sibling pair starts at an even index.
    let mut nodes = vec![BvhNode::default(); 2];
    nodes[0] = build_node(&mut items, 0, &mut nodes);
    Bvh { nodes, prims: items.iter().map(|i| i.r).collect() }
}

/// The subtree over `items` (which start at `first` in the final reference array): returns its
/// root and appends its descendants to `out` (child indices are indices of `out`). Layout:
/// both children of a node, then the left child's descendants, then the right child's.
/// Written in place rather than returned and copied by every ancestor (which moved each node
/// once per level above it).
fn build_node(items: &mut [Item], first: usize, out: &mut Vec<BvhNode>) -> BvhNode {
    let Extent { bounds, cmin, cmax } = by_chunks(items, Extent::of, Extent::merge);
    let n = items.len();
    if n <= MAX_LEAF {
        return BvhNode { min: bounds.min, left_first: first as u32, max: bounds.max, count: n as u32 };
    }
    let mid = match best_split(items, &cmin, &cmax) {
        Some((axis, split)) => {
            let scale = BINS as f64 / (cmax[axis] - cmin[axis]);
            let bin = |c: f64| (((c - cmin[axis]) * scale) as usize).min(BINS - 1);
            partition(items, |it| bin(it.centroid[axis]) < split)
        }
        None => n / 2,
    };
    let mid = if mid == 0 || mid == n { n / 2 } else { mid };
    let (l, r) = items.split_at_mut(mid);
    let pair = out.len();
    out.extend([BvhNode::default(); 2]);
    let (left, right) = if n > PARALLEL_THRESHOLD {
        // The right subtree goes to a vector of its own, appended with its indices shifted.
        let (left, (right, mut below)) = rayon::join(
            || build_node(l, first, out),
            || {
                let mut below = Vec::new();
                (build_node(r, first + mid, &mut below), below)
            },
        );
        let shift = out.len() as u32;
        let shifted = |mut node: BvhNode| {
            if node.count == 0 {
                node.left_first += shift;
            }
            node
        };
        below.iter_mut().for_each(|nd| *nd = shifted(*nd));
        out.append(&mut below);
        (left, shifted(right))
    } else {
        (build_node(l, first, out), build_node(r, first + mid, out))
    };
    out[pair] = left;
    out[pair + 1] = right;
    BvhNode { min: bounds.min, left_first: pair as u32, max: bounds.max, count: 0 }
}

/// `f` over `items`, in parallel chunks merged with `merge` for a large node (near the root,
/// where there are fewer subtrees than threads), else in one call.
fn by_chunks<T: Default + Send>(
    items: &[Item],
    f: impl Fn(&[Item]) -> T + Sync + Send,
    merge: impl Fn(T, T) -> T + Sync + Send,
) -> T {
    if items.len() > 2 * PARALLEL_CHUNK {
        items.par_chunks(PARALLEL_CHUNK).map(f).reduce(T::default, merge)
    } else {
        f(items)
    }
}

/// The box of a set of items and the range of their centroids. Merging is exact (min and
/// max), so chunks merged in any grouping give the same result.
#[derive(Clone, Copy, Debug)]
struct Extent {
    bounds: Aabb,
    cmin: [f64; 3],
    cmax: [f64; 3],
}

impl Default for Extent {
    fn default() -> Self {
        Self { bounds: Aabb::EMPTY, cmin: [f64::INFINITY; 3], cmax: [f64::NEG_INFINITY; 3] }
    }
}

impl Extent {
    fn of(items: &[Item]) -> Self {
        let mut e = Self::default();
        for it in items {
            e.bounds.grow(&it.bounds);
            for k in 0..3 {
                e.cmin[k] = e.cmin[k].min(it.centroid[k]);
                e.cmax[k] = e.cmax[k].max(it.centroid[k]);
            }
        }
        e
    }

    fn merge(mut self, o: Self) -> Self {
        self.bounds.grow(&o.bounds);
        for k in 0..3 {
            self.cmin[k] = self.cmin[k].min(o.cmin[k]);
            self.cmax[k] = self.cmax[k].max(o.cmax[k]);
        }
        self
    }
}

/// Per axis, the number of items and their box in each bin. Merging is exact (sums, min and
/// max), so chunks binned in parallel give the same bins as one pass.
#[derive(Clone, Copy, Debug)]
struct Bins {
    counts: [[usize; BINS]; 3],
    boxes: [[Aabb; BINS]; 3],
}

impl Default for Bins {
    fn default() -> Self {
        Self { counts: [[0; BINS]; 3], boxes: [[Aabb::EMPTY; BINS]; 3] }
    }
}

impl Bins {
    fn merge(mut self, o: Self) -> Self {
        for axis in 0..3 {
            for b in 0..BINS {
                self.counts[axis][b] += o.counts[axis][b];
                self.boxes[axis][b].grow(&o.boxes[axis][b]);
            }
        }
        self
    }
}

/// The cheapest binned SAH split (axis, first bin of the right side), or `None` when every
/// centroid coincides (the caller then splits at the median). A node of more than `MAX_LEAF`
/// primitives is always split, so there is no leaf cost to compare with.
fn best_split(items: &[Item], cmin: &[f64; 3], cmax: &[f64; 3]) -> Option<(usize, usize)> {
    let extent: [f64; 3] = std::array::from_fn(|k| cmax[k] - cmin[k]);
    let split_axis = extent.map(|e| !(e.is_nan() || e <= 0.0));
    let scale = extent.map(|e| BINS as f64 / e);
    // All three axes binned in one pass over the items (the items of a large node are far
    // beyond the caches; three passes read them three times).
    let bin = |chunk: &[Item]| {
        let mut bins = Bins::default();
        for it in chunk {
            for axis in 0..3 {
                if split_axis[axis] {
                    let b = (((it.centroid[axis] - cmin[axis]) * scale[axis]) as usize).min(BINS - 1);
                    bins.counts[axis][b] += 1;
                    bins.boxes[axis][b].grow(&it.bounds);
                }
            }
        }
        bins
    };
    let Bins { counts, boxes } = by_chunks(items, bin, Bins::merge);
    let mut best: Option<(f64, usize, usize)> = None;
    for axis in (0..3).filter(|&a| split_axis[a]) {
        let (counts, boxes) = (&counts[axis], &boxes[axis]);
        // Right-side sweeps: cost of bins split..BINS.
        let mut right_area = [0.0; BINS];
        let mut right_count = [0usize; BINS];
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for b in (1..BINS).rev() {
            acc.grow(&boxes[b]);
            cnt += counts[b];
            right_area[b] = acc.half_area();
            right_count[b] = cnt;
        }
        let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
        for split in 1..BINS {
            acc.grow(&boxes[split - 1]);
            cnt += counts[split - 1];
            if cnt == 0 || right_count[split] == 0 {
                continue;
            }
            let cost = acc.half_area() * cnt as f64 + right_area[split] * right_count[split] as f64;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, split));
            }
        }
    }
    best.map(|(_, axis, split)| (axis, split))
}

/// Moves the items for which `left` holds to the front; returns how many there are.
fn partition(items: &mut [Item], left: impl Fn(&Item) -> bool) -> usize {
    let mut i = 0;
    for j in 0..items.len() {
        if left(&items[j]) {
            items.swap(i, j);
            i += 1;
        }
    }
    i
}
