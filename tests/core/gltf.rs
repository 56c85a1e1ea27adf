//! glTF import on fixtures written by the test (glint_test_support::gltf): materials, lights,
//! hierarchy, skins and morphs, primitive modes, textures, and models placed by scene files.
//! Cameras are `gltf_cameras.rs`'s; files refused, each an error naming the file and the JSON
//! path or URI and never a panic, `gltf_refused.rs`'s.

use std::path::Path;

use glint_io::ImportOptions;
use glint_io::model::load_gltf;
use glint_io::{LoadOptions, load_scene_with};
use glint_scene::Model;
use glint_scene::{LightKind, Rgb};
use glint_test_support::TempDir;
use glint_test_support::gltf::{BufferAt, Fixture};
use serde_json::json;

pub(crate) fn load(path: &Path) -> Model {
    load_gltf(path, &ImportOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

pub(crate) fn error(path: &Path) -> String {
    load_gltf(path, &ImportOptions::default()).expect_err("the file must be refused").to_string()
}

pub(crate) fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn a_quad_loads_from_a_data_uri_a_file_and_a_glb_alike() {
    let dir = TempDir::new("gltf-quad");
    let f = Fixture::quad();
    let models = [
        load(&f.write_gltf(&dir, "embedded", BufferAt::DataUri)),
        load(&f.write_gltf(&dir, "external", BufferAt::File("quad.bin".into()))),
        load(&f.write_glb(&dir, "binary")),
    ];
    for m in &models {
        assert_eq!(m.meshes.len(), 1);
        assert_eq!(m.meshes[0].vertices, models[0].meshes[0].vertices);
        assert_eq!(m.meshes[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.meshes[0].normals.as_ref().map(Vec::len), Some(4));
        assert!(m.lights.is_empty() && m.cameras.is_empty());
    }
}

/// A load keeps validation's warnings apart from the importer's, so the viewer does not
/// validate the scene a second time to tell them apart (it doubled a huge model's load).
#[test]
fn a_load_keeps_validations_warnings_apart_from_the_importers() {
    let dir = TempDir::new("gltf-warning-parts");
    let path = Fixture::quad().write_gltf(&dir, "q", BufferAt::DataUri);
    let loaded = glint_io::load_scene(&path).expect("the quad opens");
    assert_eq!(loaded.scene_warnings, glint_scene::validate(&loaded.desc).warnings);
    assert!(loaded.warnings.ends_with(&loaded.scene_warnings), "{:?}", loaded.warnings);
    // The default rig's note is the importer's: in `warnings`, not in `scene_warnings`.
    let rig = |w: &glint_scene::FieldIssue| w.field == "lights" && w.problem.starts_with("the model has none");
    assert!(loaded.warnings.iter().any(rig) && !loaded.scene_warnings.iter().any(rig), "{:?}", loaded.warnings);
    // A scene file's own warning is validation's; a built-in scene's are all validation's.
    let file = dir.join("warned.toml");
    let text = "[camera]\nposition = [0.0, 0.0, -3.0]\nlook_at = [0.0, 0.0, 0.0]\n[materials.m]\nkd = 255.0\n\
        [[objects]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"m\"\n";
    std::fs::write(&file, text).expect("scene");
    let loaded = glint_io::load_scene(&file).expect("loads");
    assert!(loaded.scene_warnings.len() == 1 && loaded.warnings == loaded.scene_warnings, "{:?}", loaded.warnings);
    let whitted = glint_io::load_scene("whitted").expect("built-in");
    assert_eq!(whitted.scene_warnings, whitted.warnings);
}

#[test]
fn metallic_roughness_transmission_ior_and_emissive_strength_map_as_documented() {
    let dir = TempDir::new("gltf-materials");
    let mut f = Fixture::quad();
    f.json["extensionsUsed"] =
        json!(["KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_emissive_strength"]);
    f.json["materials"] = json!([{
        "name": "glassy gold",
        "pbrMetallicRoughness": { "baseColorFactor": [1.0, 0.5, 0.25, 1.0], "metallicFactor": 0.5, "roughnessFactor": 0.25 },
        "emissiveFactor": [0.5, 0.25, 0.0],
        "extensions": {
            "KHR_materials_transmission": { "transmissionFactor": 0.5 },
            "KHR_materials_ior": { "ior": 1.33 },
            "KHR_materials_emissive_strength": { "emissiveStrength": 4.0 }
        }
    }]);
    let m = load(&f.write_gltf(&dir, "m", BufferAt::DataUri));
    let mat = &m.materials["glassy gold"];
    // k_d = base·(1 − metallic)·(1 − transmission)·(1 − F0), F0 = 0.04 (the dielectric lobe's
    // diffuse keeps 1 − F0; it was base·(1 − metallic)·(1 − transmission), and a white plastic
    // summed to 1.04 with its k_s); k_t = base·(1 − metallic)·transmission.
    for (k, v) in [0.25, 0.125, 0.0625].into_iter().enumerate() {
        assert!(close(mat.kd.0[k], v * 0.96), "{:?}", mat.kd);
    }
    // A white rough plastic returns at most the light it receives under paths (it summed to
    // k_d + k_s = 1.04, and the path tracer warned of gain on every such import).
    f.json["extensionsUsed"] = json!([]);
    f.json["materials"] = json!([{
        "name": "white plastic",
        "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5 }
    }]);
    let plastic = &load(&f.write_gltf(&dir, "plastic", BufferAt::DataUri)).materials["white plastic"];
    let gain = plastic.gain(glint_scene::Integrator::Path);
    assert!(gain <= 1.0 + 1e-12, "k_d {:?} + k_s {:?}: gain {gain}", plastic.kd, plastic.ks);
    // Specular-glossiness keeps 1 − max(specular) for the diffuse, as its extension says (it
    // kept all: a white diffuse with specular 0.2 summed to 1.2); KHR_materials_specular's
    // coloured F0 takes its largest channel, so the diffuse keeps its hue.
    f.json["extensionsUsed"] = json!(["KHR_materials_pbrSpecularGlossiness", "KHR_materials_specular"]);
    f.json["materials"] = json!([
        { "name": "sg", "extensions": { "KHR_materials_pbrSpecularGlossiness": {
            "diffuseFactor": [1.0, 1.0, 1.0, 1.0], "specularFactor": [0.2, 0.1, 0.1], "glossinessFactor": 0.5 } } },
        { "name": "tinted", "pbrMetallicRoughness": { "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5 },
          "extensions": { "KHR_materials_specular": { "specularColorFactor": [10.0, 1.0, 1.0] } } }
    ]);
    let m = load(&f.write_gltf(&dir, "sg", BufferAt::DataUri));
    let sg = &m.materials["sg"];
    assert!(sg.kd.0.iter().all(|&d| close(d, 0.8)), "k_d = diffuse·(1 − max(specular)): {:?}", sg.kd);
    assert!(sg.gain(glint_scene::Integrator::Path) <= 1.0 + 1e-12, "{:?} {:?}", sg.kd, sg.ks);
    let tinted = &m.materials["tinted"];
    assert!(
        tinted.kd.0.iter().all(|&d| close(d, 0.6)),
        "k_d = base·(1 − max(F0)) = 0.6 in every channel: {:?}",
        tinted.kd
    );
    assert_eq!(mat.kt, Rgb([0.25, 0.125, 0.0625]));
    assert_eq!(mat.ka, mat.kd, "k_a = k_d");
    // k_s = lerp(0.04, base, metallic).
    for (k, base) in [1.0, 0.5, 0.25].into_iter().enumerate() {
        assert!(close(mat.ks.0[k], 0.04 + (base - 0.04) * 0.5), "{:?}", mat.ks);
    }
    // α = 0.25² = 0.0625: n = 2/α² − 2 = 510.
    assert!(close(mat.shininess, 510.0), "{}", mat.shininess);
    assert_eq!(mat.kr, Rgb::splat(0.0), "roughness 0.25 is above the mirror threshold");
    assert_eq!(mat.ior, 1.33);
    assert_eq!(mat.emission, Rgb([2.0, 1.0, 0.0]));
    // A smooth metal mirrors its specular colour.
    f.json["materials"] = json!([{ "name": "chrome", "pbrMetallicRoughness": {
        "baseColorFactor": [0.75, 0.75, 0.75, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.0 } }]);
    let chrome = &load(&f.write_gltf(&dir, "chrome", BufferAt::DataUri)).materials["chrome"];
    assert_eq!((chrome.kd, chrome.ks, chrome.kr), (Rgb::splat(0.0), Rgb::splat(0.75), Rgb::splat(0.75)));
    assert_eq!(chrome.shininess, glint_scene::MAX_SHININESS);
    // A smooth glass: what it mirrors (F0 = 0.04) it does not transmit, so k_r + k_t = 1, not
    // the 1.04 validation warned of as energy gain.
    f.json["extensionsUsed"] = json!(["KHR_materials_transmission"]);
    f.json["materials"] = json!([{ "name": "glass", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0 },
        "extensions": { "KHR_materials_transmission": { "transmissionFactor": 1.0 } } }]);
    let model = load(&f.write_gltf(&dir, "glass", BufferAt::DataUri));
    let glass = &model.materials["glass"];
    assert_eq!((glass.kd, glass.kr), (Rgb::splat(0.0), Rgb::splat(0.04)));
    assert!(glass.kt.0.iter().all(|&t| close(t, 0.96)), "{:?}", glass.kt);
    // Factors glTF bounds to [0, 1] are clamped with a warning naming the glTF field (the
    // coefficients they map to were refused under Glint's names: `materials.….ks`).
    f.json["materials"] = json!([{ "name": "odd", "pbrMetallicRoughness": {
        "baseColorFactor": [-1.0, 2.0, 0.5, 1.0], "metallicFactor": 2.0, "roughnessFactor": -1.0 } }]);
    let model = load(&f.write_gltf(&dir, "odd", BufferAt::DataUri));
    let odd = &model.materials["odd"];
    assert_eq!((odd.ks, odd.kd, odd.shininess), (Rgb([0.0, 1.0, 0.5]), Rgb::splat(0.0), glint_scene::MAX_SHININESS));
    for named in ["baseColorFactor.r = -1", "baseColorFactor.g = 2", "metallicFactor = 2", "roughnessFactor = -1"] {
        assert!(
            model.warnings.iter().any(|w| w.problem.starts_with(named) && w.problem.contains("[0, 1]")),
            "{named}: {:?}",
            model.warnings
        );
    }
}

#[test]
fn punctual_lights_sit_at_their_nodes_and_scale_with_the_exposure() {
    let dir = TempDir::new("gltf-lights");
    let mut f = Fixture::quad();
    f.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    f.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "type": "point", "color": [1.0, 0.5, 0.25], "intensity": 8.0, "name": "bulb" },
        { "type": "spot", "intensity": 2.0, "spot": { "innerConeAngle": 0.2, "outerConeAngle": 0.6 } },
        { "type": "directional", "intensity": 3.0 }
    ] } });
    // A parent translated by (0, 2, 0) with the point light 1 unit up; the spot and the sun
    // rotated −90° about x, so their −Z points down −Y.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    f.json["scenes"] = json!([{ "nodes": [0, 1] }]);
    f.json["nodes"] = json!([
        { "mesh": 0 },
        { "translation": [0.0, 2.0, 0.0], "children": [2, 3, 4] },
        { "translation": [0.0, 1.0, 0.0], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
        { "rotation": [-h, 0.0, 0.0, h], "extensions": { "KHR_lights_punctual": { "light": 1 } } },
        { "rotation": [-h, 0.0, 0.0, h], "extensions": { "KHR_lights_punctual": { "light": 2 } } }
    ]);
    let path = f.write_gltf(&dir, "lights", BufferAt::DataUri);
    let m = load_gltf(&path, &ImportOptions { exposure: 0.5, ..ImportOptions::default() }).unwrap();
    assert_eq!(m.lights.len(), 3);
    let (point, spot, sun) = (&m.lights[0], &m.lights[1], &m.lights[2]);
    assert_eq!((point.kind, point.name.as_str()), (LightKind::Point, "bulb"));
    assert_eq!(point.position, Some([0.0, 3.0, 0.0]));
    assert_eq!(point.diffuse, Rgb([4.0, 2.0, 1.0]), "colour × intensity × exposure");
    assert_eq!(point.specular, point.diffuse);
    assert_eq!(spot.kind, LightKind::Spot);
    let d = spot.direction.unwrap();
    assert!(close(d[0], 0.0) && close(d[1], -1.0) && d[2].abs() < 1e-12, "{d:?}");
    assert_eq!(sun.kind, LightKind::Directional);
    assert_eq!(sun.diffuse, Rgb::splat(1.5));
    assert!(sun.position.is_none());
}

