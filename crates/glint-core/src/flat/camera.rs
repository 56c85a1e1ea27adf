//! The camera, pinhole or orthographic: in f64 world space (`WorldCamera`) and as both tracers
//! store it (`GpuCamera`: an anchor on the view axis instead of the eye, layout.rs says why).

use glam::DVec3;

use super::{FlatScene, vec4, wide};
use glint_scene::{NARROW_TAN_HALF_FOV, Projection, RenderSettings, SceneDesc};
use glint_types::layout::{CAMERA_ORTHOGRAPHIC, GpuCamera, GpuPlane};

/// The camera's ray-generation vectors in f64 world space: a ray through image point
/// (ndc_x, ndc_y) leaves `position` along forward + ndc_x·right + ndc_y·up, or for an
/// `orthographic` camera leaves position + ndc_x·right + ndc_y·up along forward (unit). What
/// the flat scene stores in f32 (`stored`), and what the viewer projects world points with
/// (`image_point`: its light gizmos and ray-tree overlay): an f32 eye 5e6 from the world origin
/// would be off by 1/4.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WorldCamera {
    pub position: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub orthographic: bool,
}

/// How many of the scene's largest sides the eye may be from the centre of its bounded geometry
/// and still be stored itself, unanchored: f32 then carries its rays to the scene's size as it
/// carries the scene (`glint_scene::storage_origin`'s reach, for the same reason), and every
/// camera made around a scene keeps its bits.
const EYE_REACH: f64 = 64.0;

/// The box around a scene's bounded geometry, as the camera's anchoring judges it: its centre
/// (stored coordinates) and its largest side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneBox {
    pub centre: DVec3,
    pub side: f64,
}

impl WorldCamera {
    /// The camera as the flat scene stores it relative to `origin` (the storage origin), each
    /// vector rounded once to f32. An eye more than `EYE_REACH` of the largest sides from the
    /// centre of the bounded geometry (`scene`) is anchored nearest that centre (`anchor_of`),
    /// and so is an orthographic camera's wherever it is (where there is such geometry): its view may be far smaller than the
    /// scene, and its rays start at the eye's plane however far back that is (an eye 5e5 away in
    /// a scene 1e4 wide, stored itself, put a 0.1-high view's sphere 8 px off centre).
    /// In a scene of planes alone (`planes`, stored coordinates), which has no size, the view
    /// judges: an eye more than `EYE_REACH` of the image's heights from where its axis meets the
    /// nearest plane is anchored there (a telephoto seeing a patch of the ground from afar), if
    /// that point is nearer the origin than the eye. Any other eye is its own anchor (w = 0).
    pub fn stored(&self, origin: DVec3, scene: Option<SceneBox>, planes: &[GpuPlane]) -> GpuCamera {
        let eye = self.position - origin;
        let anchor = match scene {
            Some(b) if b.side > 0.0 && (self.orthographic || (eye - b.centre).length() > EYE_REACH * b.side) => {
                anchor_of(eye, self.forward, b.centre)
            }
            Some(_) => vec4(eye, 0.0),
            None => match self.axis_meets(eye, planes) {
                // The image's height at distance t is 2·t·|up| / |forward|. An anchor farther
                // from the origin than the eye (an axis grazing the plane) would store the
                // eye worse than the eye itself.
                Some(t)
                    if telephoto(self.forward, self.up, self.orthographic)
                        && (eye + t * self.forward).length() < eye.length() =>
                {
                    anchor_of(eye, self.forward, eye + t * self.forward)
                }
                _ => vec4(eye, 0.0),
            },
        };
        let projection = if self.orthographic { CAMERA_ORTHOGRAPHIC } else { 0.0 };
        GpuCamera {
            anchor,
            forward: vec4(self.forward, projection),
            right: vec4(self.right, 0.0),
            up: vec4(self.up, 0.0),
        }
    }

