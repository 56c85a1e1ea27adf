//! The area two coplanar surfaces share: the triangles clipped against each other in the plane
//! of the normal's dominant axis.

use glam::{DVec2, DVec3};

use super::surface::Surface;

/// An overlap below this share of the smaller face is a shared edge or corner, not an overlap.
const MIN_SHARE: f64 = 1e-6;

/// The area two surfaces share in one plane, or `None` when they are not coplanar or only
/// touch. Two planes share an infinite area.
pub(super) fn overlap_area(a: &Surface, b: &Surface) -> Option<f64> {
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

pub(super) fn triangle_area(c: &[DVec3]) -> f64 {
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
