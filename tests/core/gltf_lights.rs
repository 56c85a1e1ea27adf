//! Closed forms of the glTF light options (KHR_lights_punctual) on the single-pixel floor of
//! closed_form.rs: inverse-square attenuation with and without its range window, and the smooth
//! spot cone inside, between and outside its cones. Expected values come from the formulas of
//! docs/scene-format.md and the stored (f32) scene inputs, never from the tracer.

use glam::DVec3;
use glint_scene::MIN_ATTENUATION_DENOMINATOR;

use crate::closed_form::{FLOOR_KA, FLOOR_KD, axis_at, centre, floor_scene};
use crate::support::{SceneText, assert_rel, dv, num, probe, w3};

const REL: f64 = 1e-9;
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const I_D: [f64; 3] = [1.0, 0.5, 2.0];

/// I = I_a·k_a + f·(I_a,j·k_a + I_d·k_d·(N·L)) on the floor, I_a = 0.125, I_a,j = 0.25.
fn lit_floor(f: f64, n_dot_l: f64) -> DVec3 {
    0.125 * FLOOR_KA * DVec3::ONE + f * (0.25 * FLOOR_KA * DVec3::ONE + dv(I_D) * dv(FLOOR_KD) * n_dot_l)
}

/// A point light at `pos` over the floor with `attenuation = { … }`.
fn point_over_floor(pos: [f64; 3], attenuation: &str) -> SceneText {
    floor_scene("", 0.125)
        .light(
            "point",
            &format!("position = {pos:?}\ndiffuse = {I_D:?}\nambient = 0.25\nattenuation = {{ {attenuation} }}"),
        )
        .plane([0.0; 3], Y, "floor")
}

/// (position, d, N·L): straight above, and off to the side (3-4-5 triangle).
const PLACEMENTS: [([f64; 3], f64, f64); 4] = [
    ([0.0, 0.5, 0.0], 0.5, 1.0),
    ([0.0, 2.0, 0.0], 2.0, 1.0),
    ([0.0, 8.0, 0.0], 8.0, 1.0),
    ([3.0, 4.0, 0.0], 5.0, 0.8),
];

fn check_f_att(scene: &SceneText, f_att: f64, n_dot_l: f64, what: &str) {
    assert_rel(centre(scene), lit_floor(f_att, n_dot_l), REL, what);
    let b = probe(&scene.flat(), 0, 0);
    assert_rel(DVec3::splat(b.lights[0].f_att), DVec3::splat(f_att), REL, &format!("{what}: reported f_att"));
    assert_eq!(b.lights[0].spot, 1.0, "{what}: a point light's S");
}

#[test]
fn inverse_square_without_range_is_one_over_d_squared() {
    for (pos, d, ndl) in PLACEMENTS {
        let scene = point_over_floor(pos, "model = \"inverse_square\"");
        check_f_att(&scene, 1.0 / (d * d), ndl, &format!("inverse square, light at {pos:?}"));
    }
}

#[test]
fn inverse_square_with_range_is_windowed_by_gltf_recommendation() {
    // f_att = clamp(1 − (d/range)⁴, 0, 1) / d²: inside the range, at it, and beyond it.
    for range in [4.0, 6.5, 20.0] {
        for (pos, d, ndl) in PLACEMENTS {
            let scene = point_over_floor(pos, &format!("model = \"inverse_square\", range = {}", num(range)));
            let window = (1.0 - (d / range).powi(4)).clamp(0.0, 1.0);
            check_f_att(&scene, window / (d * d), ndl, &format!("range {range}, light at {pos:?}"));
        }
    }
    // Exactly at the range the light is gone (the spec: ignored beyond it), just inside it is not.
    let at = point_over_floor([0.0, 2.0, 0.0], "model = \"inverse_square\", range = 2.0");
    check_f_att(&at, 0.0, 1.0, "d = range");
    let inside = point_over_floor([0.0, 2.0, 0.0], "model = \"inverse_square\", range = 2.25");
    let window = 1.0 - (2.0_f64 / 2.25).powi(4);
    assert!(window > 0.3, "the window must be well away from 0 here: {window}");
    check_f_att(&inside, window / 4.0, 1.0, "d just inside the range");
}

