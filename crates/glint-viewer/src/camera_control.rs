//! Orbit, pan and zoom of the scene camera, as in most 3D editors: the camera circles its
//! look-at point, keeping the scene's up vector.

use glint_core::glam::DVec3;
use glint_scene::{CameraDesc, ObjectDesc, Projection, SceneDesc, ranges};

/// Keeps the camera off the poles, where the up vector and the view direction align.
const MAX_PITCH: f64 = 1.55;
/// How far above the floor the camera stays, as a fraction of its distance to the look-at point.
const FLOOR_CLEARANCE: f64 = 0.02;

/// The height (along the camera's up vector) of the floor: the highest plane facing up or down
/// along `up` that lies below the look-at point. `None` when there is none (a model, say).
pub fn floor_height(desc: &SceneDesc) -> Option<f64> {
    let up = DVec3::from(desc.camera.up).normalize_or(DVec3::Y);
    let target = DVec3::from(desc.camera.look_at).dot(up);
    desc.objects
        .iter()
        .filter_map(|o| match o {
            ObjectDesc::Plane(p) => Some(p),
            _ => None,
        })
        .filter(|p| DVec3::from(p.normal).normalize_or_zero().dot(up).abs() > 0.99)
        .map(|p| DVec3::from(p.point).dot(up))
        .filter(|h| *h < target)
        .reduce(f64::max)
}

/// Turns the camera around its look-at point by a drag of (dx, dy) points over a view
/// `view_width` points wide: a drag across the whole width is half a turn, whatever the window
/// size. The elevation stays off the poles and, when there is a `floor` (its height along the
/// up vector), keeps the camera above it.
pub fn orbit(cam: &mut CameraDesc, dx: f32, dy: f32, view_width: f32, floor: Option<f64>) {
    let up = DVec3::from(cam.up).normalize_or(DVec3::Y);
    let target = DVec3::from(cam.look_at);
    let offset = DVec3::from(cam.position) - target;
    let radius = offset.length();
    if radius <= 0.0 || !radius.is_finite() {
        return;
    }
    let per_point = std::f64::consts::PI / f64::from(view_width.max(1.0));
    // Spherical coordinates about `up`.
    let reference = if up.dot(DVec3::Z).abs() < 0.9 { DVec3::Z } else { DVec3::X };
    let e1 = (reference - up * reference.dot(up)).normalize();
    let e2 = up.cross(e1);
    let dir = offset / radius;
    let pitch = dir.dot(up).clamp(-1.0, 1.0).asin();
    let yaw = dir.dot(e2).atan2(dir.dot(e1));
    let mut lowest = -MAX_PITCH;
    if let Some(floor) = floor {
        let above = (floor - target.dot(up)) / radius + FLOOR_CLEARANCE;
        // A camera that is already lower (as loaded) may stay there, but not go further down.
        lowest = above.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH).min(pitch);
    }
    let yaw = yaw - f64::from(dx) * per_point;
    let pitch = (pitch + f64::from(dy) * per_point).clamp(lowest, MAX_PITCH.max(lowest));
    let new_dir = up * pitch.sin() + (e1 * yaw.cos() + e2 * yaw.sin()) * pitch.cos();
    cam.position = (target + new_dir * radius).to_array();
}

/// Moves camera and look-at point sideways by a drag of (dx, dy) points in a view
/// `view_height` points tall, so the scene follows the pointer at the look-at distance.
pub fn pan(cam: &mut CameraDesc, dx: f32, dy: f32, view_height: f32) {
    let pos = DVec3::from(cam.position);
    let target = DVec3::from(cam.look_at);
    let forward = (target - pos).normalize_or_zero();
    let right = forward.cross(DVec3::from(cam.up)).normalize_or_zero();
    let up = right.cross(forward);
    let per_point = cam.height_at_look_at() / f64::from(view_height.max(1.0));
    let shift = (-right * f64::from(dx) + up * f64::from(dy)) * per_point;
    cam.position = (pos + shift).to_array();
    cam.look_at = (target + shift).to_array();
}

