//! OBJ smoothing groups (`s 1`, `s off`): faces in a group share their vertices' normals, as
//! Blender, Assimp and three.js shade them. A file without `vn` that puts an object's faces in
//! smoothing groups was shaded faceted (its geometric normals), a classic OBJ sphere or teapot
//! looking cut from glass facets. Such an object gets vertex normals: at each position, the
//! area-weighted sum of the normals of the faces around it.

use std::collections::HashMap;

/// For each face statement (`f`) of OBJ text, in file order, whether it lies in a smoothing
/// group (`s N` with N ≠ 0; `s off` and `s 0` end one; none before the first `s`).
pub(super) fn smooth_faces(text: &[u8]) -> Vec<bool> {
    let mut smooth = false;
    let mut faces = Vec::new();
    for line in text.split(|&b| b == b'\n') {
        let mut words = line.split(u8::is_ascii_whitespace).filter(|w| !w.is_empty());
        match words.next() {
            Some(b"s") => smooth = !matches!(words.next(), None | Some(b"off" | b"0")),
            Some(b"f") => faces.push(smooth),
            _ => {}
        }
    }
    faces
}

/// One mesh of an object: its vertices and triangles.
pub(super) type Part<'a> = (&'a [[f64; 3]], &'a [[u32; 3]]);

/// Vertex normals for the meshes `parts` of one object: at each position
/// (vertices at the same coordinates share one, across the parts too, so that neither a texture
/// seam nor a change of material creases the surface), the sum of the normals of its triangles
/// weighted by their areas, normalised. `None` for a part where some position gets no usable
/// normal (only degenerate triangles around it, or faces folded flat onto each other), which
/// its faces' own normals shade instead.
pub(super) fn smooth_normals(parts: &[Part<'_>]) -> Vec<Option<Vec<[f64; 3]>>> {
    let key = |v: &[f64; 3]| v.map(f64::to_bits);
    let mut sums: HashMap<[u64; 3], [f64; 3]> = HashMap::new();
    for (vertices, triangles) in parts {
        for t in *triangles {
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            let (e1, e2) = (sub(b, a), sub(c, a));
            // |e1 × e2| is twice the area: the weight comes with the direction.
            let n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
            for v in [a, b, c] {
                let s = sums.entry(key(&v)).or_insert([0.0; 3]);
                *s = [s[0] + n[0], s[1] + n[1], s[2] + n[2]];
            }
        }
    }
    let normal = |v: &[f64; 3]| {
        let n = sums.get(&key(v)).copied().unwrap_or([0.0; 3]);
        let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        (length.is_finite() && length > 0.0).then(|| n.map(|c| c / length))
    };
    parts.iter().map(|(vertices, _)| vertices.iter().map(normal).collect()).collect()
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_take_the_smoothing_group_in_effect() {
        let text = b"f 1 2 3\ns 1\nf 1 2 3\n  f 2 3 4\ns off\nf 1 2 3\ns 2\nf 1 2 3\ns 0\nf 1 2 3\n# f 1 2 3\n";
        assert_eq!(smooth_faces(text), [false, true, true, false, true, false]);
    }

    #[test]
    fn a_vertex_normal_is_the_area_weighted_mean_of_its_faces_and_seams_share_it() {
        // Two faces of a roof meeting at the ridge (0, 1, z), one twice the other's area; the
        // ridge is written twice (a texture seam), each copy with one face.
        let v =
            [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 1.0], [2.0, -1.0, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 2.0]];
        let t = [[0, 2, 1], [3, 4, 5]];
        let n = smooth_normals(&[(&v, &t)]).remove(0).expect("usable");
        // Left face normal (−1, 1, 0)/√2 with area √2/2; right face (1, 1, 0)/√2 with area 2√2:
        // the sum (−1 + 4, 1 + 4, 0) at the ridge's bottom corner, shared by both copies.
        assert_eq!(n[1], n[4]);
        let expected = [3.0 / 34f64.sqrt(), 5.0 / 34f64.sqrt(), 0.0];
        assert!(n[1].iter().zip(expected).all(|(a, b)| (a - b).abs() < 1e-15), "{:?}", n[1]);
        // A position whose only triangle is degenerate has no normal: none are made.
        let line = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert!(smooth_normals(&[(&line, &[[0, 1, 2]])]).remove(0).is_none());
    }
}
