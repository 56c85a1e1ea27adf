//! Where a scene's f32 storage has its origin. Both tracers read positions stored in f32; in
//! world space a model 1e6 units from the world origin would be stored to 1/16 of a unit, on
//! the CPU reference too. Stored relative to an origin at the bounded geometry instead, f32
//! carries the distances within the scene, and the f64 reference is exact again for the scene
//! the file describes (to f32 of the scene's own size).

use glam::DVec3;

use crate::camera::ViewSpread;
use crate::{ObjectDesc, PlaneDesc, Projection, SceneDesc, SphereDesc};

/// How many of its largest sides a scene's box may have its centre from the world origin and
/// still be stored in world space: f32 then keeps all but log2(64) = 6 of its 24 bits for the
/// scene's own size (2^-18 of it, 4e-6), far below what an image shows, and a scene made
/// around the origin keeps its bits.
const WORLD_SPACE_REACH: f64 = 64.0;

/// The origin of `desc`'s stored coordinates (`SceneHeader::frame` once flattened): the world
/// origin for geometry around it, else the centre of the box around the bounded geometry
/// (spheres, meshes and models; planes, lights and the camera are unbounded or points, and
/// follow; in a scene of planes alone, what the eye sees of them, `seen_of_planes`) snapped to
/// a grid of the power of two nearest the box's largest side and rounded to f32 — the header
/// stores it in f32, so it is exact there.
///
/// Why the world origin for geometry around it (the box's centre within `WORLD_SPACE_REACH` of
/// its largest sides from the origin on every axis): there, world coordinates lose little over
/// coordinates relative to the box's centre, and the scenes that were always stored in world
/// space keep their bits (their images are unchanged, golden hashes included).
///
/// Why a grid: translating a scene by a multiple of its spacing moves the origin by exactly as
/// much, so the stored scene — hence both tracers' images — is the same bit for bit wherever
/// such a scene sits, as long as its coordinates are exact at both places.
///
/// Why the eye's neighbourhood in place of the box, where the camera cannot see the box
/// (`eye_neighbourhood`): the digits belong to what is seen, and stored around a box far away,
/// the eye and the plane beside it would be rounded to the box's distance.
pub fn storage_origin(desc: &SceneDesc) -> [f64; 3] {
    storage_origin_within(desc, bounded_box(desc))
}

/// `storage_origin` of `desc` whose bounded geometry spans `bounds` (`bounded_box`): for a
/// caller that keeps the box, to judge another camera without walking the vertices again.
pub fn storage_origin_within(desc: &SceneDesc, bounds: Option<(DVec3, DVec3)>) -> [f64; 3] {
    match bounds {
        Some((lo, hi)) => {
            let (lo, hi) = eye_neighbourhood(desc, lo, hi).unwrap_or((lo, hi));
            storage_origin_of_box(lo.to_array(), hi.to_array())
        }
        None => seen_of_planes(desc).map_or([0.0; 3], |(lo, hi)| storage_origin_of_box(lo.to_array(), hi.to_array())),
    }
}

/// Whether the box `bounds` around `desc`'s bounded geometry (`bounded_box`) is far from the
/// eye (more than `WORLD_SPACE_REACH` of its largest sides, as the camera's anchoring judges a
/// far eye) and out of the camera's sight (`CameraDesc::may_see` of the ball around it): the
/// one judgement both the storage origin and the camera's anchoring (`FlatScene`) follow.
pub fn far_box_out_of_sight(desc: &SceneDesc, bounds: Option<(DVec3, DVec3)>) -> bool {
    bounds.is_some_and(|(lo, hi)| box_far_out_of_sight(desc, lo, hi))
}

fn box_far_out_of_sight(desc: &SceneDesc, lo: DVec3, hi: DVec3) -> bool {
    let eye = DVec3::from(desc.camera.position);
    let (centre, side) = ((lo + hi) * 0.5, (hi - lo).max_element());
    (centre - eye).length() > WORLD_SPACE_REACH * side
        && !desc.camera.may_see(centre.to_array(), 0.5 * (hi - lo).length())
}

