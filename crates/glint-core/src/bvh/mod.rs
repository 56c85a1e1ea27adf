//! A flat bounding-volume hierarchy over the bounded primitives of a flat scene (spheres and
//! triangles; infinite planes stay a separate list), built with a binned SAH.
//!
//! Leaves point into `prims`, an array of primitive references (kind in the top bit, index
//! below). After the build, `reorder_triangles` puts the triangle array in leaf order, so that
//! a leaf's triangles are neighbours in memory. Boxes are f32, rounded outward, so they
//! contain the f32-stored primitives exactly. Traversal is in `cpu::bvh`.

use std::sync::Arc;

use bytemuck::{Pod, Zeroable};

use crate::huge_pages::HugePaged;
use glint_types::layout::{
    BvhNode, GpuSphere, GpuTriangle, NODE_REF_COUNT_BITS, PRIM_REF_INDEX, PRIM_REF_TRIANGLE, QuantizedPair,
};

mod build;
mod quantized;
mod wide;

pub use build::build;
pub use quantized::{GPU_MAX_TREE_INDEX, QuantizeError, pair_boxes, pair_refs};
pub use wide::{WIDTH, WideNode};

/// The bounded primitives a hierarchy is built over, as the flat scene stores them.
#[derive(Clone, Copy, Debug)]
pub struct Bounded<'a> {
    pub spheres: &'a [GpuSphere],
    pub triangles: &'a [GpuTriangle],
    /// The vertex positions the triangles index (xyz, w unused).
    pub vertices: &'a [[f32; 4]],
}

/// Two nodes, aligned to a 64-byte cache line: the storage unit of `BvhNodes`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
#[repr(C, align(64))]
pub struct NodePair([BvhNode; 2]);

/// A flat scene's node array, shared between the scenes `FlatScene::rebuild` makes, and stored
/// in cache-line-aligned pairs, so that the two children a traversal step tests are one line
/// to fetch (an `Arc<[BvhNode]>`'s data sits 32 bytes into its allocation, which put every
/// sibling pair across two lines), in memory advised for huge pages. Reads as `[BvhNode]`.
#[derive(Clone, Debug, Default)]
pub struct BvhNodes {
    pairs: Arc<HugePaged<NodePair>>,
    len: usize,
    depth: u32,
    /// The CPU walk's wide form, made at its first use (`wide`): a scene only the GPU traces
    /// (the viewer's rebased copies) never pays for it.
    wide: Arc<std::sync::OnceLock<HugePaged<WideNode>>>,
    /// The GPU walk's quantized form, made at its first use (`gpu`): a scene only the CPU
    /// traces never pays for it.
    gpu: Arc<std::sync::OnceLock<Result<Vec<QuantizedPair>, QuantizeError>>>,
}

/// Derived data: equal when the binary nodes are.
impl PartialEq for BvhNodes {
    fn eq(&self, other: &Self) -> bool {
        self.len == other.len && self.pairs == other.pairs && self.depth == other.depth
    }
}

impl BvhNodes {
    pub fn new(nodes: &[BvhNode]) -> Self {
        Self::with_depth(nodes, tree_depth(nodes))
    }

    fn with_depth(nodes: &[BvhNode], depth: u32) -> Self {
        let pairs = HugePaged::new(nodes.len().div_ceil(2), |pairs| {
            for (pair, c) in pairs.iter_mut().zip(nodes.chunks(2)) {
                *pair = NodePair([c[0], c.get(1).copied().unwrap_or_default()]);
            }
        });
        Self { pairs: Arc::new(pairs), len: nodes.len(), depth, wide: Arc::default(), gpu: Arc::default() }
    }

    /// `build`, stored, and collapsed for the CPU walk: all the hierarchy work a scene's first
    /// CPU trace has done, as the benchmarks time it.
    pub fn build_for_cpu(bounded: &Bounded) -> (Bvh, Self) {
        let built = build(bounded);
        let nodes = Self::new(&built.nodes);
        nodes.wide();
        (built, nodes)
    }

