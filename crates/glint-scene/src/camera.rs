//! Where the scene is seen from.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// How the camera maps the scene onto the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Projection {
    /// A pinhole at `position`: rays fan out through the field of view `fov_y`.
    #[default]
    Perspective,
    /// Parallel rays along the view axis, leaving a rectangle `view_height` tall centred on
    /// `position` (glTF's orthographic cameras, the parallel projection of CAD drawings).
    Orthographic,
}

/// Only a name, as the tags read theirs (`glint_types::tags`): serde's derive said "wanted
/// string or table" of `projection = 0`, naming neither the field's kind nor its names.
impl<'de> Deserialize<'de> for Projection {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Names;

        impl serde::de::Visitor<'_> for Names {
            type Value = Projection;

            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "a projection named by a string, one of: {}", Projection::NAMES.join(", "))
            }

            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Projection, E> {
                let found = Projection::ALL.into_iter().find(|p| p.name() == v);
                found.ok_or_else(|| E::unknown_variant(v, Projection::NAMES))
            }
        }

        d.deserialize_str(Names)
    }
}

impl Projection {
    pub const ALL: [Projection; 2] = [Projection::Perspective, Projection::Orthographic];
    /// `ALL`'s names, in its order (a test checks them against `name`).
    const NAMES: &'static [&'static str] = &["perspective", "orthographic"];

    /// As a scene file spells it.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Perspective => "perspective",
            Projection::Orthographic => "orthographic",
        }
    }

    fn is_perspective(&self) -> bool {
        *self == Projection::Perspective
    }
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub position: [f64; 3],
    #[serde(deserialize_with = "crate::exact_len::array")]
    pub look_at: [f64; 3],
    #[serde(default = "default_up", deserialize_with = "crate::exact_len::array")]
    pub up: [f64; 3],
    /// Vertical field of view in degrees, in [1e-6, 179].
    #[serde(default = "default_fov")]
    pub fov_y: f64,
    #[serde(default, skip_serializing_if = "Projection::is_perspective")]
    pub projection: Projection,
    /// An orthographic view's height in world units; not given, the height the perspective view
    /// (`fov_y`) sees at `look_at` (`CameraDesc::view_height`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub view_height: Option<f64>,
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_fov() -> f64 {
    45.0
}

/// tan(fov_y/2) under which a perspective view is narrow (a field of view under 0.9°): at any
/// distance t it sees a patch under t/64 high, and its rays are anchored near what they meet
/// (`glint_core`'s `telephoto` judges the stored camera so), however far its eye is.
pub const NARROW_TAN_HALF_FOV: f64 = 1.0 / 128.0;

/// The widest image `ball_may_be_seen` allows for: 4:1. The judgement is made without the
/// image's size (scene validation and the storage origin have only the scene), and must not
/// change with it.
pub(crate) const WIDEST_ASPECT: f64 = 4.0;

impl CameraDesc {
    /// A pinhole camera.
    pub fn perspective(position: [f64; 3], look_at: [f64; 3], up: [f64; 3], fov_y: f64) -> Self {
        CameraDesc { position, look_at, up, fov_y, projection: Projection::Perspective, view_height: None }
    }

    /// The height of the view an orthographic camera sees: `view_height`, or where it is not
    /// given, what the perspective view sees at `look_at` (`perspective_height`): switching a
    /// camera to orthographic keeps the look-at point's framing.
    pub fn view_height(&self) -> f64 {
        self.view_height.unwrap_or_else(|| self.perspective_height())
    }

    /// What the perspective view (`fov_y`) sees at `look_at`: 2·|look_at − position|·tan(fov_y/2).
    pub fn perspective_height(&self) -> f64 {
        2.0 * self.look_at_distance() * self.tan_half_fov()
    }

    /// Whether the view is narrow: orthographic (the narrowest of all), or a perspective view
    /// under `NARROW_TAN_HALF_FOV`.
    pub fn is_narrow(&self) -> bool {
        self.projection == Projection::Orthographic || self.tan_half_fov() < NARROW_TAN_HALF_FOV
    }

