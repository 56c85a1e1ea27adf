//! Objects: spheres, planes, meshes and models.

// What the parent module declares for its children.
use super::{
    DVec3, FieldIssue, MeshDesc, ObjectDesc, PlaneDesc, Report, Rgb, SceneDesc, SphereDesc, cross, num, ranges,
    shorten, sub, usable_direction, validate_light,
};
use crate::mesh::has_area;
use crate::number::{format_beyond, format_rounded};
use glint_types::layout::f32_spacing;

/// `origin`: the scene's storage origin (`storage_origin`), which mesh vertices are stored
/// relative to.
pub(super) fn validate_object(path: &str, o: &ObjectDesc, scene: &SceneDesc, origin: [f64; 3], r: &mut Report) {
    for material in o.materials() {
        if !scene.materials.contains_key(material) {
            let known: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
            r.error(
                format!("{path}.material"),
                format!(
                    "unknown material '{}'; defined materials: [{}]",
                    shorten(material),
                    shorten(&known.join(", "))
                ),
            );
        }
    }
    match o {
        ObjectDesc::Sphere(SphereDesc { center, radius, .. }) => {
            r.point(&format!("{path}.center"), *center);
            r.size(&format!("{path}.radius"), *radius, ranges::SIZE);
            if let Some(coarse) = coarsely_stored(&[*center], *radius, "radius", origin) {
                r.warn(format!("{path}.center"), format!("the sphere (radius {}) {coarse}", num(*radius)));
            }
        }
        ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
            r.point(&format!("{path}.point"), *point);
            r.direction(&format!("{path}.normal"), *normal);
        }
        ObjectDesc::Mesh(mesh) => validate_mesh(path, mesh, origin, r),
        ObjectDesc::Model(model) => {
            for (field, problem) in model.transform.problems() {
                r.error(format!("{path}.transform.{field}"), problem);
            }
            if let Some(exposure) = model.exposure {
                r.size(&format!("{path}.exposure"), exposure, ranges::EXPOSURE);
            }
            if model.lights
                && let Some(loaded) = &model.loaded
            {
                for (j, light) in loaded.lights.iter().enumerate() {
                    validate_light(&format!("{path}.lights[{j}]"), light, r);
                }
            }
            let transformed = model.transform != Default::default();
            match &model.loaded {
                // Placed beyond the coordinates a scene may hold: one error naming what placed it,
                // not one per vertex and normal component (a spider scaled by 1e300 gave 5,917).
                Some(loaded) if let Some(problem) = beyond_range(loaded, transformed) => {
                    let field = if transformed { "transform" } else { "path" };
                    r.error(format!("{path}.{field}"), problem);
                }
                // Named by the model's own mesh names (`PREFIX/NODE`), which say where to look.
                Some(loaded) => {
                    // Errors one by one; warnings of a kind once for the model (a CAD export
                    // has degenerate triangles in a hundred meshes), with how many meshes share it.
                    let mut meshes = Report::default();
                    for (k, mesh) in loaded.meshes.iter().enumerate() {
                        validate_mesh(&format!("{path} mesh {k} `{}`", mesh.name), mesh, origin, &mut meshes);
                    }
                    r.errors.append(&mut meshes.errors);
                    let mut kinds: Vec<(String, FieldIssue, usize)> = Vec::new();
                    for w in meshes.warnings {
                        let kind = w.field.rsplit('.').next().unwrap_or_default().to_string();
                        match kinds.iter_mut().find(|(k, ..)| *k == kind) {
                            Some((_, _, n)) => *n += 1,
                            None => kinds.push((kind, w, 1)),
                        }
                    }
                    for (_, first, n) in kinds {
                        let more =
                            if n > 1 { format!(" (and likewise in {} more meshes)", n - 1) } else { String::new() };
                        r.warn(first.field, format!("{}{more}", first.problem));
                    }
                }
                None => r.error(format!("{path}.path"), format!("the model `{}` was not loaded", model.path)),
            }
        }
    }
}

/// Why a placed model lies beyond the coordinates a scene may hold (`MAX_COORD`): how far its
/// vertices reach from the origin, or that some are not finite; said of the transform where one
/// placed it (`transformed`: the file's own reach is not known apart from it), else of the file.
fn beyond_range(model: &crate::LoadedModel, transformed: bool) -> Option<String> {
    let coords = || model.meshes.iter().flat_map(|m| m.vertices.iter().flatten().copied());
    let with = if transformed { "with this transform, " } else { "" };
    if coords().any(|c| !c.is_finite()) {
        return Some(format!(
            "{with}the model's vertices are not finite numbers; coordinates must lie in [{:e}, {:e}]",
            ranges::COORD.min,
            ranges::COORD.max
        ));
    }
    let reach = coords().fold(0.0f64, |m, c| m.max(c.abs()));
    (!ranges::COORD.contains(reach)).then(|| {
        format!(
            "{with}the model reaches {} from the origin; coordinates must lie in [{:e}, {:e}]",
            format_beyond(reach, ranges::COORD.max),
            ranges::COORD.min,
            ranges::COORD.max
        )
    })
}

