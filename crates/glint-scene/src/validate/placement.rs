//! Where lights and objects sit against each other: set-ups that render without an error but
//! not as a student who built them means (a lamp shut inside an opaque ball, a slab made of two
//! planes that both face out of it, one sphere written twice).

use super::near::{MeshBoxes, box_distance, closest_on_triangle, meshes_of, triangle_corners};
use super::objects::storage_origin_named;
use super::{Attenuation, FieldIssue, ObjectDesc, SceneDesc, num};
use crate::number::format_rounded;
use glam::DVec3;
use glint_types::layout::f32_spacing;

/// The placement warnings of `scene`, read from its own objects (a model's are not judged).
pub(super) fn placement_warnings(scene: &SceneDesc, boxes: &MeshBoxes) -> Vec<FieldIssue> {
    let mut out = shut_in_lights(scene);
    out.extend(same_facing_transmissive_planes(scene));
    out.extend(held_falloffs(scene, boxes));
    out
}

/// An inverse-square light with a surface nearer than the distance within which its 1/d² is
/// held (`MIN_ATTENUATION_DENOMINATOR`: d² ≥ 1e-6, so d = 1e-3): that surface is lit less than
/// 1/d² says. A model in millimetres scaled to metres with its own glTF light 3e-4 from it came
/// out 8.6 dB darker than the same model at full size, and nothing said why (a tester).
fn held_falloffs(scene: &SceneDesc, boxes: &MeshBoxes) -> Vec<FieldIssue> {
    let held = crate::limits::MIN_ATTENUATION_DENOMINATOR.sqrt();
    let mut out = Vec::new();
    // A model's own lights too: the case that asked for this is a glTF light (a tester).
    for (source, light) in scene.sourced_lights() {
        let (Attenuation::InverseSquare { .. }, Some(p)) = (light.attenuation, light.position) else { continue };
        let p = DVec3::from(p);
        let nearest = scene
            .objects
            .iter()
            .enumerate()
            .filter_map(|(k, o)| Some((k, surface_distance(o, boxes, k, p, held)?)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((k, d)) = nearest.filter(|&(_, d)| d < held) {
            // By name too: a model file's lab scene has a ground the user never wrote.
            let object = &scene.objects[k];
            let named = match object.name() {
                "" => String::new(),
                name => format!(" ({} `{}`)", object.kind_name(), crate::number::shorten(name)),
            };
            out.push(FieldIssue {
                field: format!("{source}.position"),
                problem: format!(
                    "objects[{k}]{named} comes within {} of this inverse-square light, whose 1/d² is held to 1e6 within \
                     1e-3 of it (so that the GPU's f32 stays finite): surfaces nearer than that are lit less than \
                     1/d² says; scale the scene up (a model in millimetres: scale it by 1000 and its lights' \
                     intensities by 1e6), or move the light away",
                    format_rounded(d, 2)
                ),
            });
        }
    }
    out
}

/// How near `p` the surface of `object` comes, where that is below `within` (`None` beyond it,
/// or for an object validation has yet to judge): meshes, object `k`'s boxes in `boxes`, are read
/// triangle by triangle only where their box comes that near.
fn surface_distance(object: &ObjectDesc, boxes: &MeshBoxes, k: usize, p: DVec3, within: f64) -> Option<f64> {
    match object {
        ObjectDesc::Sphere(s) => {
            return Some((DVec3::from(s.center).distance(p) - s.radius).abs()).filter(|d| *d < within);
        }
        ObjectDesc::Plane(pl) => {
            let n = DVec3::from(pl.normal).try_normalize()?;
            return Some(n.dot(p - DVec3::from(pl.point)).abs()).filter(|d| *d < within);
        }
        ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => {}
    }
    let mut nearest: Option<f64> = None;
    for (m, mesh) in meshes_of(object).into_iter().enumerate() {
        let Some((lo, hi)) = boxes.get(k, m) else { continue };
        if box_distance(p, lo, hi) >= within {
            continue;
        }
        for t in &mesh.triangles {
            let Some([a, b, c]) = triangle_corners(mesh, t) else { continue };
            if box_distance(p, a.min(b).min(c), a.max(b).max(c)) < within {
                let d = p.distance(closest_on_triangle(p, a, b, c));
                nearest = Some(nearest.map_or(d, |n| n.min(d)));
            }
        }
    }
    nearest.filter(|d| *d < within)
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

/// Spheres of a scene file beyond which the sphere pairs are not judged (`stored_contacts`):
/// the pairs grow as the square; a scene of many spheres is generated, not written by hand.
const MAX_SPHERES_PAIRED: usize = 512;

/// A sphere that f32 storage moves into or out of contact with a plane or another sphere: as
/// written they are apart (or cut), as both tracers hold them (f32, relative to the storage
/// `origin`) they touch or cut (or are apart). Its own size hides it (a radius of 899,999,990
/// at 9e8 over a floor is stored to 32 units, 3e-8 of its radius: no coarse-storage warning),
/// while the gap it loses is 10 units: it rendered sitting on the floor (a tester). A sphere
/// inside another is judged against its inner wall, and a sphere f32 moves through a plane to
/// its other side is said to (`Contact`).
pub(super) fn stored_contacts(scene: &SceneDesc, origin: [f64; 3], epsilon: f64) -> Vec<FieldIssue> {
    let origin = DVec3::from(origin);
    let f32s = |v: DVec3| DVec3::new(f64::from(v.x as f32), f64::from(v.y as f32), f64::from(v.z as f32));
    let f32_of = |x: f64| f64::from(x as f32);
    let spheres: Vec<(usize, DVec3, f64)> = scene
        .objects
        .iter()
        .enumerate()
        .filter_map(|(k, o)| match o {
            ObjectDesc::Sphere(s) => Some((k, DVec3::from(s.center) - origin, s.radius)),
            ObjectDesc::Plane(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
        })
        .collect();
    let planes = scene.objects.iter().enumerate().filter_map(|(k, o)| match o {
        ObjectDesc::Plane(p) => {
            let n = DVec3::from(p.normal).try_normalize()?;
            Some((k, n, n.dot(DVec3::from(p.point) - origin)))
        }
        ObjectDesc::Sphere(_) | ObjectDesc::Mesh(_) | ObjectDesc::Model(_) => None,
    });
    let mut pairs: Vec<Pair> = Vec::new();
    for (j, n, d) in planes {
        for &(k, c, r) in &spheres {
            let (written, stored) = (n.dot(c) - d, f32s(n).dot(f32s(c)) - f32_of(d));
            pairs.push(Pair {
                object: k,
                other: (j, "the plane"),
                written: (written - r, -written - r),
                stored: (stored - f32_of(r), -stored - f32_of(r)),
                sides: ["in front of it", "behind it"],
                size: c.abs().max_element().max(d.abs()).max(r),
                offset: c.abs().max_element().max(d.abs()) / r,
            });
        }
    }
    if spheres.len() <= MAX_SPHERES_PAIRED {
        let gaps = |d: f64, r: f64, r2: f64| (d - r - r2, (r - r2).abs() - d);
        for (a, &(k, c, r)) in spheres.iter().enumerate() {
            for &(j, c2, r2) in &spheres[a + 1..] {
                pairs.push(Pair {
                    object: j,
                    other: (k, "the sphere"),
                    written: gaps(c.distance(c2), r, r2),
                    stored: gaps(f32s(c).distance(f32s(c2)), f32_of(r), f32_of(r2)),
                    sides: ["outside each other", "one inside the other"],
                    size: c.abs().max(c2.abs()).max_element().max(r).max(r2),
                    offset: c.abs().max(c2.abs()).max_element() / r.max(r2),
                });
            }
        }
    }
    // Touching within the render's ε, which no ray resolves, or f64's rounding of the
    // difference: a sphere set on a floor by hand (centre 1.1, radius 1, floor at 0.1) is a gap
    // of 2e-16 in f64, not a gap, and a sphere 1e-11 into a plane touches it.
    pairs
        .into_iter()
        .filter_map(|p| {
            let tolerance = epsilon.max(1e-12 * p.size);
            let (was, is) = (Contact::of(p.written, tolerance), Contact::of(p.stored, tolerance));
            // Storage must move the gap by half the tolerance at least: a gap written at ε
            // itself crossed it by f32's rounding of 1e-6 (1e-6 "in front" as written, 1e-6
            // "touching" as stored; a tester), which says nothing of f32's reach.
            let moved = (p.stored.0 - p.written.0).abs().max((p.stored.1 - p.written.1).abs());
            let step = f32_spacing(p.size);
            // Bringing them nearer the storage origin helps only where their distance from it,
            // not their own size, sets f32's step there: more than twice the size, a binade up.
            let remedy = if p.offset > 2.0 {
                format!(
                    "widen the gap beyond f32's step where they lie ({}), or bring them nearer {}",
                    format_rounded(step, 2),
                    storage_origin_named(origin.to_array())
                )
            } else {
                format!("widen the gap beyond f32's step at their size ({})", format_rounded(step, 2))
            };
            (was.0 != Contact::Touching && was.0 != is.0 && moved > 0.5 * tolerance).then(|| FieldIssue {
                field: format!("objects[{}]", p.object),
                problem: format!(
                    "with {} objects[{}]: {} as written (gap {}), but {} as both tracers store them in f32 (gap {}), \
                     and so the image shows them; {remedy} (docs/numerics.md, Known limits)",
                    p.other.1,
                    p.other.0,
                    was.0.name(p.sides),
                    format_rounded(was.1, 4),
                    is.0.name(p.sides),
                    format_rounded(is.1, 4),
                ),
            })
        })
        .collect()
}

/// A sphere and a plane or another sphere, as `stored_contacts` judges them: their gaps on
/// either side (`Contact::of`) as written and as stored, the names of those sides, and the size
/// of the numbers the gaps are differences of.
struct Pair {
    object: usize,
    other: (usize, &'static str),
    written: (f64, f64),
    stored: (f64, f64),
    sides: [&'static str; 2],
    size: f64,
    /// How far from the storage origin the pair lies, in its (larger) sphere's radii.
    offset: f64,
}

/// How two surfaces lie against each other: apart on one side or the other (a sphere in front
/// of a plane or behind it, two spheres outside each other or one inside the other),
/// touching, or cutting each other.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Contact {
    Apart,
    ApartOtherSide,
    Touching,
    Cutting,
}

impl Contact {
    /// The contact of a pair whose gaps on its two sides are `front` and `back` (> 0 where
    /// the surfaces are apart that way; both < 0 where they cut), within `tolerance`, and the
    /// gap that says it (the lesser depth where they cut).
    fn of((front, back): (f64, f64), tolerance: f64) -> (Self, f64) {
        if front > tolerance {
            (Self::Apart, front)
        } else if back > tolerance {
            (Self::ApartOtherSide, back)
        } else if front.max(back) >= -tolerance {
            (Self::Touching, front.max(back))
        } else {
            (Self::Cutting, front.max(back))
        }
    }

    fn name(self, [apart, other_side]: [&'static str; 2]) -> &'static str {
        match self {
            Self::Apart => apart,
            Self::ApartOtherSide => other_side,
            Self::Touching => "touching",
            Self::Cutting => "cutting each other",
        }
    }
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
    for &(i, pi, ni) in &planes {
        // Only the nearest parallel plane on either side is a partner: between a plane and a
        // farther one facing its way, a plane facing the other way makes two slabs (double
        // glazing, front and back panes alternating, was warned of).
        let nearest = |side: f64| {
            planes
                .iter()
                .filter(|&&(_, _, nj)| ni.dot(nj).abs() > 1.0 - 1e-12)
                .map(|&(j, pj, nj)| (j, side * ni.dot(pj - pi), nj))
                .filter(|&(_, along, _)| along > 0.0)
                .min_by(|a, b| a.1.total_cmp(&b.1))
        };
        // Said once a pair, at its first plane in the file.
        // Both sides: a plane between two that face its way is one of two such pairs.
        for (j, _, _) in [1.0, -1.0].into_iter().filter_map(nearest).filter(|&(j, _, nj)| j > i && ni.dot(nj) > 0.0) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::desc::{PlaneDesc, test_scene};
    use crate::rgb::Rgb;

    /// Glass planes at z with their normals' z sign, front to back.
    fn panes(planes: &[(f64, f64)]) -> Vec<String> {
        let objects = planes
            .iter()
            .map(|&(z, facing)| {
                let plane = PlaneDesc {
                    point: [0.0, 0.0, z],
                    normal: [0.0, 0.0, facing],
                    material: "m".into(),
                    name: String::new(),
                };
                ObjectDesc::Plane(plane)
            })
            .collect();
        let mut scene = test_scene(objects);
        scene.materials.get_mut("m").expect("material").kt = Rgb([0.9; 3]);
        same_facing_transmissive_planes(&scene).into_iter().map(|w| w.field).collect()
    }

    #[test]
    fn an_inverse_square_light_nearer_a_surface_than_its_held_distance_is_warned_of() {
        use crate::desc::SphereDesc;
        use crate::light::{Attenuation, LightDesc};
        use crate::mesh::MeshDesc;
        use glint_types::LightKind;
        let warned = |attenuation: Attenuation, gap: f64| {
            let sphere = SphereDesc { center: [0.0; 3], radius: 1e-4, material: "m".into(), name: "bead".into() };
            let far_triangle =
                MeshDesc::new(vec![[1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]], vec![[0, 1, 2]], "m", "");
            let mut scene = test_scene(vec![ObjectDesc::Mesh(far_triangle), ObjectDesc::Sphere(sphere)]);
            let mut light = LightDesc::new(LightKind::Point, [0.0, 1e-4 + gap, 0.0], [0.0; 3]);
            light.attenuation = attenuation;
            scene.lights.push(light);
            held_falloffs(&scene, &MeshBoxes::of(&scene.objects))
                .into_iter()
                .map(|w| format!("{}: {}", w.field, w.problem))
                .collect::<Vec<_>>()
        };
        let square = Attenuation::InverseSquare { range: None };
        let near = warned(square, 3e-4);
        assert_eq!(near.len(), 1, "{near:?}");
        assert!(
            near[0].starts_with(
                "lights[0].position: objects[1] (sphere `bead`) comes within 0.0003 of this inverse-square light"
            ),
            "{near:?}"
        );
        assert!(warned(square, 2e-3).is_empty());
        assert!(warned(Attenuation::NONE, 3e-4).is_empty(), "a polynomial falloff is bounded by its own rule");
        // A triangle's nearest point, not its corners: the light 5e-4 over the middle of an edge.
        let edge = MeshDesc::new(vec![[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]], vec![[0, 1, 2]], "m", "");
        let mut scene = test_scene(vec![ObjectDesc::Mesh(edge)]);
        let mut light = LightDesc::new(LightKind::Point, [0.0, 5e-4, 0.0], [0.0; 3]);
        light.attenuation = square;
        scene.lights.push(light);
        assert_eq!(held_falloffs(&scene, &MeshBoxes::of(&scene.objects)).len(), 1);
        // A model's own glTF light, placed with it (`lights = true`), is judged as one of the
        // scene's: the case that asked for the warning (a tester).
        let mut glb = LightDesc::new(LightKind::Point, [0.0, 2e-4, 0.0], [0.0; 3]);
        glb.attenuation = square;
        let bead =
            MeshDesc::new(vec![[-1e-4, 0.0, 0.0], [1e-4, 0.0, 0.0], [0.0, 0.0, 1e-4]], vec![[0, 1, 2]], "m", "bead");
        let model = crate::model::Model { meshes: vec![bead], lights: vec![glb], ..Default::default() };
        let placed = crate::model_ref::LoadedModel::place("bead.glb".into(), model, &Default::default(), "bead");
        let reference = crate::model_ref::ModelDesc {
            path: "bead.glb".into(),
            transform: Default::default(),
            scene_index: None,
            name: String::new(),
            lights: true,
            exposure: None,
            loaded: Some(std::sync::Arc::new(placed)),
        };
        let scene = test_scene(vec![ObjectDesc::Model(Box::new(reference))]);
        let said = held_falloffs(&scene, &MeshBoxes::of(&scene.objects));
        assert_eq!(said.len(), 1, "{said:?}");
        assert_eq!(said[0].field, "objects[0].lights[0].position");
        assert!(said[0].problem.starts_with("objects[0] comes within 0.0002 of this inverse-square light"), "{said:?}");
    }

    #[test]
    fn same_facing_neighbours_are_warned_of_and_alternating_panes_are_not() {
        // Two slabs (double glazing): front faces −z, back faces +z, twice.
        assert!(panes(&[(-1.0, -1.0), (-0.9, 1.0), (0.0, -1.0), (0.1, 1.0)]).is_empty());
        // A slab whose back plane faces into it: said once, at the pair's first plane.
        assert_eq!(panes(&[(-1.0, -1.0), (-0.9, -1.0)]), ["objects[0]"]);
        // Listed back to front, with a farther same-facing plane beyond a correct slab.
        assert_eq!(panes(&[(1.0, 1.0), (0.0, 1.0), (-0.1, -1.0)]), ["objects[0]"]);
        // Three facing one way, the first listed between the others: both its pairs.
        assert_eq!(panes(&[(1.0, 1.0), (0.0, 1.0), (2.0, 1.0)]), ["objects[0]", "objects[0]"]);
    }
}
