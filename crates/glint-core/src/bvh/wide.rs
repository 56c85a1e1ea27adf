//! The CPU walk's form of the hierarchy: the binary tree collapsed into nodes of up to
//! `WIDTH` (8) children whose boxes are stored axis by axis, so that one step tests eight boxes
//! with the same arithmetic lane by lane (vectorised) and a ray takes a third of the dependent
//! steps. Eight, not four: incoherent rays 4.27, 4.30, 4.16 -> 5.05, 4.84, 4.70 Mrays/s on
//! `bumpy` (2 threads), primary within noise, 26 bytes a triangle instead of 20. The
//! boxes and leaves are the binary tree's own, so the walk reaches the same leaves as the binary
//! one could: only the order of steps changes, and the hit never depends on it (`cpu::bvh`).
//! The GPU walks the binary nodes (`BvhNodes`), which this is made from.

use bytemuck::{Pod, Zeroable};
use rayon::prelude::*;

use crate::huge_pages::HugePaged;
use glint_types::layout::BvhNode;

/// Children of a wide node.
pub const WIDTH: usize = 8;

/// Up to `WIDTH` children: their boxes (rows min x, y, z, max x, y, z; a column per child), and
/// per child either a leaf (`count` > 0 references from `first`) or a wide node (`count` 0,
/// index `first`). An unused column has an empty box (min +∞, max −∞), which no ray enters.
/// Whole cache lines, aligned to them.
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
#[repr(C, align(64))]
pub struct WideNode {
    pub bounds: [[f32; WIDTH]; 6],
    pub first: [u32; WIDTH],
    pub count: [u32; WIDTH],
}

const _: () = assert!(size_of::<WideNode>() == 32 * WIDTH);

impl WideNode {
    const EMPTY: Self = Self {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        first: [0; WIDTH],
        count: [0; WIDTH],
    };

    /// A node over the boxes of `children` (at most `WIDTH`), with `first` and `count` as a
    /// binary node's: the count of a leaf, 0 (and an index to be set) for an interior node.
    pub fn over(children: &[BvhNode]) -> Self {
        let mut wide = Self::EMPTY;
        for (lane, c) in children.iter().enumerate() {
            for k in 0..3 {
                wide.bounds[k][lane] = c.min[k];
                wide.bounds[k + 3][lane] = c.max[k];
            }
            (wide.first[lane], wide.count[lane]) = (c.left_first, c.count);
        }
        wide
    }

    /// The box of child `lane` as a binary node's (min, max).
    pub fn child_box(&self, lane: usize) -> ([f32; 3], [f32; 3]) {
        (std::array::from_fn(|k| self.bounds[k][lane]), std::array::from_fn(|k| self.bounds[k + 3][lane]))
    }

    /// Whether column `lane` holds a child.
    pub fn used(&self, lane: usize) -> bool {
        self.bounds[0][lane] <= self.bounds[3][lane]
    }
}

/// The binary tree `nodes` (root first) collapsed: each wide node takes the place of a binary
/// interior node and adopts, instead of its two children, the children of the child with the
/// largest surface area while that keeps it within `WIDTH` (a large box is the one rays most
/// often enter, so it is the step most worth saving). A root that is a leaf becomes a wide node
/// holding that leaf. None for an empty tree. Children that are wide nodes are numbered in the
/// order they are made, depth first, so a subtree's nodes are neighbours in memory. The root's
/// subtrees are collapsed in parallel, each into an array of its own, and appended in order.
pub fn collapse(nodes: &[BvhNode]) -> HugePaged<WideNode> {
    let Some(root) = nodes.first() else { return HugePaged::default() };
    let children = if root.count > 0 { Children::one(*root) } else { adopted(nodes, root) };
    let subtrees: Vec<Vec<WideNode>> = children
        .as_slice()
        .par_iter()
        .filter(|c| c.count == 0)
        .map(|c| {
            let mut out = vec![WideNode::EMPTY];
            fill(nodes, &adopted(nodes, c), 0, &mut out);
            out
        })
        .collect();
    let mut top = WideNode::over(children.as_slice());
    let mut at = 1;
    let inner = (0..children.len).filter(|&lane| children.nodes[lane].count == 0);
    for (lane, subtree) in inner.zip(&subtrees) {
        top.first[lane] = at as u32;
        at += subtree.len();
    }
    HugePaged::new(at, |out| {
        out[0] = top;
        let mut start = 1;
        for subtree in &subtrees {
            let shift = start as u32;
            for (slot, node) in out[start..start + subtree.len()].iter_mut().zip(subtree) {
                *slot = *node;
                for lane in (0..WIDTH).filter(|&l| node.used(l) && node.count[l] == 0) {
                    slot.first[lane] += shift;
                }
            }
            start += subtree.len();
        }
    })
}

