//! The corners of the BVH's triangles in leaf order, for the CPU walk: a leaf's triangles are
//! then one contiguous read instead of reference → triangle → three vertices, three dependent
//! cache misses per triangle on incoherent rays, in memory advised for huge pages. The GPU walk
//! reads its own copy in leaf order (`fill_gpu_leaves`), laid out for its bindings.

use std::sync::Arc;

use rayon::prelude::*;

use crate::bvh::PrimRef;
use crate::huge_pages::HugePaged;
use glint_types::layout::GpuTriangle;

/// A triangle's three corners, as stored (f32): widened, they are the values the indexed
/// mesh gives, so hits are bit-identical.
pub type Corners = [[f32; 3]; 3];

/// Made with the geometry and shared with it (`FlatScene::rebuild`, clones). Valid only for the
/// vertex, triangle and reference arrays it was made from: a scene whose arrays were replaced
/// (the GPU's rebased copy, a test's edit) reads the indexed mesh instead (`for_scene`).
#[derive(Clone, Debug, Default)]
pub struct LeafCorners {
    /// One entry per BVH primitive reference (zeros for a sphere's).
    corners: Arc<HugePaged<Corners>>,
    vertices: Arc<[[f32; 4]]>,
    triangles: Arc<[GpuTriangle]>,
    prims: Arc<[u32]>,
}

impl LeafCorners {
    /// 36 bytes per primitive reference.
    pub const BYTES_PER_PRIM: u64 = size_of::<Corners>() as u64;

    pub fn new(vertices: &Arc<[[f32; 4]]>, triangles: &Arc<[GpuTriangle]>, prims: &Arc<[u32]>) -> Self {
        let corners = HugePaged::new(prims.len(), |out| {
            out.par_iter_mut()
                .zip(&prims[..])
                .with_min_len(16384)
                .for_each(|(out, &r)| *out = reference_corners(vertices, triangles, r))
        });
        Self {
            corners: Arc::new(corners),
            vertices: vertices.clone(),
            triangles: triangles.clone(),
            prims: prims.clone(),
        }
    }

    /// The corners by reference slot, if they were made from these arrays.
    #[inline]
    pub fn for_arrays(
        &self,
        vertices: &Arc<[[f32; 4]]>,
        triangles: &Arc<[GpuTriangle]>,
        prims: &Arc<[u32]>,
    ) -> Option<&[Corners]> {
        (Arc::ptr_eq(&self.vertices, vertices)
            && Arc::ptr_eq(&self.triangles, triangles)
            && Arc::ptr_eq(&self.prims, prims)
            && self.corners.len() == prims.len())
        .then_some(&self.corners[..])
    }

    pub fn ptr_eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.corners, &other.corners)
    }
}

/// The corners of the triangle primitive reference `r` names, as stored; zeros for a sphere's.
fn reference_corners(vertices: &[[f32; 4]], triangles: &[GpuTriangle], r: u32) -> Corners {
    match PrimRef::decode(r) {
        PrimRef::Triangle(i) => {
            let t = &triangles[i as usize];
            [t.va, t.vb, t.vc].map(|v| {
                let p = vertices[v as usize];
                [p[0], p[1], p[2]]
            })
        }
        PrimRef::Sphere(_) => [[0.0; 3]; 3],
    }
}

/// The GPU walk's words for one primitive reference (bindings.wgsl's `bvh_leaf_ab`, 32 bytes):
/// corner a's bits with the reference in w, then corner b's (w 0). A sphere's reference has
/// zeros beside it. u32 words, as `bvh_nodes`: the reference is read as an integer, never
/// through a float register.
pub type GpuLeafAb = [[u32; 4]; 2];

/// Corner c of a reference's triangle (bindings.wgsl's `bvh_leaf_c`, 16 bytes), in an array of
/// its own: 48 bytes a reference in one array would put a 4-million-triangle mesh (192 MB)
/// past the 128 MiB a storage binding holds; split, the larger half holds 4,194,304.
pub type GpuLeafC = [u32; 4];

/// Bytes the GPU's leaf words take per primitive reference.
pub const GPU_LEAF_BYTES_PER_PRIM: u64 = (size_of::<GpuLeafAb>() + size_of::<GpuLeafC>()) as u64;

