//! Scene validation: every rule names the field and the allowed range.
//!
//! Validation is the only gate between user data and both tracers, so it also guarantees
//! what the tracers rely on: every number finite and small enough to stay finite in f32,
//! directions of non-zero length, attenuation that never divides by zero.

use glam::DVec3;

use super::camera::{CameraDesc, Projection};
use super::desc::{ObjectDesc, PlaneDesc, RenderSettings, SceneDesc, SphereDesc};
use super::error::FieldIssue;
use super::light::{Attenuation, LightDesc, NO_CONE_CUTOFF};
use super::material::MaterialDesc;
use super::material::material_textures;
use super::mesh::MeshDesc;
use super::number::{format_number as num, shorten};
use super::rgb::Rgb;
use super::texture::TextureDesc;
use glint_types::{LightKind, SpotFalloff};

mod coplanar;
mod epsilon;
mod integrator;
mod lights;
mod materials;
mod near;
mod objects;
mod placement;
mod tilted;

pub use crate::limits::*;
pub use epsilon::{EPSILON_SHARE, EPSILON_WARN_SHARE, epsilon_warning};
pub use integrator::{integrator_warnings, path_gain_warning};
use lights::{validate_light, validate_polynomial};
use materials::validate_material;
use objects::validate_object;

/// Six significant digits, for messages about f32-rounded values (six decimals printed the
/// least 9.9975e-7 of an attenuation as "0.000001", which seemed to meet its bound of 1e-6,
/// and 9e-8 as "0").
fn short(v: f64) -> String {
    crate::number::format_rounded(v, 6)
}

/// What validation found: hard errors and warnings (the scene still renders with warnings).
#[derive(Clone, Debug, Default)]
pub struct Report {
    pub errors: Vec<FieldIssue>,
    pub warnings: Vec<FieldIssue>,
    /// The objects' meshes' boxes, made by `validate_objects` for `validate_with_objects`.
    pub(crate) mesh_boxes: near::MeshBoxes,
}

impl Report {
    fn error(&mut self, field: impl Into<String>, problem: impl Into<String>) {
        self.errors.push(FieldIssue { field: field.into(), problem: problem.into() });
    }

    fn warn(&mut self, field: impl Into<String>, problem: impl Into<String>) {
        self.warnings.push(FieldIssue { field: field.into(), problem: problem.into() });
    }

    fn finite_in(&mut self, field: &str, value: f64, range: Range<f64>) -> bool {
        let (v, bounds) = (num(value), range.bounds());
        if !range.contains(value) {
            if !value.is_finite() {
                self.error(field, format!("{v} is not a finite number; allowed: {bounds}"));
            } else {
                self.error(field, format!("{v} is outside the allowed range {bounds}"));
            }
            false
        } else {
            true
        }
    }

    fn point(&mut self, field: &str, p: [f64; 3]) -> bool {
        let mut ok = true;
        for (axis, v) in ["x", "y", "z"].iter().zip(p) {
            if !ranges::COORD.contains(v) {
                let bounds = ranges::COORD.bounds();
                self.error(field, format!("component {axis} = {} must be a finite number in {bounds}", num(v)));
                ok = false;
            }
        }
        ok
    }

    fn direction(&mut self, field: &str, d: [f64; 3]) -> bool {
        if !self.point(field, d) {
            return false;
        }
        if !usable_direction(d) {
            self.error(
                field,
                format!("{d:?} has (near) zero length; a direction needs length > {MIN_DIRECTION_LENGTH:e}"),
            );
            return false;
        }
        true
    }

    fn colour(&mut self, field: &str, c: Rgb) -> bool {
        let mut ok = true;
        let bounds = ranges::COLOUR.bounds();
        // A grey (one number in the file, or three equal) is one value: one message.
        let [r, g, b] = c.0;
        if r.to_bits() == g.to_bits() && g.to_bits() == b.to_bits() {
            if !ranges::COLOUR.contains(r) {
                self.error(field, format!("{} (every channel) must be a finite number in {bounds}", num(r)));
                return false;
            }
            return true;
        }
        for (name, v) in ["r", "g", "b"].iter().zip(c.0) {
            if !ranges::COLOUR.contains(v) {
                self.error(field, format!("channel {name} = {} must be a finite number in {bounds}", num(v)));
                ok = false;
            }
        }
        ok
    }