/// Up to `WIDTH` binary nodes, the children of a wide node (an array, not a `Vec`: one is made
/// per wide node).
struct Children {
    nodes: [BvhNode; WIDTH],
    len: usize,
}

impl Children {
    fn one(node: BvhNode) -> Self {
        let mut nodes = [BvhNode::default(); WIDTH];
        nodes[0] = node;
        Self { nodes, len: 1 }
    }

    fn as_slice(&self) -> &[BvhNode] {
        &self.nodes[..self.len]
    }
}

/// The binary nodes a wide node over interior node `node` holds.
fn adopted(nodes: &[BvhNode], node: &BvhNode) -> Children {
    let pair = |n: &BvhNode| [nodes[n.left_first as usize], nodes[n.left_first as usize + 1]];
    let mut children = Children { nodes: [BvhNode::default(); WIDTH], len: 2 };
    [children.nodes[0], children.nodes[1]] = pair(node);
    while children.len < WIDTH {
        let widest = children
            .as_slice()
            .iter()
            .enumerate()
            .filter(|(_, c)| c.count == 0)
            .max_by(|(_, a), (_, b)| half_area(a).total_cmp(&half_area(b)));
        let Some((i, _)) = widest else { break };
        let [left, right] = pair(&children.nodes[i]);
        children.nodes.copy_within(i + 1..children.len, i + 2);
        (children.nodes[i], children.nodes[i + 1]) = (left, right);
        children.len += 1;
    }
    children
}

fn half_area(n: &BvhNode) -> f64 {
    let d: [f64; 3] = std::array::from_fn(|k| f64::from(n.max[k]) - f64::from(n.min[k]));
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// Writes wide node `at` over `children`, then the wide nodes of its interior children.
fn fill(nodes: &[BvhNode], children: &Children, at: usize, out: &mut Vec<WideNode>) {
    let mut wide = WideNode::over(children.as_slice());
    let mut inner = [(0, BvhNode::default()); WIDTH];
    let mut n_inner = 0;
    for (lane, c) in children.as_slice().iter().enumerate() {
        if c.count == 0 {
            wide.first[lane] = out.len() as u32;
            out.push(WideNode::EMPTY);
            inner[n_inner] = (out.len() - 1, *c);
            n_inner += 1;
        }
    }
    out[at] = wide;
    for (index, c) in &inner[..n_inner] {
        fill(nodes, &adopted(nodes, c), *index, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every binary leaf is a column of exactly one wide node with its box and range, every
    /// column's box lies inside the box of the column pointing at its node, every wide node but
    /// the root is pointed at once, and no wide node has fewer than two used columns unless the
    /// tree is one leaf.
    #[test]
    fn collapse_keeps_every_leaf_and_box() {
        for n in [1usize, 2, 5, 37, 1000, 20_000] {
            let tree = crate::bvh::tests::built_tree(n);
            let wide = collapse(&tree);
            let mut leaves: Vec<(u32, u32, [f32; 3], [f32; 3])> =
                tree.iter().filter(|l| l.count > 0).map(|l| (l.left_first, l.count, l.min, l.max)).collect();
            let mut found = Vec::new();
            let mut pointed = vec![0; wide.len()];
            let mut stack = vec![(0usize, None::<([f32; 3], [f32; 3])>)];
            while let Some((i, parent)) = stack.pop() {
                let w = &wide[i];
                let used = (0..WIDTH).filter(|&l| w.used(l)).count();
                assert!(used >= 2 || (tree.len() == 1 && used == 1), "{n}: node {i} has {used} children");
                for lane in (0..WIDTH).filter(|&l| w.used(l)) {
                    let (min, max) = w.child_box(lane);
                    if let Some((pmin, pmax)) = parent {
                        assert!(
                            (0..3).all(|k| pmin[k] <= min[k] && max[k] <= pmax[k]),
                            "{n}: a box outside its parent"
                        );
                    }
                    if w.count[lane] > 0 {
                        found.push((w.first[lane], w.count[lane], min, max));
                    } else {
                        pointed[w.first[lane] as usize] += 1;
                        stack.push((w.first[lane] as usize, Some((min, max))));
                    }
                }
            }
            assert!(pointed[0] == 0 && pointed[1..].iter().all(|&p| p == 1), "{n}: wide nodes not a tree");
            let key = |l: &(u32, u32, [f32; 3], [f32; 3])| l.0;
            leaves.sort_by_key(key);
            found.sort_by_key(key);
            assert_eq!(leaves, found, "{n}: leaves lost, added or changed");
            // Each wide node stands for at least one binary interior node (the count includes
            // the unused node after the root).
            let binary_inner = tree.iter().filter(|l| l.count == 0).count();
            assert!(wide.len() <= binary_inner.max(1), "{n}: {} wide nodes for {binary_inner} binary ones", wide.len());
        }
    }

    #[test]
    fn no_tree_no_wide_nodes() {
        assert!(collapse(&[]).is_empty());
    }
}
