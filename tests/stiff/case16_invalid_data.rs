//! Case 16: invalid data — NaN and infinite vertices, zero-length normals, a zero-length
//! directional light, zero and negative radii (and ones that round to 0 in f32).
//!
//! Expected: each is rejected on load with the offending field named (`objects[0].vertices[1]`,
//! …), and the GPU never receives non-finite data: every scene that passes validation, even with
//! every value at the edge of its allowed range, builds a flat scene whose every float is
//! finite and renders finite on both backends; and a flat scene built by hand around validation
//! (its fields are public) with a NaN in it is refused by the GPU tracer before upload, the
//! field named.

use std::path::Path;
use std::sync::Arc;

use glint_io::parse_scene;

use crate::Y;
use crate::gpu::{gpu_or_skip, render_both};
use crate::scene::SceneText;

fn base() -> SceneText {
    SceneText::new(16, 16, "max_depth = 2", [0.0, 1.0, -4.0], [0.0; 3], Y, 45.0)
        .material("m", "ka = 0.2\nkd = 0.6\nks = 0.2\nkr = 0.2")
        .light("point", "position = [2.0, 3.0, -2.0]")
}

/// Loads `text` and expects it to be rejected with an issue for `field`.
fn rejected(what: &str, text: &str, field: &str) {
    let err = match parse_scene(text, Path::new("invalid.toml")) {
        Ok(_) => panic!("{what}: accepted\n{text}"),
        Err(e) => e,
    };
    assert!(err.issues().iter().any(|i| i.field == field), "{what}: no issue names {field}: {err}");
    let msg = err.to_string();
    assert!(msg.contains("invalid.toml") && msg.contains(field), "{what}: the message must name file and field: {msg}");
}

#[test]
fn invalid_data_is_rejected_with_the_field_named() {
    let tri = |v: [f64; 3]| [[-1.0, 0.0, 0.0], v, [1.0, 0.0, 0.0]];
    for (what, v) in [
        ("NaN vertex", [0.0, f64::NAN, 0.0]),
        ("infinite vertex", [f64::INFINITY, 1.0, 0.0]),
        ("-inf vertex", [0.0, 1.0, f64::NEG_INFINITY]),
    ] {
        // `arr` writes NaN and inf as `NaN`/`inf`, which TOML spells `nan`/`inf`.
        let text = base().triangles(&[tri(v)], None, "m").text.replace("NaN", "nan");
        rejected(what, &text, "objects[0].vertices[1]");
    }
    let up = [0.0, 0.0, -1.0];
    for (what, n) in [
        ("zero normal", [0.0; 3]),
        ("underflowing normal", [1e-300, 0.0, 1e-300]),
        ("NaN normal", [f64::NAN, 0.0, 1.0]),
    ] {
        let text = base().triangles(&[tri([0.0, 1.0, 0.0])], Some(&[up, n, up]), "m").text.replace("NaN", "nan");
        rejected(what, &text, "objects[0].normals[1]");
        let text = base().plane([0.0; 3], n, "m").text.replace("NaN", "nan");
        rejected(what, &text, "objects[0].normal");
    }
    for (what, d) in [
        ("zero directional light", "[0.0, 0.0, 0.0]"),
        ("underflowing directional light", "[1e-200, 1e-200, 0.0]"),
        ("NaN directional light", "[nan, -1.0, 0.0]"),
    ] {
        let text = base().light("directional", &format!("direction = {d}")).sphere([0.0; 3], 1.0, "m").text;
        rejected(what, &text, "lights[1].direction");
    }
    for radius in [0.0, -1.0, -0.0, 1e-50, f64::NAN, f64::INFINITY] {
        let text = base().sphere([0.0; 3], radius, "m").text.replace("NaN", "nan");
        rejected(&format!("radius {radius}"), &text, "objects[0].radius");
    }
}

/// Every float the tracers read from a flat scene, with its name.
fn floats(flat: &glint_core::FlatScene) -> Vec<(String, f32)> {
    let mut v = Vec::new();
    let mut add = |name: String, xs: &[f32]| v.extend(xs.iter().map(|&x| (name.clone(), x)));
    let h = &flat.header;
    add("header".into(), &[h.epsilon, h.bailout]);
    add("header.ambient".into(), &h.ambient);
    add("header.background".into(), &h.background);
    let c = &flat.camera;
    add("camera".into(), &[c.anchor, c.forward, c.right, c.up].concat());
    for (i, m) in flat.materials.iter().enumerate() {
        add(format!("materials[{i}]"), &[m.ka, m.kd, m.ks, m.kr, m.kt, m.emission].concat());
        add(format!("materials[{i}]"), &[m.shininess, m.ior]);
    }
    for (i, t) in flat.textures.iter().enumerate() {
        add(format!("textures[{i}]"), &[t.transform_u, t.transform_v].concat());
    }
    for (i, t) in flat.texels.iter().enumerate() {
        add(format!("texels[{i}]"), t);
    }
    for (i, l) in flat.lights.iter().enumerate() {
        add(
            format!("lights[{i}]"),
            &[l.position, l.direction, l.diffuse, l.specular, l.ambient, l.attenuation].concat(),
        );
        add(format!("lights[{i}]"), &[l.spot_exponent, l.spot_versin_cutoff, l.range, l.spot_versin_inner]);
    }
    for (i, s) in flat.spheres.iter().enumerate() {
        add(format!("spheres[{i}]"), &s.center_radius);
    }
    for (i, p) in flat.planes.iter().enumerate() {
        add(format!("planes[{i}]"), &p.normal_offset);
    }
    for (i, p) in flat.vertices.iter().enumerate() {
        add(format!("vertices[{i}]"), p);
    }
    for (i, n) in flat.normals.iter().enumerate() {
        add(format!("normals[{i}]"), n);
    }
    v
}

