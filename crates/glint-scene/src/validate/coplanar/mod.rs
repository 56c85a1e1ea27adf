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

use glam::DVec3;
use rayon::prelude::*;

use super::super::desc::{ObjectDesc, SceneDesc};
use super::super::error::FieldIssue;
use super::super::mesh::MeshDesc;
use area::overlap_area;
use pairs::candidate_pairs;
use surface::{Resolution, Source, Surface, oriented, surface_of};

mod area;
mod pairs;
mod surface;
#[cfg(test)]
mod tests;

/// Normal cells per unit of each component.
const CELLS: f64 = 1024.0;
/// A normal this close (in cells) to a cell border goes into both cells.
const BORDER: f64 = 0.01;
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

/// A surface of a cell, and whether it is in more than one cell.
type Member = (Surface, bool);

/// `members` without the triangles whose corners are bit for bit another's (in any order), and those copies
/// with the index (in what is kept) of the first they copy.
fn without_copies(mut members: Vec<Member>) -> (Vec<Member>, Vec<(usize, Member)>) {
    // In file order, so that the copy kept, and the first pair a warning names, are the same
    // on every run (a cell's members come from an unstable sort).
    members.sort_by_key(|m| m.0.source);
    let mut first: std::collections::HashMap<[u64; 9], usize> = std::collections::HashMap::new();
    let (mut kept, mut copies) = (Vec::with_capacity(members.len()), Vec::new());
    for member in members {
        if member.0.is_plane() {
            kept.push(member);
            continue;
        }
        // The corners in a fixed order: a copy of reversed winding is the same triangle.
        let mut corners = member.0.corners.map(|c| c.to_array().map(f64::to_bits));
        corners.sort_unstable();
        let key: [u64; 9] = std::array::from_fn(|k| corners[k / 3][k % 3]);
        match first.entry(key) {
            std::collections::hash_map::Entry::Occupied(at) => copies.push((*at.get(), member)),
            std::collections::hash_map::Entry::Vacant(slot) => {
                slot.insert(kept.len());
                kept.push(member);
            }
        }
    }
    (kept, copies)
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
/// `epsilon`: the render's ε (the scene's `render.epsilon`, or a flag's).
pub(super) fn coplanar_overlaps(scene: &SceneDesc, origin: [f64; 3], epsilon: f64) -> Vec<FieldIssue> {
    // Within validation's range: the check runs before render.epsilon's own is refused, and
    // ε = 1e308 made the tolerance infinite and the grid fill memory (10 GB in 15 s).
    let epsilon = match epsilon {
        e if e.is_nan() => 0.0,
        e => e.clamp(0.0, crate::limits::MAX_EPSILON),
    };
    let at = Resolution { epsilon, origin: DVec3::from(origin) };
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
            // `times` pairs like a and b (copies of one triangle, see below).
            let mut compare = |a: &(Surface, bool), b: &(Surface, bool), times: usize| {
                let ((sa, several_a), (sb, several_b)) = (a, b);
                if (*several_a || *several_b) && first_shared_cell(sa.normal, sb.normal) != Some(cell) {
                    return;
                }
                if let Some(area) = overlap_area(sa, sb) {
                    let (x, y) = if sa.source <= sb.source { (sa.source, sb.source) } else { (sb.source, sa.source) };
                    let pairs = Overlap { area: area * times as f64, pairs: times, first: Some((x, y)), cut: false };
                    found.entry((x.object, y.object)).or_default().merge(pairs);
                }
            };
            // Copies of one triangle, corner for corner, are compared with their first copy once
            // each, the j-th standing for its j pairs with the first and the copies before it,
            // and leave the search: 200,000 copies made 1.3e7 candidate tests (22 s), each a
            // polygon clip, and were counted to the search's bound only.
            let (members, copies) = without_copies(members);
            let mut before = vec![0; members.len()];
            for (first, copy) in &copies {
                before[*first] += 1;
                compare(&members[*first], copy, before[*first]);
            }
            let budget = MAX_PAIRS_PER_SURFACE * members.len();
            let complete = candidate_pairs(&members, budget, |a, b| {
                compare(&members[a], &members[b], 1);
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
        // The field names objects[i] already: the message goes on from it ("objects[1]: the
        // plane overlaps …", not "objects[1]: objects[1] (plane) and …").
        let this = {
            let object = &scene.objects[i as usize];
            match object.name() {
                "" => format!("the {}", object.kind_name()),
                named => format!("the {} `{named}`", object.kind_name()),
            }
        };
        let with = if i == j { "itself".to_string() } else { name(j) };
        warnings.push(FieldIssue {
            field: format!("objects[{i}]"),
            problem: format!(
                "{this} overlaps {with} in one plane over {area} ({at_least}{} pair{} of surfaces, first {} and {}): a \
                 ray meets both at the same t up to rounding, so each tracer picks its own surface pixel by pixel \
                 (z-fighting); move one apart or remove the duplicate",
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
