use super::surface::triangle;
use super::*;
use crate::desc::test_scene as scene;
use crate::{MeshDesc, PlaneDesc};
use glam::DVec2;

fn mesh(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>, name: &str) -> ObjectDesc {
    ObjectDesc::Mesh(MeshDesc::new(vertices, triangles, "m", name))
}

/// The warnings for `scene`, at its own storage origin, as validation gives them.
fn overlaps(scene: &SceneDesc) -> Vec<FieldIssue> {
    coplanar_overlaps(scene, crate::storage_origin(scene), scene.render.epsilon)
}

/// Judged in world space, with no ε (the unit tests of single surfaces).
const WORLD: Resolution = Resolution { epsilon: 0.0, origin: DVec3::ZERO };

fn quad(x0: f64, y: f64, name: &str) -> ObjectDesc {
    mesh(vec![[x0, y, 0.0], [x0 + 1.0, y, 0.0], [x0 + 1.0, y, 1.0], [x0, y, 1.0]], vec![[0, 2, 1], [0, 3, 2]], name)
}

#[test]
fn half_overlapping_quads_are_named_with_their_shared_area() {
    let w = overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(0.5, 0.0, "b")]));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].problem.starts_with("the mesh `a` overlaps objects[1] (mesh `b`) in one plane"), "{}", w[0].problem);
    assert!(w[0].problem.contains("area of 5.0000e-1"), "{}", w[0].problem);
}

#[test]
fn neighbours_apart_or_sharing_an_edge_are_not_overlaps() {
    assert!(overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(1.0, 0.0, "b")])).is_empty());
    assert!(overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(0.5, 1e-3, "b")])).is_empty());
    assert!(overlaps(&scene(vec![quad(0.0, 0.0, "a")])).is_empty(), "a quad's own two triangles");
}

#[test]
fn a_face_on_a_plane_and_coincident_planes_are_found_far_from_the_origin_too() {
    let plane = |y: f64, name: &str| {
        ObjectDesc::Plane(PlaneDesc {
            point: [0.0, y, 0.0],
            normal: [0.0, -2.0, 0.0],
            material: "m".into(),
            name: name.into(),
        })
    };
    let w = overlaps(&scene(vec![quad(0.0, 0.0, "floor"), plane(0.0, "ground")]));
    assert!(w.len() == 1 && w[0].problem.contains("area of 1.0000e0"), "{w:?}");
    let w = overlaps(&scene(vec![plane(3.0, "p"), plane(3.0, "q")]));
    assert!(w.len() == 1 && w[0].problem.contains("the whole plane"), "{w:?}");
    // Far from the world origin on their own, the faces are stored relative to themselves
    // (`storage_origin`), where f32 tells 0.01 apart.
    let (a, b) = (quad(1e6, 1e6, "a"), quad(1e6 + 0.5, 1e6 + 0.01, "b"));
    assert!(overlaps(&scene(vec![a.clone(), b.clone()])).is_empty());
    // In a scene that spans 1e6 (a face at the world origin too) an f32 step is 0.0625 there:
    // a face 0.01 above another is the same plane.
    let w = overlaps(&scene(vec![a, b, quad(0.0, 0.0, "at the origin")]));
    assert_eq!(w.len(), 1, "{w:?}");
}

#[test]
fn copies_of_one_face_are_counted_whole_without_pairing_them_all() {
    // 2,000 copies: 2e6 pairs, which the search paired all (6,000 took 17 s and 1.1 GB), then
    // counted to its bound; each copy is now compared once and stands for its pairs.
    let copies = 2_000;
    let m = mesh(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2]; copies], "copies");
    let w = overlaps(&scene(vec![m]));
    assert_eq!(w.len(), 1, "{w:?}");
    let said = &w[0].problem;
    // 1999·2000/2 = 1,999,000 pairs of half a unit each.
    assert!(said.contains("overlaps itself in one plane over a summed area of 9.9950e5 (1999000 pairs"), "{said}");
    // Copies of reversed winding are the same triangle: 4 copies, 6 pairs (the pairs across the
    // two windings were counted once).
    let m = mesh(
        vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]],
        vec![[0, 1, 2], [0, 2, 1], [0, 1, 2], [2, 1, 0]],
        "wound",
    );
    let w = overlaps(&scene(vec![m]));
    assert!(w[0].problem.contains("(6 pairs"), "{w:?}");
    // 200,000 copies (22 s before; a test a copy now) are counted whole too.
    let m = mesh(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2]; 200_000], "many");
    let w = overlaps(&scene(vec![m]));
    assert!(w[0].problem.contains("(19999900000 pairs"), "{w:?}");
}

/// The plane y = `y`.
fn horizontal(y: f64) -> ObjectDesc {
    ObjectDesc::Plane(PlaneDesc {
        point: [0.0, y, 0.0],
        normal: [0.0, 1.0, 0.0],
        material: "m".into(),
        name: "".into(),
    })
}

