//! Scene validation: each invalid input is rejected with a message that names the file, the
//! field (path) and the allowed range; valid boundary values pass; k_r + k_t > 1 only warns.

use std::path::Path;

use glint_io::{SceneError, parse_scene};

/// A valid scene using every kind of light and object. Cases below replace exactly one
/// snippet of it (checked to occur exactly once).
const BASE: &str = r#"
[camera]
position = [0.0, 1.0, -5.0]
look_at = [0.0, 0.5, 0.0]

[materials.red]
ka = 0.1
kd = [0.7, 0.1, 0.1]
ks = 0.3
shininess = 32.0

[materials.glass]
ka = 0.0
kd = 0.0
kr = 0.1
kt = 0.8
ior = 1.5

[[lights]]
type = "point"
position = [2.0, 4.0, -2.0]
attenuation = { c = 1.0, l = 0.1, q = 0.01 }

[[lights]]
type = "directional"
direction = [0.3, -1.0, 0.2]

[[lights]]
type = "spot"
position = [-2.0, 4.0, 0.0]
direction = [0.5, -1.0, 0.0]
exponent = 8.0
cutoff = 30.0

[[objects]]
type = "sphere"
center = [0.0, 1.0, 0.0]
radius = 1.0
material = "red"

[[objects]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "red"

[[objects]]
type = "mesh"
vertices = [[-1.0, 0.0, 2.0], [1.0, 0.0, 2.0], [0.0, 2.0, 2.0]]
triangles = [[0, 1, 2]]
normals = [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]
material = "glass"
"#;

const FILE: &str = "cases/bad-scene.toml";

fn edited(from: &str, to: &str) -> String {
    assert_eq!(BASE.matches(from).count(), 1, "snippet {from:?} must occur exactly once in BASE");
    BASE.replacen(from, to, 1)
}

/// Parses `text` and expects a validation error for `field` whose message contains every
/// `fragment` (the allowed range, as a reader would look for it).
fn expect_invalid(text: &str, field: &str, fragments: &[&str]) {
    let err = match parse_scene(text, Path::new(FILE)) {
        Ok(_) => panic!("expected an error for {field}, but the scene was accepted:\n{text}"),
        Err(e) => e,
    };
    let msg = err.to_string();
    assert!(matches!(err, SceneError::Invalid { .. }), "{field}: not a validation error: {msg}");
    assert!(msg.contains(FILE), "{field}: message does not name the file: {msg}");
    let issue = err
        .issues()
        .iter()
        .find(|i| i.field == field)
        .unwrap_or_else(|| panic!("no issue for field {field}; got: {msg}"));
    // Only the edited field is wrong (BASE is valid).
    assert!(err.issues().iter().all(|i| i.field == field), "{field}: unrelated issues too: {msg}");
    let line = issue.to_string();
    assert!(line.starts_with(&format!("{field}: ")), "{field}: line does not start with the field: {line}");
    assert!(msg.contains(&line), "{field}: the message does not show the issue line {line:?}: {msg}");
    for f in fragments {
        assert!(line.contains(f), "{field}: message {line:?} does not contain {f:?}");
    }
}

fn expect_valid(text: &str, what: &str) -> Vec<String> {
    match parse_scene(text, Path::new(FILE)) {
        Ok((_, warnings)) => warnings.iter().map(ToString::to_string).collect(),
        Err(e) => panic!("{what}: a valid scene was rejected: {e}"),
    }
}

#[test]
fn base_scene_is_valid_without_warnings() {
    assert!(expect_valid(BASE, "BASE").is_empty());
}

#[test]
fn non_finite_numbers() {
    expect_invalid(&edited("radius = 1.0", "radius = nan"), "objects[0].radius", &["NaN", "1e9"]);
    expect_invalid(&edited("radius = 1.0", "radius = inf"), "objects[0].radius", &["inf", "1e9"]);
    expect_invalid(&edited("center = [0.0, 1.0, 0.0]", "center = [0.0, inf, 0.0]"), "objects[0].center", &["y", "1e9"]);
    expect_invalid(&edited("kd = [0.7, 0.1, 0.1]", "kd = [0.7, nan, 0.1]"), "materials.red.kd", &["g", "NaN", "[0,"]);
    expect_invalid(&edited("shininess = 32.0", "shininess = -inf"), "materials.red.shininess", &["[0, 1e6]"]);
    expect_invalid(
        &edited("position = [2.0, 4.0, -2.0]", "position = [nan, 4.0, -2.0]"),
        "lights[0].position",
        &["x", "1e9"],
    );
    expect_invalid(
        &edited("position = [0.0, 1.0, -5.0]", "position = [0.0, 1.0, -inf]"),
        "camera.position",
        &["z", "1e9"],
    );
    expect_invalid(&edited("exponent = 8.0", "exponent = nan"), "lights[2].exponent", &["[0,"]);
}

#[test]
fn radius_must_be_positive() {
    expect_invalid(&edited("radius = 1.0", "radius = -1.0"), "objects[0].radius", &["-1", "(0, 1e9]"]);
    expect_invalid(&edited("radius = 1.0", "radius = 0.0"), "objects[0].radius", &["(0, 1e9]"]);
}

#[test]
fn zero_length_directions() {
    expect_invalid(&edited("normal = [0.0, 1.0, 0.0]", "normal = [0.0, 0.0, 0.0]"), "objects[1].normal", &["length"]);
    expect_invalid(
        &edited("direction = [0.3, -1.0, 0.2]", "direction = [0.0, 0.0, 0.0]"),
        "lights[1].direction",
        &["length"],
    );
    expect_invalid(
        &edited("direction = [0.5, -1.0, 0.0]", "direction = [0.0, 0.0, 0.0]"),
        "lights[2].direction",
        &["length"],
    );
    expect_invalid(
        &edited("normals = [[0.0, 0.0, 1.0],", "normals = [[0.0, 0.0, 0.0],"),
        "objects[2].normals[0]",
        &["length"],
    );
    expect_invalid(
        &edited("look_at = [0.0, 0.5, 0.0]", "look_at = [0.0, 0.5, 0.0]\nup = [0.0, 0.0, 0.0]"),
        "camera.up",
        &["length"],
    );
    // The bound is exclusive, as the message says: a normal of length exactly 1e-12 is refused.
    expect_invalid(
        &edited("normal = [0.0, 1.0, 0.0]", "normal = [0.0, 1e-12, 0.0]"),
        "objects[1].normal",
        &["needs length > 1e-12"],
    );
}

#[test]
fn a_look_at_nearer_the_eye_than_its_bound_says_how_near_and_the_bound() {
    expect_invalid(
        &edited("look_at = [0.0, 0.5, 0.0]", "look_at = [0.0, 1.0, -4.9999999999]"),
        "camera.look_at",
        &["is 1e-10 from camera.position", "at least 1e-9"],
    );
    expect_invalid(
        &edited("look_at = [0.0, 0.5, 0.0]", "look_at = [0.0, 1.0, -5.0]"),
        "camera.look_at",
        &["equals camera.position", "at least 1e-9"],
    );
}

#[test]
fn an_orthographic_camera_needs_a_view_height_in_range_and_a_perspective_one_ignores_it_aloud() {
    let orthographic =
        |extra: &str| edited("look_at = [0.0, 0.5, 0.0]", &format!("look_at = [0.0, 0.5, 0.0]\n{extra}"));
    assert!(expect_valid(&orthographic("projection = \"orthographic\"\nview_height = 3.0"), "3.0").is_empty());
    // Not given, it is what the field of view sees at look_at: valid here.
    assert!(expect_valid(&orthographic("projection = \"orthographic\""), "derived").is_empty());
    for bad in ["0.0", "-3.0", "1e10", "nan"] {
        expect_invalid(
            &orthographic(&format!("projection = \"orthographic\"\nview_height = {bad}")),
            "camera.view_height",
            &["[1e-9, 1e9]"],
        );
    }
    // A field of view so narrow that the derived height is below the bound says how it was derived.
    expect_invalid(
        &edited(
            "look_at = [0.0, 0.5, 0.0]",
            "look_at = [0.0, 1.0, -4.99999]\nprojection = \"orthographic\"\nfov_y = 1e-6",
        ),
        "camera.view_height",
        &["not given", "2·|look_at − position|·tan(fov_y/2) = 1.75e-13, outside", "give it"],
    );
    // An invalid fov_y is refused under its own name, not again as the view height it gives.
    expect_invalid(&orthographic("projection = \"orthographic\"\nfov_y = 200.0"), "camera.fov_y", &["[1e-6, 179]"]);
    let warned = expect_valid(&orthographic("view_height = 3.0"), "perspective with a view height");
    assert!(
        warned.len() == 1 && warned[0].starts_with("camera.view_height: is used by an orthographic camera only"),
        "{warned:?}"
    );
    // Ignored by a perspective camera, but nan is refused everywhere (a tester's rendered).
    for bad in ["nan", "-1.0", "1e10"] {
        expect_invalid(&orthographic(&format!("view_height = {bad}")), "camera.view_height", &["[1e-9, 1e9]"]);
    }
    let err = parse_scene(&orthographic("projection = \"fisheye\""), Path::new(FILE)).unwrap_err().to_string();
    assert!(err.contains("unknown variant `fisheye`, expected `perspective` or `orthographic`"), "{err}");
}

#[test]
fn ior_must_be_positive() {
    for bad in ["0.0", "-1.5"] {
        expect_invalid(&edited("ior = 1.5", &format!("ior = {bad}")), "materials.glass.ior", &["(0, 1000]"]);
    }
    // Any positive ior is physical enough (ior < 1: a bubble).
    expect_valid(&edited("ior = 1.5", "ior = 0.5"), "ior 0.5");
}

#[test]
fn attenuation_that_can_reach_zero() {
    let att = "attenuation = { c = 1.0, l = 0.1, q = 0.01 }";
    let field = "lights[0].attenuation";
    // c + l·d + q·d² at d = 0 is c.
    expect_invalid(&edited(att, "attenuation = { c = 0.0, l = 0.1, q = 0.01 }"), field, &["c must be", "c = 0"]);
    expect_invalid(&edited(att, "attenuation = { c = -1.0, l = 1.0, q = 1.0 }"), field, &["c must be", "c = -1"]);
    // Falls forever: q < 0, or q = 0 and l < 0.
    expect_invalid(&edited(att, "attenuation = { c = 1.0, l = 1.0, q = -0.01 }"), field, &["q ≥ 0"]);
    expect_invalid(&edited(att, "attenuation = { c = 1.0, l = -0.1 }"), field, &["l ≥ 0"]);
    // A q that f32 rounds to 0 is judged as 0, and said to be (a tester read "q = 5e-324" as
    // contradicting "q ≥ 0").
    expect_invalid(
        &edited(att, "attenuation = { c = 1.0, l = -1e-30, q = 5e-324 }"),
        field,
        &["l ≥ 0 when q = 0 (got c = 1, l = -1e-30, q = 5e-324, 0 in f32)"],
    );
    // l < 0 with a small q: minimum 1 − 1/(4·0.1) = −1.5 at d = 5.
    expect_invalid(&edited(att, "attenuation = { c = 1.0, l = -1.0, q = 0.1 }"), field, &["d = 5"]);
    // Exactly zero at its minimum: 1 − 4/(4·1) = 0 at d = −l/(2q) = 1.
    expect_invalid(&edited(att, "attenuation = { c = 1.0, l = -2.0, q = 1.0 }"), field, &["d = 1"]);
    // A minimum just below the bound is written in significant digits, not rounded onto it
    // ("falls to 0.000001" seemed to meet "≥ 1e-6").
    expect_invalid(
        &edited(att, "attenuation = { c = 1e-6, l = -1e-9, q = 1e-9 }"),
        field,
        &["falls to 9.9975e-7 at d = 0.5"],
    );
    // A dip far below c that stays above 1e-6: near it the terms, each about c, cancel, and
    // the GPU's f32 sum made f_att infinite (c / 1.6e7) or 119 % off (c / 1e7).
    expect_invalid(
        &edited(att, "attenuation = { c = 1000000.0625, l = -2000.0, q = 1.0 }"),
        field,
        &["falls to 0.0625 at d = 1000, 16000000 times below c", "deeper than c / 1e4"],
    );
    expect_invalid(&edited(att, "attenuation = { c = 1.0, l = -2.0, q = 1.00001 }"), field, &["times below c"]);
    expect_valid(&edited(att, "attenuation = { c = 1.0, l = -2.0, q = 1.001 }"), "a dip to c / 1000");
    // The same on a spot light; a textbook's pure 1/d² is pointed to the model that has it.
    expect_invalid(
        &edited("exponent = 8.0", "exponent = 8.0\nattenuation = { c = 0.0, q = 1.0 }"),
        "lights[2].attenuation",
        &["c must be", "c = 0", "write attenuation = { model = \"inverse_square\" }"],
    );
    // `{ c = 0 }` alone names both ways out (it named only the bound; a newcomer).
    expect_invalid(
        &edited("exponent = 8.0", "exponent = 8.0\nattenuation = { c = 0.0 }"),
        "lights[2].attenuation",
        &[
            "c must be",
            "for no falloff leave attenuation out (c = 1), for the textbook 1/d² write attenuation = { model = \"inverse_square\" }",
        ],
    );
    // l < 0 whose minimum stays positive is fine: 1 − 1/(4·1) = 0.75.
    expect_valid(&edited(att, "attenuation = { c = 1.0, l = -1.0, q = 1.0 }"), "l < 0, positive minimum");
    expect_valid(&edited(att, "attenuation = { c = 0.5 }"), "constant attenuation");
    // The least c the message names is allowed (judged as f32 holds both: 1e-6 rounds down);
    // below it is not.
    expect_valid(&edited(att, "attenuation = { c = 1e-6 }"), "c at the documented least");
    expect_valid(&world_with("{ c = 1e-6 }"), "global c at the documented least");
    // The global attenuation has no inverse-square model to point to (it has c, l, q only).
    let err = parse_scene(&world_with("{ c = 0.0, q = 1.0 }"), Path::new(FILE)).unwrap_err().to_string();
    assert!(
        err.contains("world.global_attenuation: c + l·d + q·d² is c at d = 0") && !err.contains("inverse_square"),
        "{err}"
    );
    expect_invalid(&edited(att, "attenuation = { c = 9.99e-7 }"), field, &["c must be ≥ 1e-6", "c = 9.99e-7"]);
}

fn world_with(att: &str) -> String {
    edited("[camera]", &format!("[world]\nglobal_attenuation = {att}\n\n[camera]"))
}

#[test]
fn global_attenuation_is_validated_as_a_lights() {
    let world = |att: &str| edited("[camera]", &format!("[world]\nglobal_attenuation = {att}\n\n[camera]"));
    let field = "world.global_attenuation";
    expect_valid(&world("{ c = 1.0, l = 0.1, q = 0.01 }"), "global attenuation");
    expect_invalid(&world("{ c = 0.0, l = 0.1 }"), field, &["c must be", "c = 0"]);
    expect_invalid(&world("{ c = 1.0, q = -0.01 }"), field, &["q ≥ 0"]);
    expect_invalid(&world("{ c = 1.0, l = -1.0, q = 0.1 }"), field, &["d = 5"]);
    expect_invalid(&world("{ c = 1.0, l = nan }"), "world.global_attenuation.l", &["not a finite number", "allowed"]);
    expect_parse_error(&world("{ c = 1.0, k = 0.1 }"), &["k"]);
}

#[test]
fn arrays_longer_than_their_kind_are_refused_not_cut() {
    // serde read [f64; 3] from its first three items and left the rest unread: a camera at
    // [0, 1, -5, "x"] and a triangle [0, 1, 2, 99999] (a quad written as one) went through.
    let four = "invalid length 4, expected an array of length 3";
    for (from, to, says) in [
        ("position = [2.0, 4.0, -2.0]", "position = [2.0, 4.0, -2.0, 7.0]", four),
        ("position = [2.0, 4.0, -2.0]", "position = [2.0, 4.0, -2.0, \"x\"]", four),
        ("center = [0.0, 1.0, 0.0]", "center = [0.0, 1.0, 0.0, 1e300]", four),
        ("triangles = [[0, 1, 2]]", "triangles = [[0, 1, 2, 99999]]", four),
        ("direction = [0.3, -1.0, 0.2]", "direction = [0.3, -1.0, 0.2, 1.0]", four),
    ] {
        expect_parse_error(&edited(from, to), &[says]);
    }
}

#[test]
fn spot_cutoff_range() {
    for bad in ["120.0", "-1.0", "90.5", "179.0", "180.5", "nan"] {
        expect_invalid(&edited("cutoff = 30.0", &format!("cutoff = {bad}")), "lights[2].cutoff", &["[0, 90]", "180"]);
    }
    for good in ["0.0", "90.0", "180.0", "45.5"] {
        let warnings = expect_valid(&edited("cutoff = 30.0", &format!("cutoff = {good}")), &format!("cutoff {good}"));
        // Without a cone (180) the exponent does nothing (OpenGL's rule): said, not silent.
        let said = warnings.iter().any(|w| w.contains("lights[2].exponent: 8 does nothing without a cone"));
        assert_eq!(said, good == "180.0", "cutoff {good}: {warnings:?}");
    }
}

#[test]
fn negative_k_values() {
    // A grey (one number) is one value, named once; a channel of three is named by its letter.
    for (from, to, field, which) in [
        ("ka = 0.1", "ka = -0.1", "materials.red.ka", "-0.1 (every channel)"),
        ("kd = [0.7, 0.1, 0.1]", "kd = [0.7, -0.1, 0.1]", "materials.red.kd", "channel g"),
        ("ks = 0.3", "ks = [0.3, 0.3, -1e-9]", "materials.red.ks", "channel b"),
        ("kr = 0.1", "kr = -0.5", "materials.glass.kr", "-0.5 (every channel)"),
        ("kt = 0.8", "kt = [-0.8, 0.8, 0.8]", "materials.glass.kt", "channel r"),
    ] {
        expect_invalid(&edited(from, to), field, &[which, "[0, 1e9]"]);
    }
    let grey = parse_scene(&edited("ka = 0.1", "ka = -0.1"), Path::new(FILE)).expect_err("invalid");
    assert_eq!(grey.issues().len(), 1, "a grey is one message: {grey}");
}

#[test]
fn unknown_material_reference() {
    let text = edited("material = \"glass\"", "material = \"glas\"");
    expect_invalid(&text, "objects[2].material", &["'glas'", "glass", "red"]);
}

#[test]
fn mesh_index_out_of_range() {
    expect_invalid(
        &edited("triangles = [[0, 1, 2]]", "triangles = [[0, 1, 3]]"),
        "objects[2].triangles[0]",
        &["3", "[0, 2]"],
    );
}

/// A syntax or schema error (serde) rather than a validation error: the message must still
/// name the file and the offending key.
fn expect_parse_error(text: &str, fragments: &[&str]) {
    let err = parse_scene(text, Path::new(FILE)).err().unwrap_or_else(|| panic!("accepted:\n{text}"));
    let msg = err.to_string();
    assert!(matches!(err, SceneError::Parse { .. }), "not a parse error: {msg}");
    assert!(msg.contains(FILE), "message does not name the file: {msg}");
    for f in fragments {
        assert!(msg.contains(f), "message does not contain {f:?}: {msg}");
    }
}

#[test]
fn unknown_fields_are_rejected() {
    // A typo in a plain table, in a material, in a light, in an inline table and in an object
    // (internally tagged): each is an error naming the unknown key, never silently ignored.
    expect_parse_error(&edited("look_at = [0.0, 0.5, 0.0]", "look_at = [0.0, 0.5, 0.0]\nfov = 40.0"), &["fov"]);
    expect_parse_error(&edited("shininess = 32.0", "shinyness = 32.0"), &["shinyness"]);
    expect_parse_error(&edited("cutoff = 30.0", "cutoff = 30.0\ncuttoff = 20.0"), &["cuttoff"]);
    expect_parse_error(&edited("{ c = 1.0, l = 0.1, q = 0.01 }", "{ c = 1.0, l = 0.1, qq = 0.01 }"), &["qq"]);
    expect_parse_error(&edited("radius = 1.0", "raduis = 1.0"), &["raduis"]);
    expect_parse_error(&edited("[camera]", "[render]\nwidht = 10\n\n[camera]"), &["widht"]);
}

#[test]
fn wrong_types_and_missing_fields_of_objects_name_the_field() {
    // An object's fields are read by its kind's own struct, so the message names the field
    // and the line of the object (not only "expected f64").
    expect_parse_error(&edited("radius = 1.0", "radius = \"x\""), &["radius", "expected a number"]);
    expect_parse_error(&edited("center = [0.0, 1.0, 0.0]", "center = [0.0, 1.0]"), &["center", "length 3"]);
    expect_parse_error(&edited("radius = 1.0\nmaterial = \"red\"", "radius = 1.0"), &["missing field `material`"]);
    expect_parse_error(
        &edited("type = \"sphere\"", "type = \"cube\""),
        &["objects[0].type: unknown object type \"cube\"; allowed: sphere, plane, mesh"],
    );
    expect_parse_error(&edited("radius = 1.0", "radius = \"x\""), &["objects[0] (sphere): ", "radius"]);
}

#[test]
fn an_object_type_typo_names_the_field_with_its_index_and_the_allowed_values() {
    // Before: the message pointed at the `[[objects]]` header and named neither.
    let text = edited("type = \"mesh\"", "type = \"spehre\"");
    expect_parse_error(&text, &["objects[2].type: unknown object type \"spehre\"; allowed: sphere, plane, mesh"]);
    expect_parse_error(&edited("type = \"mesh\"", "type = 3"), &["objects[2].type: must be a string, one of: sphere"]);
    expect_parse_error(&edited("type = \"mesh\"\n", ""), &["objects[2].type: missing", "sphere, plane, mesh"]);
}

#[test]
fn long_echoed_values_are_shortened() {
    // A 200 kB value was echoed in full, in the parser's message and in validation's.
    let long = "x".repeat(200_000);
    for (text, what) in [
        (edited("type = \"mesh\"", &format!("type = \"{long}\"")), "object type"),
        (edited("material = \"glass\"", &format!("material = \"{long}\"")), "material name"),
        (edited("position = [2.0, 4.0, -2.0]", &format!("position = [2.0, 4.0, -2.0]\n{long} = 1")), "unknown key"),
    ] {
        let msg = parse_scene(&text, Path::new(FILE)).expect_err(what).to_string();
        assert!(msg.len() < 4_000, "{what}: {} bytes of message: {}…", msg.len(), &msg[..300]);
        assert!(msg.contains("more bytes)"), "{what}: does not say it was cut: {msg}");
    }
}

#[test]
fn an_empty_vertex_list_with_triangles_says_the_mesh_has_no_vertices() {
    // Before: "vertex index 0 is out of range; allowed: [0, 0]".
    let text = edited("vertices = [[-1.0, 0.0, 2.0], [1.0, 0.0, 2.0], [0.0, 2.0, 2.0]]", "vertices = []")
        .replace("normals = [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]\n", "");
    expect_invalid(&text, "objects[2].vertices", &["the mesh has no vertices, but its triangle refers to them"]);
}

#[test]
fn extreme_numbers_are_printed_as_written_not_as_300_digit_decimals() {
    expect_invalid(&edited("radius = 1.0", "radius = 1e300"), "objects[0].radius", &["1e300 is outside", "(0, 1e9]"]);
    expect_invalid(&edited("radius = 1.0", "radius = 5e-324"), "objects[0].radius", &["5e-324 is outside"]);
    expect_invalid(&edited("shininess = 32.0", "shininess = 1e300"), "materials.red.shininess", &["1e300 is outside"]);
    expect_invalid(&edited("ior = 1.5", "ior = -1e300"), "materials.glass.ior", &["-1e300 is outside"]);
    expect_invalid(
        &edited("position = [2.0, 4.0, -2.0]", "position = [1e300, 4.0, -2.0]"),
        "lights[0].position",
        &["x = 1e300 must"],
    );
    let err = parse_scene(&edited("radius = 1.0", "radius = 1e300"), Path::new(FILE)).unwrap_err();
    assert!(err.to_string().len() < 200, "{err}");
}

#[test]
fn a_light_written_as_an_array_says_a_light_is_a_table() {
    // Before: "wanted exactly 1 element, more than 1 element".
    let camera = "[camera]\nposition = [0.0, 1.0, -5.0]\nlook_at = [0.0, 0.5, 0.0]\n";
    let text = format!("lights = [[{{ type = \"point\", position = [0.0, 1.0, 0.0] }}]]\n{camera}");
    expect_parse_error(
        &text,
        &["invalid type: sequence, expected a light: a table ([[lights]] or { type = \"point\", … })"],
    );
    let text = format!("objects = [[{{ type = \"sphere\" }}]]\n{camera}");
    expect_parse_error(&text, &["objects[0]: an object is a table", "not an array"]);
}

#[test]
fn a_table_written_as_an_array_is_refused_not_read_by_position() {
    // Before: serde's derive read `render = [16, 12, 3]` as width 16, height 12, spp 3.
    let camera = "[camera]\nposition = [0.0, 1.0, -5.0]\nlook_at = [0.0, 0.5, 0.0]\n";
    let expected = ["invalid type: sequence, expected a table ([section] or { key = value, … })"];
    for head in [
        "render = [16, 12, 3]\n",
        "world = [0.1, [0.0, 0.0, 0.0]]\n",
        "world = { global_attenuation = [1.0, 0.0, 0.0] }\n",
        "materials = { red = [1.0, 0.5] }\n",
        "materials = { red = { checker = [0.2, 1.0] } }\n",
        "materials = { red = { texture = { path = \"t.png\", transform = [[1.0, 1.0]] } } }\n",
    ] {
        expect_parse_error(&format!("{head}{camera}"), &expected);
    }
    expect_parse_error("camera = [[0.0, 1.0, -5.0], [0.0, 0.5, 0.0]]\n", &expected);
    let model = format!("{camera}[[objects]]\ntype = \"model\"\npath = \"m.obj\"\ntransform = [[1.0, 2.0, 3.0]]\n");
    expect_parse_error(&model, &["objects[0]", "expected a table"]);
}

#[test]
fn a_model_scene_index_is_a_whole_number_as_the_format_names_them() {
    // Before: "expected usize", a type the format does not name.
    let camera = "[camera]\nposition = [0.0, 1.0, -5.0]\nlook_at = [0.0, 0.5, 0.0]\n";
    let model = format!("{camera}[[objects]]\ntype = \"model\"\npath = \"m.gltf\"\nscene_index = -1\n");
    expect_parse_error(&model, &["objects[0] (model): scene_index", "expected a whole number from 0 to 4294967295"]);
}

#[test]
fn a_checker_square_is_refused_where_its_texture_scale_would_overflow_f32() {
    // Before: (0, 1e9] was allowed, and 1e-39 rendered on the CPU while the GPU refused the scene
    // ("a NaN or an infinity in textures[0]"): 1 / (2·size) overflows f32 below 1.5e-39.
    let checker =
        |size: &str| edited("shininess = 32.0", &format!("shininess = 32.0\nchecker = {{ kd = 0.5, size = {size} }}"));
    for size in ["1e-39", "1e-10", "0.0", "2e9"] {
        expect_invalid(&checker(size), "materials.red.checker.size", &["the allowed range [1e-9, 1e9]"]);
    }
    for size in ["1e-9", "1e9"] {
        parse_scene(&checker(size), Path::new(FILE)).unwrap_or_else(|e| panic!("size {size}: {e}"));
    }
}

#[test]
fn light_messages_write_numbers_short() {
    // Before: "1000000000000…(301 digits)" and "outer_cone = 0.000…(300 digits)…1".
    let far = edited(
        "attenuation = { c = 1.0, l = 0.1, q = 0.01 }",
        "attenuation = { model = \"inverse_square\", range = 1e300 }",
    );
    expect_invalid(&far, "lights[0].attenuation.range", &["1e300 is outside the allowed range (0, 1e9]"]);
    let narrow =
        edited("exponent = 8.0\ncutoff = 30.0", "falloff = \"smooth\"\ninner_cone = 12.0\nouter_cone = 1e-300");
    expect_invalid(&narrow, "lights[2].inner_cone", &["12 is larger than outer_cone = 1e-300;"]);
}

#[test]
fn a_light_error_keeps_the_position_of_its_field() {
    // Lights are read by their derive, which keeps the parser's position of the bad value.
    expect_parse_error(
        &edited("type = \"spot\"", "type = \"spt\""),
        &["line 29, column 8", "spt", "`point`, `directional`, `spot`"],
    );
}

#[test]
fn kr_plus_kt_above_one_warns_but_loads() {
    let warnings = expect_valid(&edited("kr = 0.1", "kr = 0.5"), "k_r + k_t = 1.3");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].contains("materials.glass") && warnings[0].contains("1.3"), "{warnings:?}");
    // Exactly 1 is fine and silent.
    assert!(expect_valid(&edited("kr = 0.1", "kr = 0.2"), "k_r + k_t = 1").is_empty());
    // An excess in blue alone is one too (two channels were read, and no test told).
    let blue = edited("kr = 0.1\nkt = 0.8", "kr = [0.0, 0.0, 0.5]\nkt = [0.0, 0.0, 0.75]");
    let warnings = expect_valid(&blue, "blue k_r + k_t = 1.25");
    assert!(warnings.len() == 1 && warnings[0].contains("materials.glass.kr + kt: k_r + k_t = 1.25"), "{warnings:?}");
}