    /// The tree collapsed into wide nodes (`wide::collapse`), made once and shared by clones.
    pub fn wide(&self) -> &[WideNode] {
        self.wide.get_or_init(|| wide::collapse(self))
    }

    /// The tree in the GPU walk's form (`quantized::quantize`), made once and shared by clones.
    pub fn gpu(&self) -> Result<&[QuantizedPair], QuantizeError> {
        self.gpu
            .get_or_init(|| {
                let start = std::time::Instant::now();
                let records = quantized::quantize(self);
                log::debug!(
                    "quantized {} BVH nodes for the GPU in {:.1} ms",
                    self.len,
                    start.elapsed().as_secs_f64() * 1e3
                );
                records
            })
            .as_deref()
            .map_err(Clone::clone)
    }

    /// Edges from the root to the deepest leaf (0 for a lone leaf or no tree): a walk that
    /// pushes a node's children after popping it never holds more than `depth + 1` entries.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// Whether both are the same array (not merely equal nodes).
    pub fn ptr_eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.pairs, &other.pairs)
    }
}

/// The depth of the tree rooted at node 0 (`BvhNodes::depth`). Total on any array (tests store
/// arbitrary nodes): a child index outside it is not followed, and no more nodes are visited
/// than there are, so a malformed array cannot make it loop.
fn tree_depth(nodes: &[BvhNode]) -> u32 {
    let mut deepest = 0;
    let mut stack = Vec::new();
    if !nodes.is_empty() {
        stack.push((0usize, 0u32));
    }
    let mut visits = 0;
    while let Some((i, d)) = stack.pop() {
        let Some(node) = nodes.get(i) else { continue };
        visits += 1;
        if visits > nodes.len() {
            break;
        }
        if node.count > 0 {
            deepest = deepest.max(d);
        } else {
            let first = node.left_first as usize;
            stack.extend([(first, d + 1), (first + 1, d + 1)]);
        }
    }
    deepest
}

impl BvhNodes {
    /// Every node mapped by `f`, which keeps the tree's shape (rebasing moves the boxes): so its
    /// depth is kept, not walked again.
    pub fn map(&self, f: impl Fn(&BvhNode) -> BvhNode) -> Self {
        Self::with_depth(&self.iter().map(f).collect::<Vec<_>>(), self.depth)
    }
}

impl std::ops::Deref for BvhNodes {
    type Target = [BvhNode];

    fn deref(&self) -> &[BvhNode] {
        &bytemuck::cast_slice(&self.pairs)[..self.len]
    }
}

/// Most primitives in a leaf.
pub const MAX_LEAF: usize = 4;

const _: () = assert!(MAX_LEAF < 1 << NODE_REF_COUNT_BITS, "a leaf's count must fit NODE_REF_COUNT_BITS");

/// From this many spheres and triangles on, `Accel::Auto` traces through the BVH; below, brute
/// force is faster. Measured on the CPU tracer (2 threads, 320×240, depth 3, median of 5): with
/// spheres, brute force against BVH 12.7 / 20.6 ms at 4, 16.7 / 20.4 ms at 16, 30.8 / 29.7 ms at
/// 32, 41.6 / 30.6 ms at 64; with triangles 18.8 / 24.1 ms at 16 and 48.3 / 26.0 ms at 32.
pub const AUTO_MIN_PRIMITIVES: usize = 24;

/// A bounded primitive, decoded from its reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum PrimRef {
    Sphere(u32),
    Triangle(u32),
}

impl PrimRef {
    pub fn decode(r: u32) -> Self {
        if r & PRIM_REF_TRIANGLE != 0 { Self::Triangle(r & PRIM_REF_INDEX) } else { Self::Sphere(r) }
    }

    pub fn encode(self) -> u32 {
        match self {
            Self::Sphere(i) => i,
            Self::Triangle(i) => i | PRIM_REF_TRIANGLE,
        }
    }
}

/// An axis-aligned box in f32.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: [f32; 3],
    pub max: [f32; 3],
}

impl Aabb {
    pub const EMPTY: Self = Self { min: [f32::INFINITY; 3], max: [f32::NEG_INFINITY; 3] };