fn validate_mesh(path: &str, mesh: &MeshDesc, origin: [f64; 3], r: &mut Report) {
    let MeshDesc { vertices, triangles, normals, uvs, colours, .. } = mesh;

    if triangles.is_empty() {
        r.error(format!("{path}.triangles"), "a mesh needs at least one triangle [i, j, k]");
    }
    // Each field name is formatted only for a value at fault: a million vertices would
    // otherwise cost a million strings on every edit in the viewer.
    let in_range = |p: &[f64]| p.iter().all(|&c| ranges::COORD.contains(c));
    for (i, v) in vertices.iter().enumerate().filter(|(_, v)| !in_range(&v[..])) {
        r.point(&format!("{path}.vertices[{i}]"), *v);
    }
    let n = vertices.len();
    if n == 0 && !triangles.is_empty() {
        r.error(
            format!("{path}.vertices"),
            format!(
                "the mesh has no vertices, but {} to them; give the vertex positions [x, y, z]",
                if triangles.len() == 1 {
                    "its triangle refers".to_string()
                } else {
                    format!("its {} triangles refer", triangles.len())
                }
            ),
        );
    }
    for (i, t) in triangles.iter().enumerate().filter(|_| n > 0) {
        if let Some(bad) = t.iter().find(|&&k| k as usize >= n) {
            r.error(
                format!("{path}.triangles[{i}]"),
                format!("vertex index {bad} is out of range; allowed: [0, {}]", n.saturating_sub(1)),
            );
        }
    }
    if let Some(normals) = normals {
        if normals.len() != n {
            r.error(format!("{path}.normals"), format!("has {} entries; it needs one per vertex ({n})", normals.len()));
        }
        for (i, v) in normals.iter().enumerate().filter(|(_, v)| !(in_range(&v[..]) && usable_direction(**v))) {
            r.direction(&format!("{path}.normals[{i}]"), *v);
        }
    }
    if let Some(uvs) = uvs {
        if uvs.len() != n {
            r.error(format!("{path}.uvs"), format!("has {} entries; it needs one per vertex ({n})", uvs.len()));
        }
        for (i, uv) in uvs.iter().enumerate().filter(|(_, uv)| !in_range(&uv[..])) {
            for (axis, v) in ["u", "v"].iter().zip(uv) {
                r.finite_in(&format!("{path}.uvs[{i}].{axis}"), *v, ranges::COORD);
            }
        }
    }
    if let Some(colours) = colours {
        if colours.len() != n {
            r.error(format!("{path}.colours"), format!("has {} entries; it needs one per vertex ({n})", colours.len()));
        }
        let usable = |c: &[f64; 3]| c.iter().all(|&v| ranges::COLOUR.contains(v));
        for (i, c) in colours.iter().enumerate().filter(|(_, c)| !usable(c)) {
            r.colour(&format!("{path}.colours[{i}]"), Rgb(*c));
        }
        // Allowed (as k_d > 1 is), but 8-bit colours written as 0–255 light a mesh 255-fold.
        let brightest = colours.iter().flatten().copied().filter(|v| v.is_finite()).fold(0.0, f64::max);
        if brightest > 1.0 {
            r.warn(
                format!("{path}.colours"),
                format!(
                    "reach {}: above 1 they make k_a and k_d return more light than they receive \
                     (colours written as 0–255 need dividing by 255)",
                    num(brightest)
                ),
            );
        }
    }
    if let Some(normals) = normals.as_ref().filter(|ns| ns.len() == n) {
        let against = triangles
            .iter()
            .filter(|t| t.iter().all(|&k| (k as usize) < n))
            .filter(|t| {
                let [a, b, c] = t.map(|k| vertices[k as usize]);
                let ng = cross(sub(b, a), sub(c, a));
                t.iter().any(|&k| ng.dot(DVec3::from(normals[k as usize])) < 0.0)
            })
            .count();
        if against > 0 {
            r.warn(
                format!("{path}.normals"),
                format!(
                    "{against} triangles have a vertex normal pointing against their winding \
                         (cross(b − a, c − a)); they shade as if lit from behind"
                ),
            );
        }
    }
    // Both tracers store vertices as f32 relative to the scene's storage origin: far from it,
    // where f32 steps grow past a model's triangles (a scene spanning a far wider range than
    // its smallest details), a triangle with area in the file has none as stored.
    let relative = |p: [f64; 3]| [0, 1, 2].map(|k| p[k] - origin[k]);
    let stored = |p: [f64; 3]| relative(p).map(|c| f64::from(c as f32));
    let (mut degenerate, mut rounded_flat) = (0, 0);
    for t in triangles.iter().filter(|t| t.iter().all(|&k| (k as usize) < n)) {
        let corners = t.map(|k| vertices[k as usize]);
        if !has_area(corners) {
            degenerate += 1;
        } else if !has_area(corners.map(stored)) {
            rounded_flat += 1;
        }
    }
    if degenerate > 0 {
        r.warn(
            format!("{path}.triangles"),
            format!("{degenerate} degenerate (zero-area) triangles; they are never hit"),
        );
    }
    if rounded_flat > 0 {
        let reach = vertices.iter().flat_map(|&v| relative(v)).fold(0.0f64, |m, c| m.max(c.abs()));
        let step = f32_spacing(reach);
        let from = storage_origin_named(origin);
        r.warn(
            format!("{path}.vertices"),
            format!(
                "{rounded_flat} triangles have no area once their vertices are stored as f32, as both \
                 tracers store them (coordinates reach {reach:.3e} from {from}, where f32 steps are {step:.3e}): \
                 they are never hit; the scene spans too wide a range for details this small (render them \
                 in a scene of their own)"
            ),
        );
    } else if let Some(size) = mesh_size(mesh)
        && let Some(coarse) = coarsely_stored(vertices, size, "size", origin)
    {
        r.warn(format!("{path}.vertices"), format!("the mesh (size {}) {coarse}", format_rounded(size, 3)));
    }
}