#[test]
fn copies_of_one_plane_are_counted_to_a_bound_and_parallel_planes_are_not_paired() {
    // 2,000 parallel planes 1 apart: none overlaps, and each is tested against none of the
    // others (all 2e6 pairs were tested).
    let apart: Vec<ObjectDesc> = (0..2_000).map(|y| horizontal(f64::from(y))).collect();
    let at = Resolution { epsilon: 1e-6, origin: DVec3::ZERO };
    let members: Vec<(Surface, bool)> = (0..apart.len() as u32)
        .map(|k| (surface_of(&apart, Source { object: k, mesh: 0, triangle: u32::MAX }, at).unwrap(), false))
        .collect();
    let mut tested = 0usize;
    assert!(candidate_pairs(&members, usize::MAX, |_, _| {
        tested += 1;
        true
    }));
    assert_eq!(tested, 0, "parallel planes apart were paired");
    assert!(overlaps(&scene(apart)).is_empty());
    // 2,000 copies: 2e6 pairs, all tested and kept before (4,000 took 21 s and 877 MB); the
    // budget now stops the search at 64 tests a surface.
    let w = overlaps(&scene(vec![horizontal(0.5); 2_000]));
    assert_eq!(w.len(), MAX_WARNINGS + 1, "{w:?}");
    assert!(w[0].problem.contains("over the whole plane (at least 1 pair"), "{}", w[0].problem);
    assert!(w[MAX_WARNINGS].problem.starts_with("at least "), "{}", w[MAX_WARNINGS].problem);
}

#[test]
fn planes_over_a_floor_are_tested_only_against_the_faces_at_their_height() {
    // 200 planes 100 and more above a floor of 20,000 faces: each plane was tested against
    // every face (4,000 over 80,000 took 72 s).
    let mut objects = vec![floor(100, "floor")];
    objects.extend((0..200).map(|k| horizontal(100.0 + f64::from(k))));
    let at = Resolution { epsilon: 1e-6, origin: DVec3::ZERO };
    let ObjectDesc::Mesh(m) = &objects[0] else { unreachable!() };
    let mut members: Vec<(Surface, bool)> = (0..m.triangles.len() as u32)
        .map(|t| (triangle(m, Source { object: 0, mesh: 0, triangle: t }, at).unwrap(), false))
        .collect();
    members.extend(
        (1..objects.len() as u32)
            .map(|k| (surface_of(&objects, Source { object: k, mesh: 0, triangle: u32::MAX }, at).unwrap(), false)),
    );
    let mut tested = 0usize;
    assert!(candidate_pairs(&members, usize::MAX, |_, _| {
        tested += 1;
        true
    }));
    assert!(tested <= 9 * m.triangles.len(), "{tested} tests");
    assert!(overlaps(&scene(objects.clone())).is_empty());
    // One at the floor's height is still found over all of it.
    objects.push(horizontal(0.0));
    let w = overlaps(&scene(objects));
    assert!(w.len() == 1 && w[0].problem.contains("area of 1.0000e4"), "{w:?}");
}

#[test]
fn layers_of_one_normal_are_searched_apart_and_an_overlap_in_the_last_is_counted_whole() {
    // 25 floors of 20 × 20 quads stacked 3 apart share one normal cell; the top one holds
    // a copy of one of its triangles. A budget spent across the layers (14 candidates a
    // face a layer, 350 a face here, beyond 64) cut the search before the top floor.
    let mut objects: Vec<ObjectDesc> = (0..25)
        .map(|k| {
            let ObjectDesc::Mesh(mut m) = floor(20, &format!("floor {k}")) else { unreachable!() };
            m.vertices.iter_mut().for_each(|v| v[1] = 3.0 * f64::from(k));
            ObjectDesc::Mesh(m)
        })
        .collect();
    if let Some(ObjectDesc::Mesh(top)) = objects.last_mut() {
        let copy = top.triangles[0];
        top.triangles.push(copy);
    }
    let w = overlaps(&scene(objects));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(w[0].problem.starts_with("the mesh `floor 24` overlaps itself"), "{}", w[0].problem);
    assert!(w[0].problem.contains("(1 pair of surfaces"), "{}", w[0].problem);
}

#[test]
fn a_duplicated_triangle_inside_one_mesh_is_found() {
    let m = mesh(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2], [0, 2, 1]], "twice");
    let w = overlaps(&scene(vec![m]));
    assert!(w.len() == 1 && w[0].problem.contains("overlaps itself"), "{w:?}");
}

