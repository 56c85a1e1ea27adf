//! A node's local transform, from the numbers its JSON wrote (f64: the gltf crate keeps them in
//! f32), and every node's world transform.

use glint_scene::Mat4;

/// A node's transform numbers as the JSON wrote them, in f64: what the gltf crate keeps only
/// in f32. A geo-referenced file puts its offset in a node (an ECEF 4.8e6, where f32's step is
/// 0.5), and glTF's JSON numbers are doubles, as three.js and CesiumJS read them.
#[derive(Clone, Debug, Default, serde::Deserialize)]
pub(super) struct NodeNumbers {
    pub matrix: Option<[f64; 16]>,
    pub translation: Option<[f64; 3]>,
    pub rotation: Option<[f64; 4]>,
    pub scale: Option<[f64; 3]>,
}

/// Every node's `NodeNumbers`, in the file's order (of a .glb, its JSON chunk's); empty where
/// the nodes do not read as numbers, which the gltf crate then refuses or reads in f32.
pub(super) fn node_numbers(bytes: &[u8]) -> Vec<NodeNumbers> {
    #[derive(serde::Deserialize)]
    struct Nodes {
        #[serde(default)]
        nodes: Vec<NodeNumbers>,
    }
    json_text(bytes).and_then(|json| serde_json::from_slice::<Nodes>(&json).ok()).map_or_else(Vec::new, |n| n.nodes)
}

/// The file's JSON: the whole file, or a .glb's JSON chunk (`None` where that does not read).
pub(super) fn json_text(bytes: &[u8]) -> Option<std::borrow::Cow<'_, [u8]>> {
    if bytes.starts_with(b"glTF") {
        ::gltf::Glb::from_slice(bytes).ok().map(|glb| std::borrow::Cow::Owned(glb.json.into_owned()))
    } else {
        Some(std::borrow::Cow::Borrowed(bytes))
    }
}

/// A node's local transform: its matrix, or T·R·S from translation, rotation (a unit
/// quaternion x, y, z, w; normalised here, as glTF requires it to be unit already) and scale;
/// each as the JSON wrote it (`numbers`, by node), else as the gltf crate read it.
pub(super) fn node_matrix(node: &::gltf::Node<'_>, numbers: &[NodeNumbers]) -> Result<Mat4, String> {
    local_matrix(node.transform(), numbers.get(node.index()))
}

/// `transform` (as the gltf crate read it, in f32) with the numbers `written` in the JSON where
/// it gives them.
fn local_matrix(transform: ::gltf::scene::Transform, written: Option<&NodeNumbers>) -> Result<Mat4, String> {
    match transform {
        ::gltf::scene::Transform::Matrix { matrix } => Ok(match written.and_then(|n| n.matrix) {
            Some(m) => Mat4(std::array::from_fn(|c| std::array::from_fn(|r| m[4 * c + r]))),
            None => Mat4(matrix.map(|c| c.map(f64::from))),
        }),
        ::gltf::scene::Transform::Decomposed { translation, rotation, scale } => {
            let rotation = written.and_then(|n| n.rotation).unwrap_or(rotation.map(f64::from));
            // Held to unit length as a scene file's quaternion is: [0, 0, 2, 0] was normalised
            // without a word, where the scene format refuses it (a tester).
            if let Some(len) = glint_scene::not_unit_quaternion(rotation) {
                return Err(format!(
                    "rotation {rotation:?} is not a unit quaternion: its length is {}, and glTF asks for 1 (within \
                     1e-3 it is read)",
                    glint_scene::format_number(len)
                ));
            }
            trs_matrix(
                written.and_then(|n| n.translation).unwrap_or(translation.map(f64::from)),
                rotation,
                written.and_then(|n| n.scale).unwrap_or(scale.map(f64::from)),
            )
        }
    }
}

/// The last row of `m` where it is not (0, 0, 0, 1): a projective matrix, which glTF does not
/// allow (a node's matrix must decompose into translation, rotation and scale) and which the
/// tracers, transforming points affinely, read without that row.
pub(super) fn projective_row(m: &Mat4) -> Option<[f64; 4]> {
    let row = [m.0[0][3], m.0[1][3], m.0[2][3], m.0[3][3]];
    (row != [0.0, 0.0, 0.0, 1.0]).then_some(row)
}

