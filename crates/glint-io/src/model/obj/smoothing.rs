//! OBJ smoothing groups (`s 1`, `s 2`, `s off`): the faces of one group share their vertices'
//! normals, and an edge between two groups, or along a face outside any, stays hard, as Blender,
//! Assimp and three.js shade them. A file without `vn` that put its faces in groups was shaded
//! faceted (its geometric normals), a classic OBJ sphere or teapot cut from glass facets.
//!
//! Each triangle corner is keyed by its vertex and its face's group (or, outside any group, its
//! own face), and a vertex used under two keys is split in two; a vertex then gets the
//! area-weighted sum of the normals of its group's faces at its position — across the meshes
//! tobj split the object into (one per material) — or its own face's normal.

use std::collections::HashMap;

use glint_scene::MeshDesc;

/// For each face statement (`f`) of OBJ text, in file order, the smoothing group it lies in:
/// the N of the `s N` in effect, 0 for none (`s off`, `s 0`, or before the first `s`).
pub(super) fn face_groups(text: &[u8]) -> Vec<u32> {
    let mut group = 0;
    let mut faces = Vec::new();
    for line in text.split(|&b| b == b'\n') {
        let mut words = line.split(u8::is_ascii_whitespace).filter(|w| !w.is_empty());
        match words.next() {
            // An `s` whose group is no number (only `off` is defined) ends the group.
            Some(b"s") => group = words.next().and_then(|w| std::str::from_utf8(w).ok()?.parse().ok()).unwrap_or(0),
            Some(b"f") => faces.push(group),
            _ => {}
        }
    }
    faces
}

/// What a vertex's normal is shared with after `split`: the faces of a smoothing group at its
/// position, or its one (flat) triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Corner {
    Group(u32),
    Flat(u32),
}

/// `mesh` with each vertex used under two keys (group, or flat triangle) split in two, its
/// texture coordinates and colours with it; `groups` gives each triangle's group (0: none).
/// Returns each vertex's key.
pub(super) fn split(mesh: &mut MeshDesc, groups: &[u32]) -> Vec<Corner> {
    let mut index: HashMap<(u32, Corner), u32> = HashMap::new();
    let (mut source, mut keys) = (Vec::new(), Vec::new());
    for (t, (triangle, &group)) in mesh.triangles.iter_mut().zip(groups).enumerate() {
        let key = if group == 0 { Corner::Flat(t as u32) } else { Corner::Group(group) };
        for v in triangle.iter_mut() {
            *v = *index.entry((*v, key)).or_insert_with(|| {
                source.push(*v as usize);
                keys.push(key);
                (source.len() - 1) as u32
            });
        }
    }
    mesh.vertices = pick(&mesh.vertices, &source);
    mesh.colours = mesh.colours.as_deref().map(|c| pick(c, &source));
    mesh.uvs = mesh.uvs.as_deref().map(|uvs| pick(uvs, &source));
    keys
}

/// Gives the meshes `to_smooth` (index into `meshes`, the keys `split` returned) their
/// smoothing groups' normals. An object's normals are shared across the meshes tobj split it
/// into (one per material), so that a change of material does not crease a smooth surface.
pub(super) fn smooth_objects(meshes: &mut [MeshDesc], to_smooth: Vec<(usize, Vec<Corner>)>) {
    // Grouped by object name once: a file of many objects is not walked once per object.
    let mut objects: HashMap<String, Vec<(usize, Vec<Corner>)>> = HashMap::new();
    for (i, keys) in to_smooth {
        objects.entry(meshes[i].name.clone()).or_default().push((i, keys));
    }
    for parts in objects.into_values() {
        let geometry: Vec<Part<'_>> = parts
            .iter()
            .map(|(i, keys)| (meshes[*i].vertices.as_slice(), meshes[*i].triangles.as_slice(), keys.as_slice()))
            .collect();
        let normals = normals(&geometry);
        for ((i, _), normals) in parts.iter().zip(normals) {
            meshes[*i].normals = normals;
        }
    }
}