#[test]
fn a_coefficient_above_1_warns_and_an_8_bit_colour_is_named() {
    let warnings = expect_valid(&edited("kd = [0.7, 0.1, 0.1]", "kd = [255.0, 0.0, 0.0]"), "kd = 255");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].starts_with("materials.red.kd: 255 is above 1") && warnings[0].contains("divide it by 255"),
        "{warnings:?}"
    );
    let warnings = expect_valid(&edited("ks = 0.3", "ks = 1.5"), "ks = 1.5");
    assert!(warnings.len() == 1 && !warnings[0].contains("255"), "{warnings:?}");
    // A checker's second colour is k_d on half the squares.
    let warnings =
        expect_valid(&edited("ks = 0.3", "ks = 0.3\nchecker = { kd = 255.0, size = 0.5 }"), "checker.kd = 255");
    assert!(warnings.len() == 1 && warnings[0].starts_with("materials.red.checker.kd: 255 is above 1"), "{warnings:?}");
    assert!(expect_valid(&edited("ks = 0.3", "ks = 1.0"), "ks = 1").is_empty());
}

/// A sphere that f32 storage sets on a floor (or into another sphere) it clears as written: a
/// radius of 899,999,990 at 9e8 is stored to 32 units, a 3e-8 part of itself (no coarse-storage
/// warning), and its 10-unit gap over the floor was gone without a word (an extreme-scenes
/// tester). A sphere set on a floor by hand (centre 1.1, radius 1, floor 0.1: a gap of 2e-16 in
/// f64) is said nothing of.
#[test]
fn a_contact_f32_storage_makes_or_breaks_is_warned_of() {
    let scene = |objects: &str| {
        format!(
            "[camera]\nposition = [0.0, 20.0, -9e8]\nlook_at = [0.0, 0.0, 0.0]\n\n[materials.m]\nkd = 0.8\n\n\
             [[lights]]\ntype = \"point\"\nposition = [0.0, 9e8, -9e8]\n\n\
             [[objects]]\ntype = \"plane\"\npoint = [0.0, 0.1, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n\n\
             [[objects]]\ntype = \"sphere\"\ncenter = [3.0, 1.1, 0.0]\nradius = 1.0\nmaterial = \"m\"\n{objects}"
        )
    };
    assert!(expect_valid(&scene(""), "a sphere set on the floor by hand").is_empty());
    let giant = "\n[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 9e8, 0.0]\nradius = 899999990.0\nmaterial = \"m\"\n";
    let warnings = expect_valid(&scene(giant), "a giant sphere over the floor");
    assert_eq!(
        warnings,
        [
            "objects[2]: with the plane objects[0]: in front of it as written (gap 9.9), but cutting each other as \
             both tracers store them in f32 (gap -0.1), and so the image shows them; widen the gap beyond f32's step at \
             their size (64) (docs/numerics.md, Known limits)",
            // The small sphere under the giant one ends up inside it.
            "objects[2]: with the sphere objects[1]: outside each other as written (gap 7.9), but one inside the \
             other as both tracers store them in f32 (gap 0.1), and so the image shows them; widen the gap beyond \
             f32's step at their size (64) (docs/numerics.md, Known limits)",
        ]
    );
    // A sphere inside another, 5 clear of its inner wall as written: the outer radius of
    // 899,999,950 is stored as 899,999,936, its wall rises from 50 to 64, through the inner
    // sphere (55 to 65), which pokes 1 out of it. (Judged by their centres' distance less both
    // radii, the two were "cutting" as written and as stored, and nothing was said.)
    let shell = "\n[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 9e8, 0.0]\nradius = 899999950.0\nmaterial = \"m\"\n\n\
                 [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 60.0, 0.0]\nradius = 5.0\nmaterial = \"m\"\n";
    let warnings = expect_valid(&scene(shell), "a sphere inside a giant one");
    assert_eq!(
        warnings,
        ["objects[3]: with the sphere objects[2]: one inside the other as written (gap 5), but cutting each other \
          as both tracers store them in f32 (gap -1), and so the image shows them; widen the gap beyond f32's step \
          at their size (64) (docs/numerics.md, Known limits)"]
    );
    // A sphere of radius 5e-4 resting 1e-6 over a floor at the origin, the default ε: the gap is
    // ε itself, which f32's rounding of 1e-6 crossed ("in front" as written, "touching" as
    // stored, and the remedy to move a scene already at the origin; a models tester). Nor is
    // anything said at the ε of `--epsilon 1e-9`.
    let small = "[camera]\nposition = [0.003, 0.002, -0.004]\nlook_at = [0.0, 0.0007, 0.0]\n\n[materials.m]\nkd = 0.8\n\n\
                 [[objects]]\ntype = \"plane\"\npoint = [0.0, -1e-6, 0.0]\nnormal = [0.0, 1.0, 0.0]\nmaterial = \"m\"\n\n\
                 [[objects]]\ntype = \"sphere\"\ncenter = [-0.0013, 0.0005, 0.001]\nradius = 0.0005\nmaterial = \"m\"\n";
    let (desc, warnings) = parse_scene(small, Path::new(FILE)).expect("the small scene");
    assert!(warnings.iter().all(|w| !w.to_string().contains("store them in f32")), "{warnings:?}");
    assert!(glint_scene::epsilon_warnings_of_objects(&desc, 1e-6).is_empty());
    assert!(glint_scene::epsilon_warnings_of_objects(&desc, 1e-9).is_empty());
}

