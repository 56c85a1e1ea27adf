//! KHR_lights_punctual lights and glTF cameras, placed by their node's world transform.

use glint_scene::{Attenuation, CameraDesc, FieldIssue, LightDesc, LightKind, Rgb, SpotFalloff};
use glint_scene::{MAX_INTENSITY, Mat4, ModelCamera};
use glint_scene::{format_number as number, format_rounded};

/// An f32 the file wrote, as short as it reads back (`1e30`, not the f64 widening's
/// 1.0000000150474662e30).
fn written(v: f32) -> String {
    number(v.to_string().parse().unwrap_or(f64::from(v)))
}

fn normalized(v: [f64; 3]) -> Option<[f64; 3]> {
    let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    (len.is_finite() && len > 1e-300).then(|| v.map(|c| c / len))
}

/// The light of `node` (world transform `world`): colour × intensity × `exposure` as I_d and
/// I_s (candela for point and spot lights, lux for directional ones), down the node's −Z. An
/// intensity the scene cannot hold is an error naming the file's own fields (its path, the
/// problem), not the `lights[i].diffuse` Glint maps it to.
pub(super) fn map_light(
    light: &::gltf::khr_lights_punctual::Light<'_>,
    world: &Mat4,
    exposure: f64,
    node: usize,
    warnings: &mut Vec<FieldIssue>,
) -> Result<Option<LightDesc>, (String, String)> {
    let field = format!("nodes[{node}].extensions.KHR_lights_punctual (lights[{}])", light.index());
    let own = format!("extensions.KHR_lights_punctual.lights[{}]", light.index());
    let intensity = f64::from(light.intensity());
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err((
            format!("{own}.intensity"),
            format!("{} must be a finite number ≥ 0", written(light.intensity())),
        ));
    }
    let colour = light.color().map(|c| f64::from(c) * intensity * exposure);
    if let Some(brightest) = colour.iter().copied().filter(|c| *c > MAX_INTENSITY).reduce(f64::max) {
        let scale = MAX_INTENSITY / brightest * exposure;
        return Err((
            format!("{own}.intensity"),
            format!(
                "{} × colour × exposure {} reaches {}, beyond the {MAX_INTENSITY:e} a light may have: lower \
                 the exposure (--exposure, or a model object's exposure) to {} or less (it scales every light of \
                 the file)",
                written(light.intensity()),
                number(exposure),
                format_rounded(brightest, 3),
                format_rounded(scale, 2)
            ),
        ));
    }
    let position = world.point([0.0; 3]);
    let Some(direction) = normalized(world.vector([0.0, 0.0, -1.0])) else {
        warnings
            .push(FieldIssue { field, problem: "the node's transform has no −Z direction; light skipped".into() });
        return Ok(None);
    };
    let kind = match light.kind() {
        ::gltf::khr_lights_punctual::Kind::Directional => LightKind::Directional,
        ::gltf::khr_lights_punctual::Kind::Point => LightKind::Point,
        ::gltf::khr_lights_punctual::Kind::Spot { .. } => LightKind::Spot,
    };
    let mut desc = LightDesc {
        diffuse: Rgb(colour),
        specular: Rgb(colour),
        name: light.name().map_or_else(|| format!("light {}", light.index()), str::to_string),
        ..LightDesc::new(kind, position, direction)
    };
    if kind != LightKind::Directional {
        // glTF's falloff: 1/d², windowed by `range` when the light has one.
        desc.attenuation = Attenuation::inverse_square(light.range().map(f64::from));
    }
    if let ::gltf::khr_lights_punctual::Kind::Spot { inner_cone_angle, outer_cone_angle } = light.kind() {
        // glTF's smooth cone, 0 ≤ inner < outer ≤ π/2; the angles in degrees within the [0, 90]
        // validation allows, and a file outside that told what was made of it.
        let (inner, outer) = (f64::from(inner_cone_angle), f64::from(outer_cone_angle));
        let degrees = |a: f64| a.to_degrees().clamp(0.0, 90.0);
        let (inner_deg, outer_deg) = (degrees(inner).min(degrees(outer)), degrees(outer));
        // π/2 as the file's f32 holds it (1.5707964, above f64's π/2): a 180° cone is valid.
        let right = f64::from(std::f32::consts::FRAC_PI_2);
        if !(0.0..=right).contains(&inner) || !(0.0..=right).contains(&outer) || inner > outer {
            warnings.push(FieldIssue {
                field: format!("{own}.spot"),
                problem: format!(
                    "innerConeAngle {} and outerConeAngle {} break 0 ≤ inner ≤ outer ≤ π/2; taken as {}° and {}°",
                    written(inner_cone_angle),
                    written(outer_cone_angle),
                    format_rounded(inner_deg, 4),
                    format_rounded(outer_deg, 4)
                ),
            });
        }
        desc.falloff = SpotFalloff::Smooth;
        desc.inner_cone = Some(inner_deg);
        desc.outer_cone = Some(outer_deg);
    }
    Ok(Some(desc))
}