#[test]
fn scenes_at_the_edge_of_validation_stay_finite_on_both_backends() {
    // Every value at (or next to) the end of its allowed range that a scene may combine.
    let big = 1e9;
    let text = SceneText::new(16, 12, "max_depth = 3\nepsilon = 1000.0\nbailout = 1.0", [0.0, 1.0, -big], [0.0; 3], Y, 179.0)
        .world([big; 3], [big; 3])
        .material("m", "ka = 1e9\nkd = 1e9\nks = 1e9\nshininess = 1e6\nkr = 0.5\nkt = 0.5\nior = 1000.0\nemission = 1e9")
        .material("tiny", "ka = 1e-30\nkd = 1e-30\nshininess = 0.0\nior = 1e-30\nchecker = { kd = 1e-30, size = 1e-9 }")
        .light("point", "position = [1e9, 1e9, -1e9]\ndiffuse = 1e9\nspecular = 1e9\nambient = 1e9\nattenuation = { c = 2e-6 }")
        .light("directional", "direction = [1e-12, -1e-12, 1e-12]\ndiffuse = 1e9")
        .light("spot", "position = [0.0, 2.0, 0.0]\ndirection = [1e9, -1e9, 0.0]\ncutoff = 90.0\nexponent = 1e6\nattenuation = { c = 2e-6, l = 1e9, q = 1e9 }")
        .sphere([big, -big, big], big, "m")
        .sphere([0.0, 1.0, 0.0], 1e-30, "tiny")
        .plane([0.0, -big, 0.0], [1e-12, 1.0, 1e9], "tiny")
        .triangles(&[[[-big, 0.0, big], [big, 0.0, big], [0.0, big, big]]], Some(&[[1e-12, 0.0, -1e-12], [0.0, 1e9, -1e9], [0.0, 0.0, -1.0]]), "m");
    let flat = text.flat();
    for (name, x) in floats(&flat) {
        assert!(x.is_finite(), "{name} holds {x}: validation let a non-finite value into the flat scene");
    }
    // render_both fails on any NaN or infinite pixel of either backend.
    let both = render_both("stiff/case16", "edge-of-validation", &flat);
    assert!(both.cpu.image.pixels.iter().any(|p| p.max_element() > 0.0));
}

#[test]
fn the_gpu_tracer_refuses_a_non_finite_flat_scene() {
    let tracer = gpu_or_skip!();
    let good = base().sphere([0.0; 3], 1.0, "m").flat();
    let mut bad = good.clone();
    Arc::make_mut(&mut bad.spheres)[0].center_radius[1] = f32::NAN;
    match tracer.render(&bad, &glint_gpu::GpuOptions::default()) {
        Err(glint_gpu::GpuError::NonFinite { field }) => assert!(field.contains("spheres[0]"), "{field}"),
        other => panic!("a NaN sphere centre reached the GPU: {:?}", other.map(|r| r.status)),
    }
    let mut bad = good.clone();
    bad.lights[0].diffuse[2] = f32::INFINITY;
    assert!(matches!(
        tracer.render(&bad, &glint_gpu::GpuOptions::default()),
        Err(glint_gpu::GpuError::NonFinite { .. })
    ));
    assert_eq!(good.first_non_finite(), None);
    // A stored tag no kind has is refused by both tracers, never traced as another kind.
    let mut bad = good.clone();
    bad.lights[0].kind = 7;
    match tracer.render(&bad, &glint_gpu::GpuOptions::default()) {
        Err(e @ glint_gpu::GpuError::InvalidScene(_)) => {
            assert_eq!(e.to_string(), "invalid flat scene: 7 is not a valid light kind");
        }
        other => panic!("a light of kind 7 reached the GPU: {:?}", other.map(|r| r.status)),
    }
    let cpu = glint_core::render_cpu(&bad, &glint_core::CpuOptions::default(), glint_core::RenderControl::default());
    assert!(matches!(cpu, Err(glint_core::render::CpuRenderError::InvalidScene(_))), "{cpu:?}");
    // So are the tags the GPU had no error for (it traced an unknown integrator as Whitted's,
    // specular model as Blinn's, Fresnel as the exact one) and an object's material index
    // beyond the list (the CPU panicked, the GPU read a clamped one).
    type Edit = fn(&mut glint_core::FlatScene);
    let edits: [(&str, Edit); 4] = [
        ("7 is not a valid integrator", |s| s.header.integrator = 7),
        ("7 is not a valid specular model", |s| s.materials[0].specular_model = 7),
        ("7 is not a valid Fresnel factor", |s| s.materials[0].fresnel = 7),
        ("7 is not a valid sphere material index", |s| Arc::make_mut(&mut s.spheres)[0].material = 7),
    ];
    for (said, edit) in edits {
        let mut bad = good.clone();
        edit(&mut bad);
        match tracer.render(&bad, &glint_gpu::GpuOptions::default()) {
            Err(e @ glint_gpu::GpuError::InvalidScene(_)) => assert!(e.to_string().contains(said), "{e}"),
            other => panic!("{said}: reached the GPU: {:?}", other.map(|r| r.status)),
        }
        let cpu =
            glint_core::render_cpu(&bad, &glint_core::CpuOptions::default(), glint_core::RenderControl::default());
        assert!(matches!(cpu, Err(glint_core::render::CpuRenderError::InvalidScene(_))), "{said}: {cpu:?}");
    }
    // The valid scene renders, and its read-back is scanned for NaN and infinities.
    crate::gpu::gpu_render(tracer, &good, true);
}
