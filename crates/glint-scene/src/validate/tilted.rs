//! Huge tilted triangles near the eye: the GPU forms a triangle's plane in f32 from its corners,
//! so that near the eye the plane carries f32's rounding at the corners' distance, not at the
//! eye's. An axis-aligned triangle keeps its plane exactly (its corners share one coordinate, as
//! stored too); the CPU, in f64, is exact either way. A ground quad of half-size 1e5 rotated 30°
//! under a cube 1e-4 above it lost cube pixels to the ground on the GPU alone (33 dB; 17.7 dB at
//! 1e8), and nothing said why (numerics.md, Known limits).

use super::near::{MeshBoxes, box_distance, closest_on_triangle, meshes_of, triangle_corners};
use super::{FieldIssue, MeshDesc, ObjectDesc, SceneDesc};
use crate::number::format_rounded;
use glam::DVec3;

/// The plane's height error near the eye, as a share of its distance, from which it is warned
/// of: case 27 rotated 30° (a cube 1e-4 over the ground, 96×72) rendered at 145.0 dB on the GPU
/// at a half-size of 1e4 (4.2e-4 of the eye's height) and lost first hits from 1e5 (4.2e-3).
const VISIBLE_PLANE_ERROR: f64 = 1e-3;

/// Half f32's step at 1, 2^-24: the height error of a plane formed in f32 from corners at a
/// distance D, per unit of D (measured on rotated quads of half-size 1e3 to 1e8: 0.5 to 0.7 of it).
const F32_HALF_STEP: f64 = f32::EPSILON as f64 / 2.0;

/// The tilted-triangle warnings of `scene` from its camera: one per mesh object, one per model
/// (naming its first such mesh and how many more there are).
pub(super) fn tilted_triangles(scene: &SceneDesc, boxes: &MeshBoxes) -> Vec<FieldIssue> {
    let eye = DVec3::from(scene.camera.position);
    let mut out = Vec::new();
    for (i, object) in scene.objects.iter().enumerate() {
        let path = |k: usize, mesh: &MeshDesc| match object {
            ObjectDesc::Model(_) => format!("objects[{i}] mesh {k} `{}`", mesh.name),
            ObjectDesc::Mesh(_) | ObjectDesc::Sphere(_) | ObjectDesc::Plane(_) => format!("objects[{i}]"),
        };
        let mut found = meshes_of(object)
            .into_iter()
            .enumerate()
            .filter_map(|(k, mesh)| Some((path(k, mesh), tilted_near(mesh, boxes.get(i, k)?, eye)?)));
        if let Some((path, tilted)) = found.next() {
            let more = found.count();
            let more = if more > 0 { format!(" (and likewise in {more} more meshes)") } else { String::new() };
            out.push(FieldIssue { field: format!("{path}.vertices"), problem: format!("{}{more}", tilted.message()) });
        }
    }
    out
}

/// What a mesh's tilted triangles near the eye come to: how many, and the figures of the one
/// whose plane the GPU puts furthest off for its distance.
struct Tilted {
    count: usize,
    reach: f64,
    distance: f64,
    error: f64,
}

impl Tilted {
    fn message(&self) -> String {
        let Tilted { count, reach, distance, error } = *self;
        let triangles = if count == 1 {
            "1 tilted triangle reaches".to_string()
        } else {
            format!("{count} tilted triangles reach")
        };
        let share = if distance > 0.0 {
            format!(" ({} of that distance)", format_rounded(error / distance, 2))
        } else {
            String::new()
        };
        format!(
            "{triangles} {} from the eye, {} from it at the nearest: the GPU forms a triangle's plane in f32 from its \
             corners, which puts it up to {} off near the eye{share}; the CPU, in f64, is exact. What stands on it may \
             sink into it or float on the GPU, and its shading moves. Split it into triangles nearer the eye's distance \
             in size, or make a flat ground a `plane` object (docs/numerics.md, Known limits)",
            format_rounded(reach, 3),
            format_rounded(distance, 3),
            format_rounded(error, 2),
        )
    }
}