/// Moves the camera towards (scroll > 0) or away from its look-at point; an orthographic
/// camera, whose image a move along its axis does not change, narrows or widens its view
/// instead, within the view heights a scene allows.
pub fn zoom(cam: &mut CameraDesc, scroll: f32) {
    let target = DVec3::from(cam.look_at);
    let offset = DVec3::from(cam.position) - target;
    let factor = (-f64::from(scroll) * 0.002).exp();
    if cam.projection == Projection::Orthographic {
        let range = ranges::VIEW_HEIGHT;
        cam.view_height = Some((cam.view_height() * factor).clamp(range.min, range.max));
        return;
    }
    let new = offset * factor;
    // Never onto the look-at point itself (the view direction would vanish).
    if new.length() > 1e-3 {
        cam.position = (target + new).to_array();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cam() -> CameraDesc {
        CameraDesc::perspective([0.0, 1.0, -5.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0], 45.0)
    }

    #[test]
    fn orbit_keeps_the_distance_and_zoom_changes_it() {
        let mut c = cam();
        orbit(&mut c, 40.0, 15.0, 300.0, None);
        let d = (DVec3::from(c.position) - DVec3::from(c.look_at)).length();
        assert!((d - 5.0).abs() < 1e-9, "{d}");
        assert_ne!(c.position, cam().position);
        zoom(&mut c, 100.0);
        let d2 = (DVec3::from(c.position) - DVec3::from(c.look_at)).length();
        assert!(d2 < d);
    }

    /// The camera's angle around the up axis, and its height.
    fn yaw_and_height(c: &CameraDesc) -> (f64, f64) {
        let o = DVec3::from(c.position) - DVec3::from(c.look_at);
        (o.x.atan2(o.z), c.position[1])
    }

    #[test]
    fn a_drag_across_the_view_is_half_a_turn_and_the_camera_stays_above_the_floor_and_off_the_pole() {
        for width in [300.0, 1200.0] {
            let mut c = cam();
            orbit(&mut c, width, 0.0, width, Some(0.0));
            let (yaw, _) = yaw_and_height(&c);
            let turned = (yaw - yaw_and_height(&cam()).0).abs();
            assert!((turned - std::f64::consts::PI).abs() < 1e-9, "{turned}");
        }
        let mut c = cam();
        for _ in 0..50 {
            orbit(&mut c, 3.0, -10.0, 300.0, Some(0.0));
            assert!(yaw_and_height(&c).1 > 0.0, "under the floor: {:?}", c.position);
        }
        for _ in 0..200 {
            orbit(&mut c, 0.0, 10.0, 300.0, Some(0.0));
        }
        let o = (DVec3::from(c.position) - DVec3::from(c.look_at)).normalize();
        assert!(o.y < MAX_PITCH.sin() + 1e-12, "over the pole: {o}");
        // Without a floor the camera may look from below, still off the pole.
        let mut c = cam();
        orbit(&mut c, 0.0, -1000.0, 300.0, None);
        let o = (DVec3::from(c.position) - DVec3::from(c.look_at)).normalize();
        assert!((o.y + MAX_PITCH.sin()).abs() < 1e-9, "{o}");
    }

    #[test]
    fn pan_moves_camera_and_target_together() {
        let mut c = cam();
        pan(&mut c, 10.0, 0.0, 300.0);
        let before = DVec3::from(cam().position) - DVec3::from(cam().look_at);
        let after = DVec3::from(c.position) - DVec3::from(c.look_at);
        assert!((before - after).length() < 1e-12);
        assert_ne!(c.look_at, cam().look_at);
    }

    #[test]
    fn an_orthographic_camera_zooms_by_its_view_height_and_pans_by_it() {
        let mut c = CameraDesc { projection: Projection::Orthographic, view_height: Some(4.0), ..cam() };
        zoom(&mut c, 100.0);
        assert_eq!(c.position, cam().position, "a move along the axis would not zoom");
        let h = c.view_height.expect("set");
        assert!((h - 4.0 * (-0.2f64).exp()).abs() < 1e-12, "{h}");
        // A drag of 300 points over a view 300 points tall moves the scene by the view's height.
        let before = c.look_at;
        pan(&mut c, 0.0, 300.0, 300.0);
        assert!((c.look_at[1] - before[1] - h).abs() < 1e-12, "{:?}", c.look_at);
        // Zooming stops at the view heights a scene allows.
        for _ in 0..100 {
            zoom(&mut c, 1e4);
        }
        assert_eq!(c.view_height, Some(ranges::VIEW_HEIGHT.min));
    }
}