    /// A node's box.
    pub fn of_node(node: &BvhNode) -> Self {
        Self { min: node.min, max: node.max }
    }

    fn grow(&mut self, o: &Self) {
        for k in 0..3 {
            self.min[k] = self.min[k].min(o.min[k]);
            self.max[k] = self.max[k].max(o.max[k]);
        }
    }

    /// Half the surface area (in f64), 0 for an empty box.
    fn half_area(&self) -> f64 {
        let d: [f64; 3] = std::array::from_fn(|k| (f64::from(self.max[k]) - f64::from(self.min[k])).max(0.0));
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }

    pub fn contains(&self, o: &Self) -> bool {
        (0..3).all(|k| self.min[k] <= o.min[k] && o.max[k] <= self.max[k])
    }
}

/// x rounded down to an f32 (never above x).
pub(crate) fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f.next_down() } else { f }
}

/// x rounded up to an f32 (never below x).
pub(crate) fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

/// The box of a sphere: centre ± radius, computed in f64 and rounded outward.
pub fn sphere_box(s: &GpuSphere) -> Aabb {
    let cr = s.center_radius;
    let r = f64::from(cr[3]).abs();
    Aabb {
        min: std::array::from_fn(|k| f32_down(f64::from(cr[k]) - r)),
        max: std::array::from_fn(|k| f32_up(f64::from(cr[k]) + r)),
    }
}

/// The box of a triangle: the min and max of its (f32) vertices, exact.
pub fn triangle_box(t: &GpuTriangle, vertices: &[[f32; 4]]) -> Aabb {
    let [a, b, c] = [t.va, t.vb, t.vc].map(|i| vertices[i as usize]);
    Aabb {
        min: std::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
        max: std::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
    }
}

impl Bounded<'_> {
    /// The box of a primitive reference.
    pub fn prim_box(&self, r: u32) -> Aabb {
        match PrimRef::decode(r) {
            PrimRef::Sphere(i) => sphere_box(&self.spheres[i as usize]),
            PrimRef::Triangle(i) => triangle_box(&self.triangles[i as usize], self.vertices),
        }
    }
}

/// A built hierarchy: nodes (root first; none for a scene without bounded primitives) and the
/// primitive references the leaves point into.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bvh {
    pub nodes: Vec<BvhNode>,
    pub prims: Vec<u32>,
}