/// A student's two plausible set-ups that render without an error but not as meant (a lecturer).
#[test]
fn a_light_shut_in_an_opaque_sphere_and_a_slab_of_same_facing_planes_warn() {
    // The point light at (2, 4, -2) inside a sphere of radius 0.5 around it.
    let ball = |material: &str| {
        format!(
            "{BASE}[[objects]]\ntype = \"sphere\"\ncenter = [2.0, 4.0, -2.1]\nradius = 0.5\nmaterial = \"{material}\"\n"
        )
    };
    let warnings = expect_valid(&ball("red"), "a light in an opaque sphere");
    assert!(
        warnings.len() == 1 && warnings[0].starts_with("lights[0].position: is inside objects[3], an opaque sphere"),
        "{warnings:?}"
    );
    // Through a glass one it shines, so nothing is said.
    assert!(expect_valid(&ball("glass"), "a light in a glass sphere").is_empty());
    // A dome about the whole scene, camera and light inside: lit as without it (a tester).
    let dome =
        format!("{BASE}[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1e8\nmaterial = \"red\"\n");
    assert!(expect_valid(&dome, "a dome about the scene").is_empty());
    let plane = |y: f64, ny: f64| {
        format!(
            "[[objects]]\ntype = \"plane\"\npoint = [0.0, {y:?}, 0.0]\nnormal = [0.0, {ny:?}, 0.0]\nmaterial = \"glass\"\n"
        )
    };
    let slab = |lower: f64| BASE.to_string() + &plane(-1.0, 1.0) + &plane(-2.0, lower);
    let warnings = expect_valid(&slab(1.0), "a slab of planes facing the same way");
    assert!(
        warnings.len() == 1
            && warnings[0].starts_with(
                "objects[3]: is a transmissive plane parallel to the transmissive plane objects[4], its normal facing the same way"
            ),
        "{warnings:?}"
    );
    assert!(expect_valid(&slab(-1.0), "a slab whose planes face out of it").is_empty());
    // One sphere written twice fights for its pixels as coplanar faces do (an extreme-scenes
    // tester); one a hair apart in f64 but the same in f32 too.
    let twice = |radius: &str| {
        format!(
            "{BASE}[[objects]]\ntype = \"sphere\"\ncenter = [0.0, 1.0, 0.0]\nradius = {radius}\nmaterial = \"glass\"\n"
        )
    };
    for radius in ["1.0", "1.00000000001"] {
        let warnings = expect_valid(&twice(radius), "a sphere twice");
        assert!(
            warnings.len() == 1 && warnings[0].starts_with("objects[3]: is the sphere objects[0] again"),
            "{radius}: {warnings:?}"
        );
    }
    assert!(expect_valid(&twice("1.001"), "a sphere inside another").is_empty());
    // Far from the origin, two spheres 0.003 apart are two in the stored frame (relative to the
    // storage origin), though one in world f32, whose step is 0.0078 at 1e5 (a tester).
    let far = |dx: f64| {
        let sphere = |x: f64| {
            format!("[[objects]]\ntype = \"sphere\"\ncenter = [{x}, 0.0, 0.0]\nradius = 0.001\nmaterial = \"m\"\n")
        };
        format!(
            "[camera]\nposition = [100000.0, 0.0, -0.02]\nlook_at = [100000.0, 0.0, 0.0]\n[materials.m]\nkd = 0.8\n\
             [render]\nepsilon = 1e-9\n[[lights]]\ntype = \"directional\"\ndirection = [0.0, 0.0, 1.0]\n{}{}",
            sphere(100000.0),
            sphere(100000.0 + dx)
        )
    };
    let warnings = expect_valid(&far(0.003), "spheres apart far out");
    assert!(warnings.is_empty(), "{warnings:?}");
    let warnings = expect_valid(&far(0.0), "a sphere twice far out");
    assert!(
        warnings.len() == 1 && warnings[0].starts_with("objects[1]: is the sphere objects[0] again"),
        "{warnings:?}"
    );
}

