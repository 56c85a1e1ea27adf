//! EXT_mesh_gpu_instancing: a node's mesh drawn once per instance, each placed by its own
//! TRANSLATION, ROTATION and SCALE (in the node's space, before the node's world transform).
//! Glint's BVH has no instances, so each is a copy of the mesh: the count is bounded.

use ::gltf::Document;

use super::accessor::{self, Buffers};
use super::nodes::trs_matrix;
use super::triangle_count;
use glint_scene::Mat4;

pub(super) const EXTENSION: &str = "EXT_mesh_gpu_instancing";

/// The most triangles a file's instances may copy, all its nodes together (a forest of 10,000
/// trees of 10,000 triangles would need 100 million, and some 20 GB).
pub const MAX_INSTANCED_TRIANGLES: usize = 1 << 24;

/// The triangles a mesh's primitives make (what its instances copy).
fn mesh_triangles(mesh: &::gltf::Mesh<'_>) -> usize {
    mesh.primitives()
        .map(|p| {
            let n = p.indices().or_else(|| p.get(&::gltf::Semantic::Positions)).map_or(0, |a| a.count());
            triangle_count(p.mode(), n)
        })
        .sum()
}

/// The node's instance transforms, or `None` when it has no instancing. `budget`: the
/// triangles the file's instances may still copy, checked against the accessors' counts before
/// anything is read (a view-less accessor of 2^27 zeros costs the file nothing). An error
/// carries the JSON path at fault.
pub(super) fn instances(
    node: &::gltf::Node<'_>,
    document: &Document,
    buffers: &Buffers,
    budget: &mut usize,
) -> Result<Option<Vec<Mat4>>, (String, String)> {
    let Some(ext) = node.extension_value(EXTENSION) else { return Ok(None) };
    let path = format!("nodes[{}].extensions.{EXTENSION}", node.index());
    let attributes = ext.get("attributes").and_then(|a| a.as_object());
    let Some(attributes) = attributes else {
        return Err((format!("{path}.attributes"), "is missing or not an object".into()));
    };
    // Each attribute: an accessor index, read with every bound checked.
    let accessor_of = |name: &str| -> Result<Option<::gltf::Accessor<'_>>, (String, String)> {
        let Some(value) = attributes.get(name) else { return Ok(None) };
        let at = format!("{path}.attributes.{name}");
        let index = value.as_u64().ok_or_else(|| (at.clone(), format!("{value} is not an accessor index")))?;
        let count = document.accessors().len();
        let found = usize::try_from(index).ok().and_then(|i| document.accessors().nth(i));
        found.map(Some).ok_or_else(|| (at, format!("accessors[{index}] does not exist (the file has {count})")))
    };
    let [translation, rotation, scale] = ["TRANSLATION", "ROTATION", "SCALE"].map(accessor_of);
    let (translation, rotation, scale) = (translation?, rotation?, scale?);
    let counts = [&translation, &rotation, &scale].map(|a| a.as_ref().map(|a| a.count()));
    let Some(count) = counts.iter().flatten().copied().max() else {
        return Err((format!("{path}.attributes"), "names none of TRANSLATION, ROTATION and SCALE".into()));
    };
    if counts.iter().flatten().any(|&n| n != count) {
        return Err((format!("{path}.attributes"), format!("the attributes' counts differ: {counts:?}")));
    }
    let mesh = node.mesh();
    let copied = count.saturating_mul(mesh.as_ref().map_or(0, mesh_triangles));
    if copied > *budget {
        return Err((
            path.clone(),
            format!(
                "{count} instances of meshes[{}] make {copied} triangles; Glint copies each instance (its BVH has \
                 no instances) and allows {MAX_INSTANCED_TRIANGLES} in a file",
                mesh.map_or(0, |m| m.index()),
            ),
        ));
    }
    *budget -= copied;
    let at = |name: &'static str, p: String| (format!("{path}.attributes.{name}"), p);
    let translation =
        translation.map(|a| accessor::read_vec3(&a, buffers).map_err(|p| at("TRANSLATION", p))).transpose()?;
    let rotation =
        rotation.map(|a| accessor::read_rotations(&a, buffers).map_err(|p| at("ROTATION", p))).transpose()?;
    let scale = scale.map(|a| accessor::read_vec3(&a, buffers).map_err(|p| at("SCALE", p))).transpose()?;
    (0..count)
        .map(|k| {
            let t = translation.as_ref().map_or([0.0; 3], |v| v[k]);
            let r = rotation.as_ref().map_or([0.0, 0.0, 0.0, 1.0], |v| v[k]);
            let s = scale.as_ref().map_or([1.0; 3], |v| v[k]);
            let finite = t.iter().chain(&r).chain(&s).all(|c| c.is_finite());
            let m = if finite { trs_matrix(t, r, s) } else { Err("is not finite".into()) };
            m.map_err(|p| (format!("{path}: instance {k}"), p))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}