/// Fills the GPU walk's leaf words, one per slot of `prims`, from the indexed mesh: the same
/// f32 corners the mesh and `LeafCorners` give, so both tracers test the same triangles.
pub fn fill_gpu_leaves(
    vertices: &[[f32; 4]],
    triangles: &[GpuTriangle],
    prims: &[u32],
    ab: &mut [GpuLeafAb],
    c: &mut [GpuLeafC],
) {
    let bits = |p: [f32; 3], w: u32| [p[0].to_bits(), p[1].to_bits(), p[2].to_bits(), w];
    ab.par_iter_mut().zip(c.par_iter_mut()).zip(prims).with_min_len(16384).for_each(|((ab, c), &r)| {
        let [pa, pb, pc] = reference_corners(vertices, triangles, r);
        (*ab, *c) = ([bits(pa, r), bits(pb, 0)], bits(pc, 0));
    });
}

/// Derived data: equal when made from equal arrays, which the scene's own fields compare.
impl PartialEq for LeafCorners {
    fn eq(&self, o: &Self) -> bool {
        self.corners == o.corners
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_types::layout::PRIM_REF_TRIANGLE;

    type Arrays = (Arc<[[f32; 4]]>, Arc<[GpuTriangle]>, Arc<[u32]>);

    fn arrays() -> Arrays {
        let vertices: Arc<[[f32; 4]]> =
            vec![[0.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 0.0, 1.0], [0.0, 0.0, 1.0, 1.0]].into();
        let triangles: Arc<[GpuTriangle]> = vec![
            GpuTriangle { va: 0, vb: 1, vc: 2, mesh: 0, order: 0 },
            GpuTriangle { va: 3, vb: 2, vc: 1, mesh: 0, order: 1 },
        ]
        .into();
        // A sphere's reference between the two triangles', the second triangle first.
        let prims: Arc<[u32]> = vec![1 | PRIM_REF_TRIANGLE, 0, PRIM_REF_TRIANGLE].into();
        (vertices, triangles, prims)
    }

    #[test]
    fn corners_follow_the_references_and_only_for_the_arrays_they_came_from() {
        let (vertices, triangles, prims) = arrays();
        let leaf = LeafCorners::new(&vertices, &triangles, &prims);
        let corners = leaf.for_arrays(&vertices, &triangles, &prims).expect("made from these arrays");
        assert_eq!(corners[0], [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]]);
        assert_eq!(corners[1], [[0.0; 3]; 3]);
        assert_eq!(corners[2], [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
        // Equal contents in other arrays (a rebased copy, an edited scene): not used.
        let (other_vertices, other_triangles, other_prims) = arrays();
        assert!(leaf.for_arrays(&other_vertices, &triangles, &prims).is_none());
        assert!(leaf.for_arrays(&vertices, &other_triangles, &prims).is_none());
        assert!(leaf.for_arrays(&vertices, &triangles, &other_prims).is_none());
    }

    #[test]
    fn gpu_leaves_hold_the_same_corners_and_the_reference_bits() {
        let (vertices, triangles, prims) = arrays();
        let corners = LeafCorners::new(&vertices, &triangles, &prims);
        let corners = corners.for_arrays(&vertices, &triangles, &prims).expect("made from these arrays");
        let (mut ab, mut c) = (vec![[[7; 4]; 2]; prims.len()], vec![[7; 4]; prims.len()]);
        fill_gpu_leaves(&vertices, &triangles, &prims, &mut ab, &mut c);
        for slot in 0..prims.len() {
            assert_eq!(ab[slot][0][3], prims[slot], "slot {slot}: the reference");
            assert_eq!([ab[slot][1][3], c[slot][3]], [0, 0], "slot {slot}: unused words");
            let gpu = [ab[slot][0], ab[slot][1], c[slot]].map(|w| [0, 1, 2].map(|k| f32::from_bits(w[k])));
            assert_eq!(gpu, corners[slot], "slot {slot}: the corners");
        }
        assert_eq!(GPU_LEAF_BYTES_PER_PRIM, 48);
    }
}