/// T · R · S, R from the quaternion (x, y, z, w), which must have a usable length.
pub(super) fn trs_matrix(translation: [f64; 3], rotation: [f64; 4], scale: [f64; 3]) -> Result<Mat4, String> {
    let len = rotation.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !(len.is_finite() && len > 1e-12) {
        return Err(format!("rotation {rotation:?} is not a unit quaternion"));
    }
    let mut m = Mat4::from_quaternion(rotation);
    // Columns of R scaled by S, then the translation.
    for (column, s) in m.0.iter_mut().zip(scale) {
        for c in column.iter_mut().take(3) {
            *c *= s;
        }
    }
    m.0[3] = [translation[0], translation[1], translation[2], 1.0];
    Ok(m)
}

/// Every node's world transform in `scene` (`None` for a node outside it); a node reached twice
/// keeps its first (the walk in `load_gltf` refuses such a file).
pub(super) fn world_transforms(scene: &::gltf::Scene<'_>, nodes: usize, numbers: &[NodeNumbers]) -> Vec<Option<Mat4>> {
    let mut world = vec![None; nodes];
    let mut stack: Vec<(::gltf::Node<'_>, Mat4)> = scene.nodes().map(|n| (n, Mat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        let Ok(local) = node_matrix(&node, numbers) else { continue };
        if world[node.index()].is_some() {
            continue;
        }
        let w = parent.mul(&local);
        world[node.index()] = Some(w);
        stack.extend(node.children().map(|c| (c, w)));
    }
    world
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn trs_rotates_scales_then_translates() {
        let h = std::f32::consts::FRAC_1_SQRT_2;
        // 90° about +y: +x goes to −z.
        let m = local_matrix(
            ::gltf::scene::Transform::Decomposed {
                translation: [1.0, 2.0, 3.0],
                rotation: [0.0, h, 0.0, h],
                scale: [2.0, 1.0, 1.0],
            },
            None,
        )
        .unwrap();
        assert!(close(m.point([1.0, 0.0, 0.0]), [1.0, 2.0, 1.0]), "{:?}", m.point([1.0, 0.0, 0.0]));
        assert!(m.determinant3() > 0.0);
    }

    #[test]
    fn node_transforms_are_read_as_the_json_wrote_them_not_in_f32() {
        // An ECEF point (f32's step there is 0.5), as a translation and as a matrix.
        let ecef = [4_201_234.56, 4_779_855.21, 171_653.09];
        let json = format!(
            r#"{{"asset":{{"version":"2.0"}},"nodes":[{{"translation":{ecef:?}}},{{"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,{},{},{},1]}},{{}}]}}"#,
            ecef[0], ecef[1], ecef[2]
        );
        let numbers = node_numbers(json.as_bytes());
        let f32_read = ::gltf::scene::Transform::Decomposed {
            translation: ecef.map(|c| c as f32),
            rotation: [0.0, 0.0, 0.0, 1.0],
            scale: [1.0; 3],
        };
        assert_eq!(local_matrix(f32_read.clone(), numbers.first()).unwrap().point([0.0; 3]), ecef);
        assert_ne!(local_matrix(f32_read, None).unwrap().point([0.0; 3]), ecef, "f32 would round it");
        let m = ::gltf::scene::Transform::Matrix { matrix: Mat4::IDENTITY.0.map(|c| c.map(|x| x as f32)) };
        assert_eq!(local_matrix(m, numbers.get(1)).unwrap().point([0.0; 3]), ecef);
        assert!(numbers[2].translation.is_none() && numbers.len() == 3);
        // A GLB's JSON chunk is read the same way.
        let mut chunk = json.into_bytes();
        chunk.resize(chunk.len().next_multiple_of(4), b' ');
        let total = 12 + 8 + chunk.len() as u32;
        let glb = [b"glTF".as_slice(), &2u32.to_le_bytes(), &total.to_le_bytes()]
            .concat()
            .into_iter()
            .chain((chunk.len() as u32).to_le_bytes())
            .chain(*b"JSON")
            .chain(chunk)
            .collect::<Vec<u8>>();
        assert_eq!(node_numbers(&glb)[0].translation, Some(ecef));
    }
}
