//! KHR_lights_punctual lights and glTF cameras, placed by their node's world transform.

use glint_scene::{Attenuation, CameraDesc, FieldIssue, LightDesc, LightKind, Projection, Rgb, SpotFalloff};
use glint_scene::{MAX_INTENSITY, Mat4, ModelCamera};
use glint_scene::{format_number as number, format_rounded};

/// The end of every warning of a camera left out, which `--camera`'s error lists when its count
/// is short of the file's (`model::scene_around`).
pub(crate) const CAMERA_SKIPPED: &str = "camera skipped";

/// An f32 the file wrote, as short as it reads back (`1e30`, not the f64 widening's
/// 1.0000000150474662e30).
fn written(v: f32) -> String {
    number(v.to_string().parse().unwrap_or(f64::from(v)))
}

/// The intensity of light `index` of the file's KHR_lights_punctual as its JSON wrote it, in
/// f64 (`None` where it does not read so).
fn written_intensity(bytes: &[u8], index: usize) -> Option<f64> {
    let json: serde_json::Value = serde_json::from_slice(&super::nodes::json_text(bytes)?).ok()?;
    json.pointer(&format!("/extensions/KHR_lights_punctual/lights/{index}/intensity"))?.as_f64()
}

fn normalized(v: [f64; 3]) -> Option<[f64; 3]> {
    let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    (len.is_finite() && len > 1e-300).then(|| v.map(|c| c / len))
}

