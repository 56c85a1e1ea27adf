//! Where lights and objects sit against each other: set-ups that render without an error but
//! not as a student who built them means (a lamp shut inside an opaque ball, a slab made of two
//! planes that both face out of it, one sphere written twice).

use super::{FieldIssue, ObjectDesc, SceneDesc, num};
use glam::DVec3;

/// The placement warnings of `scene`, read from its own objects (a model's are not judged).
pub(super) fn placement_warnings(scene: &SceneDesc) -> Vec<FieldIssue> {
    let mut out = shut_in_lights(scene);
    out.extend(same_facing_transmissive_planes(scene));
    out
}

fn transmits(scene: &SceneDesc, material: &str) -> Option<bool> {
    scene.materials.get(material).map(|m| m.kt.max_channel() > 0.0)
}

/// A shadow-casting light inside an opaque sphere lights only that sphere's inside: where the
/// camera is outside it, every surface in view is in its shadow, silently. With the camera
/// inside too, the sphere is a room or a sky dome, and what the camera sees is lit (a dome of
/// radius 1e9 around a whole scene was warned of; a tester).
fn shut_in_lights(scene: &SceneDesc) -> Vec<FieldIssue> {
    let mut out = Vec::new();
    let eye = DVec3::from(scene.camera.position);
    for (i, light) in scene.lights.iter().enumerate() {
        let Some(p) = light.position.filter(|_| light.casts_shadows) else { continue };
        let p = DVec3::from(p);
        let shut_in = scene.objects.iter().enumerate().find_map(|(k, o)| match o {
            ObjectDesc::Sphere(s) => {
                let inside = |q: DVec3| q.distance(DVec3::from(s.center)) < s.radius;
                let opaque = transmits(scene, &s.material) == Some(false);
                (inside(p) && !inside(eye) && opaque).then_some((k, s.radius))
            }
            ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
        });
        if let Some((k, radius)) = shut_in {
            out.push(FieldIssue {
                field: format!("lights[{i}].position"),
                problem: format!(
                    "is inside objects[{k}], an opaque sphere (radius {}) the camera is outside of: the light \
                     reaches only that sphere's inside, and every surface in view is in its shadow (move it out, give \
                     the sphere kt > 0, or set casts_shadows = false)",
                    num(radius)
                ),
            });
        }
    }
    out
}

/// Spheres of one centre and radius as the tracers store them (f32, the centre relative to
/// the storage `origin`, as the coplanar check takes it): a ray meets both at the same t, so
/// each tracer picks its own, pixel by pixel, as with coplanar faces (which are warned of; a
/// sphere written twice was not). World f32 merged spheres 0.003 apart at x = 1e5 (a tester).
pub(super) fn duplicate_spheres(scene: &SceneDesc, origin: [f64; 3]) -> Vec<FieldIssue> {
    let mut first: std::collections::HashMap<[u32; 4], usize> = std::collections::HashMap::new();
    let mut out = Vec::new();
    for (k, o) in scene.objects.iter().enumerate() {
        let s = match o {
            ObjectDesc::Sphere(s) => s,
            ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => continue,
        };
        let c = DVec3::from(s.center) - DVec3::from(origin);
        let key = [c.x, c.y, c.z, s.radius].map(|v| (v as f32).to_bits());
        match first.get(&key) {
            Some(&i) => out.push(FieldIssue {
                field: format!("objects[{k}]"),
                problem: format!(
                    "is the sphere objects[{i}] again (the same centre and radius): a ray meets both at the same t up \
                     to rounding, so each tracer picks its own surface pixel by pixel (z-fighting), and a shadow \
                     crosses both; remove the duplicate"
                ),
            }),
            None => {
                first.insert(key, k);
            }
        }
    }
    out
}

/// A transmissive plane's normal points out of its medium, so a ray crossing it against the
/// normal enters. Two parallel transmissive planes facing the same way are two entries: a slab
/// built of them refracts twice into the glass and never out (the far plane must face away).
fn same_facing_transmissive_planes(scene: &SceneDesc) -> Vec<FieldIssue> {
    let planes: Vec<(usize, DVec3, DVec3)> = scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(k, o)| match o {
            ObjectDesc::Plane(p) if transmits(scene, &p.material) == Some(true) => {
                Some((k, DVec3::from(p.point), DVec3::from(p.normal).try_normalize()?))
            }
            ObjectDesc::Plane(_) | ObjectDesc::Sphere(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
        })
        .collect();
    let mut out = Vec::new();
    for (a, &(i, pi, ni)) in planes.iter().enumerate() {
        // The first partner only: a stack of such planes is one mistake, said once a plane.
        let partner =
            planes[a + 1..].iter().find(|&&(_, pj, nj)| ni.dot(nj) > 1.0 - 1e-12 && ni.dot(pj - pi).abs() > 0.0);
        if let Some(&(j, _, _)) = partner {
            out.push(FieldIssue {
                field: format!("objects[{i}]"),
                problem: format!(
                    "is a transmissive plane parallel to the transmissive plane objects[{j}], its normal facing the same way: a plane's \
                     normal points out of its medium, so a ray through both enters twice and never leaves; for a \
                     slab between them, turn one normal to face away from the other plane"
                ),
            });
        }
    }
    out
}