#[test]
fn inverse_square_is_capped_within_a_thousandth_of_the_light() {
    // d² is bounded below by MIN_ATTENUATION_DENOMINATOR = 1e-6 (d = 1e-3), the bound the
    // polynomial's denominator has: f_att = 1e6 at most, finite at the light itself.
    for height in [5e-4, 1e-5] {
        let scene = point_over_floor([0.0, height, 0.0], "model = \"inverse_square\"");
        let d = w3(scene.flat().lights[0].position).y;
        assert!(d * d < MIN_ATTENUATION_DENOMINATOR);
        check_f_att(&scene, 1.0 / MIN_ATTENUATION_DENOMINATOR, 1.0, &format!("light {height} above the floor"));
    }
    // Just outside the cap the law holds again.
    let scene = point_over_floor([0.0, 2e-3, 0.0], "model = \"inverse_square\"");
    let d = w3(scene.flat().lights[0].position).y;
    check_f_att(&scene, 1.0 / (d * d), 1.0, "light 2e-3 above the floor");
}

/// A smooth spot at (0, 2, 0) over the floor with its axis `deg` off the vertical, so that
/// cos θ = L_N·(−L) = cos(deg); returns the pixel, the stored cos θ and the stored cosines of
/// the (inner, outer) cones.
fn smooth_spot(deg: f64, cones: &str) -> (DVec3, f64, f64, f64) {
    smooth_spot_along(axis_at(deg), cones)
}

/// `smooth_spot` with the axis given.
fn smooth_spot_along(axis: [f64; 3], cones: &str) -> (DVec3, f64, f64, f64) {
    let scene = floor_scene("", 0.125)
        .light(
            "spot",
            &format!(
                "position = [0.0, 2.0, 0.0]\ndirection = {axis:?}\nfalloff = \"smooth\"\n{cones}\ndiffuse = {I_D:?}\nambient = 0.25"
            ),
        )
        .plane([0.0; 3], Y, "floor");
    let flat = scene.flat();
    let l = &flat.lights[0];
    // The angle to the stored axis, normalised (as the tracers take it).
    let cos_axis = -w3(l.direction).normalize().y;
    let b = probe(&flat, 0, 0);
    let got = centre(&scene);
    let s = b.lights[0].spot;
    assert_rel(got, lit_floor(s, 1.0), REL, &format!("axis {axis:?}: the pixel uses the reported S"));
    // The cones are stored as versines 1 − cos.
    (got, cos_axis, 1.0 - f64::from(l.spot_versin_inner), 1.0 - f64::from(l.spot_versin_cutoff))
}

/// glTF's smooth step: t = saturate((cos θ − cos outer) / (cos inner − cos outer)), S = t².
fn gltf_smooth(cos: f64, cos_inner: f64, cos_outer: f64) -> f64 {
    let t = ((cos - cos_outer) / (cos_inner - cos_outer)).clamp(0.0, 1.0);
    t * t
}

#[test]
fn smooth_spot_inside_between_and_outside_its_cones() {
    let cones = "inner_cone = 10.0\nouter_cone = 30.0";
    let (inner, outer) = (10.0_f64.to_radians().cos(), 30.0_f64.to_radians().cos());
    let mut ramp = Vec::new();
    for deg in [0.0, 5.0, 9.9, 10.1, 15.0, 20.0, 25.0, 29.9, 30.1, 45.0, 89.0, 120.0] {
        let (got, cos_axis, cos_inner, cos_outer) = smooth_spot(deg, cones);
        let s = gltf_smooth(cos_axis, cos_inner, cos_outer);
        assert_rel(got, lit_floor(s, 1.0), REL, &format!("{deg}° off axis, stored cosines"));
        let analytic = gltf_smooth(deg.to_radians().cos(), inner, outer);
        assert_rel(got, lit_floor(analytic, 1.0), 1e-5, &format!("{deg}° off axis, exact cosines"));
        if deg < 10.0 {
            assert_eq!(s, 1.0, "{deg}°: inside the inner cone S = 1");
        } else if deg > 30.0 {
            assert_eq!(s, 0.0, "{deg}°: outside the outer cone S = 0");
        } else {
            ramp.push(s);
        }
    }
    // Between the cones S falls strictly, through the middle of the range.
    assert!(ramp.windows(2).all(|w| w[0] > w[1]), "S does not fall across the ramp: {ramp:?}");
    assert!(ramp.iter().any(|&s| (0.2..0.8).contains(&s)), "no S in the middle of the ramp: {ramp:?}");
}