#[test]
fn invalid_utf8_gives_the_byte_offset_line_and_column() {
    let dir = glint_test_support::TempDir::new("utf8");
    let path = dir.join("latin1.toml");
    // "José" in Latin-1 on line 2: é is the single byte 0xe9, at byte offset 18.
    let mut bytes = b"# a scene\n# by Jos\xe9\n".to_vec();
    bytes.extend_from_slice(BASE.as_bytes());
    std::fs::write(&path, &bytes).unwrap();
    let err = glint_io::load_scene(path.to_str().unwrap()).expect_err("not UTF-8");
    let msg = err.to_string();
    assert!(msg.contains("latin1.toml"), "{msg}");
    assert!(msg.contains("byte 0xe9 at byte offset 18 (line 2, column 9)"), "{msg}");
}

#[test]
fn an_integer_beyond_64_bits_is_said_to_be_too_large() {
    // Before: "invalid type: integer `…` as i128, expected any valid TOML value".
    let text = edited("triangles = [[0, 1, 2]]", "triangles = [[0, 1, 99999999999999999999999]]");
    expect_parse_error(
        &text,
        &["integer `99999999999999999999999` is beyond the 64-bit integers TOML allows (at most 9223372036854775807)"],
    );
    let err = parse_scene(&text, Path::new(FILE)).unwrap_err().to_string();
    assert!(!err.contains("i128") && !err.contains("any valid TOML value"), "{err}");
}