/// Puts `triangles` in the order the leaves reference them and renumbers the references, so
/// that the triangles of a leaf (and of neighbouring leaves) are neighbours in memory.
pub fn reorder_triangles(bvh: &mut Bvh, triangles: &mut Vec<GpuTriangle>) {
    let mut reordered = Vec::with_capacity(triangles.len());
    for r in &mut bvh.prims {
        match PrimRef::decode(*r) {
            PrimRef::Triangle(i) => {
                *r = PrimRef::Triangle(reordered.len() as u32).encode();
                reordered.push(triangles[i as usize]);
            }
            PrimRef::Sphere(_) => {}
        }
    }
    *triangles = reordered;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spheres, and triangles over their own vertex array.
    #[derive(Default)]
    struct Scene {
        spheres: Vec<GpuSphere>,
        triangles: Vec<GpuTriangle>,
        vertices: Vec<[f32; 4]>,
    }

    impl Scene {
        fn tri(&mut self, a: [f32; 3], b: [f32; 3], c: [f32; 3]) {
            let va = self.vertices.len() as u32;
            self.vertices.extend([a, b, c].map(|p| [p[0], p[1], p[2], 1.0]));
            self.triangles.push(GpuTriangle {
                va,
                vb: va + 1,
                vc: va + 2,
                mesh: 0,
                order: self.triangles.len() as u32,
            });
        }

        fn bounded(&self) -> Bounded<'_> {
            Bounded { spheres: &self.spheres, triangles: &self.triangles, vertices: &self.vertices }
        }
    }

    fn sphere(c: [f32; 3], r: f32) -> GpuSphere {
        GpuSphere { center_radius: [c[0], c[1], c[2], r], material: 0, object_id: 0, power: 0.0, pad: 0 }
    }

    /// A pseudo-random scene of spheres and triangles.
    fn scene(n_spheres: usize, n_tris: usize) -> Scene {
        let mut state = 0x2545_f491_u32;
        let mut rnd = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state as f32 / u32::MAX as f32) * 20.0 - 10.0
        };
        let spheres = (0..n_spheres).map(|_| sphere([rnd(), rnd(), rnd()], 0.1 + rnd().abs() * 0.05)).collect();
        let mut out = Scene { spheres, ..Scene::default() };
        for _ in 0..n_tris {
            let a = [rnd(), rnd(), rnd()];
            let d = |a: f32, r: f32| a + r * 0.05;
            let (b, c) = ([d(a[0], rnd()), d(a[1], rnd()), a[2]], [a[0], d(a[1], rnd()), d(a[2], rnd())]);
            out.tri(a, b, c);
        }
        out
    }

    /// The binary nodes of a pseudo-random scene of about `n` primitives.
    pub(crate) fn built_tree(n: usize) -> Vec<BvhNode> {
        let sc = scene(n / 10, n - n / 10);
        build(&sc.bounded()).nodes
    }

    /// Checks the invariants; returns the number of leaves.
    fn check(bvh: &Bvh, scene: &Bounded) -> usize {
        let (spheres, triangles) = (scene.spheres, scene.triangles);
        let n = spheres.len() + triangles.len();
        assert_eq!(bvh.prims.len(), n);
        if n == 0 {
            assert!(bvh.nodes.is_empty());
            return 0;
        }
        assert!(bvh.nodes.len() <= 2 * n, "{} nodes for {n} primitives", bvh.nodes.len());
        // Every sibling pair starts at an even index (one cache line each).
        for node in bvh.nodes.iter().filter(|nd| nd.count == 0 && bvh.nodes.len() > 1) {
            assert_eq!(node.left_first % 2, 0, "a sibling pair at an odd index");
        }
        let mut seen = vec![0u32; n];
        let mut leaves = 0;
        let mut visited = vec![false; bvh.nodes.len()];
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            assert!(!visited[i], "node {i} reached twice");
            visited[i] = true;
            let node = &bvh.nodes[i];
            let b = Aabb::of_node(node);
            if node.count > 0 {
                leaves += 1;
                assert!(node.count as usize <= MAX_LEAF);
                for &r in &bvh.prims[node.left_first as usize..(node.left_first + node.count) as usize] {
                    let slot = match PrimRef::decode(r) {
                        PrimRef::Sphere(k) => k as usize,
                        PrimRef::Triangle(k) => spheres.len() + k as usize,
                    };
                    seen[slot] += 1;
                    assert!(b.contains(&scene.prim_box(r)), "leaf {i} does not contain {r}");
                }
            } else {
                for c in [node.left_first as usize, node.left_first as usize + 1] {
                    let cn = &bvh.nodes[c];
                    assert!(b.contains(&Aabb::of_node(cn)), "child {c} outside parent {i}");
                    stack.push(c);
                }
            }
        }
        // Index 1 is the unused node that aligns the pairs.
        assert!(visited.iter().enumerate().all(|(i, &v)| v || i == 1), "unreachable nodes");
        assert!(seen.iter().all(|&k| k == 1), "a primitive not in exactly one leaf");
        leaves
    }

    #[test]
    fn node_is_32_bytes_and_pod() {
        assert_eq!(size_of::<BvhNode>(), 32);
        let n = BvhNode { min: [1.0, 2.0, 3.0], left_first: 4, max: [5.0, 6.0, 7.0], count: 2 };
        assert_eq!(bytemuck::bytes_of(&n).len(), 32);
    }

    #[test]
    fn stored_nodes_read_back_and_every_sibling_pair_is_one_cache_line() {
        for count in [1, 2, 7, 1000] {
            let nodes: Vec<BvhNode> = (0..count).map(|i| BvhNode { left_first: i, ..BvhNode::default() }).collect();
            let stored = BvhNodes::new(&nodes);
            assert_eq!(stored[..], nodes[..]);
            assert_eq!(stored.as_ptr() as usize % 64, 0, "{count} nodes: pairs straddle cache lines");
            assert!(stored.ptr_eq(&stored.clone()) && !stored.ptr_eq(&BvhNodes::new(&nodes)));
        }
    }

    #[test]
    fn depth_is_the_longest_path_from_the_root_to_a_leaf() {
        let leaf = BvhNode { count: 1, ..BvhNode::default() };
        let inner = |first| BvhNode { left_first: first, count: 0, ..BvhNode::default() };
        assert_eq!(BvhNodes::new(&[]).depth(), 0);
        assert_eq!(BvhNodes::new(&[leaf]).depth(), 0);
        // Root, the unused node, a leaf and an inner node over two leaves (right side deeper).
        let tree = [inner(2), BvhNode::default(), leaf, inner(4), leaf, leaf];
        assert_eq!(BvhNodes::new(&tree).depth(), 2);
        let sc = scene(0, 5000);
        let nodes = BvhNodes::new(&build(&sc.bounded()).nodes);
        let leaves = nodes.iter().filter(|n| n.count > 0).count();
        assert!(1 << nodes.depth() >= leaves && (nodes.depth() as usize) < leaves, "depth {}", nodes.depth());
    }

    #[test]
    fn invariants_on_a_random_scene() {
        for (s, t) in [(1, 0), (0, 1), (3, 2), (20, 0), (0, 37), (50, 5000), (7, 12_000)] {
            let mut sc = scene(s, t);
            let mut bvh = build(&sc.bounded());
            check(&bvh, &sc.bounded());
            let before = sc.triangles.clone();
            reorder_triangles(&mut bvh, &mut sc.triangles);
            check(&bvh, &sc.bounded());
            let sorted = |mut v: Vec<GpuTriangle>| {
                v.sort_by_key(|t| t.order);
                v
            };
            assert_eq!(sorted(before), sorted(sc.triangles.clone()), "reordering lost or added triangles");
            let triangle_refs = bvh.prims.iter().filter_map(|&r| match PrimRef::decode(r) {
                PrimRef::Triangle(k) => Some(k),
                PrimRef::Sphere(_) => None,
            });
            assert!(triangle_refs.eq(0..t as u32), "leaves do not reference triangles in array order");
        }
    }

    #[test]
    fn empty_scene_has_no_nodes() {
        let sc = Scene::default();
        let bvh = build(&sc.bounded());
        assert!(bvh.nodes.is_empty() && bvh.prims.is_empty());
        check(&bvh, &sc.bounded());
    }

    #[test]
    fn all_primitives_at_one_point_split_at_the_median() {
        let mut sc = Scene { spheres: (0..10).map(|_| sphere([1.0, 2.0, 3.0], 0.5)).collect(), ..Scene::default() };
        for _ in 0..101 {
            sc.tri([1.0, 2.0, 3.0], [1.0, 2.0, 3.0], [1.0, 2.0, 3.0]);
        }
        let bvh = build(&sc.bounded());
        let leaves = check(&bvh, &sc.bounded());
        assert!(leaves >= 111usize.div_ceil(MAX_LEAF));
    }

    #[test]
    fn sphere_boxes_are_rounded_outward() {
        let s = sphere([0.1, 1e7, -3.3], 0.3);
        let b = sphere_box(&s);
        for k in 0..3 {
            let (c, r) = (f64::from(s.center_radius[k]), f64::from(s.center_radius[3]));
            assert!(f64::from(b.min[k]) <= c - r && f64::from(b.max[k]) >= c + r);
        }
    }

    #[test]
    fn prim_refs_round_trip() {
        for p in [PrimRef::Sphere(0), PrimRef::Sphere(77), PrimRef::Triangle(0), PrimRef::Triangle(PRIM_REF_INDEX)] {
            assert_eq!(PrimRef::decode(p.encode()), p);
        }
    }
}