#[test]
fn the_hierarchy_composes_in_f64_and_a_mirror_keeps_faces_outward() {
    let dir = TempDir::new("gltf-hierarchy");
    let mut f = Fixture::quad();
    f.json["scenes"] = json!([{ "nodes": [0] }]);
    f.json["nodes"] = json!([
        { "scale": [2.0, 2.0, 2.0], "children": [1] },
        { "translation": [1.0, 0.0, 0.0], "children": [2] },
        { "matrix": [-1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0], "mesh": 0 }
    ]);
    let m = load(&f.write_gltf(&dir, "h", BufferAt::DataUri));
    let mesh = &m.meshes[0];
    // x → −x, then +1, then ×2: vertex (1, 0, 0) lands at (0, 0, 0), (0, 1, 0) at (2, 2, 0).
    assert_eq!(mesh.vertices[1], [0.0, 0.0, 0.0]);
    assert_eq!(mesh.vertices[3], [2.0, 2.0, 0.0]);
    // The mirrored quad still faces +z: its triangles' geometric normal agrees with the normals.
    let [a, b, c] = mesh.triangles[0].map(|i| mesh.vertices[i as usize]);
    let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
    assert!(u[0] * v[1] - u[1] * v[0] > 0.0, "winding restored: {:?}", mesh.triangles);
    assert_eq!(mesh.normals.as_ref().unwrap()[0], [0.0, 0.0, 1.0], "the normal still points +z, unit length");
    assert!(m.warnings.iter().all(|w| !w.field.ends_with(".matrix")), "{:?}", m.warnings);
    // A projective matrix (its last row not 0, 0, 0, 1), which glTF does not allow, is read
    // without that row, and said to be (it was read silently).
    f.json["nodes"][2]["matrix"] =
        json!([1.0, 0.0, 0.0, 0.5, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
    let m = load(&f.write_gltf(&dir, "p", BufferAt::DataUri));
    assert!(
        m.warnings
            .iter()
            .any(|w| w.field == "nodes[2].matrix" && w.problem.starts_with("its last row is [0.5, 0.0, 0.0, 1.0]")),
        "{:?}",
        m.warnings
    );
}

/// Morph targets blend by the node's weights, else the mesh's (glTF 2.0 §3.7.2.2); without
/// weights, or at zero, the base shape stands.
#[test]
fn morph_targets_take_the_node_weights_else_the_meshes() {
    let dir = TempDir::new("gltf-morph");
    let mut f = Fixture::quad();
    // Target 0 lifts every vertex by 1 along z and tilts the normals to +x; target 1 moves x.
    let lift = f.push_f32(&[0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1.]);
    let tilt = f.push_f32(&[1., 0., -1., 1., 0., -1., 1., 0., -1., 1., 0., -1.]);
    let slide = f.push_f32(&[1., 0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0.]);
    let accessors = f.json["accessors"].as_array_mut().unwrap();
    for view in [lift, tilt, slide] {
        accessors.push(json!({ "bufferView": view, "componentType": 5126, "count": 4, "type": "VEC3",
                               "min": [0.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0] }));
    }
    f.json["meshes"][0]["primitives"][0]["targets"] = json!([{ "POSITION": 3, "NORMAL": 4 }, { "POSITION": 5 }]);
    f.json["meshes"][0]["weights"] = json!([0.5, 0.0]);
    let m = load(&f.write_gltf(&dir, "mesh-weights", BufferAt::DataUri));
    assert_eq!(m.meshes[0].vertices[2], [1.0, 1.0, 0.5], "lifted by half");
    let n = m.meshes[0].normals.as_ref().unwrap()[0];
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!(close(n[0], h) && close(n[2], h), "(0, 0, 1) + ½(1, 0, −1), normalised: {n:?}");
    f.json["nodes"][0]["weights"] = json!([0.25, 2.0]);
    let m = load(&f.write_gltf(&dir, "node-weights", BufferAt::DataUri));
    assert_eq!(m.meshes[0].vertices[2], [3.0, 1.0, 0.25], "the node's weights win");
    f.json["nodes"][0]["weights"] = json!([0.0, 0.0]);
    assert_eq!(load(&f.write_gltf(&dir, "zero", BufferAt::DataUri)).meshes[0].vertices[2], [1.0, 1.0, 0.0]);
}

/// A skin is posed by its joints' node transforms times their inverse bind matrices, blended by
/// each vertex's weights; the skinned node's own transform is ignored (glTF 2.0 §3.7.3.3).
#[test]
fn a_skin_is_posed_by_its_joints_and_ignores_its_nodes_transform() {
    let dir = TempDir::new("gltf-skin");
    let mut f = Fixture::quad();
    // Vertex 0 follows joint 0 (its weight 0.5 alone, normalised to 1), vertex 1 joint 1 (no
    // weight: its first joint), vertex 2 joint 1, vertex 3 half of each.
    let joints = f.push_u16(&[0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0]);
    let weights = f.push_f32(&[0.5, 0., 0., 0., 0., 0., 0., 0., 1., 0., 0., 0., 0.5, 0.5, 0., 0.]);
    // Joint 1's inverse bind matrix undoes a bind pose 1 along x.
    let ibm = f.push_f32(&[
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., //
        1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., 0., -1., 0., 0., 1.,
    ]);
    let accessors = f.json["accessors"].as_array_mut().unwrap();
    accessors.push(json!({ "bufferView": joints, "componentType": 5123, "count": 4, "type": "VEC4" }));
    accessors.push(json!({ "bufferView": weights, "componentType": 5126, "count": 4, "type": "VEC4" }));
    accessors.push(json!({ "bufferView": ibm, "componentType": 5126, "count": 2, "type": "MAT4" }));
    f.json["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = json!(3);
    f.json["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = json!(4);
    f.json["skins"] = json!([{ "joints": [1, 2], "inverseBindMatrices": 5 }]);
    f.json["scenes"] = json!([{ "nodes": [0, 1] }]);
    f.json["nodes"] = json!([
        { "mesh": 0, "skin": 0, "translation": [5.0, 5.0, 5.0] },
        { "translation": [0.0, 0.0, 1.0], "children": [2] },
        { "translation": [1.0, 0.0, 2.0] }
    ]);
    let m = load(&f.write_gltf(&dir, "skin", BufferAt::DataUri));
    let v = &m.meshes[0].vertices;
    // Joint 0 at z = 1; joint 1 at (1, 0, 3) in the world, bound at x = 1: x + 0, z + 3.
    assert_eq!(v[0], [0.0, 0.0, 1.0], "joint 0, not the node's (5, 5, 5)");
    assert_eq!(v[1], [1.0, 0.0, 3.0], "no weight: its first joint, 1");
    assert_eq!(v[2], [1.0, 1.0, 3.0], "joint 1");
    assert_eq!(v[3], [0.0, 1.0, 2.0], "half of each");
    // A joint outside the rendered scene cannot pose it.
    f.json["scenes"] = json!([{ "nodes": [0] }]);
    let message = error(&f.write_gltf(&dir, "outside", BufferAt::DataUri));
    assert!(message.contains("skins[0].joints[0]") && message.contains("not in the rendered scene"), "{message}");
}

/// KHR_mesh_quantization (what gltfpack writes): positions as normalised shorts with the
/// dequantisation in the node's scale, normals as normalised bytes, texture coordinates as
/// unnormalised shorts, all 4-byte aligned. The file requires the extension.
#[test]
fn quantised_attributes_are_read_where_the_file_requires_mesh_quantization() {
    let dir = TempDir::new("gltf-quantized");
    let mut f = Fixture::quad();
    let positions = f.push_u16(&[0, 0, 0, 0, 32767, 0, 0, 0, 32767, 32767, 0, 0, 0, 32767, 0, 0]);
    // Bytes (0, 0, 127, pad) a vertex: +z.
    let normals = f.push_u16(&[0, 127, 0, 127, 0, 127, 0, 127]);
    let uvs = f.push_u16(&[0, 0, 2, 0, 2, 2, 0, 2]);
    for (view, stride) in [(positions, 8), (normals, 4)] {
        f.json["bufferViews"][view]["byteStride"] = json!(stride);
    }
    f.json["accessors"] = json!([
        { "bufferView": positions, "componentType": 5122, "normalized": true, "count": 4, "type": "VEC3",
          "min": [0, 0, 0], "max": [32767, 32767, 0] },
        { "bufferView": normals, "componentType": 5120, "normalized": true, "count": 4, "type": "VEC3" },
        f.json["accessors"][2].clone(),
        { "bufferView": uvs, "componentType": 5123, "count": 4, "type": "VEC2" }
    ]);
    f.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(3);
    f.json["nodes"][0]["scale"] = json!([3.0, 3.0, 3.0]);
    f.json["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
    f.json["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
    f.json["images"] = json!([{ "uri": "tex.png" }]);
    f.json["textures"] = json!([{ "source": 0 }]);
    f.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    glint_test_support::texture::write_png(&dir.join("tex.png"), 1, 1, &[255, 255, 255, 255]);
    let m = load(&f.write_glb(&dir, "quantized"));
    let mesh = &m.meshes[0];
    assert_eq!(mesh.vertices[2], [3.0, 3.0, 0.0], "32767 normalised is 1, scaled by the node");
    assert_eq!(mesh.normals.as_ref().unwrap()[1], [0.0, 0.0, 1.0]);
    assert_eq!(mesh.uvs.as_ref().unwrap()[2], [2.0, 2.0], "unnormalised shorts are their values");
    assert!(m.warnings.iter().all(|w| !w.field.starts_with("extensions")), "{:?}", m.warnings);
    assert!(m.warnings.iter().all(|w| !w.problem.contains("KHR_mesh_quantization")), "{:?}", m.warnings);
    // The same file without the extension listed: read alike, with a warning per attribute.
    f.json.as_object_mut().expect("JSON").remove("extensionsUsed");
    f.json.as_object_mut().expect("JSON").remove("extensionsRequired");
    let m = load(&f.write_glb(&dir, "undeclared"));
    assert_eq!(m.meshes[0].vertices[2], [3.0, 3.0, 0.0]);
    let warned: Vec<&str> = m
        .warnings
        .iter()
        .filter(|w| w.problem.contains("KHR_mesh_quantization"))
        .map(|w| w.field.rsplit('.').next().unwrap_or(""))
        .collect();
    assert_eq!(warned, ["POSITION", "NORMAL"], "{:?}", m.warnings);
}

#[test]
fn colour_0_becomes_vertex_colours_from_floats_bytes_and_shorts_its_alpha_left_out() {
    let dir = TempDir::new("gltf-vertex-colours");
    let mut f = Fixture::quad();
    let floats = f.push_f32(&[1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 0.25, 2.0, 2.0, 2.0]);
    // Normalised bytes (r, g, b, a) a vertex, two to a u16, little-endian.
    let bytes = f.push_u16(&[255, 255 << 8, 255 << 8, 255 << 8, 51 | (102 << 8), 255 << 8, 0, 0]);
    let shorts = f.push_u16(&[65535, 0, 0, 65535, 0, 65535, 0, 0, 0, 0, 65535, 0, 32768, 32768, 32768, 65535]);
    let wanted: [(usize, u32, &str, [[f64; 3]; 4]); 3] = [
        (floats, 5126, "VEC3", [[1.0, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.25], [2.0, 2.0, 2.0]]),
        (bytes, 5121, "VEC4", [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.2, 0.4, 0.0], [0.0, 0.0, 0.0]]),
        (shorts, 5123, "VEC4", [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [32768.0 / 65535.0; 3]]),
    ];
    for (k, (view, component_type, kind, expected)) in wanted.into_iter().enumerate() {
        let mut g = f.clone();
        let accessor = json!({ "bufferView": view, "componentType": component_type, "count": 4, "type": kind,
            "normalized": component_type != 5126 });
        g.json["accessors"].as_array_mut().unwrap().push(accessor);
        g.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(3);
        let m = load(&g.write_glb(&dir, &format!("colours-{k}")));
        let colours = m.meshes[0].colours.as_ref().expect("COLOR_0 read");
        for (v, (got, want)) in colours.iter().zip(expected).enumerate() {
            assert!(
                got.iter().zip(want).all(|(a, b)| close(*a, b)),
                "{kind} {component_type}: vertex {v} {got:?} != {want:?}"
            );
        }
    }
    assert!(load(&f.write_glb(&dir, "none")).meshes[0].colours.is_none(), "no COLOR_0, no colours");
    // Refused, naming the attribute: integers that are not normalised, too few elements, and
    // a negative or non-finite float.
    let broken = [
        (json!({ "bufferView": bytes, "componentType": 5121, "count": 4, "type": "VEC4" }), "wanted VEC3 or VEC4"),
        (
            json!({ "bufferView": floats, "componentType": 5126, "count": 3, "type": "VEC3" }),
            "has 3 elements, POSITION 4",
        ),
    ];
    for (k, (accessor, message)) in broken.into_iter().enumerate() {
        let mut g = f.clone();
        g.json["accessors"].as_array_mut().unwrap().push(accessor);
        g.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(3);
        let e = error(&g.write_glb(&dir, &format!("broken-{k}")));
        assert!(e.contains("meshes[0].primitives[0].attributes.COLOR_0") && e.contains(message), "{e}");
    }
    for (k, bad) in [-0.5_f32, f32::NAN].into_iter().enumerate() {
        let mut g = f.clone();
        let view = g.push_f32(&[1.0, 1.0, 1.0, 1.0, bad, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
        let accessor = json!({ "bufferView": view, "componentType": 5126, "count": 4, "type": "VEC3" });
        g.json["accessors"].as_array_mut().unwrap().push(accessor);
        g.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(3);
        let e = error(&g.write_glb(&dir, &format!("bad-{k}")));
        assert!(e.contains("attributes.COLOR_0") && e.contains("element 1: component g"), "{e}");
    }
}

#[test]
fn an_unlit_material_shows_its_base_colour_as_emission_whatever_the_light() {
    let dir = TempDir::new("gltf-unlit");
    let mut f = Fixture::quad();
    f.json["extensionsUsed"] = json!(["KHR_materials_unlit"]);
    f.json["extensionsRequired"] = json!(["KHR_materials_unlit"]);
    f.json["materials"] = json!([{
        "name": "flat",
        "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.4, 0.6, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.0 },
        "emissiveFactor": [1.0, 0.0, 0.0],
        "extensions": { "KHR_materials_unlit": {} }
    }]);
    let path = f.write_glb(&dir, "unlit");
    let m = load(&path);
    let mat = &m.materials["flat"];
    let black = Rgb::splat(0.0);
    assert_eq!((mat.ka, mat.kd, mat.ks, mat.kr, mat.kt), (black, black, black, black, black), "no reflection term");
    assert_eq!(
        mat.emission,
        Rgb([0.2, 0.4, 0.6]),
        "E_m is the base colour; metallic, roughness and emissive are ignored"
    );
    assert!(m.warnings.iter().all(|w| w.field != "extensionsUsed"), "read, not 'unsupported': {:?}", m.warnings);
    // In the lab scene, under its default key and fill lights: every pixel of the quad is E_m.
    let loaded = load_scene_with(path.to_str().unwrap(), &LoadOptions::default()).unwrap();
    let flat = glint_core::FlatScene::build(&loaded.desc, &loaded.desc.render);
    let image = super::render::render_cpu_checked(&flat, 0, true).image;
    let quad =
        loaded.desc.objects.iter().position(|o| matches!(o, glint_scene::ObjectDesc::Model(_))).expect("the model")
            as u32;
    let on_quad: Vec<_> = image.pixels.iter().zip(&image.first_hit).filter(|(_, h)| **h == quad).collect();
    assert!(on_quad.len() > 100, "only {} pixels see the quad", on_quad.len());
    // E_m as both tracers store it, in f32.
    let stored = [0.2_f32, 0.4, 0.6].map(f64::from);
    for (p, _) in on_quad {
        assert_eq!(p.to_array(), stored, "an unlit pixel is its base colour");
    }
    // Its base texture is the emission texture; vertex colours, which multiply k_a and k_d only,
    // are left out with a warning.
    f.json["images"] = json!([{ "uri": "tex.png" }]);
    f.json["textures"] = json!([{ "source": 0 }]);
    f.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    glint_test_support::texture::write_png(&dir.join("tex.png"), 1, 1, &[255, 128, 0, 255]);
    // Not read, so not refused either: a negative channel.
    let colours = f.push_f32(&[1.0, 1.0, 1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
    f.json["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "bufferView": colours, "componentType": 5126, "count": 4, "type": "VEC3" }));
    f.json["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = json!(3);
    let textured = f.write_gltf(&dir, "unlit-textured", BufferAt::DataUri);
    let m = load(&textured);
    let mat = &m.materials["flat"];
    assert!(mat.texture.is_none() && mat.emission_texture.is_some(), "the base texture is E_m's");
    assert!(m.meshes[0].colours.is_none());
    let warned = m.warnings.iter().find(|w| w.field.ends_with("attributes.COLOR_0")).expect("COLOR_0 warned");
    assert!(warned.problem.contains("unlit"), "{}", warned.problem);
    // Every pixel of the quad is E_m times the texel (sRGB (255, 128, 0), linear (1, 0.2158605, 0)).
    let loaded = load_scene_with(textured.to_str().unwrap(), &LoadOptions::default()).unwrap();
    let flat = glint_core::FlatScene::build(&loaded.desc, &loaded.desc.render);
    let image = super::render::render_cpu_checked(&flat, 0, true).image;
    let expected = glam::DVec3::from_array(stored) * glam::DVec3::new(1.0, 0.2158605, 0.0);
    let seen = image.pixels.iter().zip(&image.first_hit).filter(|(_, h)| **h == quad).map(|(p, _)| *p);
    let worst = seen.map(|p| (p - expected).abs().max_element()).fold(0.0, f64::max);
    assert!(worst < 1e-6, "an unlit textured pixel is {worst:e} off E_m·T");
}

#[test]
fn gpu_instancing_places_a_copy_of_the_mesh_per_instance() {
    let dir = TempDir::new("gltf-instancing");
    let mut f = Fixture::quad();
    let translation = f.push_f32(&[0.0, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 20.0, 0.0]);
    // A quarter turn about z as normalised shorts (x, y, z, w), then none, then none.
    let (q, one) = (23170_u16, 32767_u16);
    let rotation = f.push_u16(&[0, 0, q, q, 0, 0, 0, one, 0, 0, 0, one]);
    let scale = f.push_f32(&[1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 1.0, 1.0, 1.0]);
    let accessors = f.json["accessors"].as_array_mut().unwrap();
    accessors.push(json!({ "bufferView": translation, "componentType": 5126, "count": 3, "type": "VEC3" }));
    accessors
        .push(json!({ "bufferView": rotation, "componentType": 5122, "normalized": true, "count": 3, "type": "VEC4" }));
    accessors.push(json!({ "bufferView": scale, "componentType": 5126, "count": 3, "type": "VEC3" }));
    f.json["extensionsUsed"] = json!(["EXT_mesh_gpu_instancing"]);
    f.json["extensionsRequired"] = json!(["EXT_mesh_gpu_instancing"]);
    f.json["nodes"][0]["translation"] = json!([0.0, 0.0, -1.0]);
    f.json["nodes"][0]["extensions"] =
        json!({ "EXT_mesh_gpu_instancing": { "attributes": { "TRANSLATION": 3, "ROTATION": 4, "SCALE": 5 } } });
    let m = load(&f.write_glb(&dir, "instanced"));
    assert_eq!(m.meshes.len(), 3, "one copy per instance");
    // Corner (1, 0, 0) of the quad: turned to (0, 1), then doubled and moved 10, then moved 20;
    // every instance in the node's space, then the node's translation.
    let corner = |k: usize| m.meshes[k].vertices[1];
    let near = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-4);
    assert!(near(corner(0), [0.0, 1.0, -1.0]), "{:?}", corner(0));
    assert!(near(corner(1), [12.0, 0.0, -1.0]), "{:?}", corner(1));
    assert!(near(corner(2), [1.0, 20.0, -1.0]), "{:?}", corner(2));
    assert!(m.meshes[1].name.ends_with("#1"), "{}", m.meshes[1].name);
    assert!(m.warnings.iter().all(|w| w.field != "extensionsUsed"), "read, not 'unsupported': {:?}", m.warnings);
    // Counts that differ, an accessor that is not there, and no attribute at all are errors.
    for (attributes, message) in [
        (json!({ "TRANSLATION": 3, "SCALE": 0 }), "the attributes' counts differ"),
        (json!({ "TRANSLATION": 9 }), "accessors[9] does not exist"),
        (json!({}), "names none of TRANSLATION, ROTATION and SCALE"),
        (json!({ "ROTATION": 3 }), "wanted VEC4 of FLOAT or normalized BYTE/SHORT"),
        // 2^27 instances of the quad's 2 triangles, from a sparse view-less accessor the file
        // holds as a few bytes: refused before anything is read (3 GB of translations).
        (json!({ "TRANSLATION": 6 }), "make 268435456 triangles"),
    ] {
        let mut g = f.clone();
        let sparse = json!({ "count": 1, "indices": { "bufferView": rotation, "componentType": 5121 },
            "values": { "bufferView": translation } });
        let many = json!({ "componentType": 5126, "count": 1 << 27, "type": "VEC3", "sparse": sparse });
        g.json["accessors"].as_array_mut().unwrap().push(many);
        g.json["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = attributes;
        let e = error(&g.write_glb(&dir, "broken"));
        assert!(e.contains("nodes[0].extensions.EXT_mesh_gpu_instancing") && e.contains(message), "{e}");
    }
}

#[test]
fn strips_and_fans_are_traced_points_and_lines_skipped_with_a_warning() {
    let dir = TempDir::new("gltf-modes");
    let mut f = Fixture::quad();
    let prim = |mode: u32| json!({ "attributes": { "POSITION": 0 }, "mode": mode });
    f.json["meshes"] = json!([{ "primitives": [prim(5), prim(6), prim(0), prim(1)] }]);
    let m = load(&f.write_gltf(&dir, "modes", BufferAt::DataUri));
    assert_eq!(m.meshes.len(), 2, "strip and fan");
    assert_eq!(m.meshes[0].triangles, vec![[0, 1, 2], [2, 1, 3]]);
    assert_eq!(m.meshes[1].triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert!(m.meshes[0].normals.is_none(), "no NORMAL: faceted");
    assert!(m.warnings.iter().any(|w| w.field == "meshes[0]" && w.problem.contains("Points")), "{:?}", m.warnings);
    f.json["meshes"] = json!([{ "primitives": [prim(0)] }]);
    let message = error(&f.write_gltf(&dir, "points", BufferAt::DataUri));
    assert!(message.contains("points.gltf") && message.contains("no triangles"), "{message}");
}

#[test]
fn a_scene_file_places_a_model_by_reference_and_saves_the_reference() {
    let dir = TempDir::new("gltf-in-scene");
    Fixture::quad().write_glb(&dir, "quad");
    let scene = dir.join("lab.toml");
    std::fs::write(
        &scene,
        r#"
[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]

[materials.red]
kd = [0.8, 0.1, 0.1]

# The scene's own material of this name overrides the model's.
[materials."tile/white"]
kd = [0.2, 0.3, 0.4]

[[objects]]
type = "sphere"
center = [3, 0, 0]
radius = 1
material = "red"

[[objects]]
type = "model"
path = "quad.glb"
name = "tile"
transform = { translate = [10, 0, 0], rotate = [0, 0, 90], scale = 2 }
"#,
    )
    .unwrap();
    let loaded = load_scene_with(scene.to_str().unwrap(), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    let glint_scene::ObjectDesc::Model(model) = &loaded.desc.objects[1] else { panic!("a model object") };
    let placed = &model.loaded.as_ref().expect("loaded").meshes[0];
    // (1, 0, 0) scaled to (2, 0, 0), turned 90° about z to (0, 2, 0), moved to (10, 2, 0).
    let v = placed.vertices[1];
    assert!(close(v[0], 10.0) && close(v[1], 2.0) && v[2].abs() < 1e-12, "{v:?}");
    assert_eq!(placed.material, "tile/white");
    assert_eq!(loaded.desc.materials["tile/white"].kd, Rgb([0.2, 0.3, 0.4]), "the scene's override");
    let flat = glint_core::FlatScene::build(&loaded.desc, &loaded.desc.render);
    assert_eq!(flat.triangles.len(), 2);
    // Saved: the reference and the override, no vertices; loading the saved file gives the same.
    let text = glint_io::to_toml(&loaded.desc).unwrap();
    assert!(text.contains("quad.glb") && !text.contains("vertices"), "{text}");
    let again = dir.join("again.toml");
    std::fs::write(&again, &text).unwrap();
    let reloaded = load_scene_with(again.to_str().unwrap(), &LoadOptions::default()).unwrap();
    assert_eq!(reloaded.desc, loaded.desc);
    // Bad references and transforms name the field.
    for (edit, wanted) in [
        ("path = \"missing.glb\"", "objects[1].path"),
        ("path = \"quad.glb\"\ntransform = { scale = 0 }", "objects[1].transform.scale"),
        (
            "path = \"quad.glb\"\ntransform = { rotate = [0, 0, 1], quaternion = [0, 0, 0, 1] }",
            "objects[1].transform.quaternion",
        ),
        (
            "path = \"quad.glb\"\ntransform = { matrix = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], translate = [1, 0, 0] }",
            "objects[1].transform.matrix",
        ),
        (
            "path = \"quad.glb\"\ntransform = { matrix = [1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0] }",
            "objects[1].transform.matrix: its bottom row",
        ),
        // Placed beyond the coordinates a scene holds: one error on the transform, not one per
        // vertex component; a scale whose product underflows is named as written.
        (
            "path = \"quad.glb\"\ntransform = { scale = 1e300 }",
            "objects[1].transform: with this transform, the model reaches 1e300",
        ),
        ("path = \"quad.glb\"\ntransform = { scale = 1e-300 }", "objects[1].transform.scale: its factors' product"),
    ] {
        let bad = dir.join("bad.toml");
        std::fs::write(
            &bad,
            format!("[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n[materials.m]\n[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n[[objects]]\ntype = \"model\"\n{edit}\n"),
        )
        .unwrap();
        let message = load_scene_with(bad.to_str().unwrap(), &LoadOptions::default()).unwrap_err().to_string();
        assert!(message.contains("bad.toml") && message.contains(wanted), "{edit}: {message}");
        assert!(!message.contains("vertices["), "{edit}: an error per vertex: {message}");
    }
}

#[test]
fn base_colour_and_emissive_textures_keep_their_sampler_transform_and_texcoords() {
    let dir = TempDir::new("gltf-textures");
    glint_test_support::texture::write_png(&dir.join("tex.png"), 2, 1, &[255, 0, 0, 255, 0, 0, 255, 255]);
    let mut f = Fixture::quad();
    let uv = f.push_f32(&[0., 0., 1., 0., 1., 1., 0., 1.]);
    f.json["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({ "bufferView": uv, "componentType": 5126, "count": 4, "type": "VEC2" }));
    f.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(3);
    f.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    f.json["images"] = json!([{ "uri": "tex.png" }]);
    f.json["samplers"] = json!([{ "magFilter": 9728, "wrapS": 33071, "wrapT": 33648 }]);
    f.json["textures"] = json!([{ "source": 0, "sampler": 0 }]);
    f.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0,
        "extensions": { "KHR_texture_transform": { "offset": [0.5, 0.0], "rotation": 0.25, "scale": [2.0, 1.0] } } });
    f.json["materials"][0]["emissiveTexture"] = json!({ "index": 0 });
    f.json["materials"][0]["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    let m = load(&f.write_gltf(&dir, "textured", BufferAt::File("textured.bin".into())));
    let mat = &m.materials["white"];
    let t = mat.texture.as_ref().expect("a base-colour texture");
    let image = t.image.as_ref().expect("decoded");
    assert_eq!((image.width(), image.height(), t.path.as_str()), (2, 1, "tex.png"));
    assert_eq!(
        (t.wrap_s, t.wrap_t, t.filter),
        (glint_scene::Wrap::ClampToEdge, glint_scene::Wrap::MirroredRepeat, glint_scene::Filter::Nearest)
    );
    let tr = t.transform.as_ref().expect("KHR_texture_transform");
    assert_eq!((tr.offset, tr.rotation, tr.scale), ([0.5, 0.0], 0.25, [2.0, 1.0]));
    assert!(m.warnings.iter().all(|w| w.field != "extensionsUsed"), "it is read, not 'unsupported': {:?}", m.warnings);
    assert!(m.warnings.iter().all(|w| w.field != "materials"), "nothing left out: {:?}", m.warnings);
    // What the seed's model has no term for is named, once for the model.
    let mut more = f.clone();
    more.json["materials"][0]["normalTexture"] = json!({ "index": 0 });
    more.json["materials"][0]["alphaMode"] = json!("MASK");
    let m2 = load(&more.write_gltf(&dir, "normal-mapped", BufferAt::File("normal-mapped.bin".into())));
    let left_out: Vec<&str> =
        m2.warnings.iter().filter(|w| w.field == "materials").map(|w| w.problem.as_str()).collect();
    assert_eq!(
        left_out,
        [
            "what Glint's model does not read, left out: alphaMode MASK (traced opaque) (1 material), normalTexture (1 material)"
        ]
    );
    let e = mat.emission_texture.as_ref().expect("an emission texture");
    assert!(std::sync::Arc::ptr_eq(e.image.as_ref().unwrap(), image), "one image decoded once");
    assert_eq!(m.meshes[0].uvs.as_deref(), Some(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]][..]));
    // A texture reading a set the primitive lacks is named by that set.
    let mut other_set = f.clone();
    other_set.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0, "texCoord": 2 });
    let m3 = load(&other_set.write_gltf(&dir, "other-set", BufferAt::File("other-set.bin".into())));
    assert!(m3.meshes[0].uvs.is_none());
    assert!(
        m3.warnings.iter().any(|w| w.problem.contains("reads TEXCOORD_2, which it does not have")),
        "{:?}",
        m3.warnings
    );
    // A texture outside the model's folder is refused naming the image.
    f.json["images"] = json!([{ "uri": "../tex.png" }]);
    let sub = dir.join("sub");
    std::fs::create_dir(&sub).unwrap();
    let message = error(&f.write_gltf(&sub, "escape", BufferAt::DataUri));
    assert!(message.contains("images[0].uri") && message.contains("../tex.png"), "{message}");
}

#[test]
fn a_misspelt_override_of_a_model_material_is_warned_about_with_the_models_names() {
    let dir = TempDir::new("gltf-override-typo");
    Fixture::quad().write_glb(&dir, "quad");
    let scene = dir.join("lab.toml");
    let text = |materials: &str| {
        format!(
            "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n{materials}\n\
             [[objects]]\ntype = \"model\"\npath = \"quad.glb\"\nname = \"tile\"\n"
        )
    };
    let warnings = |materials: &str| {
        std::fs::write(&scene, text(materials)).unwrap();
        load_scene_with(scene.to_str().unwrap(), &LoadOptions::default()).unwrap_or_else(|e| panic!("{e}")).warnings
    };
    let found = warnings("[materials.\"tile/whit\"]\nkd = 0.2");
    let w = found.iter().find(|w| w.field == "materials.\"tile/whit\"").unwrap_or_else(|| panic!("{found:?}"));
    assert!(w.problem.contains("overrides nothing") && w.problem.contains("its materials: \"white\""), "{w:?}");
    // The override itself, and a material named for no model, are not warned about.
    for materials in ["[materials.\"tile/white\"]\nkd = 0.2", "[materials.\"other/x\"]\nkd = 0.2"] {
        let found = warnings(materials);
        assert!(found.iter().all(|w| !w.problem.contains("overrides nothing")), "{materials}: {found:?}");
    }
}

#[test]
fn a_saved_edit_of_a_textured_model_material_loads_again_with_the_models_images() {
    let dir = TempDir::new("gltf-override-texture");
    let models = dir.join("models");
    std::fs::create_dir(&models).unwrap();
    // One image inside the file (a data: URI, named `images[0]`), one beside it (`tex.png`,
    // relative to the model's folder): neither can be read from the scene's folder.
    glint_test_support::texture::write_png(&models.join("tex.png"), 2, 1, &[255, 0, 0, 255, 0, 0, 255, 255]);
    let png = std::fs::read(models.join("tex.png")).unwrap();
    let data = format!("data:image/png,{}", png.iter().map(|b| format!("%{b:02X}")).collect::<String>());
    let mut f = Fixture::quad();
    f.json["images"] = json!([{ "uri": data }, { "uri": "tex.png" }]);
    f.json["textures"] = json!([{ "source": 0 }, { "source": 1 }]);
    f.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    f.json["materials"][0]["emissiveTexture"] = json!({ "index": 1 });
    f.json["materials"][0]["emissiveFactor"] = json!([1.0, 1.0, 1.0]);
    f.write_glb(&models, "tile");
    let scene = dir.join("lab.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\n\n\
         [[objects]]\ntype = \"model\"\npath = \"models/tile.glb\"\nname = \"tile\"\n",
    )
    .unwrap();
    let mut desc = load_scene_with(scene.to_str().unwrap(), &LoadOptions::default()).unwrap().desc;
    // The viewer's edit of the imported material, then its Save.
    desc.materials.get_mut("tile/white").unwrap().kd = Rgb([0.1, 0.2, 0.3]);
    let text = glint_io::to_toml(&desc).unwrap();
    assert!(text.contains("images[0]") && text.contains("tex.png"), "{text}");
    std::fs::write(dir.join("saved.toml"), &text).unwrap();
    let reloaded = load_scene_with(dir.join("saved.toml").to_str().unwrap(), &LoadOptions::default())
        .unwrap_or_else(|e| panic!("the saved scene does not load: {e}\n{text}"));
    let m = &reloaded.desc.materials["tile/white"];
    assert_eq!(m.kd, Rgb([0.1, 0.2, 0.3]));
    assert_eq!(m.texture.as_ref().and_then(|t| t.image.as_ref()).map(|i| i.width()), Some(2));
    assert_eq!(reloaded.desc, desc);
}

#[test]
fn a_zero_normal_facets_the_primitive_with_a_warning() {
    // As an OBJ's zero normals are warned of; a glTF's (BoxBadNormals) faceted its box silently.
    let dir = TempDir::new("gltf-zero-normal");
    let mut f = Fixture::quad();
    let view = f.push_f32(&[0., 0., 0., 0., 0., 1., 0., 0., 1., 0., 0., 1.]);
    let accessors = f.json["accessors"].as_array_mut().expect("accessors");
    accessors.push(json!({ "bufferView": view, "componentType": 5126, "count": 4, "type": "VEC3" }));
    let index = accessors.len() - 1;
    f.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = json!(index);
    let m = load(&f.write_gltf(&dir, "zero", BufferAt::DataUri));
    assert!(m.meshes[0].normals.is_none(), "faceted");
    let warned = m.warnings.iter().find(|w| w.field.ends_with("attributes.NORMAL")).expect("warned");
    assert!(warned.problem.starts_with("has zero-length or non-finite normals"), "{warned:?}");
    // The fixture's own normals: no warning.
    let m = load(&Fixture::quad().write_gltf(&dir, "unit", BufferAt::DataUri));
    assert!(m.warnings.iter().all(|w| !w.field.ends_with("NORMAL")), "{:?}", m.warnings);
}

#[test]
fn normals_under_a_tiny_node_scale_are_kept() {
    // Nodes scaled by 1e-3 twice (a tester's file): the cofactor transform scaled each normal's
    // length by s² = 1e-12, the importer took that for a zero normal, and a smooth sphere was
    // shaded faceted without a word.
    let dir = TempDir::new("gltf-tiny-scale");
    let mut f = Fixture::quad();
    f.json["scenes"][0]["nodes"] = json!([1]);
    f.json["nodes"] = json!([
        { "mesh": 0, "name": "quad" },
        { "scale": [1e-3, 1e-3, 1e-3], "children": [2] },
        { "scale": [1e-3, 1e-3, 1e-3], "children": [0] }
    ]);
    let m = load(&f.write_gltf(&dir, "tiny", BufferAt::DataUri));
    let normals = m.meshes[0].normals.as_ref().expect("the file's normals are kept");
    assert!(normals.iter().all(|n| close(n[2], 1.0)), "{normals:?}");
    assert!(close(m.meshes[0].vertices[2][0], 1e-6), "{:?}", m.meshes[0].vertices);
}

/// An accessor without a bufferView and without sparse values is zeros (glTF 2.0,
/// "Accessors"); the gltf crate's validation called its bufferView missing, and a valid file
/// (a models tester's morph target of zero offsets) was refused. Here the texture coordinates.
#[test]
fn an_accessor_without_a_buffer_view_or_sparse_values_is_read_as_zeros() {
    let dir = TempDir::new("gltf-viewless");
    let mut f = Fixture::quad();
    let n = f.json["accessors"].as_array().expect("accessors").len();
    f.json["accessors"]
        .as_array_mut()
        .expect("accessors")
        .push(json!({ "componentType": 5126, "count": 4, "type": "VEC2" }));
    f.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(n);
    // Texture coordinates are read for a textured material.
    f.json["images"] = json!([{ "uri": "tex.png" }]);
    f.json["textures"] = json!([{ "source": 0 }]);
    f.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": 0 });
    glint_test_support::texture::write_png(&dir.join("tex.png"), 1, 1, &[255, 255, 255, 255]);
    let m = load(&f.write_glb(&dir, "viewless"));
    assert_eq!(m.meshes[0].uvs.as_deref(), Some(&[[0.0, 0.0]; 4][..]));
}

/// A scene without `nodes` is valid glTF 2.0 (an empty one), which the gltf crate's parser
/// refuses: a models tester's SceneWithoutNodes.gltf was "not a valid glTF 2.0 file: missing
/// field 'nodes'". Another scene of such a file loads, from JSON and from GLB (whose JSON
/// chunk is rewritten); the empty one is refused as having no nodes.
#[test]
fn a_scene_without_nodes_leaves_the_files_other_scenes_readable() {
    let dir = TempDir::new("gltf-scene-without-nodes");
    let mut f = Fixture::quad();
    f.json["scenes"].as_array_mut().expect("scenes").push(json!({ "name": "empty" }));
    let files = [f.write_glb(&dir, "two"), f.write_gltf(&dir, "two", BufferAt::DataUri)];
    for path in &files {
        let m = load(path);
        assert_eq!(m.meshes.len(), 1, "{}: the quad of scene 0", path.display());
        let options = ImportOptions { scene_index: Some(1), ..ImportOptions::default() };
        let err = load_gltf(path, &options).expect_err("scene 1 is empty").to_string();
        assert!(err.contains("scenes[1].nodes"), "{}: {err}", path.display());
    }
}