#[test]
fn a_ray_tree_the_bailout_cannot_stop_is_warned_about_with_its_worst_case() {
    // Glass (k_r = 0.1, k_t = 0.8) branches at every hit; at depth 1024 without a bailout the
    // tree can reach 2^1025 − 1 rays a sample. The default bailout ends each branch where its
    // own weight falls below 1/255 (0.1² already does): a small tree however deep.
    let text = edited("[camera]", "[render]\nmax_depth = 1024\nbailout = 0.0\n\n[camera]");
    let warnings = expect_valid(&text, "depth 1024");
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(warnings[0].starts_with("render.max_depth: materials.glass reflects and refracts"), "{warnings:?}");
    assert!(warnings[0].contains("up to 2^1025 − 1"), "{warnings:?}");
    let text = edited("[camera]", "[render]\nmax_depth = 1024\n\n[camera]");
    assert!(expect_valid(&text, "depth 1024, bailout 1/255").is_empty());
    assert!(expect_valid(&edited("[camera]", "[render]\nmax_depth = 15\nbailout = 0.0\n\n[camera]"), "15").is_empty());
}

/// `BASE` with a texture on the red material, loaded from `scene.toml` in a folder holding
/// `ok.png`, an `image.txt` that is not an image, and a sub-folder with the scene file, so that
/// `../` escapes it.
fn texture_error(texture: &str, field: &str, fragments: &[&str]) {
    let dir = glint_test_support::TempDir::new("texture-validation");
    let scenes = dir.join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    glint_test_support::texture::write_png(&dir.join("outside.png"), 1, 1, &[255, 0, 0, 255]);
    glint_test_support::texture::write_png(&scenes.join("ok.png"), 1, 1, &[255, 0, 0, 255]);
    std::fs::write(scenes.join("image.txt"), "not an image").unwrap();
    let file = scenes.join("scene.toml");
    std::fs::write(&file, edited("shininess = 32.0", &format!("shininess = 32.0\n{texture}"))).unwrap();
    let err = glint_io::load_scene(&file).expect_err("a bad texture is an error");
    let msg = err.to_string();
    assert!(matches!(err, SceneError::Invalid { .. }) && msg.contains("scene.toml"), "{field}: {msg}");
    let issue = err.issues().iter().find(|i| i.field == field).unwrap_or_else(|| panic!("no issue for {field}: {msg}"));
    for f in fragments {
        assert!(issue.problem.contains(f), "{field}: {issue} does not contain {f:?}");
    }
}