#[test]
fn smooth_spot_defaults_are_gltfs() {
    // Without cones: inner 0°, outer 45° (innerConeAngle 0, outerConeAngle π/4).
    for deg in [0.0, 20.0, 44.0, 46.0] {
        let (got, ..) = smooth_spot(deg, "");
        let s = gltf_smooth(deg.to_radians().cos(), 1.0, 45.0_f64.to_radians().cos());
        assert_rel(got, lit_floor(s, 1.0), 1e-5, &format!("defaults, {deg}° off axis"));
    }
}

#[test]
fn smooth_spot_with_equal_cones_is_a_hard_closed_cone() {
    // inner = outer: the step the ramp tends to, 1 inside the closed cone and 0 outside, and
    // no division by zero.
    for (deg, s) in [(0.0, 1.0), (29.0, 1.0), (31.0, 0.0), (60.0, 0.0)] {
        let (got, ..) = smooth_spot(deg, "inner_cone = 30.0\nouter_cone = 30.0");
        assert_rel(got, lit_floor(s, 1.0), REL, &format!("30° cone, {deg}° off axis"));
    }
    // Exactly on the cone in the stored data: a 0° cone on its axis, and 90° off the axis of a
    // 90° cone (A·(−L) = 0 = cos 90° exactly).
    let (got, cos_axis, ..) = smooth_spot(0.0, "inner_cone = 0.0\nouter_cone = 0.0");
    assert_eq!(cos_axis, 1.0);
    assert_rel(got, lit_floor(1.0, 1.0), REL, "on the axis of a 0° cone");
    let (got, ..) = smooth_spot(0.5, "inner_cone = 0.0\nouter_cone = 0.0");
    assert_rel(got, lit_floor(0.0, 1.0), REL, "0.5° off the axis of a 0° cone");
    let (got, cos_axis, cos_inner, cos_outer) =
        smooth_spot_along([1.0, 0.0, 0.0], "inner_cone = 90.0\nouter_cone = 90.0");
    assert_eq!((cos_axis, cos_inner, cos_outer), (0.0, 0.0, 0.0));
    assert_rel(got, lit_floor(1.0, 1.0), REL, "exactly 90° off the axis of a 90° cone");
}

#[test]
fn smooth_spot_with_inverse_square_multiplies_both() {
    // f_att·S: the spot 2 above the floor, range 4, 20° off a 10°–30° cone.
    let scene = floor_scene("", 0.125)
        .light(
            "spot",
            &format!(
                "position = [0.0, 2.0, 0.0]\ndirection = {:?}\nfalloff = \"smooth\"\ninner_cone = 10.0\nouter_cone = 30.0\n\
                 attenuation = {{ model = \"inverse_square\", range = 4.0 }}\ndiffuse = {I_D:?}\nambient = 0.25",
                axis_at(20.0)
            ),
        )
        .plane([0.0; 3], Y, "floor");
    let flat = scene.flat();
    let l = &flat.lights[0];
    let s = gltf_smooth(
        -w3(l.direction).normalize().y,
        1.0 - f64::from(l.spot_versin_inner),
        1.0 - f64::from(l.spot_versin_cutoff),
    );
    let f_att = (1.0 - 0.5_f64.powi(4)) / 4.0;
    assert_rel(centre(&scene), lit_floor(f_att * s, 1.0), REL, "f_att·S");
    let b = probe(&flat, 0, 0);
    assert_rel(DVec3::new(b.lights[0].f_att, b.lights[0].spot, 0.0), DVec3::new(f_att, s, 0.0), REL, "probe");
}

