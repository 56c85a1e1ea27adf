//! Which surfaces of one normal cell are compared: planes by their offsets, faces through
//! uniform grids over the plane, layer by layer, within a budget of tests.

use glam::DVec2;

use super::surface::Surface;

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
pub(super) fn candidate_pairs(
    members: &[(Surface, bool)],
    budget: usize,
    mut pair: impl FnMut(usize, usize) -> bool,
) -> bool {
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
    // A cell holds every face of its normal, at any height: floors stacked in a building, the
    // sides of a voxel terrain. Each face's height along the first normal, and how far it may
    // be off (its tolerance, and how far its own normal's difference can carry its corners).
    let n0 = first.normal;
    let height = |m: usize| {
        let s = &members[m].0;
        let reach = s.corners.iter().fold(0.0_f64, |r, c| r.max(c.abs().max_element()));
        (n0.dot(s.corners[0]), s.tolerance + (s.normal - n0).length() * 2.0 * reach)
    };
    // Planes are paired only with surfaces near their height, each test counted against the
    // budget: 4,000 copies of one plane made 8e6 pairs (21 s, 877 MB), 4,000 parallel planes
    // 8e6 tests, and 4,000 planes over an 80,000-face floor 3.2e8 (72 s). Planes with planes
    // within the largest tolerance of each other's offset (sorted; parallel planes share the
    // cell's orientation); planes with the faces whose height is within that tolerance and how
    // far the plane's normal and the face's corners carry it (sorted by height).
    let mut left = budget;
    planes.sort_by(|&a, &b| members[a].0.offset.total_cmp(&members[b].0.offset));
    let tolerance = members.iter().map(|(s, _)| s.tolerance).fold(0.0, f64::max);
    // Only a cell with planes needs the faces by height (a million-face mesh has none).
    let (reach, by_height) = if planes.is_empty() {
        (0.0, Vec::new())
    } else {
        let reach = faces
            .iter()
            .map(|f| members[f.2].0.corners.iter().fold(0.0_f64, |r, c| r.max(c.abs().max_element())))
            .fold(0.0, f64::max);
        let mut by_height: Vec<(f64, usize)> = faces.iter().map(|f| (height(f.2).0, f.2)).collect();
        by_height.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        (reach, by_height)
    };
    let mut test = |a: usize, b: usize| {
        if left == 0 {
            return false;
        }
        left -= 1;
        pair(a, b)
    };
    for (k, &p) in planes.iter().enumerate() {
        let plane = &members[p].0;
        for &q in &planes[k + 1..] {
            if members[q].0.offset - plane.offset > tolerance {
                break;
            }
            if !test(p, q) {
                return false;
            }
        }
        let window = 2.0 * tolerance + (plane.normal - n0).length() * 2.0 * reach;
        let from = by_height.partition_point(|(h, _)| *h < plane.offset - window);
        for &(h, f) in &by_height[from..] {
            if h > plane.offset + window {
                break;
            }
            if !test(p, f) {
                return false;
            }
        }
    }
    // The faces split into layers that cannot meet, each gridded on its own.
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
