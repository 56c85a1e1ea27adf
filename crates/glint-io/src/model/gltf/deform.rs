//! A primitive's shape as the scene stands: morph targets blended by the node's (else the
//! mesh's) default weights, and skins posed by their joints' current node transforms (glTF 2.0
//! §3.7.3, §3.7.4). Animations are not played: a file's still pose is what it shows without
//! them, as three.js, Blender and Assimp show it.

use ::gltf::Primitive;
use glint_scene::Mat4;

use super::accessor::{self, Buffers};

/// How a primitive's vertices reach world space.
#[derive(Clone, Debug)]
pub(super) enum Placement {
    /// One matrix: the node's world transform.
    Rigid(Mat4),
    /// A skin: per joint, the joint node's world transform times its inverse bind matrix. The
    /// skinned node's own transform is ignored, as the specification requires.
    Skinned(Vec<Mat4>),
}

/// The joint matrices of `skin`, from each joint node's world transform (`world[node]`, `None`
/// for a node outside the rendered scene) and the skin's inverse bind matrices (identity
/// where it has none). An error carries the JSON path at fault.
pub(super) fn joint_matrices(
    skin: &::gltf::Skin<'_>,
    world: &[Option<Mat4>],
    buffers: &Buffers,
) -> Result<Vec<Mat4>, (String, String)> {
    let path = format!("skins[{}]", skin.index());
    let inverse_bind = match skin.inverse_bind_matrices() {
        Some(acc) => accessor::read_mat4(&acc, buffers).map_err(|p| (format!("{path}.inverseBindMatrices"), p))?,
        None => vec![Mat4::IDENTITY; skin.joints().len()],
    };
    if inverse_bind.len() < skin.joints().len() {
        return Err((
            format!("{path}.inverseBindMatrices"),
            format!("has {} matrices for {} joints", inverse_bind.len(), skin.joints().len()),
        ));
    }
    skin.joints()
        .zip(inverse_bind)
        .enumerate()
        .map(|(j, (joint, ibm))| match world[joint.index()] {
            Some(w) => Ok(w.mul(&ibm)),
            None => Err((
                format!("{path}.joints[{j}]"),
                format!("node {} is not in the rendered scene, so it cannot pose the skin", joint.index()),
            )),
        })
        .collect()
}

/// Adds the morph targets' POSITION (and NORMAL) displacements times `weights` to the
/// primitive's own; a target without an attribute leaves it as it is.
pub(super) fn morph(
    primitive: &Primitive<'_>,
    weights: &[f64],
    positions: &mut [[f64; 3]],
    normals: Option<&mut Vec<[f64; 3]>>,
    buffers: &Buffers,
    path: &str,
) -> Result<(), (String, String)> {
    let mut normals = normals;
    for (t, target) in primitive.morph_targets().enumerate() {
        let w = weights.get(t).copied().unwrap_or(0.0);
        if w == 0.0 {
            continue;
        }
        let attribute = |name: &str| format!("{path}.targets[{t}].{name}");
        let add = |acc: Option<::gltf::Accessor<'_>>, name: &str, into: &mut [[f64; 3]]| {
            let Some(acc) = acc else { return Ok(()) };
            let deltas = accessor::read_vec3(&acc, buffers).map_err(|p| (attribute(name), p))?;
            if deltas.len() != into.len() {
                return Err((attribute(name), format!("has {} elements, POSITION {}", deltas.len(), into.len())));
            }
            for (v, d) in into.iter_mut().zip(deltas) {
                for k in 0..3 {
                    v[k] += w * d[k];
                }
            }
            Ok(())
        };
        add(target.positions(), "POSITION", positions)?;
        if let Some(n) = normals.as_deref_mut() {
            add(target.normals(), "NORMAL", n)?;
        }
    }
    Ok(())
}

/// A JOINTS_n / WEIGHTS_n pair: each vertex's four joint indices and their weights.
type InfluenceSet = (Vec<[u32; 4]>, Vec<[f64; 4]>);

/// Each vertex's matrix: one for a rigid primitive (not a copy per vertex), else one a vertex.
#[derive(Clone, Debug)]
pub(super) enum VertexMatrices {
    Rigid { matrix: Mat4, count: usize },
    Blended(Vec<Mat4>),
}

