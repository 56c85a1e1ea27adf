//! Scene validation: every rule names the field and the allowed range.
//!
//! Validation is the only gate between user data and both tracers, so it also guarantees
//! what the tracers rely on: every number finite and small enough to stay finite in f32,
//! directions of non-zero length, attenuation that never divides by zero.

use glam::DVec3;

use super::desc::{MaterialDesc, MeshDesc, ObjectDesc, PlaneDesc, RenderSettings, SceneDesc, SphereDesc};
use super::error::FieldIssue;
use super::light::{Attenuation, LightDesc, LightKind, NO_CONE_CUTOFF, SpotFalloff};
use super::number::{format_number as num, shorten};
use super::rgb::Rgb;
use super::texture::{TextureDesc, material_textures};

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
/// The Beckmann roughness m (RMS microfacet slope) of the Cook–Torrance lobe lies in
/// [MIN_ROUGHNESS, MAX_ROUGHNESS]. At m = 1 (a mean slope of 45°) the V-groove G and the
/// Beckmann lobe are at the end of what they model (from m > 1/√2 on, D peaks away from the
/// normal); a rougher surface is a diffuse one. At m = 1e-3 D peaks at 1/m² = 1e6, the bound
/// validation puts on f_att too, and m² = 1e-6 and m²·cos⁴α stay normal f32 numbers on the GPU
/// wherever the lobe is not cut off; a smoother surface is a mirror (k_r).
pub const MIN_ROUGHNESS: f64 = 1e-3;
pub const MAX_ROUGHNESS: f64 = 1.0;
/// Smallest value c + l·d + q·d² may take: f_att = 1/(…) stays ≤ 1e6, so that radiance stays
/// far from f32 overflow on the GPU. The inverse-square model divides by max(d², this) for the
/// same bound: a point within 1e-3 of its light gets f_att = 1e6 at most.
pub const MIN_ATTENUATION_DENOMINATOR: f64 = 1e-6;

/// The values one number of a scene may take. Validation checks every number against its
/// entry in [`ranges`], and the viewer's editors take their ranges from there too, so an
/// editor neither clamps a valid value away nor offers an invalid one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range<T> {
    pub min: T,
    pub max: T,
    /// (min, max] instead of [min, max], for what the tracers divide by (a size, an index of
    /// refraction): the value must stay above `min` when rounded to f32, as both tracers read it.
    pub min_excluded: bool,
    /// The useful values span decades: an editor shows them on a logarithmic scale.
    pub log: bool,
}

impl<T> Range<T> {
    /// [min, max] on a linear scale.
    pub const fn linear(min: T, max: T) -> Self {
        Self { min, max, min_excluded: false, log: false }
    }

    /// [min, max] on a logarithmic scale.
    pub const fn logarithmic(min: T, max: T) -> Self {
        Self { min, max, min_excluded: false, log: true }
    }

    /// (min, max] on a logarithmic scale.
    pub const fn logarithmic_above(min: T, max: T) -> Self {
        Self { min, max, min_excluded: true, log: true }
    }
}

impl Range<f64> {
    /// Whether `v` is a finite number in the range.
    pub fn contains(&self, v: f64) -> bool {
        let above_min = if self.min_excluded { as_f32(v) > self.min } else { v >= self.min };
        v.is_finite() && above_min && v <= self.max
    }
}

impl Range<u32> {
    pub fn contains(&self, v: u32) -> bool {
        (self.min..=self.max).contains(&v)
    }
}

/// The allowed range of every number a scene holds, one entry per kind of field.
pub mod ranges {
    use super::{
        MAX_COORD, MAX_DEPTH, MAX_EPSILON, MAX_IMAGE_SIDE, MAX_INTENSITY, MAX_IOR, MAX_ROUGHNESS, MAX_SHININESS,
        MAX_SPOT_EXPONENT, MAX_SPP, MIN_ROUGHNESS, Range,
    };