    /// Where world point `p` lies in the image ([0, 1]², y down), and its depth along the view
    /// axis in units of `forward` (a point behind the eye, or on its plane, has depth ≤ 0 and
    /// no place). Inverts `camera_ray` for orthogonal right and up.
    pub fn image_point(&self, p: DVec3) -> (Option<(f64, f64)>, f64) {
        let q = p - self.position;
        let depth = q.dot(self.forward) / self.forward.length_squared();
        if depth <= 0.0 {
            return (None, depth);
        }
        let scale = if self.orthographic { 1.0 } else { depth };
        let ndc_x = q.dot(self.right) / self.right.length_squared() / scale;
        let ndc_y = q.dot(self.up) / self.up.length_squared() / scale;
        (Some(((ndc_x + 1.0) / 2.0, (1.0 - ndc_y) / 2.0)), depth)
    }

    /// The nearest t > 0 (in units of `forward`) at which the view axis from `eye` meets one of
    /// `planes`.
    fn axis_meets(&self, eye: DVec3, planes: &[GpuPlane]) -> Option<f64> {
        let hits = planes.iter().filter_map(|p| {
            let n = wide(p.normal_offset);
            let t = (f64::from(p.normal_offset[3]) - n.dot(eye)) / n.dot(self.forward);
            (t.is_finite() && t > 0.0).then_some(t)
        });
        hits.min_by(f64::total_cmp)
    }
}

/// Whether a camera of these ray-generation vectors sees, at any distance, a patch less than
/// 1/`EYE_REACH` of that distance high (a vertical field of view under 0.9°): the image's
/// height at distance t is 2·t·|up| / |forward|. Its rays are anchored near what they meet,
/// however large the scene: from the eye, the f32 direction's step (6e-8) is a fixed share of
/// a pixel that grows as the field narrows. An orthographic camera is the narrowest of all (its
/// view as high at any distance), a telephoto.
pub(crate) fn telephoto(forward: DVec3, up: DVec3, orthographic: bool) -> bool {
    // `CameraDesc::is_narrow`'s judgement on the camera's vectors, |up| = tan(fov_y/2)·|forward|:
    // the same up to their rounding, a few ulps of tan(fov_y/2) = 1/128.
    orthographic || up.length() < NARROW_TAN_HALF_FOV * forward.length()
}

/// `GpuCamera::anchor` for an eye at `eye` (stored coordinates, f64) looking along `forward`:
/// the point of the axis nearest `near` (a point of the scene), or the eye itself when `near` is
/// behind it. Its distance w from the eye is rounded to f32 first and the anchor placed from
/// that value, so that the stored axis passes through the point of this axis at w (a rounded w
/// would slide it along the axis by w·2^-24). Given the file's f64 forward, the stored axis
/// passes through that point, not through the eye: the f32 forward's error (6e-8) turns the
/// camera about the anchor, in the scene, where about the eye it would move the scene's image
/// by w·6e-8 (stiff case 22).
pub(crate) fn anchor_of(eye: DVec3, forward: DVec3, near: DVec3) -> [f32; 4] {
    let w = ((near - eye).dot(forward) / forward.length_squared()).max(0.0) as f32;
    vec4(eye + f64::from(w) * forward, w)
}

/// The eye of a stored camera, in its stored coordinates: anchor − w·forward, in f64.
pub fn camera_eye(camera: &GpuCamera) -> DVec3 {
    wide(camera.anchor) - f64::from(camera.anchor[3]) * wide(camera.forward)
}

