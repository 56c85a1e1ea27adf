//! Coplanar overlapping surfaces: two faces (or a face and a plane, or two planes) that lie in
//! one plane and overlap. A ray meets both at the same t up to rounding, and which one it
//! reports is decided by that rounding, pixel by pixel and differently on the two tracers
//! ("z-fighting"). No tie rule can help when the two t values round differently, so the scene
//! is warned, naming both objects and the overlap's area (docs/numerics.md, case 19).
//!
//! Faces are bucketed by their unit normal (cells of 1/1024 per component, a face near a cell
//! border in both cells), then swept along one axis of the plane within a bucket, so that a
//! million-triangle mesh costs about one sort and a flat grid of k faces about k tests.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};

use super::super::desc::{MeshDesc, ObjectDesc, SceneDesc};
use super::super::error::FieldIssue;

/// Normal cells per unit of each component.
const CELLS: f64 = 1024.0;
/// A normal this close (in cells) to a cell border goes into both cells.
const BORDER: f64 = 0.05;
/// Surfaces within this many f32 spacings (at their coordinates' magnitude) are one plane to
/// both tracers.
const F32_STEPS: f64 = 4.0;
/// An overlap below this share of the smaller face is a shared edge or corner, not an overlap.
const MIN_SHARE: f64 = 1e-6;
/// Warnings printed before the rest are counted in one line.
const MAX_WARNINGS: usize = 8;

/// Where a planar surface comes from: an object, and for a mesh its mesh and triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Source {
    object: u32,
    mesh: u32,
    /// The triangle's index; `u32::MAX` for a plane object.
    triangle: u32,
}

/// A planar surface in world space: a triangle, or an infinite plane (`corners` unused).
#[derive(Clone, Debug)]
struct Surface {
    source: Source,
    normal: DVec3,
    offset: f64,
    plane: bool,
    corners: [DVec3; 3],
    tolerance: f64,
}

impl Surface {
    fn new(source: Source, normal: DVec3, point: DVec3, corners: Option<[DVec3; 3]>) -> Option<Self> {
        let normal = normal.try_normalize()?;
        // One orientation per plane: the largest component positive, so back-to-back faces
        // share a bucket.
        let normal = if normal[normal.abs().max_position()] < 0.0 { -normal } else { normal };
        let magnitude = corners.iter().flatten().chain([&point]).fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
        let tolerance = F32_STEPS * f32_spacing(magnitude);
        let (plane, corners) = (corners.is_none(), corners.unwrap_or([point; 3]));
        Some(Self { source, normal, offset: normal.dot(point), plane, corners, tolerance })
    }

    fn is_plane(&self) -> bool {
        self.plane
    }

    /// The normal's cells: its own, and the neighbours across any border it is close to.
    fn cells(&self) -> Vec<[i32; 3]> {
        let mut cells = vec![[0; 3]];
        for k in 0..3 {
            let x = self.normal[k] * CELLS;
            let cell = x.floor();
            let near = if x - cell < BORDER {
                Some(cell - 1.0)
            } else if cell + 1.0 - x < BORDER {
                Some(cell + 1.0)
            } else {
                None
            };
            let mut more = Vec::new();
            for c in &mut cells {
                c[k] = cell as i32;
                if let Some(n) = near {
                    let mut other = *c;
                    other[k] = n as i32;
                    more.push(other);
                }
            }
            cells.extend(more);
        }
        cells
    }
}

/// The distance between adjacent f32 values at `x`.
fn f32_spacing(x: f64) -> f64 {
    2f64.powf(x.max(f64::from(f32::MIN_POSITIVE)).log2().floor() - 23.0)
}

/// What one pair of objects shares.
#[derive(Debug, Default)]
struct Overlap {
    area: f64,
    pairs: usize,
    first: Option<(Source, Source)>,
}