    /// How high what the camera shows at `look_at` is, in its projection.
    pub fn height_at_look_at(&self) -> f64 {
        match self.projection {
            Projection::Perspective => self.perspective_height(),
            Projection::Orthographic => self.view_height(),
        }
    }

    /// How far the camera is from what it shows, for sizing what is drawn over its image: the
    /// distance to `look_at`, or for an orthographic camera (whose eye may be anywhere back
    /// along its axis) the distance at which the perspective view is as high as its view.
    pub fn framing_distance(&self) -> f64 {
        match self.projection {
            Projection::Perspective => self.look_at_distance(),
            Projection::Orthographic => self.view_height() / (2.0 * self.tan_half_fov()),
        }
    }

    /// The field of view (degrees) whose perspective view is `height` high at `look_at`:
    /// switching an orthographic camera to perspective keeps the framing.
    pub fn fov_seeing(&self, height: f64) -> f64 {
        (2.0 * (0.5 * height / self.look_at_distance()).atan()).to_degrees()
    }

    /// tan(fov_y/2): the perspective view's half-height at distance 1.
    pub fn tan_half_fov(&self) -> f64 {
        (self.fov_y.to_radians() * 0.5).tan()
    }

    /// How far this view's rays spread from its axis out to the corners of a `WIDEST_ASPECT`
    /// image: what `may_see` and the storage origin judge by.
    pub(crate) fn spread(&self) -> ViewSpread {
        let corner = WIDEST_ASPECT.hypot(1.0);
        match self.projection {
            Projection::Perspective => ViewSpread::Angle((self.tan_half_fov() * corner).atan()),
            Projection::Orthographic => ViewSpread::Across(0.5 * self.view_height() * corner),
        }
    }

    fn look_at_distance(&self) -> f64 {
        (DVec3::from(self.look_at) - DVec3::from(self.position)).length()
    }

    /// Whether any part of the ball of `radius` around `centre` may be seen by this camera
    /// directly: `ball_may_be_seen`, or for an orthographic camera `ball_may_be_seen_parallel`.
    pub fn may_see(&self, centre: [f64; 3], radius: f64) -> bool {
        let eye = DVec3::from(self.position);
        let forward = DVec3::from(self.look_at) - eye;
        match self.spread() {
            ViewSpread::Angle(half_diagonal) => {
                ball_may_be_seen(eye, forward, half_diagonal, DVec3::from(centre), radius)
            }
            ViewSpread::Across(half_diagonal) => {
                ball_may_be_seen_parallel(eye, forward, half_diagonal, DVec3::from(centre), radius)
            }
        }
    }
}

/// How far a view's rays spread from its axis, out to the corners of a `WIDEST_ASPECT` image
/// (`CameraDesc::spread`): in angle for a perspective view, across the axis for an orthographic
/// one's parallel rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ViewSpread {
    Angle(f64),
    Across(f64),
}

/// `ball_may_be_seen` for parallel rays along `forward` leaving the eye's plane up to
/// `half_diagonal` from the axis: the ball reaches in front of the eye's plane, and within the
/// corners around the axis.
fn ball_may_be_seen_parallel(eye: DVec3, forward: DVec3, half_diagonal: f64, centre: DVec3, radius: f64) -> bool {
    let Some(axis) = forward.try_normalize() else {
        return true;
    };
    let to_ball = centre - eye;
    let ahead = to_ball.dot(axis);
    let across = (to_ball - ahead * axis).length();
    // Unsure (a NaN) counts as seen.
    !(ahead < -radius || across > half_diagonal + radius)
}

