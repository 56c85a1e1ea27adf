//! Scene validation: every rule names the field and the allowed range.
//!
//! Validation is the only gate between user data and both tracers, so it also guarantees
//! what the tracers rely on: every number finite and small enough to stay finite in f32,
//! directions of non-zero length, attenuation that never divides by zero.

use glam::DVec3;

use super::desc::{
    Attenuation, LightDesc, LightKind, MaterialDesc, MeshDesc, NO_CONE_CUTOFF, ObjectDesc, PlaneDesc, RenderSettings,
    SceneDesc, SphereDesc,
};
use super::error::FieldIssue;
use super::rgb::Rgb;

/// Coordinates and sizes are limited so that squares and sums stay finite in f32
/// (the GPU tracer computes |o − c|² for spheres).
pub const MAX_COORD: f64 = 1e9;
pub const MAX_SHININESS: f64 = 1e6;
pub const MAX_SPOT_EXPONENT: f64 = 1e6;
pub const MAX_INTENSITY: f64 = 1e9;
pub const MAX_IMAGE_SIDE: u32 = 16384;
pub const MAX_SPP: u32 = 4096;
pub const MAX_DEPTH: u32 = 1024;
pub const MAX_EPSILON: f64 = 1e3;
pub const MAX_IOR: f64 = 1e3;
/// Smallest value c + l·d + q·d² may take: f_att = 1/(…) stays ≤ 1e6, so that radiance stays
/// far from f32 overflow on the GPU.
pub const MIN_ATTENUATION_DENOMINATOR: f64 = 1e-6;

/// Six significant digits without trailing zeros, for messages about f32-rounded values.
fn short(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.') } else { &s };
    s.to_string()
}

/// The value the tracers will see: both read the scene in f32.
fn as_f32(v: f64) -> f64 {
    f64::from(v as f32)
}

/// What validation found: hard errors and warnings (the scene still renders with warnings).
#[derive(Debug, Default)]
pub struct Report {
    pub errors: Vec<FieldIssue>,
    pub warnings: Vec<FieldIssue>,
}

impl Report {
    fn error(&mut self, field: impl Into<String>, problem: impl Into<String>) {
        self.errors.push(FieldIssue { field: field.into(), problem: problem.into() });
    }

    fn warn(&mut self, field: impl Into<String>, problem: impl Into<String>) {
        self.warnings.push(FieldIssue { field: field.into(), problem: problem.into() });
    }

    fn finite_in(&mut self, field: &str, v: f64, lo: f64, hi: f64) -> bool {
        if !v.is_finite() {
            self.error(field, format!("{v} is not a finite number; allowed: [{lo}, {hi}]"));
            false
        } else if v < lo || v > hi {
            self.error(field, format!("{v} is outside the allowed range [{lo}, {hi}]"));
            false
        } else {
            true
        }
    }

    fn point(&mut self, field: &str, p: [f64; 3]) -> bool {
        let mut ok = true;
        for (axis, v) in ["x", "y", "z"].iter().zip(p) {
            if !v.is_finite() || v.abs() > MAX_COORD {
                self.error(
                    field,
                    format!("component {axis} = {v} must be a finite number in [-{MAX_COORD:e}, {MAX_COORD:e}]"),
                );
                ok = false;
            }
        }
        ok
    }

    fn direction(&mut self, field: &str, d: [f64; 3]) -> bool {
        if !self.point(field, d) {
            return false;
        }
        let len2 = d.iter().map(|v| v * v).sum::<f64>();
        // Must stay a usable direction after rounding to f32 and normalising there.
        if len2.sqrt() < 1e-12 {
            self.error(field, format!("{d:?} has (near) zero length; a direction needs length > 1e-12"));
            return false;
        }
        true
    }

    fn colour(&mut self, field: &str, c: Rgb, hi: f64) -> bool {
        let mut ok = true;
        for (name, v) in ["r", "g", "b"].iter().zip(c.0) {
            if !v.is_finite() || v < 0.0 || v > hi {
                self.error(field, format!("channel {name} = {v} must be a finite number in [0, {hi:e}]"));
                ok = false;
            }
        }
        ok
    }
}

/// Checks the render settings (also used for command-line overrides).
pub fn validate_settings(s: &RenderSettings, report: &mut Report) {
    let side = |r: &mut Report, name: &str, v: u32| {
        if v == 0 || v > MAX_IMAGE_SIDE {
            r.error(format!("render.{name}"), format!("{v} is outside the allowed range [1, {MAX_IMAGE_SIDE}]"));
        }
    };
    side(report, "width", s.width);
    side(report, "height", s.height);
    if s.spp == 0 || s.spp > MAX_SPP {
        report.error("render.spp", format!("{} is outside the allowed range [1, {MAX_SPP}]", s.spp));
    }
    if s.max_depth > MAX_DEPTH {
        report.error("render.max_depth", format!("{} is outside the allowed range [0, {MAX_DEPTH}]", s.max_depth));
    }
    report.finite_in("render.bailout", s.bailout, 0.0, 1.0);
    report.finite_in("render.epsilon", s.epsilon, 0.0, MAX_EPSILON);
}