pub(super) fn storage_origin_named(origin: [f64; 3]) -> String {
    if origin == [0.0; 3] {
        "the origin".to_string()
    } else {
        format!("the scene's storage origin [{}, {}, {}]", num(origin[0]), num(origin[1]), num(origin[2]))
    }
}

/// Storage error, as a share of an object's size, from which it is warned about: an object
/// 10,000 pixels across moves by a pixel.
const VISIBLE_STORAGE_ERROR: f64 = 1e-4;

/// Why points stored as f32 relative to `origin` (as both tracers store them) may move an
/// object of `size` (its `measure`: "radius", "size") visibly: the rest of a warning, or
/// `None`. A scene that spans far more than an object (a ground of 1e8 under spheres at map
/// coordinates puts the storage origin at the ground's centre) keeps the object to f32 of that
/// span, not of its own size; no triangle need lose its area for the image to change. A scene
/// far from the world origin whose own storage origin f32 cannot put near it has the same fault.
fn coarsely_stored(points: &[[f64; 3]], size: f64, measure: &str, origin: [f64; 3]) -> Option<String> {
    let reach = points.iter().flat_map(|p| [0, 1, 2].map(|k| (p[k] - origin[k]).abs())).fold(0.0, f64::max);
    let error = 0.5 * f32_spacing(reach);
    if !(size > 0.0 && reach.is_finite()) || error <= VISIBLE_STORAGE_ERROR * size {
        return None;
    }
    let far = origin.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    let remedy = if far > 0.0 && reach <= f32_spacing(far) {
        format!(
            "the scene lies too far from the world origin for f32 to put its storage origin nearer (steps of {} \
             there): move it nearer the world origin",
            num(f32_spacing(far))
        )
    } else {
        // Where the whole scene is only offset, moving it to the world origin is the remedy:
        // near it the storage origin is the world origin, exact for what is near.
        "the scene spans too wide a range for a detail this small where it lies: move the whole scene to the world \
         origin if it is only offset, else render this detail on its own"
            .to_string()
    };
    Some(format!(
        "is stored as f32 {} from {}, to {} ({} of its {measure}; the GPU errs more): {remedy} (docs/numerics.md, \
         Known limits)",
        format_rounded(reach, 3),
        storage_origin_named(origin),
        format_rounded(error, 3),
        format_rounded(error / size, 2),
    ))
}

