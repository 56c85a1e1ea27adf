//! How near a point geometry comes: the boxes and nearest points the warnings that judge a
//! scene from a point (the eye, a light) share. Meshes are read where they are, never copied:
//! validation runs on every edit in the viewer.

use glam::DVec3;

use super::{MeshDesc, ObjectDesc};

/// The box around a mesh's vertices; `None` for a mesh without vertices or with one that is
/// not finite (validation's errors say so).
pub(super) fn mesh_box(mesh: &MeshDesc) -> Option<(DVec3, DVec3)> {
    let (lo, hi) = mesh
        .vertices
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &v| (lo.min(DVec3::from(v)), hi.max(DVec3::from(v))));
    (lo.is_finite() && hi.is_finite()).then_some((lo, hi))
}

/// Each object's meshes' boxes (`mesh_box`; none for a sphere or a plane), made with the
/// objects' part of validation so that what judges the scene from the camera or a light reads
/// no vertex of a mesh it passes over: a camera drag re-validates on every step, and a model of
/// a million vertices is not read again for it.
#[derive(Clone, Debug, Default)]
pub(crate) struct MeshBoxes(Vec<Vec<Option<(DVec3, DVec3)>>>);

impl MeshBoxes {
    pub(super) fn of(objects: &[ObjectDesc]) -> Self {
        Self(objects.iter().map(|o| meshes_of(o).into_iter().map(mesh_box).collect()).collect())
    }

    /// The box of mesh `mesh` of object `object`.
    pub(super) fn get(&self, object: usize, mesh: usize) -> Option<(DVec3, DVec3)> {
        self.0.get(object)?.get(mesh).copied().flatten()
    }
}

/// An object's meshes: a mesh's one, a model's in its order, none of a sphere or a plane.
pub(super) fn meshes_of(object: &ObjectDesc) -> Vec<&MeshDesc> {
    match object {
        ObjectDesc::Mesh(mesh) => vec![mesh],
        ObjectDesc::Model(model) => model.loaded.iter().flat_map(|l| &l.meshes).collect(),
        ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) => Vec::new(),
    }
}

/// The distance from `p` to the box [lo, hi]; 0 inside it.
pub(super) fn box_distance(p: DVec3, lo: DVec3, hi: DVec3) -> f64 {
    (lo - p).max(p - hi).max(DVec3::ZERO).length()
}

/// The corners of triangle `t` of `mesh`; `None` where an index is out of range.
pub(super) fn triangle_corners(mesh: &MeshDesc, t: &[u32; 3]) -> Option<[DVec3; 3]> {
    let corner = |k: u32| mesh.vertices.get(k as usize).map(|&v| DVec3::from(v));
    Some([corner(t[0])?, corner(t[1])?, corner(t[2])?])
}

/// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, 5.1.5): by
/// the region of the triangle's plane p projects into, a corner, an edge or the face.
pub(super) fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_point_is_a_corner_an_edge_or_the_face() {
        let (a, b, c) = (DVec3::ZERO, DVec3::X, DVec3::Y);
        assert_eq!(closest_on_triangle(DVec3::new(-1.0, -1.0, 3.0), a, b, c), a);
        assert_eq!(closest_on_triangle(DVec3::new(2.0, -0.5, 0.0), a, b, c), b);
        assert_eq!(closest_on_triangle(DVec3::new(0.5, -2.0, 1.0), a, b, c), DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(closest_on_triangle(DVec3::new(1.0, 1.0, 0.0), a, b, c), DVec3::new(0.5, 0.5, 0.0));
        assert_eq!(closest_on_triangle(DVec3::new(0.25, 0.25, -4.0), a, b, c), DVec3::new(0.25, 0.25, 0.0));
    }
}
