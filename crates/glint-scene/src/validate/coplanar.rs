//! Coplanar overlapping surfaces: two faces (or a face and a plane, or two planes) that lie in
//! one plane and overlap. A ray meets both at the same t up to rounding, and which one it
//! reports is decided by that rounding, pixel by pixel and differently on the two tracers
//! ("z-fighting"). No tie rule can help when the two t values round differently, so the scene
//! is warned, naming both objects and the overlap's area (docs/numerics.md, case 19).
//!
//! Faces are bucketed by their unit normal (cells of 1/1024 per component, a face near a cell
//! border in both cells), then put into a uniform grid over the plane within a bucket, so that a
//! million-triangle mesh costs about one sort and a flat grid of k faces about k tests: 0.1 s
//! for the bumpy sphere's million triangles on two cores.

use std::collections::BTreeMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::super::desc::{ObjectDesc, SceneDesc};
use super::super::error::FieldIssue;
use super::super::mesh::MeshDesc;
use glint_types::layout::f32_spacing;

/// Normal cells per unit of each component.
const CELLS: f64 = 1024.0;
/// A normal this close (in cells) to a cell border goes into both cells.
const BORDER: f64 = 0.01;
/// Surfaces within this many f32 spacings (at the magnitude of their stored coordinates) are
/// one plane to both tracers.
const F32_STEPS: f64 = 4.0;
/// An overlap below this share of the smaller face is a shared edge or corner, not an overlap.
const MIN_SHARE: f64 = 1e-6;
/// An overlap is warned when its area is at least this share of the square of the two
/// objects' size (their bounding boxes' diagonal): a fold of slivers at a tessellated pole
/// (the bumpy sphere's, 9e-8 of a 2.9-unit sphere) z-fights where no pixel can show it.
const MIN_VISIBLE: f64 = 1e-6;
/// Warnings printed before the rest are counted in one line.
const MAX_WARNINGS: usize = 8;
/// Candidate pairs of faces tested in one normal cell, per surface in it, before its search
/// stops: a flat triangulated grid tests about 14 a face and layers that cannot meet are
/// searched apart, but copies of one face pair each with all the others (6,000 copies of one
/// triangle, 1.8e7 pairs, took 17 s and 1.1 GB; 200,000 did not finish). The bound keeps time
/// and memory linear; the warning then says "at least" (and a cell cut short before its first
/// overlap says nothing).
const MAX_PAIRS_PER_SURFACE: usize = 64;

/// Where a planar surface comes from: an object, and for a mesh its mesh and triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
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

/// What decides whether two surfaces are one plane: the scene's ε, and the origin its positions
/// are stored relative to (`storage_origin`), where f32's spacing is judged.
#[derive(Clone, Copy, Debug)]
struct Resolution {
    epsilon: f64,
    origin: DVec3,
}

impl Surface {
    /// The magnitude of what the tracers store: a triangle's corners relative to the storage
    /// origin, a plane's offset from it.
    fn new(source: Source, normal: DVec3, point: DVec3, corners: Option<[DVec3; 3]>, at: Resolution) -> Option<Self> {
        let normal = oriented(normal)?;
        let magnitude = match &corners {
            Some(c) => c.iter().fold(0.0_f64, |m, p| m.max((*p - at.origin).abs().max_element())),
            None => normal.dot(point - at.origin).abs(),
        };
        let tolerance = (F32_STEPS * f32_spacing(magnitude)).max(at.epsilon);
        let (plane, corners) = (corners.is_none(), corners.unwrap_or([point; 3]));
        Some(Self { source, normal, offset: normal.dot(point), plane, corners, tolerance })
    }

    fn is_plane(&self) -> bool {
        self.plane
    }
}

/// Calls `f` with the cell of the unit `normal` (in its one orientation), and the neighbours
/// across any border it is close to, each packed into a u64 (11 bits a component).
fn cells(normal: DVec3, mut f: impl FnMut(u64)) {
    let mut choices = [[0i64; 2]; 3];
    let mut counts = [1usize; 3];
    for k in 0..3 {
        let x = normal[k] * CELLS;
        let cell = x.floor();
        choices[k][0] = cell as i64;
        if x - cell < BORDER {
            (choices[k][1], counts[k]) = (cell as i64 - 1, 2);
        } else if cell + 1.0 - x < BORDER {
            (choices[k][1], counts[k]) = (cell as i64 + 1, 2);
        }
    }
    let pack = |c: i64| (c + CELLS as i64 + 1) as u64 & 0x7ff;
    for i in 0..counts[0] {
        for j in 0..counts[1] {
            for k in 0..counts[2] {
                f(pack(choices[0][i]) << 22 | pack(choices[1][j]) << 11 | pack(choices[2][k]));
            }
        }
    }
}

