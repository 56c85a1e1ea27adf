//! The Materials panel shows, for a material a model file brought in, what the file said
//! (glTF factors, MTL statements) beside the seed's coefficients they were mapped to; and it
//! edits the specular model with each model's parameters.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_scene::{Fresnel, SpecularModel};
use glint_test_support::gltf::{BufferAt, Fixture};
use glint_viewer::ViewerApp;
use serde_json::json;

use crate::edits::assert_current_agreement;
use crate::support::{choose, gpu_image, mean_abs_diff, settle, temp_dir, viewer};

/// Every one of `labels` is shown.
fn assert_shown(h: &Harness<'static, ViewerApp>, labels: &[&str]) {
    for l in labels {
        assert!(h.query_all_by_label(l).count() > 0, "{l:?} is not shown");
    }
}

#[test]
fn an_mtl_material_shows_its_statements_beside_the_mapped_coefficients() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    choose(&mut h, "Materials", "Material", "mirror");
    assert!(h.query_by_label("Mapped on import").is_none(), "a scene's own material has no source");

    let dir = temp_dir("mtl-source");
    std::fs::write(
        dir.join("m.mtl"),
        "newmtl glass\nKd 0.1 0.1 0.1\nKs 0.9 0.9 0.9\nNs 80\nNi 1.33\nd 0.25\nillum 4\n",
    )
    .unwrap();
    let path = dir.join("model.obj");
    std::fs::write(&path, "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl glass\nf 1 2 3\n").unwrap();
    h.state_mut().open(&path.display().to_string());
    choose(&mut h, "Materials", "Material", "model/glass");
    assert_shown(&h, &["MTL in model.obj", "Kd = 0.1 0.1 0.1", "Ks = 0.9 0.9 0.9", "Ns = 80", "Ni = 1.33"]);
    assert_shown(&h, &["d = 0.25", "illum = 4", "Mapped on import"]);
    // illum 4: k_r = Ks, k_t = 1 − d.
    assert_shown(&h, &["k_r = 0.9 0.9 0.9", "k_t = 0.75 0.75 0.75", "ior = 1.33", "n = 80"]);
    assert!(h.query_by_label("Ka = 0.1 0.1 0.1").is_none(), "a statement the file lacks is not made up");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_gltf_material_shows_its_factors_beside_the_mapped_coefficients() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("gltf-source");
    let mut fixture = Fixture::quad();
    fixture.json["extensionsUsed"] = json!(["KHR_materials_ior", "KHR_materials_transmission"]);
    fixture.json["materials"][0] = json!({
        "name": "glassy",
        "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.5, 0.25, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.05 },
        "extensions": { "KHR_materials_ior": { "ior": 1.7 }, "KHR_materials_transmission": { "transmissionFactor": 0.5 } }
    });
    let path = fixture.write_gltf(&dir, "model", BufferAt::DataUri);
    h.state_mut().open(&path.display().to_string());
    assert!(h.state().message.is_none(), "{:?}", h.state().message);
    choose(&mut h, "Materials", "Material", "model/glassy");
    assert_shown(&h, &["glTF in model.gltf", "baseColorFactor = 1 0.5 0.25 1", "metallicFactor = 0"]);
    assert_shown(&h, &["roughnessFactor = 0.05", "transmissionFactor = 0.5"]);
    // Transmission takes half the diffuse part, and the diffuse keeps 1 − F0 (glTF's Fresnel
    // mix): k_d = 0.5·base·0.96; a dielectric's F0 is 0.04, mirrored when smooth, and not
    // transmitted: k_t = 0.5·base·0.96.
    assert_shown(&h, &["k_d = 0.48 0.24 0.12", "k_t = 0.48 0.24 0.12", "k_r = 0.04 0.04 0.04"]);
    assert_eq!(h.query_all_by_label("ior = 1.7").count(), 2, "the file's ior and the mapped one");
    // Computed values to 7 digits (n was 319997.9999999999).
    assert_shown(&h, &["n = 319998"]);
    let _ = std::fs::remove_dir_all(dir);
}

/// The mirror sphere's highlight under Cook–Torrance: the model, its roughness and its Fresnel
/// factor set through the panel reach the document and the GPU image, which still agrees with
/// the CPU reference; Blinn's shininess makes way for m and F.
#[test]
fn cook_torrance_with_its_roughness_and_fresnel_is_set_in_the_materials_panel() {
    let Some(mut h) = viewer("whitted", (1000.0, 900.0)) else { return };
    let blinn = gpu_image(&h);
    choose(&mut h, "Materials", "Material", "mirror");
    assert!(h.query_by_label("Roughness m").is_none(), "no m under Blinn");
    choose(&mut h, "Materials", "Specular model", "Cook–Torrance F·D·G/(N·V)");
    settle(&mut h);
    let m = &h.state().doc.desc.materials["mirror"];
    assert_eq!((m.specular_model, m.roughness, m.fresnel), (SpecularModel::CookTorrance, 0.25, Fresnel::Exact));
    assert!(h.query_by_label("Shininess n").is_none(), "Blinn's n is not Cook–Torrance's");
    let ct = gpu_image(&h);
    assert!(mean_abs_diff(&blinn, &ct) > 1e-6, "Cook–Torrance must change the mirror's highlight");
    assert_current_agreement(&h);

    h.get_by_role_and_label(Role::Slider, "Roughness m").set_value_accesskit(0.05);
    settle(&mut h);
    assert!((h.state().doc.desc.materials["mirror"].roughness - 0.05).abs() < 1e-12);
    let sharp = gpu_image(&h);
    assert!(mean_abs_diff(&ct, &sharp) > 1e-6, "a smaller m must narrow the highlight");
    assert_current_agreement(&h);

    choose(&mut h, "Materials", "Fresnel", "Schlick (from the ior)");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.materials["mirror"].fresnel, Fresnel::Schlick);
    assert!(mean_abs_diff(&sharp, &gpu_image(&h)) > 0.0, "Schlick's F must change the image");
    assert_current_agreement(&h);
    assert!(h.state().doc.issues.is_empty(), "{:?}", h.state().doc.issues);
}