/// An n × n grid of unit-square quads in the plane y = 0, as one mesh.
fn floor(n: u32, name: &str) -> ObjectDesc {
    let side = n + 1;
    let vertices = (0..side * side).map(|k| [f64::from(k % side), 0.0, f64::from(k / side)]).collect();
    let triangles = (0..n * n)
        .flat_map(|q| {
            let a = q / n * side + q % n;
            [[a, a + side + 1, a + 1], [a, a + side, a + side + 1]]
        })
        .collect();
    mesh(vertices, triangles, name)
}

/// Faces of every size from 0.01 to 1000 (grids of several levels) in one plane: the pairs
/// reported are exactly the pairs whose boxes overlap, each once.
#[test]
fn every_overlapping_pair_of_faces_of_any_size_is_reported_once() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for k in 0..400u32 {
        let size = 10f64.powf(-2.0 + 5.0 * next().powi(3));
        let (x, z) = (next() * 1000.0, next() * 1000.0);
        vertices.extend([[x, 0.0, z], [x + size, 0.0, z + 0.3 * size], [x + 0.2 * size, 0.0, z + size]]);
        triangles.push([3 * k, 3 * k + 2, 3 * k + 1]);
    }
    let desc = scene(vec![mesh(vertices, triangles, "scatter")]);
    let ObjectDesc::Mesh(m) = &desc.objects[0] else { unreachable!() };
    let members: Vec<(Surface, bool)> = (0..m.triangles.len() as u32)
        .map(|t| (triangle(m, Source { object: 0, mesh: 0, triangle: t }, WORLD).unwrap(), false))
        .collect();
    let mut reported = Vec::new();
    assert!(candidate_pairs(&members, usize::MAX, |a, b| {
        reported.push((a.min(b), a.max(b)));
        true
    }));
    let boxed = |s: &Surface| {
        let flat = s.corners.map(|c| DVec2::new(c.z, c.x));
        (flat[0].min(flat[1]).min(flat[2]) - s.tolerance, flat[0].max(flat[1]).max(flat[2]) + s.tolerance)
    };
    let mut expected = Vec::new();
    for a in 0..members.len() {
        for b in a + 1..members.len() {
            let ((alo, ahi), (blo, bhi)) = (boxed(&members[a].0), boxed(&members[b].0));
            if alo.cmple(bhi).all() && blo.cmple(ahi).all() {
                expected.push((a, b));
            }
        }
    }
    let count = reported.len();
    reported.sort_unstable();
    reported.dedup();
    assert_eq!(reported.len(), count, "a pair reported twice");
    assert_eq!(reported, expected);
    assert!(expected.len() > 100, "the sizes overlap often enough to mean something: {}", expected.len());
}

#[test]
fn a_flat_grid_costs_about_one_test_a_face_and_a_ground_under_it_is_found() {
    let n = 150;
    let desc = scene(vec![floor(n, "floor")]);
    let ObjectDesc::Mesh(m) = &desc.objects[0] else { unreachable!() };
    let members: Vec<(Surface, bool)> = (0..m.triangles.len() as u32)
        .map(|t| (triangle(m, Source { object: 0, mesh: 0, triangle: t }, WORLD).unwrap(), false))
        .collect();
    let mut pairs = 0usize;
    assert!(candidate_pairs(&members, usize::MAX, |_, _| {
        pairs += 1;
        true
    }));
    let faces = members.len();
    // Each triangle's box meets its quad's other triangle and the 16 of the quads around
    // (shared edges and corners): 8.5 pairs a face. A sweep along one axis tested every face
    // against three rows, 6n = 900 a face.
    assert!(pairs <= 9 * faces, "{pairs} candidate pairs for {faces} faces");
    assert!(overlaps(&desc).is_empty(), "neighbours sharing edges are not overlaps");
    // One quad of the size of the whole grid under it: too large for the grid's cells, so
    // compared with every face, and the overlap is the whole floor.
    let ground = mesh(
        vec![[0.0, 0.0, 0.0], [150.0, 0.0, 0.0], [150.0, 0.0, 150.0], [0.0, 0.0, 150.0]],
        vec![[0, 2, 1], [0, 3, 2]],
        "ground",
    );
    let w = overlaps(&scene(vec![floor(n, "floor"), ground]));
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].problem.contains("overlaps objects[1] (mesh `ground`) in one plane")
            && w[0].problem.contains("area of 2.2500e4"),
        "{}",
        w[0].problem
    );
}

mod bumpy {
    use super::*;

    /// The bumpy sphere folds slivers at its poles within an f32 step of each other's plane:
    /// overlaps of 9e-8 on a sphere 2.9 units across, which no pixel shows.
    #[test]
    fn the_bumpy_spheres_pole_is_not_warned() {
        // The built-in scene's default resolution (glint-io's `DEFAULT_RESOLUTION`).
        let desc = crate::bumpy::bumpy(500);
        assert!(coplanar_overlaps(&desc, crate::storage_origin(&desc), desc.render.epsilon).is_empty());
    }
}