/// The box around the eye out to its nearest plane (`around_the_eye`), where it takes the place
/// of the bounded geometry's box `lo`..`hi`: where that box is far and out of sight
/// (`far_box_out_of_sight`) and a plane passes the eye. A floor 0.01 under an eye with a sphere
/// 3e5 behind it, stored around the sphere, was level with the stored eye, and vanished from the
/// image.
fn eye_neighbourhood(desc: &SceneDesc, lo: DVec3, hi: DVec3) -> Option<(DVec3, DVec3)> {
    if !box_far_out_of_sight(desc, lo, hi) {
        return None;
    }
    seen_of_planes(desc)
}

/// What the eye sees of the planes, which have no size: for a narrow view
/// (`CameraDesc::is_narrow`) that sees all of them only near where its axis meets the nearest,
/// the patch there, as high as the view (`the_patch_seen`); else the box around the eye out to
/// its nearest plane (`around_the_eye`).
///
/// Why the patch: a narrow view's eye is anchored there (`glint_core`'s `WorldCamera::stored`),
/// and what it shows lies within its view of it; stored around a far eye, the plane's offset
/// and the anchor were rounded to the eye's distance, which a grazing view magnifies along
/// the ground (an orthographic view 4 high, 0.1° over a checkered plane from 1e6: 881 of 19,200
/// pixels of the CPU's image on the wrong square). Why the eye otherwise: a wider view sees the
/// plane near the eye too, and f32 holds it to the eye's height over it; in world space a floor
/// 2 under an eye at 1e7 was lit 20 % off (the eye, the light and the plane's offset rounded
/// to 1). An eye whose neighbourhood is stored in world space stays so, with its bits.
fn seen_of_planes(desc: &SceneDesc) -> Option<(DVec3, DVec3)> {
    let near = around_the_eye(desc);
    let in_world_space = near.is_some_and(|(lo, hi)| storage_origin_of_box(lo.to_array(), hi.to_array()) == [0.0; 3]);
    if in_world_space {
        return near;
    }
    the_patch_seen(desc).or(near)
}

/// A plane as the eye sees it: its unit normal towards the eye, and the eye's height over it.
fn facing_the_eye(point: [f64; 3], normal: [f64; 3], eye: DVec3) -> Option<(DVec3, f64)> {
    let n = DVec3::from(normal).try_normalize()?;
    let h = n.dot(eye - DVec3::from(point));
    (h.is_finite() && h != 0.0).then(|| if h > 0.0 { (n, h) } else { (-n, -h) })
}

/// The patch of the nearest plane a narrow view's axis meets ahead of the eye, as high as the
/// view is there: `None` for a wider view, an axis that meets no plane, or a view whose rays
/// meet some plane (that one or another: a wall beside the eye) nearer than half that
/// distance, or the plane it looks at beyond twice it — a view within its field of grazing
/// the plane sees it from near its eye to the horizon. Judged at the corners of a
/// `WIDEST_ASPECT` image, as `CameraDesc::may_see` judges.
fn the_patch_seen(desc: &SceneDesc) -> Option<(DVec3, DVec3)> {
    let c = &desc.camera;
    if !c.is_narrow() {
        return None;
    }
    let eye = DVec3::from(c.position);
    let axis = (DVec3::from(c.look_at) - eye).try_normalize()?;
    let planes: Vec<(f64, f64)> = desc
        .objects
        .iter()
        .filter_map(|object| match object {
            // Each plane's eye height h and the sine of the axis's angle towards it.
            ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
                facing_the_eye(*point, *normal, eye).map(|(n, h)| (h, -n.dot(axis)))
            }
            ObjectDesc::Sphere(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
        })
        .collect();
    let (h, sin_e) = planes.iter().copied().filter(|p| p.1 > 0.0).min_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)))?;
    let t = h / sin_e;
    let view = c.spread();
    let farthest = view.farthest(h, sin_e);
    if farthest > 2.0 * t || planes.iter().any(|&(h, sin_e)| view.nearest(h, sin_e) < 0.5 * t) {
        return None;
    }
    let half = 0.5
        * match c.projection {
            Projection::Orthographic => c.view_height(),
            Projection::Perspective => 2.0 * t * c.tan_half_fov(),
        };
    let patch = eye + t * axis;
    (half.is_finite() && half > 0.0).then_some((patch - half, patch + half))
}