/// Warnings for every pair of objects (or one object with itself) whose planar surfaces
/// overlap coplanar within `epsilon` or the f32 resolution at their coordinates.
pub(super) fn coplanar_overlaps(scene: &SceneDesc) -> Vec<FieldIssue> {
    let epsilon = scene.render.epsilon.max(0.0);
    let surfaces = surfaces(&scene.objects, epsilon);
    let mut buckets: BTreeMap<[i32; 3], Vec<u32>> = BTreeMap::new();
    for (i, s) in surfaces.iter().enumerate() {
        for cell in s.cells() {
            buckets.entry(cell).or_default().push(i as u32);
        }
    }
    let mut found: BTreeMap<(u32, u32), Overlap> = BTreeMap::new();
    let mut seen = std::collections::HashSet::new();
    for members in buckets.values().filter(|m| m.len() > 1) {
        for (a, b) in candidate_pairs(&surfaces, members) {
            let (sa, sb) = (&surfaces[a as usize], &surfaces[b as usize]);
            let key = if sa.source <= sb.source { (a, b) } else { (b, a) };
            if !seen.insert(key) {
                continue;
            }
            if let Some(area) = overlap_area(sa, sb) {
                let (x, y) = if sa.source <= sb.source { (sa.source, sb.source) } else { (sb.source, sa.source) };
                let o = found.entry((x.object, y.object)).or_default();
                o.area += area;
                o.pairs += 1;
                o.first.get_or_insert((x, y));
            }
        }
    }
    let mut warnings = Vec::new();
    let total = found.len();
    for ((i, j), o) in found.into_iter().take(MAX_WARNINGS) {
        let Some((x, y)) = o.first else { continue };
        let name = |k: u32| {
            let object = &scene.objects[k as usize];
            match object.name() {
                "" => format!("objects[{k}] ({})", object.kind_name()),
                named => format!("objects[{k}] ({} `{named}`)", object.kind_name()),
            }
        };
        let area =
            if o.area.is_finite() { format!("an area of {:.4e}", o.area) } else { "the whole plane".to_string() };
        let with = if i == j { "overlaps itself".to_string() } else { format!("and {} overlap", name(j)) };
        warnings.push(FieldIssue {
            field: format!("objects[{i}]"),
            problem: format!(
                "{} {with} in one plane over {area} ({} pair{} of surfaces, first {} and {}): a ray meets both at \
                 the same t up to rounding, so each tracer picks its own surface pixel by pixel (z-fighting); move \
                 one apart or remove the duplicate",
                name(i),
                o.pairs,
                if o.pairs == 1 { "" } else { "s" },
                describe(x, &scene.objects),
                describe(y, &scene.objects),
            ),
        });
    }
    if total > MAX_WARNINGS {
        warnings.push(FieldIssue {
            field: "objects".into(),
            problem: format!("{} more pairs of objects overlap coplanar", total - MAX_WARNINGS),
        });
    }
    warnings
}

/// A surface by its object and, for a mesh, its triangle.
fn describe(s: Source, objects: &[ObjectDesc]) -> String {
    let object = s.object;
    match &objects[object as usize] {
        ObjectDesc::Plane(_) | ObjectDesc::Sphere(_) => format!("objects[{object}]"),
        ObjectDesc::Mesh(_) => format!("objects[{object}] triangle {}", s.triangle),
        ObjectDesc::Model(m) => {
            let mesh = m.loaded.as_ref().and_then(|l| l.meshes.get(s.mesh as usize)).map_or("", |x| x.name.as_str());
            format!("objects[{object}] triangle {} of mesh {} `{mesh}`", s.triangle, s.mesh)
        }
    }
}

/// Every plane and triangle of the scene in world space (spheres have no plane).
fn surfaces(objects: &[ObjectDesc], epsilon: f64) -> Vec<Surface> {
    let mut out = Vec::new();
    let mesh_faces = |object: u32, k: u32, mesh: &MeshDesc, out: &mut Vec<Surface>| {
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let corner = |i: u32| mesh.vertices.get(i as usize).map(|&v| DVec3::from(v));
            let (Some(a), Some(b), Some(c)) = (corner(tri[0]), corner(tri[1]), corner(tri[2])) else {
                continue;
            };
            let source = Source { object, mesh: k, triangle: t as u32 };
            out.extend(Surface::new(source, (b - a).cross(c - a), a, Some([a, b, c])));
        }
    };
    for (i, object) in objects.iter().enumerate() {
        let object_index = i as u32;
        match object {
            ObjectDesc::Sphere(_) => {}
            ObjectDesc::Plane(p) => {
                let source = Source { object: object_index, mesh: 0, triangle: u32::MAX };
                out.extend(Surface::new(source, DVec3::from(p.normal), DVec3::from(p.point), None));
            }
            ObjectDesc::Mesh(mesh) => mesh_faces(object_index, 0, mesh, &mut out),
            ObjectDesc::Model(m) => {
                for (k, mesh) in m.loaded.iter().flat_map(|l| l.meshes.iter()).enumerate() {
                    mesh_faces(object_index, k as u32, mesh, &mut out);
                }
            }
        }
    }
    for s in &mut out {
        s.tolerance = s.tolerance.max(epsilon);
    }
    out
}