#[test]
fn a_model_objects_own_lights_shine_when_asked_placed_and_scaled_by_its_exposure() {
    // A colour KHR_lights_punctual allows, each channel in [0, 1] (I_D's 2 is taken as 1).
    const BULB: [f64; 3] = [1.0, 0.5, 0.25];
    use glint_io::{LoadOptions, load_scene_with};
    use glint_test_support::gltf::Fixture;
    use serde_json::json;
    let dir = glint_test_support::TempDir::new("model-object-lights");
    // A quad with a point light 2 units above the model's origin, 100 units to the side.
    let mut f = Fixture::quad();
    f.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    f.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "point", "color": BULB, "intensity": 4.0, "name": "bulb" }
    ] } });
    f.json["scenes"] = json!([{ "nodes": [0, 1] }]);
    f.json["nodes"] = json!([
        { "mesh": 0 },
        { "translation": [-100.0, 2.0, 0.0], "extensions": { "KHR_lights_punctual": { "light": 0 } } }
    ]);
    f.write_glb(&dir, "lamp");
    let scene = |extra: &str| {
        let base = floor_scene("", 0.125).plane([0.0; 3], Y, "floor");
        format!(
            "{}[[objects]]\ntype = \"model\"\npath = \"lamp.glb\"\ntransform = {{ translate = [100.0, 0.0, 0.0] }}\n{extra}\n",
            base.text
        )
    };
    let load = |text: &str| {
        let file = dir.join("lit.toml");
        std::fs::write(&file, text).unwrap();
        load_scene_with(file.to_str().unwrap(), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}")).desc
    };
    // Off by default: the lab scene brings its own lights (here none: ambient only).
    let off = load(&scene(""));
    assert_eq!(glint_core::FlatScene::build(&off, &off.render).lights.len(), 0);
    // On, with an exposure: the light at the placed node, colour × intensity × exposure.
    let on = load(&scene("lights = true\nexposure = 0.25"));
    let flat = glint_core::FlatScene::build(&on, &on.render);
    assert_eq!(flat.lights.len(), 1);
    // Stored relative to the model's mesh, 100 from the world origin (`storage_origin`).
    assert_eq!(w3(flat.lights[0].position) + flat.frame_origin(), DVec3::new(0.0, 2.0, 0.0));
    let lit = crate::support::render(&flat).image.get(0, 0);
    // 1/d² at d = 2 straight above; glTF lights have no ambient term.
    let want = 0.125 * FLOOR_KA * DVec3::ONE + 0.25 * dv(BULB) * dv(FLOOR_KD);
    assert_rel(lit, want, REL, "the model's light on the floor");
    // A bright imported light is named where an overflow error lists the brightest sources.
    let bright = load(&scene("lights = true\nexposure = 1000"));
    let causes = glint_scene::overflow_causes(&bright, 5, glint_scene::Integrator::Whitted, false);
    assert!(causes.contains("the brightest sources: objects[1].lights[0].specular = 4000"), "{causes}");
    // Saved, the reference keeps the choice and the lights stay in the file, not the scene.
    let text = glint_io::to_toml(&on).unwrap();
    assert!(text.contains("lights = true") && text.contains("exposure = 0.25"), "{text}");
    assert!(!text.contains("[[lights]]"), "{text}");
    assert_eq!(load(&text), on);
    // A bad exposure names the field and its range.
    let file = dir.join("bad.toml");
    std::fs::write(&file, scene("lights = true\nexposure = 0.0")).unwrap();
    let err = load_scene_with(file.to_str().unwrap(), &LoadOptions::default()).unwrap_err().to_string();
    assert!(err.contains("objects[1].exposure"), "{err}");
}