    /// A size in a range (min, max] (its maximum shown as 1e9 and the like).
    fn size(&mut self, field: &str, v: f64, range: Range<f64>) {
        if !range.contains(v) {
            let why = range.why_outside(v);
            self.error(field, format!("{} is outside the allowed range {}{why}", num(v), range.bounds()));
        }
    }

    fn count(&mut self, field: &str, v: u32, range: Range<u32>) {
        if !range.contains(v) {
            self.error(field, format!("{v} is outside the allowed range [{}, {}]", range.min, range.max));
        }
    }
}

/// Checks the render settings (also used for command-line overrides).
pub fn validate_settings(s: &RenderSettings, report: &mut Report) {
    report.count("render.width", s.width, ranges::IMAGE_SIDE);
    report.count("render.height", s.height, ranges::IMAGE_SIDE);
    report.count("render.spp", s.spp, ranges::SPP);
    report.count("render.max_depth", s.max_depth, ranges::DEPTH);
    report.finite_in("render.bailout", s.bailout, ranges::BAILOUT);
    report.finite_in("render.epsilon", s.epsilon, ranges::EPSILON);
}

/// Validates a whole scene. Errors make the scene unusable; warnings are printed.
pub fn validate(scene: &SceneDesc) -> Report {
    validate_with_objects(scene, &validate_objects(scene))
}

/// The objects' part of `validate`. It reads nothing of the scene but the objects, the
/// material names and (for the coplanar-overlap and stored-contact warnings) `render.epsilon`,
/// so an editor may keep it while only the camera, lights, world, settings or
/// material values change (a camera drag over a million triangles) and pass it to
/// `validate_with_objects`.
pub fn validate_objects(scene: &SceneDesc) -> Report {
    let mut r = Report::default();
    let origin = crate::storage_origin(scene);
    for (i, object) in scene.objects.iter().enumerate() {
        validate_object(&format!("objects[{i}]"), object, scene, origin, &mut r);
    }
    r.mesh_boxes = near::MeshBoxes::of(&scene.objects);
    if r.errors.is_empty() {
        r.warnings.extend(coplanar::coplanar_overlaps(scene, origin, scene.render.epsilon));
        r.warnings.extend(placement::duplicate_spheres(scene, origin));
        r.warnings.extend(placement::stored_contacts(scene, origin, scene.render.epsilon));
    }
    r
}

/// The warnings of `validate_objects` a setting changes, judged at ε = `epsilon`: coplanar
/// overlaps and stored contacts. `glint render --epsilon` judges the flag's ε with it (the
/// file's ε warned of a z-fight the flag had removed, and of a sphere touching a floor 1e-6
/// below it at --epsilon 1e-9; testers).
pub fn epsilon_warnings_of_objects(scene: &SceneDesc, epsilon: f64) -> Vec<FieldIssue> {
    let origin = crate::storage_origin(scene);
    let mut out = coplanar::coplanar_overlaps(scene, origin, epsilon);
    out.extend(placement::stored_contacts(scene, origin, epsilon));
    out
}

/// `validate`, with the objects' part already done (`validate_objects` of a scene with the
/// same objects and material names); the same report.
pub fn validate_with_objects(scene: &SceneDesc, objects: &Report) -> Report {
    let mut r = Report::default();
    validate_settings(&scene.render, &mut r);
    validate_camera(scene, &mut r);
    r.colour("world.ambient", scene.world.ambient);
    r.colour("world.background", scene.world.background);
    let g = scene.world.global_attenuation;
    validate_polynomial("world.global_attenuation", g.c, g.l, g.q, &mut r);
    for (name, m) in &scene.materials {
        validate_material(&format!("materials.{name}"), m, &mut r);
    }
    for (i, light) in scene.lights.iter().enumerate() {
        validate_light(&format!("lights[{i}]"), light, &mut r);
    }
    r.errors.extend_from_slice(&objects.errors);
    r.warnings.extend_from_slice(&objects.warnings);
    r.warnings.extend(placement::placement_warnings(scene, &objects.mesh_boxes));
    // From the camera, so here and not with the objects' own warnings.
    if objects.errors.is_empty() {
        r.warnings.extend(tilted::tilted_triangles(scene, &objects.mesh_boxes));
    }
    r.warnings.extend(settings_warnings(scene, &scene.render));
    r
}

