//! A model's polygon faces as triangles that cover exactly the polygon. A convex polygon is
//! a fan from its first vertex (what every importer does, and what Glint always did); a
//! concave one, which a fan would cover with overlapping triangles of both orientations
//! (z-fighting speckles and holes), is cut into ears (`earcut`) in its own plane.

/// How one polygon was cut.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Cut {
    /// A triangle, or a convex polygon (or one with no plane: collinear or a point) as a fan.
    Fan,
    /// A concave polygon cut into ears, n − 2 triangles.
    Ears,
    /// A polygon whose edges cross: its ears cover fewer than n − 2 triangles.
    SelfIntersecting,
}

/// Appends the triangles of `polygon` (indices into `positions`, in the file's order) to
/// `out`, each turning as the polygon turns.
pub(super) fn triangulate(positions: &[[f64; 3]], polygon: &[u32], out: &mut Vec<[u32; 3]>) -> Cut {
    let fan = |out: &mut Vec<[u32; 3]>| out.extend(polygon.windows(2).skip(1).map(|w| [polygon[0], w[0], w[1]]));
    // Most faces are triangles: no plane to find.
    if polygon.len() == 3 {
        fan(out);
        return Cut::Fan;
    }
    let at = |i: u32| positions[i as usize];
    let normal = newell_normal(polygon.iter().map(|&i| at(i)));
    if normal == [0.0; 3] {
        // No net area: a point, collinear corners, or lobes of opposite turn that cancel (a
        // bow-tie `f 1 2 3 4` over (0,0) (1,0) (0,1) (1,1)), whose edges cross.
        let lobes = polygon.windows(2).skip(1).any(|w| {
            let (a, b, c) = (at(polygon[0]), at(w[0]), at(w[1]));
            let (e, f) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
            [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]] != [0.0; 3]
        });
        fan(out);
        return if lobes { Cut::SelfIntersecting } else { Cut::Fan };
    }
    if is_convex(polygon.len(), |k| at(polygon[k]), normal) {
        fan(out);
        return Cut::Fan;
    }
    // The plane's coordinates: the two axes the normal leans on least, in the order that
    // keeps the polygon's turn (so each ear can be oriented against it).
    let k = (0..3).max_by(|&a, &b| normal[a].abs().total_cmp(&normal[b].abs())).unwrap_or(2);
    let (u, v) = if normal[k] > 0.0 { ((k + 1) % 3, (k + 2) % 3) } else { ((k + 2) % 3, (k + 1) % 3) };
    let flat: Vec<[f64; 2]> = polygon.iter().map(|&i| [at(i)[u], at(i)[v]]).collect();
    let mut ears: Vec<u32> = Vec::with_capacity(3 * (polygon.len() - 2));
    earcut::Earcut::new().earcut(flat.iter().copied(), &[], &mut ears);
    let before = out.len();
    for t in ears.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        let turn = (flat[b][0] - flat[a][0]) * (flat[c][1] - flat[a][1])
            - (flat[b][1] - flat[a][1]) * (flat[c][0] - flat[a][0]);
        // The plane's axes keep the polygon counter-clockwise: an ear turning the other way
        // is written the other way round.
        out.push(if turn >= 0.0 { [a, b, c] } else { [a, c, b] }.map(|i| polygon[i]));
    }
    // Ears that do not cover the outline's area (a repeated vertex drops an ear but not area).
    let covered = earcut::deviation(flat.iter().copied(), &[] as &[u32], &ears);
    // NaN (no area at all) counts as not covered.
    if out.len() > before && covered <= 1e-6 { Cut::Ears } else { Cut::SelfIntersecting }
}

/// The polygon's area-weighted normal (Newell's method): exact for a planar polygon, the
/// best plane's for a slightly bent one, zero for one without area.
fn newell_normal(points: impl Iterator<Item = [f64; 3]> + Clone) -> [f64; 3] {
    let next = points.clone().cycle().skip(1);
    points.zip(next).fold([0.0; 3], |n, (p, q)| {
        [
            n[0] + (p[1] - q[1]) * (p[2] + q[2]),
            n[1] + (p[2] - q[2]) * (p[0] + q[0]),
            n[2] + (p[0] - q[0]) * (p[1] + q[1]),
        ]
    })
}

/// Whether every corner of the ring `corner(0..n)` turns the way `normal` says. A corner
/// straight to within rounding (a vertex on an edge: a T-junction) counts as turning that way,
/// so that such a convex face stays the fan every importer makes of it.
fn is_convex(n: usize, corner: impl Fn(usize) -> [f64; 3], normal: [f64; 3]) -> bool {
    let length = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let scale = length(normal);
    (0..n).all(|i| {
        let (p, q, r) = (corner((i + n - 1) % n), corner(i), corner((i + 1) % n));
        let (e, f) = ([q[0] - p[0], q[1] - p[1], q[2] - p[2]], [r[0] - q[0], r[1] - q[1], r[2] - q[2]]);
        let cross = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
        let turn = cross[0] * normal[0] + cross[1] * normal[1] + cross[2] * normal[2];
        turn >= -STRAIGHT * length(e) * length(f) * scale
    })
}