/// The smallest cell two oriented unit normals share.
fn first_shared_cell(a: DVec3, b: DVec3) -> Option<u64> {
    let mut of_a = Vec::with_capacity(8);
    cells(a, |c| of_a.push(c));
    let mut shared = None;
    cells(b, |c| {
        if of_a.contains(&c) {
            shared = Some(shared.map_or(c, |s: u64| s.min(c)));
        }
    });
    shared
}

/// A plane's unit normal in its one orientation (the largest component positive), so that
/// back-to-back faces share a cell; `None` for a degenerate one.
fn oriented(normal: DVec3) -> Option<DVec3> {
    let n = normal.try_normalize()?;
    Some(if n[n.abs().max_position()] < 0.0 { -n } else { n })
}

/// What one pair of objects shares.
#[derive(Debug, Default)]
struct Overlap {
    area: f64,
    pairs: usize,
    first: Option<(Source, Source)>,
    /// Whether a cell's search stopped at `MAX_PAIRS_PER_SURFACE`: more pairs than counted.
    cut: bool,
}

impl Overlap {
    fn add(&mut self, area: f64, pair: (Source, Source)) {
        self.merge(Self { area, pairs: 1, first: Some(pair), cut: false });
    }

    /// `other` counted in; `first` stays the smallest pair, whatever order the cells were
    /// compared in.
    fn merge(&mut self, other: Self) {
        self.area += other.area;
        self.pairs += other.pairs;
        self.cut |= other.cut;
        self.first = match (self.first, other.first) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
    }
}