/// The diagonal of a mesh's vertices' box, `None` for a mesh of one point or none.
fn mesh_size(mesh: &MeshDesc) -> Option<f64> {
    let (lo, hi) = super::near::mesh_box(mesh)?;
    let size = (hi - lo).length();
    (size.is_finite() && size > 0.0).then_some(size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_object_f32_storage_moves_visibly_is_warned_about_with_its_cause() {
        let scene: SceneDesc =
            toml::from_str("[camera]\nposition = [0.0, 0.0, -4.0]\nlook_at = [0.0, 0.0, 0.0]\n").expect("scene");
        let sphere = |center: [f64; 3], radius: f64, origin: [f64; 3]| {
            let mut r = Report::default();
            let object =
                ObjectDesc::Sphere(SphereDesc { center, radius, material: String::new(), name: String::new() });
            validate_object("objects[0]", &object, &scene, origin, &mut r);
            r.warnings.into_iter().map(|w| format!("{}: {}", w.field, w.problem)).collect::<Vec<_>>()
        };
        // Spheres at map coordinates stored in world space (a ground of 1e8 under them keeps the
        // origin there): f32 steps of 0.25 move a radius of 0.75 by a sixth of it.
        let far = sphere([1234567.3, -2345678.9, 345678.1], 0.75, [0.0; 3]);
        assert_eq!(far.len(), 1, "{far:?}");
        assert!(far[0].starts_with("objects[0].center: the sphere (radius 0.75) is stored as f32 2350000 from the origin, to 0.125 (0.17 of its radius"), "{far:?}");
        assert!(far[0].contains("move the whole scene to the world origin if it is only offset"), "{far:?}");
        // Stored near its own origin it keeps its size's digits; at the origin, as every scene
        // made there.
        assert!(sphere([1234567.3, -2345678.9, 345678.1], 0.75, [1234567.0, -2345679.0, 345678.0]).is_empty());
        assert!(sphere([0.9, 1.1, 1.6], 1.1, [0.0; 3]).is_empty());
        // A micro-scene beyond what f32 can put an origin near: the cause is the distance.
        let micro = sphere([0.0, 4779855.25, 0.0], 1.1e-6, [0.0, 4779855.0, 0.0]);
        assert!(micro[0].contains("move it nearer the world origin"), "{micro:?}");
        // A mesh likewise, by its own size.
        let mut r = Report::default();
        validate_mesh("m", &tiny(1e3), [0.0; 3], &mut r);
        assert!(
            r.warnings.iter().any(|w| w.field == "m.vertices" && w.problem.starts_with("the mesh (size ")),
            "{:?}",
            r.warnings
        );
    }

    /// A triangle of 1e-3 sides at `offset`, and one of zero area.
    fn tiny(offset: f64) -> MeshDesc {
        let vertices = [[0.0, 0.0, 0.0], [1e-3, 0.0, 0.0], [0.0, 1e-3, 0.0], [2e-3, 0.0, 0.0]]
            .map(|v| v.map(|c| c + offset))
            .to_vec();
        MeshDesc::new(vertices, vec![[0, 1, 2], [0, 1, 3]], "m", "")
    }

    fn warnings(offset: f64, origin: [f64; 3]) -> Vec<String> {
        let mut report = Report::default();
        validate_mesh("m", &tiny(offset), origin, &mut report);
        assert!(report.errors.is_empty(), "{:?}", report.errors);
        report.warnings.into_iter().map(|w| format!("{}: {}", w.field, w.problem)).collect()
    }

    #[test]
    fn a_triangle_that_loses_its_area_in_f32_is_warned_with_the_cause() {
        let degenerate = "m.triangles: 1 degenerate (zero-area) triangles; they are never hit";
        assert_eq!(warnings(0.0, [0.0; 3]), [degenerate]);
        // At 1e5 from the storage origin an f32 step is 7.8e-3, more than the triangle's sides.
        let far = warnings(1e5, [0.0; 3]);
        assert_eq!(far.len(), 2, "{far:?}");
        assert!(
            far[1].starts_with("m.vertices: 1 triangles have no area once their vertices are stored as f32")
                && far[1].contains("coordinates reach 1.000e5 from the origin, where f32 steps are 7.812e-3"),
            "{far:?}"
        );
        // Stored relative to an origin beside it, it keeps its area.
        assert_eq!(warnings(1e5, [1e5; 3]), [degenerate]);
        let beside = warnings(0.0, [-1e5, 0.0, 0.0]);
        assert!(beside[1].contains("from the scene's storage origin [-100000, 0, 0]"), "{beside:?}");
    }

    #[test]
    fn the_scene_s_storage_origin_decides() {
        let scene = crate::desc::test_scene;
        let lost = |r: &Report| r.warnings.iter().any(|w| w.problem.contains("no area once"));
        // Alone, 1e5 from the world origin: stored beside it, nothing is lost.
        let alone = super::super::validate_objects(&scene(vec![ObjectDesc::Mesh(tiny(1e5))]));
        assert!(alone.errors.is_empty() && !lost(&alone), "{alone:?}");
        // With a mesh at the world origin the scene spans 1e5, and is stored around the origin.
        let wide =
            super::super::validate_objects(&scene(vec![ObjectDesc::Mesh(tiny(1e5)), ObjectDesc::Mesh(tiny(0.0))]));
        assert!(lost(&wide), "{wide:?}");
    }
}