fn tilted_near(mesh: &MeshDesc, (lo, hi): (DVec3, DVec3), eye: DVec3) -> Option<Tilted> {
    // Whole meshes first: a triangle's plane can only be off by VISIBLE_PLANE_ERROR of its
    // distance r where f32's step at r + its size s exceeds that, so a mesh whose size is not
    // some 17,000 times its box's distance from the eye is passed over unread (a camera drag over
    // a million-triangle model validates on every step).
    if !could_be_off(hi - lo, eye, lo, hi) {
        return None;
    }
    let mut worst: Option<Tilted> = None;
    let mut count = 0;
    for t in &mesh.triangles {
        let Some([a, b, c]) = triangle_corners(mesh, t) else { continue };
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let n = (b - a).cross(c - a);
        let axis_aligned = n.to_array().iter().filter(|&&x| x == 0.0).count() >= 2;
        if axis_aligned || !could_be_off(hi - lo, eye, lo, hi) {
            continue;
        }
        let distance = eye.distance(closest_on_triangle(eye, a, b, c));
        let reach = [a, b, c].iter().map(|p| eye.distance(*p)).fold(0.0, f64::max);
        let error = F32_HALF_STEP * reach;
        if error <= VISIBLE_PLANE_ERROR * distance {
            continue;
        }
        count += 1;
        let share = |t: &Tilted| if t.distance > 0.0 { t.error / t.distance } else { f64::INFINITY };
        let this = Tilted { count: 0, reach, distance, error };
        if worst.as_ref().is_none_or(|w| share(&this) > share(w)) {
            worst = Some(this);
        }
    }
    worst.map(|w| Tilted { count, ..w })
}

/// Whether something of size `extent` in the box [lo, hi] can have its plane off by more than
/// VISIBLE_PLANE_ERROR of its distance from `eye`: its corners are at most r + s from the
/// eye, r at least the box's distance.
fn could_be_off(extent: DVec3, eye: DVec3, lo: DVec3, hi: DVec3) -> bool {
    F32_HALF_STEP * extent.length() > (VISIBLE_PLANE_ERROR - F32_HALF_STEP) * box_distance(eye, lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ground quad of half-size `h` rotated 30° about z, the eye 2 above its centre.
    fn rotated_ground(h: f64) -> SceneDesc {
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let rot = |[x, y, z]: [f64; 3]| [x * c - y * s, x * s + y * c, z];
        let vertices = [[-h, 0.0, -h], [h, 0.0, -h], [h, 0.0, h], [-h, 0.0, h]].map(rot).to_vec();
        let ground = MeshDesc::new(vertices, vec![[0, 2, 1], [0, 3, 2]], "ground", "");
        let mut scene = crate::desc::test_scene(vec![ObjectDesc::Mesh(ground)]);
        scene.camera.position = rot([0.0, 2.0, 0.0]);
        scene
    }

    fn warnings(scene: &SceneDesc) -> Vec<String> {
        tilted_triangles(scene, &MeshBoxes::of(&scene.objects))
            .into_iter()
            .map(|w| format!("{}: {}", w.field, w.problem))
            .collect()
    }

    #[test]
    fn a_huge_tilted_ground_near_the_eye_is_named_with_how_far_the_gpu_puts_it_off() {
        // Half-size 1e4: the plane is off by 2^-24·14142 = 8.4e-4, below 1e-3 of the eye's 2.
        assert!(warnings(&rotated_ground(1e3)).is_empty());
        assert!(warnings(&rotated_ground(1e4)).is_empty());
        let far = warnings(&rotated_ground(1e5));
        assert_eq!(far.len(), 1, "{far:?}");
        assert!(
            far[0].starts_with(
                "objects[0].vertices: 2 tilted triangles reach 141000 from the eye, 2 from it at the nearest: \
                 the GPU forms a triangle's plane in f32 from its corners, which puts it up to 0.0084 off near the eye \
                 (0.0042 of that distance)"
            ) && far[0].contains("make a flat ground a `plane` object"),
            "{far:?}"
        );
    }

    #[test]
    fn an_axis_aligned_ground_or_a_far_eye_is_not_warned_about() {
        let h = 1e8;
        let flat = MeshDesc::new(
            vec![[-h, 0.0, -h], [h, 0.0, -h], [h, 0.0, h], [-h, 0.0, h]],
            vec![[0, 2, 1], [0, 3, 2]],
            "ground",
            "",
        );
        let mut scene = crate::desc::test_scene(vec![ObjectDesc::Mesh(flat)]);
        scene.camera.position = [0.0, 2.0, 0.0];
        assert!(warnings(&scene).is_empty());
        // Seen from as far as it is wide, the same rotated quad's error is f32's at its distance.
        let mut distant = rotated_ground(1e5);
        distant.camera.position = [0.0, 3e5, 0.0];
        assert!(warnings(&distant).is_empty());
    }
}