/// `values` at the indices `source`, in its order.
fn pick<T: Copy>(values: &[T], source: &[usize]) -> Vec<T> {
    source.iter().map(|&i| values[i]).collect()
}

/// One mesh of an object after `split`: its vertices, triangles and the vertices' keys.
pub(super) type Part<'a> = (&'a [[f64; 3]], &'a [[u32; 3]], &'a [Corner]);

/// The vertex normals of the meshes `parts` of one object (see the module comment). `None` for
/// a part where some vertex of a triangle with area gets no usable normal (faces of one group
/// folded flat onto each other), which its faces' own normals shade instead. A vertex of
/// triangles without area alone, which are never hit, gets any unit normal.
pub(super) fn normals(parts: &[Part<'_>]) -> Vec<Option<Vec<[f64; 3]>>> {
    // Each part's face normals, |n| twice the area: the weight comes with the direction.
    let faces: Vec<Vec<[f64; 3]>> = parts
        .iter()
        .map(|(vertices, triangles, _)| triangles.iter().map(|t| area_normal(vertices, t)).collect())
        .collect();
    let mut sums: HashMap<(u32, [u64; 3]), [f64; 3]> = HashMap::new();
    for ((vertices, triangles, keys), faces) in parts.iter().zip(&faces) {
        for (t, n) in triangles.iter().zip(faces) {
            for &v in t {
                if let Corner::Group(g) = keys[v as usize] {
                    let s = sums.entry((g, key_of(&vertices[v as usize]))).or_insert([0.0; 3]);
                    *s = [s[0] + n[0], s[1] + n[1], s[2] + n[2]];
                }
            }
        }
    }
    parts
        .iter()
        .zip(&faces)
        .map(|((vertices, triangles, keys), faces)| {
            // Whether each vertex belongs to a triangle with area, whose shading reads it.
            let mut read = vec![false; vertices.len()];
            for (t, n) in triangles.iter().zip(faces) {
                if unit(*n).is_some() {
                    t.iter().for_each(|&v| read[v as usize] = true);
                }
            }
            let normal = |(v, key): (usize, &Corner)| {
                let n = match *key {
                    Corner::Group(g) => sums.get(&(g, key_of(&vertices[v]))).copied().unwrap_or([0.0; 3]),
                    Corner::Flat(t) => faces[t as usize],
                };
                unit(n).or((!read[v]).then_some([0.0, 0.0, 1.0]))
            };
            keys.iter().enumerate().map(normal).collect()
        })
        .collect()
}

/// Triangle `t`'s normal scaled by twice its area: (b − a) × (c − a).
fn area_normal(vertices: &[[f64; 3]], t: &[u32; 3]) -> [f64; 3] {
    let [a, b, c] = t.map(|i| vertices[i as usize]);
    let (e1, e2) = (sub(b, a), sub(c, a));
    [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
}

/// `n` of unit length, where it has a direction.
fn unit(n: [f64; 3]) -> Option<[f64; 3]> {
    let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (length.is_finite() && length > 0.0).then(|| n.map(|c| c / length))
}

/// A position as a hash key: its exact coordinates.
fn key_of(v: &[f64; 3]) -> [u64; 3] {
    v.map(f64::to_bits)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_take_the_smoothing_group_in_effect() {
        let text =
            b"f 1 2 3\ns 1\nf 1 2 3\n  f 2 3 4\ns off\nf 1 2 3\ns 2\nf 1 2 3\ns 0\nf 1 2 3\ns x\nf 1 2 3\n# f 1 2 3\n";
        assert_eq!(face_groups(text), [0, 1, 1, 0, 2, 0, 0]);
    }

    fn mesh(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>) -> MeshDesc {
        MeshDesc::new(vertices, triangles, "m", "o")
    }

    #[test]
    fn a_group_shares_area_weighted_normals_and_an_edge_between_groups_stays_hard() {
        // A roof: two faces meeting at the ridge (0, 1, z), the right one twice the left's
        // area, sharing the ridge's vertices 1 and 2.
        let roof = || {
            mesh(vec![[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0], [2.0, -1.0, 0.0]], vec![[0, 2, 1], [3, 1, 2]])
        };
        let mut one = roof();
        let keys = split(&mut one, &[1, 1]);
        assert_eq!(one.vertices.len(), 4, "one group: nothing split");
        let n = normals(&[(&one.vertices, &one.triangles, &keys)]).remove(0).expect("usable");
        // Left face (−1, 1, 0)/√2 of area √2/2, right (1, 1, 0)/√2 of area √2: the sum
        // (−1 + 2, 1 + 2, 0) at the ridge.
        let ridge = one.vertices.iter().position(|v| *v == [0.0, 1.0, 0.0]).expect("the ridge");
        let expected = [1.0 / 10f64.sqrt(), 3.0 / 10f64.sqrt(), 0.0];
        assert!(n[ridge].iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15), "{:?}", n[ridge]);
        // Two groups, or one face outside any: the ridge is split, each side its face's normal.
        for groups in [[1, 2], [0, 1]] {
            let mut two = roof();
            let keys = split(&mut two, &groups);
            assert_eq!(two.vertices.len(), 6, "{groups:?}: the two ridge vertices split");
            let n = normals(&[(&two.vertices, &two.triangles, &keys)]).remove(0).expect("usable");
            let h = std::f64::consts::FRAC_1_SQRT_2;
            assert!(two.triangles[0].iter().all(|&v| (n[v as usize][0] + h).abs() < 1e-15), "{groups:?}: {n:?}");
            assert!(two.triangles[1].iter().all(|&v| (n[v as usize][0] - h).abs() < 1e-15), "{groups:?}: {n:?}");
        }
    }

    #[test]
    fn meshes_of_one_object_share_a_group_and_a_vertex_of_only_degenerate_triangles_is_never_read() {
        // The roof's two faces as two meshes (two materials): the same ridge normal on both.
        let (mut left, mut right) = (
            mesh(vec![[-1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, 1.0, 0.0]], vec![[0, 1, 2]]),
            mesh(vec![[2.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0]], vec![[0, 1, 2]]),
        );
        let (kl, kr) = (split(&mut left, &[1]), split(&mut right, &[1]));
        let n = normals(&[(&left.vertices, &left.triangles, &kl), (&right.vertices, &right.triangles, &kr)]);
        let (l, r) = (n[0].as_ref().expect("left"), n[1].as_ref().expect("right"));
        assert_eq!(l[2], r[1], "the ridge's bottom corner");
        // The same two meshes of two objects are smoothed apart: each ridge its face's normal.
        let named = |m: &MeshDesc, name: &str| MeshDesc { name: name.into(), ..m.clone() };
        let mut meshes = vec![named(&left, "a"), named(&right, "a"), named(&left, "b"), named(&right, "c")];
        let keys = [&kl, &kr, &kl, &kr].map(|k| k.clone());
        smooth_objects(&mut meshes, keys.into_iter().enumerate().collect());
        let normal = |m: usize, v: usize| meshes[m].normals.as_ref().expect("smoothed")[v];
        assert_eq!((normal(0, 2), normal(1, 1)), (l[2], r[1]), "object a: as one object");
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let near = |n: [f64; 3], m: [f64; 3]| n.iter().zip(m).all(|(a, b)| (a - b).abs() < 1e-15);
        assert!(near(normal(2, 2), [-h, h, 0.0]) && near(normal(3, 1), [h, h, 0.0]), "objects b and c: apart");
        // A line of three points: no triangle with area reads its vertices.
        let mut line = mesh(vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], vec![[0, 1, 2]]);
        let keys = split(&mut line, &[1]);
        assert!(normals(&[(&line.vertices, &line.triangles, &keys)])[0].is_some());
    }
}
