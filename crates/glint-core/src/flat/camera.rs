//! The pinhole camera: in f64 world space (`WorldCamera`) and as both tracers store it
//! (`GpuCamera`: an anchor on the view axis instead of the eye, layout.rs says why).

use glam::DVec3;

use super::{FlatScene, vec4};
use glint_scene::{RenderSettings, SceneDesc};
use glint_types::layout::GpuCamera;

/// The pinhole camera's ray-generation vectors in f64 world space: a ray through image point
/// (ndc_x, ndc_y) leaves `position` along forward + ndc_x·right + ndc_y·up. What the flat
/// scene stores in f32 (`stored`), and what the viewer projects world points with (its light
/// gizmos and ray-tree overlay): an f32 eye 5e6 from the world origin would be off by 1/4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldCamera {
    pub position: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
}

/// The xyz of a stored vector, widened exactly to f64.
fn wide(v: [f32; 4]) -> DVec3 {
    DVec3::new(v[0].into(), v[1].into(), v[2].into())
}

/// How many of the scene's largest sides the eye may be from the coordinates' origin and still
/// be stored itself, unanchored: f32 then carries its rays to the scene's size as it carries
/// the scene (`glint_scene::storage_origin`'s reach, for the same reason), and every camera
/// made around a scene keeps its bits.
const EYE_REACH: f64 = 64.0;

impl WorldCamera {
    /// The camera as the flat scene stores it relative to `origin` (the storage origin), each
    /// vector rounded once to f32. An eye more than `EYE_REACH` times `scene_size` (the largest
    /// side of the bounded geometry) from the origin is anchored (`anchor_of`); a nearer one,
    /// or one in a scene of planes alone (no size to judge by), is its own anchor (w = 0).
    pub fn stored(&self, origin: DVec3, scene_size: f64) -> GpuCamera {
        let eye = self.position - origin;
        let far = scene_size > 0.0 && eye.length() > EYE_REACH * scene_size;
        GpuCamera {
            anchor: if far { anchor_of(eye, self.forward) } else { vec4(eye, 0.0) },
            forward: vec4(self.forward, 0.0),
            right: vec4(self.right, 0.0),
            up: vec4(self.up, 0.0),
        }
    }
}

/// `GpuCamera::anchor` for an eye at `eye` (stored coordinates, f64) looking along `forward`:
/// the point of the axis nearest the coordinates' origin, or the eye itself when the origin is
/// behind it. Its distance w from the eye is rounded to f32 first and the anchor placed from
/// that value, so that the stored axis passes through the point of this axis at w (a rounded w
/// would slide it along the axis by w·2^-24). Given the file's f64 forward, the stored axis
/// passes through that point, not through the eye: the f32 forward's error (6e-8) turns the
/// camera about the anchor, in the scene, where about the eye it would move the scene's image
/// by w·6e-8 (stiff case 22).
pub(crate) fn anchor_of(eye: DVec3, forward: DVec3) -> [f32; 4] {
    let w = (-eye.dot(forward) / forward.length_squared()).max(0.0) as f32;
    vec4(eye + f64::from(w) * forward, w)
}

/// The eye of a stored camera, in its stored coordinates: anchor − w·forward, in f64.
pub fn camera_eye(camera: &GpuCamera) -> DVec3 {
    wide(camera.anchor) - f64::from(camera.anchor[3]) * wide(camera.forward)
}

/// The stored forward, widened.
pub fn camera_forward(camera: &GpuCamera) -> DVec3 {
    wide(camera.forward)
}

impl FlatScene {
    /// The camera of `desc` at `settings`' aspect ratio, in f64 world space.
    pub fn world_camera(desc: &SceneDesc, settings: &RenderSettings) -> WorldCamera {
        let c = &desc.camera;
        let position = DVec3::from(c.position);
        let forward = (DVec3::from(c.look_at) - position).normalize();
        let right = forward.cross(DVec3::from(c.up)).normalize();
        let up = right.cross(forward);
        let half_h = (c.fov_y.to_radians() * 0.5).tan();
        let half_w = half_h * f64::from(settings.width) / f64::from(settings.height);
        WorldCamera { position, forward, right: right * half_w, up: up * half_h }
    }
}