    pub const IMAGE_SIDE: Range<u32> = Range::logarithmic(1, MAX_IMAGE_SIDE);
    pub const SPP: Range<u32> = Range::logarithmic(1, MAX_SPP);
    /// Recursion depth: 0 is local shading only.
    pub const DEPTH: Range<u32> = Range::logarithmic(0, MAX_DEPTH);
    pub const BAILOUT: Range<f64> = Range::linear(0.0, 1.0);
    pub const EPSILON: Range<f64> = Range::logarithmic(0.0, MAX_EPSILON);
    pub const FOV_Y: Range<f64> = Range::linear(1e-6, 179.0);
    /// Each component of a position or direction.
    pub const COORD: Range<f64> = Range::linear(-MAX_COORD, MAX_COORD);
    /// Each channel of a colour or intensity (reflectances, emission, light intensities).
    pub const COLOUR: Range<f64> = Range::linear(0.0, MAX_INTENSITY);
    pub const SHININESS: Range<f64> = Range::logarithmic(0.0, MAX_SHININESS);
    pub const IOR: Range<f64> = Range::logarithmic_above(0.0, MAX_IOR);
    /// The Beckmann roughness m of the Cook–Torrance lobe.
    pub const ROUGHNESS: Range<f64> = Range::logarithmic(MIN_ROUGHNESS, MAX_ROUGHNESS);
    /// A sphere's radius and a checker's square size.
    pub const SIZE: Range<f64> = Range::logarithmic_above(0.0, MAX_COORD);
    /// Each of the attenuation coefficients c, l, q (their sum has a rule of its own).
    pub const ATTENUATION: Range<f64> = Range::linear(-MAX_INTENSITY, MAX_INTENSITY);
    pub const SPOT_EXPONENT: Range<f64> = Range::logarithmic(0.0, MAX_SPOT_EXPONENT);
    /// A model's exposure (`--exposure`, `exposure` of a model object).
    pub const EXPOSURE: Range<f64> = Range::logarithmic_above(0.0, 1e6);
    /// A spot cone's half-angle in degrees; `NO_CONE_CUTOFF` is allowed besides.
    pub const CUTOFF: Range<f64> = Range::linear(0.0, 90.0);
    /// The smooth falloff's inner and outer cone half-angles in degrees (inner ≤ outer besides).
    pub const CONE: Range<f64> = Range::linear(0.0, 90.0);
    /// The inverse-square model's range window, in scene units.
    pub const LIGHT_RANGE: Range<f64> = Range::logarithmic_above(0.0, MAX_COORD);
}

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
#[derive(Clone, Debug, Default)]
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

    fn finite_in(&mut self, field: &str, value: f64, range: Range<f64>) -> bool {
        let (v, lo, hi) = (num(value), num(range.min), num(range.max));
        if !range.contains(value) {
            if !value.is_finite() {
                self.error(field, format!("{v} is not a finite number; allowed: [{lo}, {hi}]"));
            } else {
                self.error(field, format!("{v} is outside the allowed range [{lo}, {hi}]"));
            }
            false
        } else {
            true
        }
    }

    fn point(&mut self, field: &str, p: [f64; 3]) -> bool {
        let mut ok = true;
        let (lo, hi) = (ranges::COORD.min, ranges::COORD.max);
        for (axis, v) in ["x", "y", "z"].iter().zip(p) {
            if !ranges::COORD.contains(v) {
                self.error(field, format!("component {axis} = {} must be a finite number in [{lo:e}, {hi:e}]", num(v)));
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

    fn colour(&mut self, field: &str, c: Rgb) -> bool {
        let mut ok = true;
        let (lo, hi) = (ranges::COLOUR.min, ranges::COLOUR.max);
        for (name, v) in ["r", "g", "b"].iter().zip(c.0) {
            if !ranges::COLOUR.contains(v) {
                self.error(field, format!("channel {name} = {} must be a finite number in [{lo}, {hi:e}]", num(v)));
                ok = false;
            }
        }
        ok
    }

    /// A size in a range (min, max] (its maximum shown as 1e9 and the like).
    fn size(&mut self, field: &str, v: f64, range: Range<f64>) {
        if !range.contains(v) {
            self.error(field, format!("{} is outside the allowed range ({}, {:e}]", num(v), range.min, range.max));
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

/// The objects' part of `validate`. It reads nothing of the scene but the objects and the
/// material names, so an editor may keep it while only the camera, lights, world, settings or
/// material values change (a camera drag over a million triangles) and pass it to
/// `validate_with_objects`.
pub fn validate_objects(scene: &SceneDesc) -> Report {
    let mut r = Report::default();
    for (i, object) in scene.objects.iter().enumerate() {
        validate_object(&format!("objects[{i}]"), object, scene, &mut r);
    }
    r
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
    if let Some(warning) = super::ray_tree::unbounded_ray_tree(scene, &scene.render) {
        r.warn("render.max_depth", warning);
    }
    r
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
        r.colour(&format!("{path}.{field}"), v);
    }
    r.colour(&format!("{path}.emission"), m.emission);
    r.finite_in(&format!("{path}.shininess"), m.shininess, ranges::SHININESS);
    r.finite_in(&format!("{path}.roughness"), m.roughness, ranges::ROUGHNESS);
    if !ranges::IOR.contains(m.ior) {
        let (lo, hi) = (ranges::IOR.min, ranges::IOR.max);
        r.error(format!("{path}.ior"), format!("{} is outside the allowed range ({lo}, {hi}]", num(m.ior)));
    }
    if let Some(ch) = &m.checker {
        r.colour(&format!("{path}.checker.kd"), ch.kd);
        r.size(&format!("{path}.checker.size"), ch.size, ranges::SIZE);
        if m.texture.is_some() {
            r.error(format!("{path}.checker"), "a material has a checker or a texture, not both");
        }
    }
    for (field, texture) in material_textures(m) {
        if let Some(t) = texture {
            validate_texture(&format!("{path}.{field}"), t, r);
        }
    }
    let sum = (0..3).map(|i| m.kr.0[i] + m.kt.0[i]).fold(0.0, f64::max);
    if sum > 1.0 {
        r.warn(
            format!("{path}.kr + kt"),
            format!("k_r + k_t = {} > 1: the surface returns more light than it receives", num(sum)),
        );
    }
}

/// A texture's transform, and that its image was decoded (`load_textures`, or an importer).
fn validate_texture(path: &str, t: &TextureDesc, r: &mut Report) {
    if t.image.is_none() {
        r.error(
            format!("{path}.path"),
            format!("`{}` was not decoded (scene descriptions built in code call scene::load_textures)", t.path),
        );
    }
    if let Some(tr) = &t.transform {
        for (axis, v) in ["u", "v"].iter().zip(tr.offset) {
            r.finite_in(&format!("{path}.transform.offset.{axis}"), v, ranges::COORD);
        }
        for (axis, v) in ["u", "v"].iter().zip(tr.scale) {
            r.finite_in(&format!("{path}.transform.scale.{axis}"), v, ranges::COORD);
        }
        r.finite_in(&format!("{path}.transform.rotation"), tr.rotation, ranges::COORD);
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
    r.colour(&format!("{path}.diffuse"), l.diffuse);
    r.colour(&format!("{path}.specular"), l.specular);
    r.colour(&format!("{path}.ambient"), l.ambient);
    if l.kind == LightKind::Directional {
        if !l.attenuation.is_none() {
            r.error(format!("{path}.attenuation"), "a directional light is not attenuated (f_att = 1); remove it");
        }
    } else {
        validate_attenuation(&format!("{path}.attenuation"), l.attenuation, r);
    }
    match (l.kind, l.falloff) {
        (LightKind::Spot, SpotFalloff::Power) => {
            validate_power_cone(path, l, r);
            for (field, v) in [("inner_cone", l.inner_cone), ("outer_cone", l.outer_cone)] {
                if v.is_some() {
                    r.error(
                        format!("{path}.{field}"),
                        "belongs to falloff = \"smooth\"; this spot has the power falloff (exponent, cutoff)",
                    );
                }
            }
        }
        (LightKind::Spot, SpotFalloff::Smooth) => {
            validate_smooth_cone(path, l, r);
            if l.exponent != 0.0 {
                r.error(
                    format!("{path}.exponent"),
                    "belongs to falloff = \"power\"; a smooth spot has inner_cone and outer_cone",
                );
            }
            if l.cutoff != NO_CONE_CUTOFF {
                r.error(
                    format!("{path}.cutoff"),
                    "belongs to falloff = \"power\"; a smooth spot's cone ends at outer_cone",
                );
            }
        }
        (LightKind::Point | LightKind::Directional, _) => {
            let only_spots = [
                ("exponent", l.exponent != 0.0, "an exponent"),
                ("cutoff", l.cutoff != NO_CONE_CUTOFF, "a cutoff"),
                ("falloff", !l.falloff.is_power(), "a falloff"),
                ("inner_cone", l.inner_cone.is_some(), "an inner_cone"),
                ("outer_cone", l.outer_cone.is_some(), "an outer_cone"),
            ];
            for (field, present, what) in only_spots {
                if present {
                    r.error(
                        format!("{path}.{field}"),
                        format!("only spot lights have {what} (this is a {kind} light)"),
                    );
                }
            }
        }
    }
}

/// The power falloff: exponent s and the hard cutoff.
fn validate_power_cone(path: &str, l: &LightDesc, r: &mut Report) {
    r.finite_in(&format!("{path}.exponent"), l.exponent, ranges::SPOT_EXPONENT);
    let c = l.cutoff;
    if !(ranges::CUTOFF.contains(c) || c == NO_CONE_CUTOFF) {
        let (lo, hi) = (ranges::CUTOFF.min, ranges::CUTOFF.max);
        r.error(
            format!("{path}.cutoff"),
            format!("{} is outside the allowed range [{lo}, {hi}] or {NO_CONE_CUTOFF} (no cone)", num(c)),
        );
    }
}

/// The smooth falloff: 0 ≤ inner ≤ outer ≤ 90 degrees.
fn validate_smooth_cone(path: &str, l: &LightDesc, r: &mut Report) {
    let (inner, outer) = l.cone_angles();
    let inner_ok = r.finite_in(&format!("{path}.inner_cone"), inner, ranges::CONE);
    let outer_ok = r.finite_in(&format!("{path}.outer_cone"), outer, ranges::CONE);
    if inner_ok && outer_ok && inner > outer {
        r.error(
            format!("{path}.inner_cone"),
            format!("{inner} is larger than outer_cone = {outer}; allowed: 0 ≤ inner_cone ≤ outer_cone ≤ 90"),
        );
    }
}

fn validate_attenuation(path: &str, a: Attenuation, r: &mut Report) {
    match a {
        Attenuation::Polynomial { c, l, q } => validate_polynomial(path, c, l, q, r),
        Attenuation::InverseSquare { range: Some(range) } => {
            if !ranges::LIGHT_RANGE.contains(range) {
                let (lo, hi) = (ranges::LIGHT_RANGE.min, ranges::LIGHT_RANGE.max);
                r.error(format!("{path}.range"), format!("{range} is outside the allowed range ({lo}, {hi:e}]"));
            }
        }
        Attenuation::InverseSquare { range: None } => {}
    }
}

/// c + l·d + q·d² must stay positive for every distance d ≥ 0.
fn validate_polynomial(path: &str, c: f64, l: f64, q: f64, r: &mut Report) {
    // Check all three (no short circuit) so that every bad coefficient is reported.
    let checks: Vec<bool> = [("c", c), ("l", l), ("q", q)]
        .into_iter()
        .map(|(n, v)| r.finite_in(&format!("{path}.{n}"), v, ranges::ATTENUATION))
        .collect();
    let finite = checks.iter().all(|&ok| ok);
    if !finite {
        return;
    }
    // Judge the coefficients the tracers will use: rounded to f32.
    let (given_c, given_l, given_q) = (c, l, q);
    let (c, l, q) = (as_f32(c), as_f32(l), as_f32(q));
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
        r.error(path, format!("{p} (got c = {}, l = {}, q = {})", num(given_c), num(given_l), num(given_q)));
    }
}

fn validate_object(path: &str, o: &ObjectDesc, scene: &SceneDesc, r: &mut Report) {
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
        }
        ObjectDesc::Plane(PlaneDesc { point, normal, .. }) => {
            r.point(&format!("{path}.point"), *point);
            r.direction(&format!("{path}.normal"), *normal);
        }
        ObjectDesc::Mesh(mesh) => validate_mesh(path, mesh, r),
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
            match &model.loaded {
                // Named by the model's own mesh names (`PREFIX/NODE`), which say where to look.
                Some(loaded) => {
                    // Errors one by one; warnings of a kind once for the model (a CAD export
                    // has degenerate triangles in a hundred meshes), with how many meshes share it.
                    let mut meshes = Report::default();
                    for (k, mesh) in loaded.meshes.iter().enumerate() {
                        validate_mesh(&format!("{path} mesh {k} `{}`", mesh.name), mesh, &mut meshes);
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

fn validate_mesh(path: &str, mesh: &MeshDesc, r: &mut Report) {
    let MeshDesc { vertices, triangles, normals, uvs, .. } = mesh;

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
                "the mesh has no vertices, but its {} index them; give the vertex positions [x, y, z]",
                if triangles.len() == 1 { "triangle".to_string() } else { format!("{} triangles", triangles.len()) }
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
        let usable = |d: &[f64; 3]| in_range(&d[..]) && d.iter().map(|c| c * c).sum::<f64>().sqrt() >= 1e-12;
        for (i, v) in normals.iter().enumerate().filter(|(_, v)| !usable(v)) {
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

fn sub(a: [f64; 3], b: [f64; 3]) -> DVec3 {
    DVec3::from(a) - DVec3::from(b)
}

fn cross(a: DVec3, b: impl Into<DVec3>) -> DVec3 {
    a.cross(b.into())
}

fn norm(a: impl Into<DVec3>) -> f64 {
    a.into().length()
}