/// Pairs of a bucket's surfaces whose extents overlap along the plane's first axis (planes
/// overlap everything): a sweep over the faces sorted by where they start.
fn candidate_pairs(surfaces: &[Surface], members: &[u32]) -> Vec<(u32, u32)> {
    let axis = surfaces[members[0] as usize].normal.abs().max_position();
    let u = (axis + 1) % 3;
    let mut planes = Vec::new();
    let mut faces: Vec<(f64, f64, u32)> = Vec::new();
    for &m in members {
        let s = &surfaces[m as usize];
        if s.is_plane() {
            planes.push(m);
        } else {
            let (lo, hi) =
                s.corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| (lo.min(c[u]), hi.max(c[u])));
            faces.push((lo - s.tolerance, hi + s.tolerance, m));
        }
    }
    faces.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut pairs = Vec::new();
    for (k, &(_, hi, a)) in faces.iter().enumerate() {
        for &(lo, _, b) in &faces[k + 1..] {
            if lo > hi {
                break;
            }
            pairs.push((a, b));
        }
    }
    for (k, &p) in planes.iter().enumerate() {
        pairs.extend(planes[k + 1..].iter().map(|&q| (p, q)));
        pairs.extend(faces.iter().map(|&(.., f)| (p, f)));
    }
    pairs
}

/// The area two surfaces share in one plane, or `None` when they are not coplanar or only
/// touch. Two planes share an infinite area.
fn overlap_area(a: &Surface, b: &Surface) -> Option<f64> {
    let tolerance = a.tolerance.max(b.tolerance);
    let on = |s: &Surface, p: &DVec3| (s.normal.dot(*p) - s.offset).abs() <= tolerance;
    match (a.is_plane(), b.is_plane()) {
        (true, true) => {
            let parallel = a.normal.cross(b.normal).length() <= 1e-9;
            (parallel && (a.offset - b.offset).abs() <= tolerance).then_some(f64::INFINITY)
        }
        (true, false) => b.corners.iter().all(|p| on(a, p)).then(|| triangle_area(&b.corners)),
        (false, true) => a.corners.iter().all(|p| on(b, p)).then(|| triangle_area(&a.corners)),
        (false, false) => {
            if !(a.corners.iter().all(|p| on(b, p)) && b.corners.iter().all(|p| on(a, p))) {
                return None;
            }
            // Areas in the plane of the dropped axis, scaled back by the normal's component.
            let axis = a.normal.abs().max_position();
            let flat = |s: &Surface| s.corners.iter().map(|p| drop_axis(*p, axis)).collect::<Vec<_>>();
            let scale = 1.0 / a.normal[axis].abs();
            let shared = polygon_area(&clip(&flat(a), &flat(b))) * scale;
            let smaller = triangle_area(&a.corners).min(triangle_area(&b.corners));
            (shared > MIN_SHARE * smaller).then_some(shared)
        }
    }
}

fn drop_axis(p: DVec3, axis: usize) -> DVec2 {
    DVec2::new(p[(axis + 1) % 3], p[(axis + 2) % 3])
}

fn triangle_area(c: &[DVec3]) -> f64 {
    0.5 * (c[1] - c[0]).cross(c[2] - c[0]).length()
}

fn polygon_area(p: &[DVec2]) -> f64 {
    let twice: f64 = (0..p.len()).map(|i| p[i].perp_dot(p[(i + 1) % p.len()])).sum();
    0.5 * twice.abs()
}