/// Warnings for every pair of objects (or one object with itself) whose planar surfaces
/// overlap coplanar within `epsilon` or the f32 resolution at their stored coordinates
/// (relative to the scene's storage origin).
///
/// Two passes, so that memory stays small on meshes of millions of triangles: every surface's
/// normal cells (one 24-byte entry each, sorted), then the surfaces of each shared cell made
/// whole and compared.
///
/// `origin`: the scene's storage origin (`storage_origin`), where f32's spacing is judged.
pub(super) fn coplanar_overlaps(scene: &SceneDesc, origin: [f64; 3]) -> Vec<FieldIssue> {
    let at = Resolution { epsilon: scene.render.epsilon.max(0.0), origin: DVec3::from(origin) };
    let mut bounds = vec![(DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)); scene.objects.len()];
    // (cell, surface, whether the surface is in more than one cell)
    let mut entries: Vec<(u64, Source, bool)> = Vec::new();
    for_each_normal(&scene.objects, &mut bounds, |source, normal| {
        let first = entries.len();
        cells(normal, |cell| entries.push((cell, source, false)));
        if entries.len() > first + 1 {
            entries[first..].iter_mut().for_each(|e| e.2 = true);
        }
    });
    entries.par_sort_unstable_by_key(|e| e.0);
    // Each shared cell on its own (in parallel); a pair of surfaces that share several cells
    // (near a border) is counted in the smallest of them only.
    // Gathered by pair of objects within each cell: copies of a face make pairs by the million,
    // and a list of them took gigabytes.
    let overlaps: Vec<BTreeMap<(u32, u32), Overlap>> = entries
        .par_chunk_by(|a, b| a.0 == b.0)
        .filter(|run| run.len() > 1)
        .map(|run| {
            let members: Vec<(Surface, bool)> = run
                .iter()
                .filter_map(|&(_, source, several)| surface_of(&scene.objects, source, at).map(|s| (s, several)))
                .collect();
            let cell = run[0].0;
            let mut found: BTreeMap<(u32, u32), Overlap> = BTreeMap::new();
            let budget = MAX_PAIRS_PER_SURFACE * members.len();
            let complete = candidate_pairs(&members, budget, |a, b| {
                let ((sa, several_a), (sb, several_b)) = (&members[a], &members[b]);
                if (*several_a || *several_b) && first_shared_cell(sa.normal, sb.normal) != Some(cell) {
                    return true;
                }
                if let Some(area) = overlap_area(sa, sb) {
                    let (x, y) = if sa.source <= sb.source { (sa.source, sb.source) } else { (sb.source, sa.source) };
                    found.entry((x.object, y.object)).or_default().add(area, (x, y));
                }
                true
            });
            // A cell cut short: every pair of objects found in it may have more.
            if !complete {
                found.values_mut().for_each(|o| o.cut = true);
            }
            found
        })
        .collect();
    let mut found: BTreeMap<(u32, u32), Overlap> = BTreeMap::new();
    for cell in overlaps {
        for (objects, o) in cell {
            found.entry(objects).or_default().merge(o);
        }
    }
    // Each object's size: the diagonal of its faces' bounding box (a plane has none).
    let size2 = |k: u32| {
        let (lo, hi) = bounds[k as usize];
        if lo.x <= hi.x { (hi - lo).length_squared() } else { 0.0 }
    };
    found.retain(|&(i, j), o| o.area >= MIN_VISIBLE * size2(i).max(size2(j)));
    let mut warnings = Vec::new();
    let total = found.len();
    // A search cut short may have missed pairs of objects too.
    let at_least = if found.values().any(|o| o.cut) { "at least " } else { "" };
    for ((i, j), o) in found.into_iter().take(MAX_WARNINGS) {
        let Some((x, y)) = o.first else { continue };
        let name = |k: u32| {
            let object = &scene.objects[k as usize];
            match object.name() {
                "" => format!("objects[{k}] ({})", object.kind_name()),
                named => format!("objects[{k}] ({} `{named}`)", object.kind_name()),
            }
        };
        // An object's own faces can cover one place several times (copies of a face): their
        // pairs' areas add up to more than the place, so the sum is called one.
        let (at_least, summed) = (if o.cut { "at least " } else { "" }, if i == j { "a summed " } else { "an " });
        let area = if o.area.is_finite() {
            format!("{summed}area of {at_least}{:.4e}", o.area)
        } else {
            "the whole plane".to_string()
        };
        let with = if i == j { "overlaps itself".to_string() } else { format!("and {} overlap", name(j)) };
        warnings.push(FieldIssue {
            field: format!("objects[{i}]"),
            problem: format!(
                "{} {with} in one plane over {area} ({at_least}{} pair{} of surfaces, first {} and {}): a ray meets \
                 both at the same t up to rounding, so each tracer picks its own surface pixel by pixel \
                 (z-fighting); move one apart or remove the duplicate",
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
            problem: format!("{at_least}{} more pairs of objects overlap coplanar", total - MAX_WARNINGS),
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

/// Calls `f` with every plane and triangle of the scene (spheres have none) and its oriented
/// unit normal, and grows each object's bounds by its mesh vertices. Only the normal: this
/// runs once per triangle, and the whole surface is made only for those sharing a cell.
fn for_each_normal(objects: &[ObjectDesc], bounds: &mut [(DVec3, DVec3)], mut f: impl FnMut(Source, DVec3)) {
    let mut mesh_normals = |object: u32, k: u32, mesh: &MeshDesc, f: &mut dyn FnMut(Source, DVec3)| {
        let b = &mut bounds[object as usize];
        for &v in &mesh.vertices {
            (b.0, b.1) = (b.0.min(DVec3::from(v)), b.1.max(DVec3::from(v)));
        }
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let corner = |i: u32| mesh.vertices.get(i as usize).map(|&v| DVec3::from(v));
            let (Some(a), Some(b), Some(c)) = (corner(tri[0]), corner(tri[1]), corner(tri[2])) else { continue };
            if let Some(n) = oriented((b - a).cross(c - a)) {
                f(Source { object, mesh: k, triangle: t as u32 }, n);
            }
        }
    };
    for (i, object) in objects.iter().enumerate() {
        let object_index = i as u32;
        match object {
            ObjectDesc::Sphere(_) => {}
            ObjectDesc::Plane(p) => {
                if let Some(n) = oriented(DVec3::from(p.normal)) {
                    f(Source { object: object_index, mesh: 0, triangle: u32::MAX }, n);
                }
            }
            ObjectDesc::Mesh(mesh) => mesh_normals(object_index, 0, mesh, &mut f),
            ObjectDesc::Model(m) => {
                for (k, mesh) in m.loaded.iter().flat_map(|l| l.meshes.iter()).enumerate() {
                    mesh_normals(object_index, k as u32, mesh, &mut f);
                }
            }
        }
    }
}

fn triangle(mesh: &MeshDesc, source: Source, at: Resolution) -> Option<Surface> {
    let tri = mesh.triangles.get(source.triangle as usize)?;
    let corner = |i: u32| mesh.vertices.get(i as usize).map(|&v| DVec3::from(v));
    let (a, b, c) = (corner(tri[0])?, corner(tri[1])?, corner(tri[2])?);
    Surface::new(source, (b - a).cross(c - a), a, Some([a, b, c]), at)
}

/// The surface `source` names, its tolerance at least `at.epsilon`.
fn surface_of(objects: &[ObjectDesc], source: Source, at: Resolution) -> Option<Surface> {
    match objects.get(source.object as usize)? {
        ObjectDesc::Sphere(_) => None,
        ObjectDesc::Plane(p) => Surface::new(source, DVec3::from(p.normal), DVec3::from(p.point), None, at),
        ObjectDesc::Mesh(mesh) => triangle(mesh, source, at),
        ObjectDesc::Model(m) => triangle(m.loaded.as_ref()?.meshes.get(source.mesh as usize)?, source, at),
    }
}

/// A face covering more cells of a grid than this (a large face among small ones, a ground under
/// tiles) goes into a coarser one.
const MAX_FACE_CELLS: i64 = 4096;
/// Each grid's cells are this many times the finer one's across; there are `LEVELS` grids.
const LEVEL_SCALE: f64 = 64.0;
const LEVELS: u8 = 8;
/// The grid has at most this many cells along each axis of the plane.
const MAX_GRID_SIDE: f64 = 65536.0;

/// Calls `pair` with every two of a bucket's surfaces whose extents in the plane overlap
/// (planes overlap everything), until it returns false or `budget` candidates were tested;
/// whether it went through them all. Faces go into uniform grids over the plane's two axes, the
/// finest with cells about a median face across and each next one 64 times coarser, each face
/// into the finest where it covers at most 4,096 cells: a flat grid of k faces costs about k
/// tests, and a large face among small ones meets them through the few coarse cells each small
/// one covers. Each pair is reported once, from the cell holding the lower corner of the two
/// extents' intersection. (A sweep along one axis paired every face with its whole row: 2.7e9
/// pairs and 12 GB for a floor of 700 × 700 quads.)
fn candidate_pairs(members: &[(Surface, bool)], budget: usize, mut pair: impl FnMut(usize, usize) -> bool) -> bool {
    let Some((first, _)) = members.first() else { return true };
    let axis = first.normal.abs().max_position();
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut planes = Vec::new();
    // Each face's extent in (u, v), widened by its tolerance, and its member index.
    let mut faces: Vec<(DVec2, DVec2, usize)> = Vec::new();
    for (m, (s, _)) in members.iter().enumerate() {
        if s.is_plane() {
            planes.push(m);
        } else {
            let flat = s.corners.map(|c| DVec2::new(c[u], c[v]));
            let (lo, hi) = (flat[0].min(flat[1]).min(flat[2]), flat[0].max(flat[1]).max(flat[2]));
            faces.push((lo - s.tolerance, hi + s.tolerance, m));
        }
    }
    // Planes with planes: only those whose offsets are within the largest tolerance of each
    // other (sorted by offset; parallel planes share the cell's orientation), each test counted
    // against the budget: 4,000 copies of one plane made 8e6 pairs (21 s, 877 MB), and 4,000
    // parallel planes 8e6 tests. Planes with faces: each with every face, outside the budget
    // (planes are few; a ground under a million-triangle terrain meets each of them once).
    let mut left = budget;
    planes.sort_by(|&a, &b| members[a].0.offset.total_cmp(&members[b].0.offset));
    let window = planes.iter().map(|&p| members[p].0.tolerance).fold(0.0, f64::max);
    for (k, &p) in planes.iter().enumerate() {
        for &q in &planes[k + 1..] {
            if members[q].0.offset - members[p].0.offset > window {
                break;
            }
            if left == 0 {
                return false;
            }
            left -= 1;
            if !pair(p, q) {
                return false;
            }
        }
        for &(.., f) in &faces {
            if !pair(p, f) {
                return false;
            }
        }
    }
    // A cell holds every face of its normal, at any height: floors stacked in a building, the
    // sides of a voxel terrain. Faces are split into layers that cannot meet (their heights
    // along the first normal, widened by their tolerance and by how far their own normal's
    // difference can carry their corners), and each layer is gridded on its own.
    let n0 = first.normal;
    let height = |m: usize| {
        let s = &members[m].0;
        let reach = s.corners.iter().fold(0.0_f64, |r, c| r.max(c.abs().max_element()));
        (n0.dot(s.corners[0]), s.tolerance + (s.normal - n0).length() * 2.0 * reach)
    };
    let mut layered: Vec<(f64, f64, (DVec2, DVec2, usize))> = faces
        .iter()
        .map(|&f| {
            let (h, slack) = height(f.2);
            (h - slack, h + slack, f)
        })
        .collect();
    layered.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let mut start = 0;
    let mut top = f64::NEG_INFINITY;
    for k in 0..=layered.len() {
        if k == layered.len() || (k > start && layered[k].0 > top) {
            let layer: Vec<(DVec2, DVec2, usize)> = layered[start..k].iter().map(|l| l.2).collect();
            if !grid_pairs(&layer, &mut left, &mut pair) {
                return false;
            }
            (start, top) = (k, f64::NEG_INFINITY);
        }
        if k < layered.len() {
            top = top.max(layered[k].1);
        }
    }
    true
}

/// `candidate_pairs` for the faces of one layer (extent in the plane, member index): a uniform
/// grid per level of size (see `candidate_pairs`). `left` is the budget of candidates still to
/// test; false once it is spent or `pair` says stop.
fn grid_pairs(faces: &[(DVec2, DVec2, usize)], left: &mut usize, pair: &mut impl FnMut(usize, usize) -> bool) -> bool {
    // One candidate tested, reported or not: the tests are what grows with copies of a face.
    let mut test = |a: usize, b: usize, report: bool| {
        if *left == 0 {
            return false;
        }
        *left -= 1;
        !report || pair(a, b)
    };
    if faces.len() < 2 {
        return true;
    }
    let overlap = |a: usize, b: usize| {
        let ((alo, ahi, _), (blo, bhi, _)) = (faces[a], faces[b]);
        alo.cmple(bhi).all() && blo.cmple(ahi).all()
    };
    let lo = faces.iter().fold(DVec2::INFINITY, |m, f| m.min(f.0));
    let span = faces.iter().fold(DVec2::NEG_INFINITY, |m, f| m.max(f.1)) - lo;
    let mut extents: Vec<f64> = faces.iter().map(|(a, b, _)| (*b - *a).max_element()).collect();
    let middle = extents.len() / 2;
    let median = *extents.select_nth_unstable_by(middle, f64::total_cmp).1;
    let cell = median.max(span.max_element() / MAX_GRID_SIDE).max(f64::MIN_POSITIVE);
    // The cell of point `p` in grid `level`.
    let index = |p: DVec2, level: u8| {
        let i = ((p - lo) / (cell * LEVEL_SCALE.powi(i32::from(level)))).floor().min(DVec2::splat(MAX_GRID_SIDE));
        (i.x.max(0.0) as i64, i.y.max(0.0) as i64)
    };
    let cells = |f: usize, level: u8| (index(faces[f].0, level), index(faces[f].1, level));
    // Each face in the finest grid where it covers at most MAX_FACE_CELLS cells.
    let mut entries: Vec<(u8, (i64, i64), usize)> = Vec::with_capacity(faces.len() * 4);
    let mut level_of = vec![0u8; faces.len()];
    for (f, level_of_f) in level_of.iter_mut().enumerate() {
        let level = (0..LEVELS)
            .find(|&l| {
                let ((i0, j0), (i1, j1)) = cells(f, l);
                (i1 - i0 + 1) * (j1 - j0 + 1) <= MAX_FACE_CELLS
            })
            .unwrap_or(LEVELS - 1);
        *level_of_f = level;
        let ((i0, j0), (i1, j1)) = cells(f, level);
        for i in i0..=i1 {
            entries.extend((j0..=j1).map(|j| (level, (i, j), f)));
        }
    }
    entries.sort_unstable();
    // Two faces of one grid: from the cell holding the lower corner of their boxes'
    // intersection, which both cover.
    for run in entries.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
        for (k, &(level, here, a)) in run.iter().enumerate() {
            for &(_, _, b) in &run[k + 1..] {
                let report = overlap(a, b) && index(faces[a].0.max(faces[b].0), level) == here;
                if !test(faces[a].2, faces[b].2, report) {
                    return false;
                }
            }
        }
    }
    // A face and the faces of each coarser grid, found in the few coarse cells it covers, again
    // from the cell of the intersection's lower corner.
    let used: std::collections::BTreeSet<u8> = level_of.iter().copied().collect();
    for a in 0..faces.len() {
        for &level in used.range(level_of[a] + 1..) {
            let ((i0, j0), (i1, j1)) = cells(a, level);
            for i in i0..=i1 {
                for j in j0..=j1 {
                    let start = entries.partition_point(|e| (e.0, e.1) < (level, (i, j)));
                    for &(_, _, b) in entries[start..].iter().take_while(|e| (e.0, e.1) == (level, (i, j))) {
                        let report = overlap(a, b) && index(faces[a].0.max(faces[b].0), level) == (i, j);
                        if !test(faces[a].2, faces[b].2, report) {
                            return false;
                        }
                    }
                }
            }
        }
    }
    true
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
    use crate::desc::test_scene as scene;
    use crate::{MeshDesc, PlaneDesc};

    fn mesh(vertices: Vec<[f64; 3]>, triangles: Vec<[u32; 3]>, name: &str) -> ObjectDesc {
        ObjectDesc::Mesh(MeshDesc::new(vertices, triangles, "m", name))
    }

    /// The warnings for `scene`, at its own storage origin, as validation gives them.
    fn overlaps(scene: &SceneDesc) -> Vec<FieldIssue> {
        coplanar_overlaps(scene, crate::storage_origin(scene))
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
        assert!(w[0].problem.contains("objects[0] (mesh `a`) and objects[1] (mesh `b`)"), "{}", w[0].problem);
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
    fn copies_of_one_face_are_counted_to_a_bound_not_paired_all() {
        // 2,000 copies: 2e6 pairs, which the search paired all (6,000 took 17 s and 1.1 GB).
        let copies = 2_000;
        let m = mesh(vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2]; copies], "copies");
        let w = overlaps(&scene(vec![m]));
        assert_eq!(w.len(), 1, "{w:?}");
        let said = &w[0].problem;
        assert!(said.contains("overlaps itself in one plane over a summed area of at least"), "{said}");
        assert!(said.contains("(at least "), "{said}");
    }

    #[test]
    fn copies_of_one_plane_are_counted_to_a_bound_and_parallel_planes_are_not_paired() {
        let plane = |y: f64| {
            ObjectDesc::Plane(PlaneDesc {
                point: [0.0, y, 0.0],
                normal: [0.0, 1.0, 0.0],
                material: "m".into(),
                name: "".into(),
            })
        };
        // 2,000 parallel planes 1 apart: none overlaps, and each is tested against none of the
        // others (all 2e6 pairs were tested).
        let apart: Vec<ObjectDesc> = (0..2_000).map(|y| plane(f64::from(y))).collect();
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
        // 2,000 copies: 2e6 pairs, all of which were kept (4,000 took 21 s and 877 MB).
        let w = overlaps(&scene(vec![plane(0.5); 2_000]));
        assert_eq!(w.len(), MAX_WARNINGS + 1, "{w:?}");
        assert!(w[0].problem.contains("over the whole plane (at least 1 pair"), "{}", w[0].problem);
        assert!(w[MAX_WARNINGS].problem.starts_with("at least "), "{}", w[MAX_WARNINGS].problem);
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
        assert!(w[0].problem.contains("objects[24] (mesh `floor 24`) overlaps itself"), "{}", w[0].problem);
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
            w[0].problem.contains("and objects[1] (mesh `ground`) overlap")
                && w[0].problem.contains("area of 2.2500e4"),
            "{}",
            w[0].problem
        );
    }
}

#[cfg(test)]
mod bumpy {
    use super::*;

    /// The bumpy sphere folds slivers at its poles within an f32 step of each other's plane:
    /// overlaps of 9e-8 on a sphere 2.9 units across, which no pixel shows.
    #[test]
    fn the_bumpy_spheres_pole_is_not_warned() {
        // The built-in scene's default resolution (glint-io's `DEFAULT_RESOLUTION`).
        let desc = crate::bumpy::bumpy(500);
        assert!(coplanar_overlaps(&desc, crate::storage_origin(&desc)).is_empty());
    }
}
