//! Light gizmos: where each light is, projected with the scene camera, as polylines in
//! image coordinates ([0, 1]², y down) for the view to draw over the GPU image.

use egui::Color32;
use glint_core::WorldCamera;
use glint_core::glam::DVec3;
use glint_scene::{LightKind, SceneDesc, SpotFalloff};

#[derive(Clone, Debug, PartialEq)]
pub struct Gizmo {
    pub colour: Color32,
    /// Marker position of the light (point and spot lights).
    pub marker: Option<(f32, f32)>,
    /// Outline polylines (spot cone, direction arrows).
    pub lines: Vec<Vec<(f32, f32)>>,
    pub selected: bool,
}

/// Image position of world point `p` (`WorldCamera::image_point`), or `None` behind the
/// camera or within 1e-6 of its eye's plane.
pub fn project(cam: &WorldCamera, p: DVec3) -> Option<(f32, f32)> {
    match cam.image_point(p) {
        (Some((x, y)), depth) if depth > 1e-6 => Some((x as f32, y as f32)),
        _ => None,
    }
}

fn polyline(cam: &WorldCamera, points: impl IntoIterator<Item = DVec3>) -> Vec<(f32, f32)> {
    points.into_iter().filter_map(|p| project(cam, p)).collect()
}

fn colour(rgb: [f64; 3]) -> Color32 {
    let m = rgb.iter().copied().fold(1e-9, f64::max);
    let c = rgb.map(|x| (255.0 * (x / m).clamp(0.0, 1.0)) as u8);
    Color32::from_rgb(c[0].max(60), c[1].max(60), c[2].max(60))
}

pub fn gizmos(desc: &SceneDesc, cam: &WorldCamera, selected: usize) -> Vec<Gizmo> {
    let look_at = DVec3::from_array(desc.camera.look_at);
    // An orthographic eye may be anywhere back along its axis: sized by what the view shows.
    let scale = desc.camera.framing_distance() * 0.15;
    desc.lights
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let mut g = Gizmo { colour: colour(l.diffuse.0), marker: None, lines: Vec::new(), selected: i == selected };
            let pos = l.position.map(DVec3::from_array);
            let dir = l.direction.map(|d| DVec3::from_array(d).normalize_or_zero());
            match (l.kind, pos, dir) {
                (LightKind::Point, Some(p), _) => g.marker = project(cam, p),
                (LightKind::Spot, Some(p), Some(d)) => {
                    g.marker = project(cam, p);
                    g.lines.push(polyline(cam, [p, p + d * scale * 2.0]));
                    // The cone's edge: the cutoff, or where the smooth falloff reaches 0.
                    let edge = match l.falloff {
                        SpotFalloff::Power => l.cutoff,
                        SpotFalloff::Smooth => l.cone_angles().1,
                    };
                    if edge < 90.0 {
                        // The cone's rim at a fixed distance along the axis, and four edges.
                        let (a, b) = d.any_orthonormal_pair();
                        let rim_r = scale * edge.to_radians().tan().min(4.0);
                        let centre = p + d * scale;
                        let rim: Vec<DVec3> = (0..=32)
                            .map(|k| {
                                let t = f64::from(k) / 32.0 * std::f64::consts::TAU;
                                centre + (a * t.cos() + b * t.sin()) * rim_r
                            })
                            .collect();
                        for k in [0, 8, 16, 24] {
                            g.lines.push(polyline(cam, [p, rim[k]]));
                        }
                        g.lines.push(polyline(cam, rim));
                    }
                }
                (LightKind::Directional, _, Some(d)) => {
                    // Parallel arrows falling onto the look-at point.
                    let (a, _) = d.any_orthonormal_pair();
                    for off in [-1.0, 0.0, 1.0] {
                        let end = look_at + a * off * scale * 0.5;
                        g.lines.push(polyline(cam, [end - d * scale * 2.0, end]));
                    }
                }
                _ => {}
            }
            g
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_look_at_point_projects_to_the_centre() {
        let cam = WorldCamera {
            position: DVec3::new(0.0, 0.0, -5.0),
            forward: DVec3::Z,
            right: DVec3::new(0.5, 0.0, 0.0),
            up: DVec3::new(0.0, 0.4, 0.0),
            orthographic: false,
        };
        let (x, y) = project(&cam, DVec3::ZERO).expect("in front");
        assert!((x - 0.5).abs() < 1e-6 && (y - 0.5).abs() < 1e-6);
        let (x, y) = project(&cam, DVec3::new(2.5, 2.0, 0.0)).expect("in front");
        assert!((x - 1.0).abs() < 1e-6 && y.abs() < 1e-6, "{x} {y}");
        assert!(project(&cam, DVec3::new(0.0, 0.0, -10.0)).is_none());
        // Orthographic, right and up are the half-width and half-height at any depth.
        let parallel = WorldCamera { orthographic: true, ..cam };
        for z in [0.0, 100.0] {
            let (x, y) = project(&parallel, DVec3::new(0.25, 0.2, z)).expect("in front");
            assert!((x - 0.75).abs() < 1e-6 && (y - 0.25).abs() < 1e-6, "{x} {y}");
        }
        assert!(project(&parallel, DVec3::new(0.0, 0.0, -5.0)).is_none(), "on the eye's plane");
    }
}