impl FlatScene {
    /// The camera of `desc` at `settings`' aspect ratio, in f64 world space: right and up
    /// scaled by tan(fov_y/2) for a pinhole, by half the view's height for an orthographic
    /// camera.
    pub fn world_camera(desc: &SceneDesc, settings: &RenderSettings) -> WorldCamera {
        let c = &desc.camera;
        let position = DVec3::from(c.position);
        let forward = (DVec3::from(c.look_at) - position).normalize();
        let right = forward.cross(DVec3::from(c.up)).normalize();
        let up = right.cross(forward);
        let orthographic = c.projection == Projection::Orthographic;
        let half_h = if orthographic { 0.5 * c.view_height() } else { c.tan_half_fov() };
        let half_w = half_h * f64::from(settings.width) / f64::from(settings.height);
        WorldCamera { position, forward, right: right * half_w, up: up * half_h, orthographic }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_io::parse_scene;

    fn flat(eye: [f64; 3], centre: [f64; 3]) -> FlatScene {
        let text = format!(
            "[camera]\nposition = {eye:?}\nlook_at = {centre:?}\n[materials.m]\nkd = 0.5\n\
             [[objects]]\ntype = \"sphere\"\ncenter = {centre:?}\nradius = 1.0\nmaterial = \"m\"\n"
        );
        let (desc, _) = parse_scene(&text, std::path::Path::new("t.toml")).expect("scene");
        FlatScene::build(&desc, &desc.render)
    }

    #[test]
    fn an_eye_near_its_scene_is_its_own_anchor_wherever_the_scene_is_stored() {
        // Stored in world space (within 64 sides of the origin per axis), |eye| > 64 sides, but
        // 3 from the sphere: the eye, not a point of the axis near the world origin.
        let s = flat([103.0, 100.0, 0.0], [100.0, 100.0, 0.0]);
        assert_eq!(s.header.frame[..3], [0.0; 3]);
        assert_eq!(s.camera.anchor, [103.0, 100.0, 0.0, 0.0]);
    }

    fn over_a_plane(eye: [f64; 3], look_at: [f64; 3], fov: f64) -> FlatScene {
        let text = format!(
            "[camera]\nposition = {eye:?}\nlook_at = {look_at:?}\nfov_y = {fov:?}\n[materials.m]\nkd = 0.5\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n"
        );
        let (desc, _) = parse_scene(&text, std::path::Path::new("t.toml")).expect("scene");
        FlatScene::build(&desc, &desc.render)
    }

    #[test]
    fn over_planes_alone_a_telephoto_is_anchored_where_its_axis_meets_the_nearest() {
        let (eye, focus) = ([480_000.3, 600_000.0, 640_000.2], [0.3, 0.0, 0.2]);
        let s = over_a_plane(eye, focus, 5.7e-4);
        let a = wide(s.camera.anchor);
        assert!(a.y.abs() < 1e-3 && (a - DVec3::from(focus)).length() < 1e-2, "anchored at {a}, not on the plane");
        assert!((f64::from(s.camera.anchor[3]) - 1e6).abs() < 1.0);
        // A normal lens over the plane, a telephoto whose axis leaves it, and one whose axis
        // grazes it far beyond the eye (an anchor at 1e11 would store the eye 3e3 off) keep their
        // eyes.
        assert_eq!(over_a_plane(eye, focus, 40.0).camera.anchor[3], 0.0);
        assert_eq!(over_a_plane(eye, [0.3, 1_200_000.0, 0.2], 5.7e-4).camera.anchor[3], 0.0);
        assert_eq!(over_a_plane([0.0, 1.0, 0.0], [6e8, 0.99, 8e8], 0.5).camera.anchor[3], 0.0);
    }

    #[test]
    fn a_far_eye_is_anchored_at_its_scene() {
        // 1.1e6 from a sphere stored in world space: anchored on its axis at the sphere's centre,
        // the eye where the file puts it to the anchor's rounding.
        let (eye, centre) = ([-480_000.0, 360_000.0, -800_000.0], [0.3, -0.2, 0.7]);
        let s = flat(eye, centre);
        let w = f64::from(s.camera.anchor[3]);
        let distance = (DVec3::from(eye) - DVec3::from(centre)).length();
        assert!((w - distance).abs() <= distance * 2f64.powi(-24), "w = {w}, {distance}");
        // On the axis through the centre; along it, where w's f32 rounding slid it.
        let (a, f) = (wide(s.camera.anchor), wide(s.camera.forward));
        let to_centre = DVec3::from(centre) - a;
        let across = to_centre - to_centre.dot(f) * f;
        assert!(across.length() < 1e-6, "the anchor {a} is {across} off the axis through the centre");
        assert!(to_centre.dot(f).abs() <= distance * 2f64.powi(-24), "the anchor {a} slid too far");
        let moved = camera_eye(&s.camera) - DVec3::from(eye);
        // The stored forward's rounding turns the camera about the anchor: the eye moves by up
        // to w·2^-24 sideways.
        assert!(moved.length() < w * 2f64.powi(-23), "eye off by {moved}");
    }
}