#[cfg(test)]
impl VertexMatrices {
    fn len(&self) -> usize {
        match self {
            Self::Rigid { count, .. } => *count,
            Self::Blended(matrices) => matrices.len(),
        }
    }
}

impl std::ops::Index<usize> for VertexMatrices {
    type Output = Mat4;

    fn index(&self, vertex: usize) -> &Mat4 {
        match self {
            Self::Rigid { matrix, count } => {
                assert!(vertex < *count, "vertex {vertex} of {count}");
                matrix
            }
            Self::Blended(matrices) => &matrices[vertex],
        }
    }
}

/// Each vertex's matrix under `placement`: the rigid one, or the joints' matrices blended by
/// the vertex's JOINTS_n and WEIGHTS_n (every set the primitive has). The weights are divided by
/// their sum, as three.js does, so that one that does not quite sum to 1 (or a fifth influence
/// in a second set) cannot pull the vertex toward the origin; a vertex with no weight follows
/// its first joint.
pub(super) fn vertex_matrices(
    primitive: &Primitive<'_>,
    placement: &Placement,
    count: usize,
    buffers: &Buffers,
    path: &str,
) -> Result<VertexMatrices, (String, String)> {
    let joints = match placement {
        Placement::Rigid(m) => return Ok(VertexMatrices::Rigid { matrix: *m, count }),
        Placement::Skinned(joints) => joints,
    };
    let attribute = |name: &str| format!("{path}.attributes.{name}");
    let mut sets: Vec<InfluenceSet> = Vec::new();
    for set in 0.. {
        let (jname, wname) = (format!("JOINTS_{set}"), format!("WEIGHTS_{set}"));
        let (Some(j), Some(w)) =
            (primitive.get(&::gltf::Semantic::Joints(set)), primitive.get(&::gltf::Semantic::Weights(set)))
        else {
            if set == 0 {
                return Err((attribute("JOINTS_0"), "a skinned primitive needs JOINTS_0 and WEIGHTS_0".into()));
            }
            break;
        };
        let indices = accessor::read_joints(&j, buffers).map_err(|p| (attribute(&jname), p))?;
        let weights = accessor::read_weights(&w, buffers).map_err(|p| (attribute(&wname), p))?;
        for (name, len) in [(&jname, indices.len()), (&wname, weights.len())] {
            if len != count {
                return Err((attribute(name), format!("has {len} elements, POSITION {count}")));
            }
        }
        sets.push((indices, weights));
    }
    let blended = (0..count)
        .map(|v| {
            let influences = || sets.iter().flat_map(|(js, ws)| js[v].into_iter().zip(ws[v]));
            let total: f64 = influences().map(|(_, w)| w).sum();
            let mut blended = Mat4([[0.0; 4]; 4]);
            let mut add = |j: u32, w: f64| {
                let m = joints.get(j as usize).ok_or_else(|| {
                    (
                        attribute("JOINTS_n"),
                        format!("element {v} names joint {j}; the skin has {} joints", joints.len()),
                    )
                })?;
                for (column, joint_column) in blended.0.iter_mut().zip(&m.0) {
                    for (c, jc) in column.iter_mut().zip(joint_column) {
                        *c += w * jc;
                    }
                }
                Ok::<(), (String, String)>(())
            };
            if total > 0.0 && total.is_finite() {
                for (j, w) in influences().filter(|&(_, w)| w != 0.0) {
                    add(j, w / total)?;
                }
            } else {
                add(sets[0].0[v][0], 1.0)?;
            }
            Ok(blended)
        })
        .collect::<Result<Vec<_>, (String, String)>>()?;
    Ok(VertexMatrices::Blended(blended))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rigid_placement_gives_every_vertex_its_matrix() {
        let json = br#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{}}]}]}"#;
        let gltf = ::gltf::Gltf::from_slice_without_validation(json).unwrap();
        let primitive = gltf.meshes().next().unwrap().primitives().next().unwrap();
        let mut m = Mat4::IDENTITY;
        m.0[3] = [1.0, 2.0, 3.0, 1.0];
        let matrices = vertex_matrices(&primitive, &Placement::Rigid(m), 2, &Buffers::default(), "p").unwrap();
        assert_eq!(matrices.len(), 2);
        assert_eq!(matrices[1].point([0.0; 3]), [1.0, 2.0, 3.0]);
    }
}
