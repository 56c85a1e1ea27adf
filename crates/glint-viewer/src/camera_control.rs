//! Orbit, pan and zoom of the scene camera, as in most 3D editors: the camera circles its
//! look-at point, keeping the scene's up vector.

use glint_core::glam::DVec3;
use glint_core::scene::CameraDesc;

/// Radians per point of drag.
const ORBIT_SPEED: f64 = 0.008;
/// Keeps the camera off the poles, where the up vector and the view direction align.
const MAX_PITCH: f64 = 1.55;

/// Turns the camera around its look-at point by a drag of (dx, dy) points.
pub fn orbit(cam: &mut CameraDesc, dx: f32, dy: f32) {
    let up = DVec3::from(cam.up).normalize_or(DVec3::Y);
    let target = DVec3::from(cam.look_at);
    let offset = DVec3::from(cam.position) - target;
    let radius = offset.length();
    if radius <= 0.0 || !radius.is_finite() {
        return;
    }
    // Spherical coordinates about `up`.
    let reference = if up.dot(DVec3::Z).abs() < 0.9 { DVec3::Z } else { DVec3::X };
    let e1 = (reference - up * reference.dot(up)).normalize();
    let e2 = up.cross(e1);
    let dir = offset / radius;
    let pitch = dir.dot(up).clamp(-1.0, 1.0).asin();
    let yaw = dir.dot(e2).atan2(dir.dot(e1));
    let yaw = yaw - f64::from(dx) * ORBIT_SPEED;
    let pitch = (pitch + f64::from(dy) * ORBIT_SPEED).clamp(-MAX_PITCH, MAX_PITCH);
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
    let distance = (target - pos).length();
    let per_point = 2.0 * distance * (cam.fov_y.to_radians() / 2.0).tan() / f64::from(view_height.max(1.0));
    let shift = (-right * f64::from(dx) + up * f64::from(dy)) * per_point;
    cam.position = (pos + shift).to_array();
    cam.look_at = (target + shift).to_array();
}

/// Moves the camera towards (scroll > 0) or away from its look-at point.
pub fn zoom(cam: &mut CameraDesc, scroll: f32) {
    let target = DVec3::from(cam.look_at);
    let offset = DVec3::from(cam.position) - target;
    let factor = (-f64::from(scroll) * 0.002).exp();
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
        CameraDesc { position: [0.0, 1.0, -5.0], look_at: [0.0, 1.0, 0.0], up: [0.0, 1.0, 0.0], fov_y: 45.0 }
    }

    #[test]
    fn orbit_keeps_the_distance_and_zoom_changes_it() {
        let mut c = cam();
        orbit(&mut c, 40.0, 15.0);
        let d = (DVec3::from(c.position) - DVec3::from(c.look_at)).length();
        assert!((d - 5.0).abs() < 1e-9, "{d}");
        assert_ne!(c.position, cam().position);
        zoom(&mut c, 100.0);
        let d2 = (DVec3::from(c.position) - DVec3::from(c.look_at)).length();
        assert!(d2 < d);
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
}