/// Whether any part of the ball of `radius` around `centre` may lie within the view of an eye at
/// `eye` looking along `forward` whose rays reach `half_diagonal` (radians) off the axis at the
/// corners of a `WIDEST_ASPECT` image (`ViewSpread::Angle`): within that cone, widened by the
/// ball's angular radius. False only for what the camera certainly does not see directly (behind it, or far
/// off to a side); an eye inside the ball sees it.
fn ball_may_be_seen(eye: DVec3, forward: DVec3, half_diagonal: f64, centre: DVec3, radius: f64) -> bool {
    let to_ball = centre - eye;
    let distance = to_ball.length();
    if !(distance > radius && forward.length() > 0.0) {
        return true;
    }
    let limit = half_diagonal + (radius / distance).asin();
    // Unsure (a NaN) counts as seen.
    to_ball.angle_between(forward).partial_cmp(&limit) != Some(std::cmp::Ordering::Greater)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_projection_is_read_by_its_name_alone() {
        assert_eq!(Projection::NAMES, Projection::ALL.map(Projection::name));
        #[derive(Debug, Deserialize)]
        struct Field {
            projection: Projection,
        }
        let read = |text: &str| toml::from_str::<Field>(text).map_err(|e| e.to_string());
        assert_eq!(read("projection = \"orthographic\"").map(|f| f.projection), Ok(Projection::Orthographic));
        let e = read("projection = 0").unwrap_err();
        assert!(e.contains("expected a projection named by a string, one of: perspective, orthographic"), "{e}");
        let e = read("projection = \"fisheye\"").unwrap_err();
        assert!(e.contains("unknown variant `fisheye`, expected `perspective` or `orthographic`"), "{e}");
    }

    #[test]
    fn a_ball_is_seen_ahead_and_not_behind_or_far_to_a_side() {
        let camera = CameraDesc::perspective([0.0; 3], [0.0, 0.0, 1.0], default_up(), 40.0);
        assert!(camera.may_see([0.0, 0.0, 100.0], 1.0));
        assert!(!camera.may_see([0.0, 0.0, -100.0], 1.0));
        assert!(!camera.may_see([0.0, 100.0, 0.0], 1.0));
        // 4:1 at 40°: the corners are 56.4° off the axis; a ball of radius 1 at 100 reaches 0.57° nearer.
        let at = |deg: f64| [100.0 * deg.to_radians().sin(), 0.0, 100.0 * deg.to_radians().cos()];
        assert!(camera.may_see(at(56.5), 1.0));
        assert!(!camera.may_see(at(57.2), 1.0));
        // An eye inside the ball, or on its surface, sees it.
        assert!(camera.may_see([0.0, 0.0, -0.5], 1.0));
    }

    #[test]
    fn an_orthographic_camera_sees_what_lies_in_front_of_its_plane_within_its_rectangle() {
        let camera = CameraDesc {
            projection: Projection::Orthographic,
            view_height: Some(2.0),
            ..CameraDesc::perspective([0.0; 3], [0.0, 0.0, 1.0], default_up(), 40.0)
        };
        assert!(camera.may_see([0.0, 0.0, 1e6], 1.0));
        // Behind the eye's plane, but reaching through it.
        assert!(camera.may_see([0.0, 0.0, -0.5], 1.0));
        assert!(!camera.may_see([0.0, 0.0, -2.0], 1.0));
        // A 4:1 image 2 high reaches √17 ≈ 4.12 from the axis at its corners, at any distance.
        assert!(camera.may_see([5.0, 0.0, 1e6], 1.0));
        assert!(!camera.may_see([5.2, 0.0, 1.0], 1.0));
        // Not given, the view height is the perspective view's at look_at: 2·1·tan(20°).
        let framed = CameraDesc { view_height: None, ..camera.clone() };
        assert!((framed.view_height() - 2.0 * 20f64.to_radians().tan()).abs() < 1e-15);
        // Back to perspective with the field of view that frames it so; a framing distance at
        // which a 40° view is as high.
        assert!((camera.fov_seeing(2.0) - 90.0).abs() < 1e-12);
        assert!((camera.framing_distance() - 1.0 / 20f64.to_radians().tan()).abs() < 1e-12);
    }
}