/// What a view's spread (`CameraDesc::spread`) sees of a plane.
impl ViewSpread {
    /// The nearest any ray meets a plane the eye is `h` over, the axis heading towards it at an
    /// angle whose sine is `sin_e` (∞ where none does).
    fn nearest(&self, h: f64, sin_e: f64) -> f64 {
        match *self {
            ViewSpread::Angle(spread) => {
                let steepest = (sin_e.clamp(-1.0, 1.0).asin() + spread).min(std::f64::consts::FRAC_PI_2);
                if steepest > 0.0 { h / steepest.sin() } else { f64::INFINITY }
            }
            ViewSpread::Across(across) => {
                let cos_e = (1.0 - sin_e * sin_e).max(0.0).sqrt();
                if sin_e > 0.0 { (h - across * cos_e).max(0.0) / sin_e } else { f64::INFINITY }
            }
        }
    }

    /// The farthest any ray meets the plane the axis meets (`sin_e` > 0; ∞ where a ray misses it).
    fn farthest(&self, h: f64, sin_e: f64) -> f64 {
        match *self {
            ViewSpread::Angle(spread) => {
                let shallowest = sin_e.clamp(-1.0, 1.0).asin() - spread;
                if shallowest > 0.0 { h / shallowest.sin() } else { f64::INFINITY }
            }
            ViewSpread::Across(across) => (h + across * (1.0 - sin_e * sin_e).max(0.0).sqrt()) / sin_e,
        }
    }
}

/// The box around the eye out to its nearest plane, `None` when no plane passes it (at a
/// finite, non-zero height).
fn around_the_eye(desc: &SceneDesc) -> Option<(DVec3, DVec3)> {
    let eye = DVec3::from(desc.camera.position);
    let heights = desc.objects.iter().filter_map(|object| match object {
        ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
            let h = DVec3::from(*normal).normalize().dot(eye - DVec3::from(*point)).abs();
            (h.is_finite() && h > 0.0).then_some(h)
        }
        ObjectDesc::Sphere(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
    });
    let height = heights.min_by(f64::total_cmp)?;
    Some((eye - height, eye + height))
}

/// `storage_origin` of a scene whose bounded geometry spans `lo`..`hi` (finite).
pub fn storage_origin_of_box(lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
    let (lo, hi) = (DVec3::from(lo), DVec3::from(hi));
    let centre = (lo + hi) * 0.5;
    let side = (hi - lo).max_element();
    if centre.abs().max_element() <= WORLD_SPACE_REACH * side || !centre.is_finite() {
        return [0.0; 3];
    }
    let snapped = if side > 0.0 {
        let g = 2f64.powi(side.log2().round().clamp(-1000.0, 1000.0) as i32);
        (centre / g).round() * g
    } else {
        centre
    };
    let origin = snapped.to_array().map(|c| f64::from(c as f32));
    // Beyond f32's range (values validation has yet to refuse): world space, as stored before.
    if origin.iter().all(|c| c.is_finite()) { origin } else { [0.0; 3] }
}

/// The largest side of the box around the scene's bounded geometry (spheres, meshes and models;
/// `None` without any): its size, as the storage origin and the offsets judge it.
pub fn scene_extent(desc: &SceneDesc) -> Option<f64> {
    bounded_box(desc).map(|(lo, hi)| (hi - lo).max_element())
}