/// The warnings `settings` give `scene`: a ray tree that can grow past its bound, an ε as large
/// as the scene, what the integrator leaves out or lacks. Validation gives those of the scene's
/// own settings; `glint render` judges flags that change them with the same function.
pub fn settings_warnings(scene: &SceneDesc, settings: &RenderSettings) -> Vec<FieldIssue> {
    let mut out = Vec::new();
    if let Some(problem) = super::ray_tree::unbounded_ray_tree(scene, settings) {
        out.push(FieldIssue { field: "render.max_depth".into(), problem });
    }
    if let Some(problem) = epsilon_warning(scene, settings) {
        out.push(FieldIssue { field: "render.epsilon".into(), problem });
    }
    out.extend(integrator_warnings(scene, settings));
    out
}

fn validate_camera(scene: &SceneDesc, r: &mut Report) {
    let c = &scene.camera;
    let ok = r.point("camera.position", c.position) & r.point("camera.look_at", c.look_at);
    let up_ok = r.direction("camera.up", c.up);
    r.finite_in("camera.fov_y", c.fov_y, ranges::FOV_Y);
    if !(ok && up_ok) {
        return;
    }
    let f = sub(c.look_at, c.position);
    let flen = norm(f);
    if flen < 1e-9 {
        let problem = if flen == 0.0 {
            "equals camera.position; the camera needs a viewing direction (look_at at least 1e-9 from it)".to_string()
        } else {
            format!(
                "is {} from camera.position; the camera needs a viewing direction (look_at at least 1e-9 from it)",
                crate::number::format_rounded(flen, 2)
            )
        };
        r.error("camera.look_at", problem);
        return;
    }
    let cr = cross(f, c.up);
    if norm(cr) <= 1e-9 * flen * norm(c.up) {
        r.error("camera.up", "is parallel to the viewing direction (look_at − position); choose another up vector");
    }
    validate_view_height(c, r);
}

/// An orthographic camera's view height, given or derived from the field of view; a view
/// height given to a perspective camera does nothing, and is said to.
fn validate_view_height(c: &CameraDesc, r: &mut Report) {
    match (c.projection, c.view_height) {
        (Projection::Perspective, None) => {}
        // Checked as where it is read: nan, inf and values out of range are refused everywhere,
        // and the viewer's projection switch reads it (a tester's nan rendered with a warning).
        (Projection::Perspective, Some(h)) => {
            if r.finite_in("camera.view_height", h, ranges::VIEW_HEIGHT) {
                r.warn(
                    "camera.view_height",
                    "is used by an orthographic camera only (camera.projection = \"orthographic\"); ignored",
                );
            }
        }
        (Projection::Orthographic, Some(h)) => {
            r.finite_in("camera.view_height", h, ranges::VIEW_HEIGHT);
        }
        (Projection::Orthographic, None) => {
            let h = c.view_height();
            // Derived from fov_y: an invalid one is refused under its own name alone.
            if ranges::FOV_Y.contains(c.fov_y) && !ranges::VIEW_HEIGHT.contains(h) {
                r.error(
                    "camera.view_height",
                    format!(
                        "not given, it is the height the field of view sees at look_at, \
                         2·|look_at − position|·tan(fov_y/2) = {}, outside the allowed range {}; give it",
                        crate::number::format_rounded(h, 3),
                        ranges::VIEW_HEIGHT.bounds()
                    ),
                );
            }
        }
    }
}

fn sub(a: [f64; 3], b: [f64; 3]) -> DVec3 {
    DVec3::from(a) - DVec3::from(b)
}

fn cross(a: DVec3, b: impl Into<DVec3>) -> DVec3 {
    a.cross(b.into())
}

fn norm(a: impl Into<DVec3>) -> f64 {
    a.into().length()
}