/// The light of `node` (world transform `world`): colour × intensity × `exposure` as I_d and
/// I_s (candela for point and spot lights, lux for directional ones), down the node's −Z. An
/// intensity the scene cannot hold is an error naming the file's own fields (its path, the
/// problem), not the `lights[i].diffuse` Glint maps it to.
///
/// The gltf crate keeps the intensity in f32, where a number beyond f32's range is infinite:
/// `bytes` (the file's) give it as the JSON wrote it then, so that 1e300 is said as 1e300.
pub(super) fn map_light(
    light: &::gltf::khr_lights_punctual::Light<'_>,
    world: &Mat4,
    exposure: f64,
    node: usize,
    bytes: &[u8],
    warnings: &mut Vec<FieldIssue>,
) -> Result<Option<LightDesc>, (String, String)> {
    let field = format!("nodes[{node}].extensions.KHR_lights_punctual (lights[{}])", light.index());
    let own = format!("extensions.KHR_lights_punctual.lights[{}]", light.index());
    let intensity = match f64::from(light.intensity()) {
        i if i.is_infinite() => written_intensity(bytes, light.index()).unwrap_or(i),
        i => i,
    };
    // As written: f32's rounding of 1e300 is infinite, and was said as "inf" (a tester).
    let said = if intensity == f64::from(light.intensity()) { written(light.intensity()) } else { number(intensity) };
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err((format!("{own}.intensity"), format!("{said} must be a finite number ≥ 0")));
    }
    // The file's own fields named, not the lights[i].diffuse Glint maps them to (a colour of
    // −1 was refused as "lights[0].diffuse: channel r = -1", of another light's index).
    let (rgb, color) = (["r", "g", "b"], light.color());
    for (k, c) in color.into_iter().enumerate() {
        if !(c.is_finite() && c >= 0.0) {
            return Err((format!("{own}.color"), format!("{} = {} must be in [0, 1]", rgb[k], written(c))));
        }
    }
    if let Some(range) = light.range().filter(|r| !(r.is_finite() && *r > 0.0)) {
        return Err((format!("{own}.range"), format!("{} must be a finite number > 0", written(range))));
    }
    let colour = color.map(|c| f64::from(c.min(1.0)) * intensity * exposure);
    if let Some(k) = color.iter().position(|c| *c > 1.0) {
        warnings.push(FieldIssue {
            field: format!("{own}.color"),
            problem: format!("{} = {} is outside [0, 1]; taken as 1", rgb[k], written(color[k])),
        });
    }
    if let Some(brightest) = colour.iter().copied().filter(|c| *c > MAX_INTENSITY).reduce(f64::max) {
        let scale = MAX_INTENSITY / brightest * exposure;
        return Err((
            format!("{own}.intensity"),
            format!(
                "{said} × colour × exposure {} reaches {}, beyond the {MAX_INTENSITY:e} a light may have \
                 (intensity × colour × exposure must lie in [0, {MAX_INTENSITY:e}]): lower the exposure \
                 (--exposure, or a model object's exposure) to {} or less (it scales every light of the file)",
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

/// A camera at its node: the eye at the origin, looking down −Z with +Y up; perspective
/// (`perspective_view`) or orthographic (`orthographic_view`).
pub(super) fn map_camera(
    camera: &::gltf::Camera<'_>,
    world: &Mat4,
    node: usize,
    warnings: &mut Vec<FieldIssue>,
) -> Option<ModelCamera> {
    let field = format!("nodes[{node}].camera (cameras[{}])", camera.index());
    let position = world.point([0.0; 3]);
    let (Some(forward), Some(up)) =
        (normalized(world.vector([0.0, 0.0, -1.0])), normalized(world.vector([0.0, 1.0, 0.0])))
    else {
        warnings.push(FieldIssue { field, problem: format!("the node's transform is degenerate; {CAMERA_SKIPPED}") });
        return None;
    };
    let look_at = std::array::from_fn(|k| position[k] + forward[k]);
    let (desc, aspect) = match camera.projection() {
        ::gltf::camera::Projection::Perspective(p) => {
            let (fov_y, aspect) = perspective_view(&p, camera.index(), &field, warnings)?;
            (CameraDesc::perspective(position, look_at, up, fov_y), aspect)
        }
        ::gltf::camera::Projection::Orthographic(o) => {
            let (view_height, aspect) = orthographic_view(&o, camera.index(), &field, warnings)?;
            let pinhole = CameraDesc::perspective(position, look_at, up, 45.0);
            (CameraDesc { projection: Projection::Orthographic, view_height: Some(view_height), ..pinhole }, aspect)
        }
    };
    if world.determinant3() < 0.0 {
        // A mirroring node turns the camera's +X to the image's left; Glint's camera (eye, target,
        // up) has no handedness to carry that, and a silently unmirrored view misleads.
        warnings.push(FieldIssue {
            field,
            problem: "the node mirrors (a negative scale): Glint's camera does not mirror its image, so the \
                      view is the unmirrored one, its right forward × up"
                .into(),
        });
    }
    Some(ModelCamera {
        name: camera.name().map_or_else(|| format!("camera {}", camera.index()), str::to_string),
        camera: desc,
        aspect: aspect.map(crate::model::widen),
    })
}

/// A perspective camera's field of view (degrees) and aspect ratio, or `None` (said) where the
/// field of view is outside what a scene's camera may have.
fn perspective_view(
    p: &::gltf::camera::Perspective<'_>,
    index: usize,
    field: &str,
    warnings: &mut Vec<FieldIssue>,
) -> Option<(f64, Option<f32>)> {
    let fov_y = f64::from(p.yfov()).to_degrees();
    // Judged by the range a scene's camera has, so that a yfov a hair under π is skipped as
    // yfov 0 is, not refused later under Glint's `camera.fov_y`.
    let range = glint_scene::ranges::FOV_Y;
    if !(fov_y.is_finite() && range.contains(fov_y)) {
        let (lo, hi) = (range.min.to_radians(), range.max.to_radians());
        warnings.push(FieldIssue {
            field: field.to_string(),
            problem: format!(
                "yfov {} (cameras[{index}].perspective.yfov) is outside [{}, {}] radians ({}° to {}°); {CAMERA_SKIPPED}",
                written(p.yfov()),
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
                field: field.to_string(),
                problem: format!(
                    "aspectRatio {} (cameras[{index}].perspective.aspectRatio) is not a positive number; left out, \
                     the image keeps its width and height",
                    written(*a)
                ),
            });
        }
        usable
    });
    Some((fov_y, aspect))
}

/// An orthographic camera's view height (2·ymag: xmag and ymag are the view's half-width and
/// half-height) and aspect ratio (xmag / ymag), or `None` (said) where ymag gives no view height
/// a scene's camera may have. The specification requires both to be non-zero and allows no
/// negative ones; a negative xmag is left out, and the image keeps its width.
fn orthographic_view(
    o: &::gltf::camera::Orthographic<'_>,
    index: usize,
    field: &str,
    warnings: &mut Vec<FieldIssue>,
) -> Option<(f64, Option<f32>)> {
    let height = 2.0 * f64::from(o.ymag());
    let range = glint_scene::ranges::VIEW_HEIGHT;
    if !range.contains(height) {
        warnings.push(FieldIssue {
            field: field.to_string(),
            problem: format!(
                "ymag {} (cameras[{index}].orthographic.ymag) gives no view height in {} (2·ymag); {CAMERA_SKIPPED}",
                written(o.ymag()),
                range.bounds()
            ),
        });
        return None;
    }
    let aspect = o.xmag() / o.ymag();
    if !(aspect.is_finite() && aspect > 0.0) {
        warnings.push(FieldIssue {
            field: field.to_string(),
            problem: format!(
                "xmag {} (cameras[{index}].orthographic.xmag) is not a positive number; left out, the image keeps \
                 its width and height",
                written(o.xmag())
            ),
        });
        return Some((height, None));
    }
    Some((height, Some(aspect)))
}