/// The box around every finite sphere and vertex of the scene (`None` without any): what
/// validation has yet to judge is skipped, not trusted.
pub fn bounded_box(desc: &SceneDesc) -> Option<(DVec3, DVec3)> {
    let mut lo = DVec3::INFINITY;
    let mut hi = DVec3::NEG_INFINITY;
    let mut add = |p: DVec3| {
        if p.is_finite() {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    };
    for object in &desc.objects {
        match object {
            ObjectDesc::Sphere(SphereDesc { center, radius, .. }) if radius.is_finite() => {
                add(DVec3::from(*center) - *radius);
                add(DVec3::from(*center) + *radius);
            }
            ObjectDesc::Mesh(mesh) => mesh.vertices.iter().for_each(|&v| add(DVec3::from(v))),
            ObjectDesc::Model(model) => {
                for mesh in model.loaded.iter().flat_map(|m| &m.meshes) {
                    mesh.vertices.iter().for_each(|&v| add(DVec3::from(v)));
                }
            }
            ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) => {}
        }
    }
    (lo.x <= hi.x).then_some((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::MeshDesc;
    use crate::desc::test_scene as with;

    fn sphere(center: [f64; 3], radius: f64) -> ObjectDesc {
        ObjectDesc::Sphere(SphereDesc { center, radius, material: "m".into(), name: String::new() })
    }

    fn triangle(offset: [f64; 3], size: f64) -> ObjectDesc {
        let at = |x: f64, y: f64| [offset[0] + x * size, offset[1] + y * size, offset[2]];
        ObjectDesc::Mesh(MeshDesc::new(vec![at(0.0, 0.0), at(1.0, 0.0), at(0.0, 1.0)], vec![[0, 1, 2]], "m", ""))
    }

    #[test]
    fn geometry_around_the_world_origin_is_stored_in_world_space() {
        assert_eq!(storage_origin(&with(vec![])), [0.0; 3]);
        assert_eq!(storage_origin(&with(vec![sphere([0.5, 1.0, 0.0], 1.0)])), [0.0; 3]);
        // The box's centre 256 from the origin, its side 4: still world space; 260: not.
        assert_eq!(storage_origin(&with(vec![sphere([256.0, 0.0, 0.0], 2.0)])), [0.0; 3]);
        assert_eq!(storage_origin(&with(vec![sphere([260.0, 0.0, 0.0], 2.0)])), [260.0, 0.0, 0.0]);
        // Planes do not count: a floor under a scene far away does not pull the origin back.
        let floor = ObjectDesc::Plane(PlaneDesc {
            point: [1e6, 0.0, 0.0],
            normal: [1.0, 0.0, 0.0],
            material: "m".into(),
            name: String::new(),
        });
        assert_eq!(storage_origin(&with(vec![floor])), [0.0; 3]);
    }

    #[test]
    fn planes_alone_far_from_the_world_origin_are_stored_around_the_eye() {
        let floor = ObjectDesc::Plane(PlaneDesc {
            point: [1e7, 0.0, 0.0],
            normal: [0.0, 1.0, 0.0],
            material: "m".into(),
            name: String::new(),
        });
        let mut desc = with(vec![floor]);
        desc.camera.position = [1e7 + 0.5, 2.0, -3.0];
        desc.camera.look_at = [1e7, 0.0, 0.0];
        // 2 over the floor: a grid of 4, the origin within it of the eye.
        let o = storage_origin(&desc);
        assert!(DVec3::from(o).distance(DVec3::from(desc.camera.position)) < 4.0, "{o:?}");
        assert_eq!(o, o.map(|c| f64::from(c as f32)));
        // Near the world origin (for its height): world space, as always.
        desc.camera.position = [0.5, 2.0, -3.0];
        assert_eq!(storage_origin(&desc), [0.0; 3]);
    }

    #[test]
    fn a_narrow_view_of_planes_alone_is_stored_around_the_patch_it_sees() {
        let floor = ObjectDesc::Plane(PlaneDesc {
            point: [0.0; 3],
            normal: [0.0, 1.0, 0.0],
            material: "m".into(),
            name: String::new(),
        });
        let mut desc = with(vec![floor]);
        // 0.1° over the floor from 1e6, looking at a patch near the world origin: stored around
        // the eye, 1.7e3 over the floor, the floor's offset was rounded to 1e-4.
        let e = 0.1f64.to_radians();
        desc.camera.position = [1e6 * e.cos(), 1e6 * e.sin(), 0.0];
        desc.camera.look_at = [0.0; 3];
        assert_ne!(storage_origin(&desc), [0.0; 3], "a wide view is stored around the eye");
        desc.camera.projection = Projection::Orthographic;
        desc.camera.view_height = Some(4.0);
        assert_eq!(storage_origin(&desc), [0.0; 3], "the patch lies at the world origin");
        desc.camera.projection = Projection::Perspective;
        desc.camera.fov_y = 2.0 * (2.0f64 / 1e6).atan().to_degrees();
        assert_eq!(storage_origin(&desc), [0.0; 3], "so does a telephoto's, 4 high there");
        // A telephoto within its field of view of grazing the floor sees it from near its eye
        // to the horizon: stored around the eye.
        desc.camera.fov_y = 0.5;
        let by_the_eye = storage_origin(&desc);
        assert_ne!(by_the_eye, [0.0; 3]);
        // So does a view of the patch with a wall 1 beside the eye, which it sees from 229 on
        // (a review's: 227 of 1,536 pixels of the wall on the other square).
        desc.camera.fov_y = 2.0 * (2.0f64 / 1e6).atan().to_degrees();
        let wall = ObjectDesc::Plane(PlaneDesc {
            point: [0.0, 0.0, 1.0],
            normal: [0.0, 0.0, 1.0],
            material: "m".into(),
            name: String::new(),
        });
        desc.objects.push(wall);
        let o = DVec3::from(storage_origin(&desc));
        assert!(o.distance(DVec3::from(desc.camera.position)) < 4.0, "stored at {o}, not around the eye");
        // An eye whose neighbourhood is stored in world space keeps it, narrow view or not.
        desc.objects.pop();
        desc.camera.position = [0.0, 10.0, 0.0];
        desc.camera.look_at = [0.0, 0.0, 50.0];
        desc.camera.fov_y = 0.5;
        assert_eq!(storage_origin(&desc), [0.0; 3]);
    }

    #[test]
    fn far_geometry_is_stored_around_its_box_on_a_grid_of_its_size() {
        // A unit triangle at 452331.127 (a projected map coordinate): the grid is 1, so the
        // origin is the nearest integer to the box's centre.
        let o = storage_origin(&with(vec![triangle([452_331.127, 5_411_876.883, 81.5], 1.0)]));
        assert_eq!(o, [452_332.0, 5_411_877.0, 82.0]);
        // Moved by a multiple of the grid, the origin moves by exactly as much.
        let moved = storage_origin(&with(vec![triangle([452_331.127 + 64.0, 5_411_876.883, 81.5], 1.0)]));
        assert_eq!(moved[0] - o[0], 64.0);
        // Exact in f32, which stores it.
        for c in o.into_iter().chain(moved) {
            assert_eq!(f64::from(c as f32), c);
        }
    }

    #[test]
    fn an_origin_beyond_f32_s_grid_is_rounded_to_f32() {
        // A 1e-3 model at 5e8 (within the coordinates validation allows): 5e11 grid steps.
        let o = storage_origin(&with(vec![triangle([5e8 + 0.3, 0.0, 0.0], 1e-3)]));
        assert_eq!(f64::from(o[0] as f32), o[0]);
        assert!((o[0] - 5e8).abs() <= 5e8 * f64::from(f32::EPSILON), "{o:?}");
    }

    #[test]
    fn non_finite_coordinates_are_left_to_validation() {
        let o = storage_origin(&with(vec![triangle([f64::NAN, 0.0, 0.0], 1.0), sphere([1e6, 0.0, 0.0], 1.0)]));
        assert_eq!(o, [1e6, 0.0, 0.0]);
        assert_eq!(storage_origin(&with(vec![sphere([f64::INFINITY, 0.0, 0.0], 1.0)])), [0.0; 3]);
        assert_eq!(storage_origin(&with(vec![sphere([1e300, 0.0, 0.0], 1.0)])), [0.0; 3]);
    }

    #[test]
    fn a_far_box_the_camera_cannot_see_leaves_the_digits_to_the_eye_and_its_ground() {
        let floor = |y: f64| {
            ObjectDesc::Plane(PlaneDesc {
                point: [0.0, y, 0.0],
                normal: [0.0, 1.0, 0.0],
                material: "m".into(),
                name: String::new(),
            })
        };
        let mut desc = with(vec![sphere([0.0, 3e5, 0.0], 1.0), floor(0.0)]);
        desc.camera.position = [0.0, 0.01, -0.001];
        desc.camera.look_at = [0.0; 3];
        // The sphere is behind the eye, which sits 0.01 over the floor: the world origin.
        assert_eq!(storage_origin(&desc), [0.0; 3]);
        // Far from the world origin: an origin at the eye's 0.02, not at the sphere 3e5 away.
        let shift = |mut d: SceneDesc, dx: f64| {
            d.camera.position[0] += dx;
            d.camera.look_at[0] += dx;
            for object in &mut d.objects {
                if let ObjectDesc::Sphere(s) = object {
                    s.center[0] += dx;
                }
            }
            d
        };
        let o = storage_origin(&shift(desc.clone(), 1e6));
        assert!((o[0] - 1e6).abs() < 0.02 && o[1].abs() < 0.02, "{o:?}");
        // Looking at the sphere instead, or with no plane beside the eye: around the sphere.
        let mut looking = desc.clone();
        looking.camera.look_at = [0.0, 3e5, 0.0];
        assert_eq!(storage_origin(&looking), [0.0, 3e5, 0.0]);
        desc.objects.pop();
        assert_eq!(storage_origin(&desc), [0.0, 3e5, 0.0]);
    }
}