#[test]
fn bad_texture_paths_name_the_file_field_and_reason() {
    let field = "materials.red.texture.path";
    texture_error("texture = { path = \"missing.png\" }", field, &["missing.png", "No such file"]);
    texture_error(
        "texture = { path = \"../outside.png\" }",
        field,
        &["../outside.png", "outside the folder of the file that names it"],
    );
    texture_error("texture = { path = \"/etc/passwd\" }", field, &["/etc/passwd", "absolute path"]);
    texture_error("texture = { path = \"file:///etc/passwd\" }", field, &["scheme `file:`"]);
    texture_error("texture = { path = \"image.txt\" }", field, &["not a PNG or JPEG"]);
    texture_error("emission_texture = { path = \"nope.jpg\" }", "materials.red.emission_texture.path", &["nope.jpg"]);
    // The good image with a bad transform or alongside a checker: validation names those fields.
    texture_error(
        "texture = { path = \"ok.png\", transform = { scale = [1e12, 1.0] } }",
        "materials.red.texture.transform.scale.u",
        &["1000000000000", "[-1e9, 1e9]"],
    );
    texture_error(
        "texture = { path = \"ok.png\" }\nchecker = { kd = 0.5, size = 1.0 }",
        "materials.red.checker",
        &["not both"],
    );
    // A missing texture is one error among the others, all said at once (it hid them), and
    // validation's own "not decoded" for its field is not said again.
    texture_error("texture = { path = \"missing.png\" }\nior = 0.0", "materials.red.ior", &["(0, 1000]"]);
    texture_error("texture = { path = \"missing.png\" }\nior = 0.0", field, &["No such file"]);
    let dir = glint_test_support::TempDir::new("texture-and-others");
    let file = dir.join("scene.toml");
    std::fs::write(&file, edited("shininess = 32.0", "texture = { path = \"missing.png\" }")).unwrap();
    let err = glint_io::load_scene(&file).expect_err("missing texture");
    assert_eq!(err.issues().len(), 1, "{err}");
}