/// Validates a whole scene. Errors make the scene unusable; warnings are printed.
pub fn validate(scene: &SceneDesc) -> Report {
    let mut r = Report::default();
    validate_settings(&scene.render, &mut r);
    validate_camera(scene, &mut r);
    r.colour("world.ambient", scene.world.ambient, MAX_INTENSITY);
    r.colour("world.background", scene.world.background, MAX_INTENSITY);
    for (name, m) in &scene.materials {
        validate_material(&format!("materials.{name}"), m, &mut r);
    }
    for (i, light) in scene.lights.iter().enumerate() {
        validate_light(&format!("lights[{i}]"), light, &mut r);
    }
    for (i, object) in scene.objects.iter().enumerate() {
        validate_object(&format!("objects[{i}]"), object, scene, &mut r);
    }
    r
}

fn validate_camera(scene: &SceneDesc, r: &mut Report) {
    let c = &scene.camera;
    let ok = r.point("camera.position", c.position) & r.point("camera.look_at", c.look_at);
    let up_ok = r.direction("camera.up", c.up);
    r.finite_in("camera.fov_y", c.fov_y, 1e-6, 179.0);
    if !(ok && up_ok) {
        return;
    }
    let f = sub(c.look_at, c.position);
    let flen = norm(f);
    if flen < 1e-9 {
        r.error("camera.look_at", "equals camera.position; the camera needs a viewing direction");
        return;
    }
    let cr = cross(f, c.up);
    if norm(cr) <= 1e-9 * flen * norm(c.up) {
        r.error("camera.up", "is parallel to the viewing direction (look_at − position); choose another up vector");
    }
}

fn validate_material(path: &str, m: &MaterialDesc, r: &mut Report) {
    for (field, v) in [("ka", m.ka), ("kd", m.kd), ("ks", m.ks), ("kr", m.kr), ("kt", m.kt)] {
        r.colour(&format!("{path}.{field}"), v, MAX_INTENSITY);
    }
    r.colour(&format!("{path}.emission"), m.emission, MAX_INTENSITY);
    r.finite_in(&format!("{path}.shininess"), m.shininess, 0.0, MAX_SHININESS);
    if !m.ior.is_finite() || as_f32(m.ior) <= 0.0 || m.ior > MAX_IOR {
        r.error(format!("{path}.ior"), format!("{} is outside the allowed range (0, {MAX_IOR}]", m.ior));
    }
    if let Some(ch) = &m.checker {
        r.colour(&format!("{path}.checker.kd"), ch.kd, MAX_INTENSITY);
        if !ch.size.is_finite() || as_f32(ch.size) <= 0.0 || ch.size > MAX_COORD {
            r.error(
                format!("{path}.checker.size"),
                format!("{} is outside the allowed range (0, {MAX_COORD:e}]", ch.size),
            );
        }
    }
    let sum = (0..3).map(|i| m.kr.0[i] + m.kt.0[i]).fold(0.0, f64::max);
    if sum > 1.0 {
        r.warn(
            format!("{path}.kr + kt"),
            format!("k_r + k_t = {sum} > 1: the surface returns more light than it receives"),
        );
    }
}

fn validate_light(path: &str, l: &LightDesc, r: &mut Report) {
    let kind = l.kind.name();
    match (l.kind, l.position) {
        (LightKind::Directional, Some(_)) => r.error(
            format!("{path}.position"),
            "a directional light has no position (remove it or use type = \"point\")",
        ),
        (LightKind::Point | LightKind::Spot, None) => {
            r.error(format!("{path}.position"), format!("a {kind} light needs a position [x, y, z]"))
        }
        (_, Some(p)) => {
            r.point(&format!("{path}.position"), p);
        }
        (_, None) => {}
    }
    match (l.kind, l.direction) {
        (LightKind::Point, Some(_)) => {
            r.error(format!("{path}.direction"), "a point light has no direction (use type = \"spot\")")
        }
        (LightKind::Directional | LightKind::Spot, None) => r.error(
            format!("{path}.direction"),
            format!("a {kind} light needs a direction [x, y, z] of non-zero length"),
        ),
        (_, Some(d)) => {
            r.direction(&format!("{path}.direction"), d);
        }
        (_, None) => {}
    }
    r.colour(&format!("{path}.diffuse"), l.diffuse, MAX_INTENSITY);
    r.colour(&format!("{path}.specular"), l.specular, MAX_INTENSITY);
    r.colour(&format!("{path}.ambient"), l.ambient, MAX_INTENSITY);
    if l.kind == LightKind::Directional {
        if !l.attenuation.is_none() {
            r.error(format!("{path}.attenuation"), "a directional light is not attenuated (f_att = 1); remove it");
        }
    } else {
        validate_attenuation(&format!("{path}.attenuation"), l.attenuation, r);
    }
    if l.kind == LightKind::Spot {
        r.finite_in(&format!("{path}.exponent"), l.exponent, 0.0, MAX_SPOT_EXPONENT);
        let c = l.cutoff;
        if !(c.is_finite() && ((0.0..=90.0).contains(&c) || c == NO_CONE_CUTOFF)) {
            r.error(
                format!("{path}.cutoff"),
                format!("{c} is outside the allowed range [0, 90] or {NO_CONE_CUTOFF} (no cone)"),
            );
        }
    } else {
        if l.exponent != 0.0 {
            r.error(format!("{path}.exponent"), format!("only spot lights have an exponent (this is a {kind} light)"));
        }
        if l.cutoff != NO_CONE_CUTOFF {
            r.error(format!("{path}.cutoff"), format!("only spot lights have a cutoff (this is a {kind} light)"));
        }
    }
}

