//! A planar surface as the coplanar check compares it: a triangle or an infinite plane, its
//! oriented unit normal, its offset, and the tolerance within which another is the same plane.

use glam::DVec3;

use crate::desc::ObjectDesc;
use crate::mesh::MeshDesc;
use glint_types::layout::f32_spacing;

/// Surfaces within this many f32 spacings (at the magnitude of their stored coordinates) are
/// one plane to both tracers.
const F32_STEPS: f64 = 4.0;

/// Where a planar surface comes from: an object, and for a mesh its mesh and triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(super) struct Source {
    pub(super) object: u32,
    pub(super) mesh: u32,
    /// The triangle's index; `u32::MAX` for a plane object.
    pub(super) triangle: u32,
}

/// A planar surface in world space: a triangle, or an infinite plane (`corners` unused).
#[derive(Clone, Debug)]
pub(super) struct Surface {
    pub(super) source: Source,
    pub(super) normal: DVec3,
    pub(super) offset: f64,
    pub(super) plane: bool,
    pub(super) corners: [DVec3; 3],
    pub(super) tolerance: f64,
}

/// What decides whether two surfaces are one plane: the scene's ε, and the origin its positions
/// are stored relative to (`storage_origin`), where f32's spacing is judged.
#[derive(Clone, Copy, Debug)]
pub(super) struct Resolution {
    pub(super) epsilon: f64,
    pub(super) origin: DVec3,
}

impl Surface {
    /// The magnitude of what the tracers store: a triangle's corners relative to the storage
    /// origin, a plane's offset from it.
    pub(super) fn new(
        source: Source,
        normal: DVec3,
        point: DVec3,
        corners: Option<[DVec3; 3]>,
        at: Resolution,
    ) -> Option<Self> {
        let normal = oriented(normal)?;
        let magnitude = match &corners {
            Some(c) => c.iter().fold(0.0_f64, |m, p| m.max((*p - at.origin).abs().max_element())),
            None => normal.dot(point - at.origin).abs(),
        };
        let tolerance = (F32_STEPS * f32_spacing(magnitude)).max(at.epsilon);
        let (plane, corners) = (corners.is_none(), corners.unwrap_or([point; 3]));
        Some(Self { source, normal, offset: normal.dot(point), plane, corners, tolerance })
    }

    pub(super) fn is_plane(&self) -> bool {
        self.plane
    }
}

/// A plane's unit normal in its one orientation (the largest component positive), so that
/// back-to-back faces share a cell; `None` for a degenerate one.
pub(super) fn oriented(normal: DVec3) -> Option<DVec3> {
    let n = normal.try_normalize()?;
    Some(if n[n.abs().max_position()] < 0.0 { -n } else { n })
}

pub(super) fn triangle(mesh: &MeshDesc, source: Source, at: Resolution) -> Option<Surface> {
    let tri = mesh.triangles.get(source.triangle as usize)?;
    let corner = |i: u32| mesh.vertices.get(i as usize).map(|&v| DVec3::from(v));
    let (a, b, c) = (corner(tri[0])?, corner(tri[1])?, corner(tri[2])?);
    Surface::new(source, (b - a).cross(c - a), a, Some([a, b, c]), at)
}

/// The surface `source` names, its tolerance at least `at.epsilon`.
pub(super) fn surface_of(objects: &[ObjectDesc], source: Source, at: Resolution) -> Option<Surface> {
    match objects.get(source.object as usize)? {
        ObjectDesc::Sphere(_) => None,
        ObjectDesc::Plane(p) => Surface::new(source, DVec3::from(p.normal), DVec3::from(p.point), None, at),
        ObjectDesc::Mesh(mesh) => triangle(mesh, source, at),
        ObjectDesc::Model(m) => triangle(m.loaded.as_ref()?.meshes.get(source.mesh as usize)?, source, at),
    }
}