/// A perspective camera at its node: the eye at the origin, looking down −Z with +Y up.
/// Orthographic cameras are skipped with a warning (Glint's camera is a pinhole).
pub(super) fn map_camera(
    camera: &::gltf::Camera<'_>,
    world: &Mat4,
    node: usize,
    warnings: &mut Vec<FieldIssue>,
) -> Option<ModelCamera> {
    let field = format!("nodes[{node}].camera (cameras[{}])", camera.index());
    let ::gltf::camera::Projection::Perspective(p) = camera.projection() else {
        warnings.push(FieldIssue { field, problem: "orthographic cameras are not supported; skipped".into() });
        return None;
    };
    let position = world.point([0.0; 3]);
    let (Some(forward), Some(up)) =
        (normalized(world.vector([0.0, 0.0, -1.0])), normalized(world.vector([0.0, 1.0, 0.0])))
    else {
        warnings.push(FieldIssue { field, problem: "the node's transform is degenerate; camera skipped".into() });
        return None;
    };
    if world.determinant3() < 0.0 {
        // A mirroring node turns the camera's +X to the image's left; Glint's camera (eye, target,
        // up) has no handedness to carry that, and a silently unmirrored view misleads.
        warnings.push(FieldIssue {
            field: field.clone(),
            problem: "the node mirrors (a negative scale): Glint's camera does not mirror its image, so the \
                      view is the unmirrored one, its right forward × up"
                .into(),
        });
    }
    let fov_y = f64::from(p.yfov()).to_degrees();
    // Judged by the range a scene's camera has, so that a yfov a hair under π is skipped as
    // yfov 0 is, not refused later under Glint's `camera.fov_y`.
    let range = glint_scene::ranges::FOV_Y;
    if !(fov_y.is_finite() && range.contains(fov_y)) {
        let (lo, hi) = (range.min.to_radians(), range.max.to_radians());
        warnings.push(FieldIssue {
            field,
            problem: format!(
                "yfov {} (cameras[{}].perspective.yfov) is outside [{}, {}] radians ({}° to {}°); camera skipped",
                written(p.yfov()),
                camera.index(),
                format_rounded(lo, 3),
                format_rounded(hi, 6),
                number(range.min),
                number(range.max)
            ),
        });
        return None;
    }
    // The specification requires aspectRatio > 0: another is left out, said, and the image
    // keeps its size.
    let aspect = p.aspect_ratio().filter(|a| {
        let usable = a.is_finite() && *a > 0.0;
        if !usable {
            warnings.push(FieldIssue {
                field: field.clone(),
                problem: format!(
                    "aspectRatio {} (cameras[{}].perspective.aspectRatio) is not a positive number; left out, the \
                     image keeps its width and height",
                    written(*a),
                    camera.index()
                ),
            });
        }
        usable
    });
    Some(ModelCamera {
        name: camera.name().map_or_else(|| format!("camera {}", camera.index()), str::to_string),
        camera: CameraDesc { position, look_at: std::array::from_fn(|k| position[k] + forward[k]), up, fov_y },
        aspect: aspect.map(crate::model::widen),
    })
}