/// `subject` clipped by the convex triangle `clipper` (Sutherland–Hodgman), either winding.
fn clip(subject: &[DVec2], clipper: &[DVec2]) -> Vec<DVec2> {
    let turn = (clipper[1] - clipper[0]).perp_dot(clipper[2] - clipper[0]).signum();
    let mut out = subject.to_vec();
    for i in 0..clipper.len() {
        let (a, b) = (clipper[i], clipper[(i + 1) % clipper.len()]);
        let inside = |p: DVec2| turn * (b - a).perp_dot(p - a) >= 0.0;
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (pin, qin) = (inside(p), inside(q));
            if pin {
                out.push(p);
            }
            if pin != qin {
                let (dp, dq) = ((b - a).perp_dot(p - a), (b - a).perp_dot(q - a));
                out.push(p + (q - p) * (dp / (dp - dq)));
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraDesc, MeshDesc, PlaneDesc, RenderSettings, WorldDesc};

    fn mesh(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>, name: &str) -> ObjectDesc {
        ObjectDesc::Mesh(MeshDesc {
            vertices,
            triangles,
            normals: None,
            uvs: None,
            material: "m".into(),
            name: name.into(),
        })
    }

    fn quad(x0: f64, y: f64, name: &str) -> ObjectDesc {
        mesh(vec![[x0, y, 0.0], [x0 + 1.0, y, 0.0], [x0 + 1.0, y, 1.0], [x0, y, 1.0]], vec![[0, 2, 1], [0, 3, 2]], name)
    }

    fn scene(objects: Vec<ObjectDesc>) -> SceneDesc {
        let camera = CameraDesc { position: [0.0, 2.0, -5.0], look_at: [0.0; 3], up: [0.0, 1.0, 0.0], fov_y: 40.0 };
        SceneDesc {
            description: String::new(),
            provenance: String::new(),
            render: RenderSettings::default(),
            camera,
            world: WorldDesc::default(),
            materials: BTreeMap::new(),
            lights: Vec::new(),
            objects,
        }
    }

    #[test]
    fn half_overlapping_quads_are_named_with_their_shared_area() {
        let w = coplanar_overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(0.5, 0.0, "b")]));
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(w[0].problem.contains("objects[0] (mesh `a`) and objects[1] (mesh `b`)"), "{}", w[0].problem);
        assert!(w[0].problem.contains("area of 5.0000e-1"), "{}", w[0].problem);
    }

    #[test]
    fn neighbours_apart_or_sharing_an_edge_are_not_overlaps() {
        assert!(coplanar_overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(1.0, 0.0, "b")])).is_empty());
        assert!(coplanar_overlaps(&scene(vec![quad(0.0, 0.0, "a"), quad(0.5, 1e-3, "b")])).is_empty());
        assert!(coplanar_overlaps(&scene(vec![quad(0.0, 0.0, "a")])).is_empty(), "a quad's own two triangles");
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
        let w = coplanar_overlaps(&scene(vec![quad(0.0, 0.0, "floor"), plane(0.0, "ground")]));
        assert!(w.len() == 1 && w[0].problem.contains("area of 1.0000e0"), "{w:?}");
        let w = coplanar_overlaps(&scene(vec![plane(3.0, "p"), plane(3.0, "q")]));
        assert!(w.len() == 1 && w[0].problem.contains("the whole plane"), "{w:?}");
        // At 1e6 an f32 step is 0.0625: a face 0.01 above another is the same plane there.
        let w = coplanar_overlaps(&scene(vec![quad(1e6, 1e6, "a"), quad(1e6 + 0.5, 1e6 + 0.01, "b")]));
        assert_eq!(w.len(), 1, "{w:?}");
    }

    #[test]
    fn a_duplicated_triangle_inside_one_mesh_is_found() {
        let m = mesh(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2], [0, 2, 1]], "twice");
        let w = coplanar_overlaps(&scene(vec![m]));
        assert!(w.len() == 1 && w[0].problem.contains("overlaps itself"), "{w:?}");
    }
}