/// The sine of the angle below which a corner counts as straight.
const STRAIGHT: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    fn area_and_normal(positions: &[[f64; 3]], triangles: &[[u32; 3]]) -> (f64, [f64; 3]) {
        triangles.iter().fold((0.0, [0.0; 3]), |(area, sum), t| {
            let [a, b, c] = t.map(|i| positions[i as usize]);
            let (e, f) = ([b[0] - a[0], b[1] - a[1], b[2] - a[2]], [c[0] - a[0], c[1] - a[1], c[2] - a[2]]);
            let n = [e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]];
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            (area + len / 2.0, [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]])
        })
    }

    #[test]
    fn a_convex_polygon_with_a_vertex_on_an_edge_within_rounding_is_still_the_fan() {
        // (0.03, 0.21, 0.3) lies on the edge from the origin to (0.1, 0.7, 1) in decimal, not in
        // binary.
        let quad = [[0.0, 0.0, 0.0], [0.03, 0.21, 0.3], [0.1, 0.7, 1.0], [-0.7, 0.1, 0.0]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&quad, &[0, 1, 2, 3], &mut out), Cut::Fan);
        assert_eq!(out, [[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn a_bow_tie_whose_lobes_cancel_is_a_polygon_whose_edges_cross() {
        // Newell's normal is exactly 0: the two lobes turn opposite ways with equal areas.
        let bow_tie = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&bow_tie, &[0, 1, 2, 3], &mut out), Cut::SelfIntersecting);
        let line = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
        assert_eq!(triangulate(&line, &[0, 1, 2, 3], &mut Vec::new()), Cut::Fan, "no area is no crossing");
    }

    #[test]
    fn a_convex_polygon_is_the_fan_from_its_first_vertex() {
        let square = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.5, 1.0, 0.0], [0.0, 1.0, 0.0]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&square, &[0, 1, 2, 3, 4], &mut out), Cut::Fan, "a straight corner is convex");
        assert_eq!(out, [[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    }

    #[test]
    fn a_concave_polygon_is_cut_into_ears_covering_its_area_once_facing_its_way() {
        // An L in the plane x = 2 (area 3), both ways round, and a U bent slightly out of plane.
        let l = [[2.0, 0.0, 0.0], [2.0, 2.0, 0.0], [2.0, 2.0, 1.0], [2.0, 1.0, 1.0], [2.0, 1.0, 2.0], [2.0, 0.0, 2.0]];
        // From (2, 2, 1), beside the notch, a fan covers the notch too.
        for order in [[2u32, 3, 4, 5, 0, 1], [2, 1, 0, 5, 4, 3]] {
            let mut out = Vec::new();
            assert_eq!(triangulate(&l, &order, &mut out), Cut::Ears);
            assert_eq!(out.len(), 4);
            let (area, normal) = area_and_normal(&l, &out);
            let expected = newell_normal(order.iter().map(|&i| l[i as usize]));
            assert!((area - 3.0).abs() < 1e-12, "area {area}: the ears overlap or leave a hole");
            assert!((normal[0] - expected[0]).abs() < 1e-12 && normal[0].abs() > 5.9, "{normal:?} {expected:?}");
        }
        let ring = [2u32, 3, 4, 5, 0, 1];
        let fan: Vec<[u32; 3]> = ring.windows(2).skip(1).map(|w| [ring[0], w[0], w[1]]).collect();
        assert!(area_and_normal(&l, &fan).0 > 3.0 + 1e-9, "the fan this replaces overlaps itself");
    }

    #[test]
    fn a_self_intersecting_or_flat_polygon_is_named_or_fanned() {
        let bow = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.5, 2.0, 0.0]];
        let mut out = Vec::new();
        assert_eq!(triangulate(&bow, &[0, 1, 2, 3, 4], &mut out), Cut::SelfIntersecting);
        // A repeated vertex in a concave face drops an ear, not area.
        let l = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 2.0, 0.0]];
        out.clear();
        assert_eq!(triangulate(&l, &[0, 1, 2, 2, 3, 4, 5], &mut out), Cut::Ears);
        let line = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]];
        out.clear();
        assert_eq!(triangulate(&line, &[0, 1, 2, 3], &mut out), Cut::Fan, "no plane: the fan, as before");
        assert_eq!(out.len(), 2);
    }
}
