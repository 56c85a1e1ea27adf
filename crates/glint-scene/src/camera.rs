//! Where the scene is seen from.

use glam::DVec3;
use serde::{Deserialize, Serialize};

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
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_fov() -> f64 {
    45.0
}

/// The widest image `ball_may_be_seen` allows for: 4:1. The judgement is made without the
/// image's size (scene validation and the storage origin have only the scene), and must not
/// change with it.
const WIDEST_ASPECT: f64 = 4.0;

impl CameraDesc {
    /// `ball_may_be_seen` from this camera.
    pub fn may_see(&self, centre: [f64; 3], radius: f64) -> bool {
        let eye = DVec3::from(self.position);
        let tan_half_fov = (self.fov_y.to_radians() * 0.5).tan();
        ball_may_be_seen(eye, DVec3::from(self.look_at) - eye, tan_half_fov, DVec3::from(centre), radius)
    }
}

/// Whether any part of the ball of `radius` around `centre` may lie within the view of an eye at
/// `eye` looking along `forward` with tan(fov_y/2) = `tan_half_fov`: within the cone around the
/// view axis through the corners of a `WIDEST_ASPECT` image, widened by the ball's angular
/// radius. False only for what the camera certainly does not see directly (behind it, or far
/// off to a side); an eye inside the ball sees it.
fn ball_may_be_seen(eye: DVec3, forward: DVec3, tan_half_fov: f64, centre: DVec3, radius: f64) -> bool {
    let to_ball = centre - eye;
    let distance = to_ball.length();
    if !(distance > radius && forward.length() > 0.0) {
        return true;
    }
    let half_diagonal = (tan_half_fov * WIDEST_ASPECT.hypot(1.0)).atan();
    let limit = half_diagonal + (radius / distance).asin();
    // Unsure (a NaN) counts as seen.
    to_ball.angle_between(forward).partial_cmp(&limit) != Some(std::cmp::Ordering::Greater)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ball_is_seen_ahead_and_not_behind_or_far_to_a_side() {
        let camera = CameraDesc { position: [0.0; 3], look_at: [0.0, 0.0, 1.0], up: default_up(), fov_y: 40.0 };
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
}
