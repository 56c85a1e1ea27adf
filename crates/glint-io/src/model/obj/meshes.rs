//! The faces tobj read, made the model's meshes: polygons cut into triangles, normals kept or
//! made from smoothing groups, texture coordinates and vertex colours carried over.

use super::mtl::{DEFAULT_MATERIAL, default_material};
use super::{polygon, smoothing};
use glint_scene::{FieldIssue, MeshDesc, Model, usable_direction};

/// One mesh per tobj model with triangles pushed onto `out.meshes`, its material the one of
/// `names` (the MTL materials' scene names) tobj gave it, else the default. `bytes`: the text
/// tobj parsed, whose face statements carry the smoothing groups.
pub(super) fn add_meshes(models: &[tobj::Model], bytes: &[u8], names: &[String], out: &mut Model) {
    // Smoothing groups are per face statement; tobj's meshes hold the faces in file order.
    let groups = smoothing::face_groups(bytes);
    let arities: Vec<Vec<usize>> = models.iter().map(|m| face_arities(&m.mesh)).collect();
    let aligned = arities.iter().map(Vec::len).sum::<usize>() == groups.len();
    let (mut first_face, mut to_smooth) = (0, Vec::new());
    for (model, arities) in models.iter().zip(&arities) {
        let in_groups = aligned.then(|| &groups[first_face..first_face + arities.len()]);
        first_face += arities.len();
        let mesh = &model.mesh;
        let vertices: Vec<[f64; 3]> = mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
        // tobj refuses face indices beyond the file's vertices, and validation checks again.
        let (triangles, face_of) = triangles(&vertices, mesh, arities, &model.name, &mut out.warnings);
        if triangles.is_empty() {
            continue;
        }
        let mut normals: Option<Vec<[f64; 3]>> = (mesh.normals.len() == mesh.positions.len())
            .then(|| mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]).collect());
        // A zero or non-finite normal cannot shade: the whole object is shaded faceted.
        let zero_normals = normals.as_ref().is_some_and(|ns| ns.iter().any(|n| !usable_direction(*n)));
        if zero_normals {
            normals = None;
        }
        // Each triangle's smoothing group, where the file gives no (usable) normals but groups.
        let smoothing: Option<Vec<u32>> = in_groups
            .filter(|groups| normals.is_none() && groups.iter().any(|&g| g != 0))
            .map(|groups| face_of.iter().map(|&f| groups[f]).collect());
        if zero_normals {
            let instead = if smoothing.is_some() {
                "normals made from its smoothing groups"
            } else {
                "its faces' geometric normals"
            };
            out.warnings.push(FieldIssue {
                field: format!("object `{}`", model.name),
                problem: format!("has zero-length normals; shaded with {instead}"),
            });
        }
        // OBJ's v grows upwards from the image's bottom row; glTF's (and Glint's) downwards
        // from the top row.
        let uvs = (mesh.texcoords.len() / 2 == vertices.len() && !mesh.texcoords.is_empty())
            .then(|| mesh.texcoords.chunks_exact(2).map(|t| [t[0], 1.0 - t[1]]).collect::<Vec<_>>());
        // As the file wrote them, linear as its Kd (multiplied by it).
        let colours = (!mesh.vertex_color.is_empty() && mesh.vertex_color.len() == mesh.positions.len())
            .then(|| mesh.vertex_color.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect::<Vec<_>>());
        let material = match mesh.material_id.and_then(|i| names.get(i)) {
            Some(name) => name.clone(),
            None => {
                out.materials.entry(DEFAULT_MATERIAL.into()).or_insert_with(default_material);
                DEFAULT_MATERIAL.into()
            }
        };
        let textured =
            out.materials.get(&material).is_some_and(|m| m.texture.is_some() || m.emission_texture.is_some());
        if textured && uvs.is_none() {
            let which =
                if mesh.texcoords.is_empty() { "none of its faces give" } else { "only some of its faces give" };
            out.warnings.push(FieldIssue {
                field: format!("object `{}`", model.name),
                problem: format!(
                    "its material `{material}` is textured but {which} texture coordinates (`vt`): planar ones are used"
                ),
            });
        }
        let mut desc = MeshDesc { vertices, triangles, normals, uvs, colours, material, name: model.name.clone() };
        if let Some(groups) = smoothing {
            to_smooth.push((out.meshes.len(), smoothing::split(&mut desc, &groups)));
        }
        out.meshes.push(desc);
    }
    smoothing::smooth_objects(&mut out.meshes, to_smooth);
}

/// How many vertices each face statement tobj read into `mesh` has.
fn face_arities(mesh: &tobj::Mesh) -> Vec<usize> {
    // tobj lists no arities when every face is a triangle.
    if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.iter().map(|&n| n as usize).collect()
    }
}

/// The mesh's faces (of `arities` vertices) as triangles: polygons cut by
/// `polygon::triangulate`, points and lines left out; and for each triangle, the face (of the
/// mesh's, in order) it was cut from. A polygon whose edges cross is warned once per object.
fn triangles(
    vertices: &[[f64; 3]],
    mesh: &tobj::Mesh,
    arities: &[usize],
    object: &str,
    warnings: &mut Vec<FieldIssue>,
) -> (Vec<[u32; 3]>, Vec<usize>) {
    let mut out = Vec::with_capacity(mesh.indices.len() / 3);
    let mut face_of = Vec::with_capacity(mesh.indices.len() / 3);
    let (mut start, mut crossing) = (0, Vec::new());
    for (face, &n) in arities.iter().enumerate() {
        let polygon = &mesh.indices[start..start + n];
        start += n;
        if n >= 3 && polygon::triangulate(vertices, polygon, &mut out) == polygon::Cut::SelfIntersecting {
            crossing.push((face, n));
        }
        face_of.resize(out.len(), face);
    }
    if let Some((face, n)) = crossing.first() {
        let more = match crossing.len() {
            1 => String::new(),
            2 => " (and 1 more face)".to_string(),
            k => format!(" (and {} more faces)", k - 1),
        };
        // Its triangles may overlap where its edges cross: the z-fighting warning that names
        // them then told the user to "move one apart or remove the duplicate" of triangles the
        // file never held (a tester's bow-tie quad).
        warnings.push(FieldIssue {
            field: format!("object `{object}`"),
            problem: format!(
                "face {face} (of {n} vertices) crosses itself{more}; cut into the triangles its outline allows, \
                 which may overlap where its edges cross (a z-fighting warning naming its triangles is this \
                 face's): redraw the face in a modelling tool"
            ),
        });
    }
    (out, face_of)
}