#[test]
fn a_texture_in_a_description_built_in_code_must_be_decoded() {
    // parse_scene decodes relative to the file it names; a path that does not exist there is
    // the same error as from a scene file.
    let text = edited("shininess = 32.0", "shininess = 32.0\ntexture = { path = \"nowhere/t.png\" }");
    let err = parse_scene(&text, Path::new(FILE)).expect_err("no such texture");
    assert!(err.issues().iter().any(|i| i.field == "materials.red.texture.path"), "{err}");
    // And a description whose texture was never decoded does not validate.
    let (mut desc, _) = parse_scene(BASE, Path::new(FILE)).expect("BASE is valid");
    desc.materials.get_mut("red").unwrap().texture = Some(glint_scene::TextureDesc {
        path: "t.png".into(),
        wrap_s: Default::default(),
        wrap_t: Default::default(),
        filter: Default::default(),
        transform: None,
        image: None,
    });
    let report = glint_scene::validate(&desc);
    assert!(report.errors.iter().any(|i| i.field == "materials.red.texture.path" && i.problem.contains("not decoded")));
}

#[test]
fn inverse_square_range_must_be_positive() {
    let att = "{ c = 1.0, l = 0.1, q = 0.01 }";
    for bad in ["0.0", "-5.0", "1e10", "1e-50"] {
        expect_invalid(
            &edited(att, &format!("{{ model = \"inverse_square\", range = {bad} }}")),
            "lights[0].attenuation.range",
            &["(0, 1e9]"],
        );
    }
    expect_invalid(
        &edited(att, "{ model = \"inverse_square\", range = nan }"),
        "lights[0].attenuation.range",
        &["NaN", "(0, 1e9]"],
    );
    for good in [
        "{ model = \"inverse_square\" }",
        "{ model = \"inverse_square\", range = 20 }",
        "{ model = \"polynomial\", q = 1.0 }",
    ] {
        assert!(expect_valid(&edited(att, good), good).is_empty());
    }
    // A directional light is not attenuated, by either model.
    expect_invalid(
        &edited(
            "direction = [0.3, -1.0, 0.2]",
            "direction = [0.3, -1.0, 0.2]\nattenuation = { model = \"inverse_square\" }",
        ),
        "lights[1].attenuation",
        &["not attenuated"],
    );
}