/// c + l·d + q·d² must stay positive for every distance d ≥ 0.
fn validate_attenuation(path: &str, a: Attenuation, r: &mut Report) {
    // Check all three (no short circuit) so that every bad coefficient is reported.
    let checks: Vec<bool> = [("c", a.c), ("l", a.l), ("q", a.q)]
        .into_iter()
        .map(|(n, v)| r.finite_in(&format!("{path}.{n}"), v, -MAX_INTENSITY, MAX_INTENSITY))
        .collect();
    let finite = checks.iter().all(|&ok| ok);
    if !finite {
        return;
    }
    // Judge the coefficients the tracers will use: rounded to f32.
    let (c, l, q) = (as_f32(a.c), as_f32(a.l), as_f32(a.q));
    let min = MIN_ATTENUATION_DENOMINATOR;
    let problem = if c < min {
        Some(format!("c + l·d + q·d² is c at d = 0, so c must be ≥ {min:e}"))
    } else if q < 0.0 || (q == 0.0 && l < 0.0) {
        Some("c + l·d + q·d² falls below 0 at a large distance: it needs q ≥ 0, and l ≥ 0 when q = 0".to_string())
    } else if l < 0.0 && c - l * l / (4.0 * q) < min {
        let d = -l / (2.0 * q);
        Some(format!(
            "c + l·d + q·d² falls to {} at d = {}; it must stay ≥ {min:e} for all d ≥ 0",
            short(c - l * l / (4.0 * q)),
            short(d)
        ))
    } else {
        None
    };
    if let Some(p) = problem {
        r.error(path, format!("{p} (got c = {}, l = {}, q = {})", a.c, a.l, a.q));
    }
}

fn validate_object(path: &str, o: &ObjectDesc, scene: &SceneDesc, r: &mut Report) {
    if !scene.materials.contains_key(o.material()) {
        let known: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
        r.error(
            format!("{path}.material"),
            format!("unknown material '{}'; defined materials: [{}]", o.material(), known.join(", ")),
        );
    }
    match o {
        ObjectDesc::Sphere(SphereDesc { center, radius, .. }) => {
            r.point(&format!("{path}.center"), *center);
            if !radius.is_finite() || as_f32(*radius) <= 0.0 || *radius > MAX_COORD {
                r.error(format!("{path}.radius"), format!("{radius} is outside the allowed range (0, {MAX_COORD:e}]"));
            }
        }
        ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
            r.point(&format!("{path}.point"), *point);
            r.direction(&format!("{path}.normal"), *normal);
        }
        ObjectDesc::Mesh(MeshDesc { vertices, triangles, normals, .. }) => {
            if triangles.is_empty() {
                r.error(format!("{path}.triangles"), "a mesh needs at least one triangle [i, j, k]");
            }
            for (i, v) in vertices.iter().enumerate() {
                r.point(&format!("{path}.vertices[{i}]"), *v);
            }
            let n = vertices.len();
            for (i, t) in triangles.iter().enumerate() {
                if let Some(bad) = t.iter().find(|&&k| k as usize >= n) {
                    r.error(
                        format!("{path}.triangles[{i}]"),
                        format!("vertex index {bad} is out of range; allowed: [0, {}]", n.saturating_sub(1)),
                    );
                }
            }
            if let Some(normals) = normals {
                if normals.len() != n {
                    r.error(
                        format!("{path}.normals"),
                        format!("has {} entries; it needs one per vertex ({n})", normals.len()),
                    );
                }
                for (i, v) in normals.iter().enumerate() {
                    r.direction(&format!("{path}.normals[{i}]"), *v);
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
            let degenerate = triangles
                .iter()
                .filter(|t| t.iter().all(|&k| (k as usize) < n))
                .filter(|t| {
                    let [a, b, c] = t.map(|k| vertices[k as usize]);
                    norm(cross(sub(b, a), sub(c, a))) == 0.0
                })
                .count();
            if degenerate > 0 {
                r.warn(
                    format!("{path}.triangles"),
                    format!("{degenerate} degenerate (zero-area) triangles; they are never hit"),
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