#[test]
fn attenuation_fields_of_the_other_model_are_errors() {
    // Not silently ignored: the message names the field and the model it belongs to.
    let att = "{ c = 1.0, l = 0.1, q = 0.01 }";
    expect_parse_error(
        &edited(att, "{ model = \"inverse_square\", q = 0.01 }"),
        &["attenuation.q", "model = \"polynomial\"", "has only range"],
    );
    expect_parse_error(
        &edited(att, "{ c = 1.0, range = 5.0 }"),
        &["attenuation.range", "model = \"inverse_square\"", "has only c, l, q"],
    );
    expect_parse_error(&edited(att, "{ model = \"inverse_square\", rnage = 5.0 }"), &["attenuation.rnage", "range"]);
    expect_parse_error(&edited(att, "{ model = \"cubic\" }"), &["cubic", "\"polynomial\" or \"inverse_square\""]);
    expect_parse_error(
        &edited(att, "{ model = \"inverse_square\", range = \"far\" }"),
        &["range", "expected a number"],
    );
}

/// BASE's spot light with the smooth falloff and `cones` instead of its exponent and cutoff.
fn smooth_spot(cones: &str) -> String {
    edited("exponent = 8.0\ncutoff = 30.0", &format!("falloff = \"smooth\"\n{cones}"))
}

#[test]
fn smooth_spot_cones_in_range_and_ordered() {
    let range = "[0, 90]";
    expect_invalid(&smooth_spot("inner_cone = -1.0\nouter_cone = 30.0"), "lights[2].inner_cone", &[range]);
    expect_invalid(&smooth_spot("inner_cone = 10.0\nouter_cone = 91.0"), "lights[2].outer_cone", &[range]);
    expect_invalid(&smooth_spot("outer_cone = nan"), "lights[2].outer_cone", &["NaN", range]);
    expect_invalid(
        &smooth_spot("inner_cone = 40.0\nouter_cone = 30.0"),
        "lights[2].inner_cone",
        &["40", "outer_cone = 30", "0 ≤ inner_cone ≤ outer_cone ≤ 90"],
    );
    // The default outer cone (45°) bounds an inner cone given alone.
    expect_invalid(&smooth_spot("inner_cone = 50.0"), "lights[2].inner_cone", &["outer_cone = 45"]);
    for good in [
        "",
        "inner_cone = 0.0\nouter_cone = 0.0",
        "inner_cone = 90.0\nouter_cone = 90.0",
        "inner_cone = 0\nouter_cone = 90",
    ] {
        assert!(expect_valid(&smooth_spot(good), good).is_empty());
    }
}

#[test]
fn spot_fields_of_the_other_falloff_are_errors() {
    let smooth = "falloff = \"smooth\"";
    expect_invalid(
        &edited("cutoff = 30.0", &format!("cutoff = 180.0\n{smooth}")),
        "lights[2].exponent",
        &["falloff = \"power\""],
    );
    expect_invalid(&edited("exponent = 8.0", smooth), "lights[2].cutoff", &["falloff = \"power\"", "outer_cone"]);
    expect_invalid(
        &edited("cutoff = 30.0", "cutoff = 30.0\ninner_cone = 10.0"),
        "lights[2].inner_cone",
        &["falloff = \"smooth\""],
    );
    let point = "attenuation = { c = 1.0, l = 0.1, q = 0.01 }";
    expect_invalid(&edited(point, &format!("{point}\n{smooth}")), "lights[0].falloff", &["only spot lights"]);
    expect_invalid(
        &edited(point, &format!("{point}\nouter_cone = 20.0")),
        "lights[0].outer_cone",
        &["only spot lights"],
    );
    expect_parse_error(&edited("cutoff = 30.0", "cutoff = 30.0\nfalloff = \"linear\""), &["linear", "smooth"]);
}

#[test]
fn cook_torrance_roughness_in_range_and_fresnel_by_name() {
    let ct = |fields: &str| edited("shininess = 32.0", &format!("specular_model = \"cook_torrance\"\n{fields}"));
    for bad in ["0.0", "0.0009", "1.5", "-0.3", "nan", "inf"] {
        expect_invalid(&ct(&format!("roughness = {bad}")), "materials.red.roughness", &["[0.001, 1]"]);
    }
    for good in ["0.001", "0.25", "1.0"] {
        expect_valid(&ct(&format!("roughness = {good}\nfresnel = \"schlick\"")), good);
    }
    // The Fresnel choice is a name: a typo or a number says which names there are.
    expect_parse_error(&ct("fresnel = \"shlick\""), &["shlick", "exact", "schlick"]);
    expect_parse_error(&ct("fresnel = 1"), &["fresnel"]);
    expect_parse_error(&edited("shininess = 32.0", "specular_model = \"cook-torrance\""), &["cook_torrance"]);
}

#[test]
fn an_epsilon_out_of_range_is_refused_at_once_beside_a_mesh() {
    // The coplanar-overlap check ran with ε = 1e308 before ε was refused: its tolerance was
    // infinite and its grid took 10 GB in 15 s.
    let text = r#"
[render]
epsilon = 1e308
[camera]
position = [0.0, 0.0, -5.0]
look_at = [0.0, 0.0, 0.0]
[materials.m]
[[objects]]
type = "mesh"
material = "m"
vertices = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]
triangles = [[0, 1, 2], [1, 3, 2]]
"#;
    expect_invalid(text, "render.epsilon", &["1e308", "[0, 1000]"]);
}

#[test]
fn the_largest_depth_is_refused_not_an_overflow_in_its_ray_tree_warning() {
    // The warning of a ray tree that doubles at every level, made in the same pass, added 1 to
    // max_depth = u32::MAX: a panic in debug builds (`cargo test`, `cargo run`).
    let text = format!("[render]\nmax_depth = 4294967295\nbailout = 0.0\n{BASE}");
    expect_invalid(&text, "render.max_depth", &["4294967295", "[0, 1024]"]);
}

#[test]
fn objects_or_lights_written_as_one_table_say_they_are_arrays() {
    // `[objects]` for `[[objects]]` was "invalid type: map, expected a sequence" (a tester).
    let head = "[camera]\nposition = [0.0, 0.0, -5.0]\nlook_at = [0.0, 0.0, 0.0]\n";
    for (table, expected) in [
        (
            "[objects]\ntype = \"sphere\"\n",
            "expected an array of objects ([[objects]], or objects = [{ type = \"sphere\", … }])",
        ),
        (
            "[lights]\ntype = \"point\"\n",
            "expected an array of lights ([[lights]], or lights = [{ type = \"point\", … }])",
        ),
        ("objects = 1\n", "invalid type: integer `1`, expected an array of objects"),
    ] {
        let text = if table.starts_with('[') { format!("{head}{table}") } else { format!("{table}{head}") };
        let err = parse_scene(&text, Path::new(FILE)).unwrap_err().to_string();
        assert!(err.contains(expected), "{err}");
    }
}
