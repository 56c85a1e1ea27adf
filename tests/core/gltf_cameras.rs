//! glTF cameras: each from its node, skipped with a warning where Glint cannot look through it,
//! chosen by `--camera`, or made to frame the model.

use glint_io::ImportOptions;
use glint_io::model::load_gltf;
use glint_io::{LoadOptions, load_scene_with};
use glint_scene::Projection;
use glint_test_support::TempDir;
use glint_test_support::gltf::{BufferAt, Fixture};
use serde_json::json;

use super::gltf::{close, load};

#[test]
fn a_camera_wider_than_a_scene_allows_is_skipped_as_a_zero_one_is() {
    let dir = TempDir::new("gltf-wide");
    let mut f = Fixture::quad();
    f.json["cameras"] = json!([
        { "type": "perspective", "perspective": { "yfov": 3.13, "znear": 0.1 } },
        { "type": "perspective", "perspective": { "yfov": 0.5, "znear": 0.1 } }
    ]);
    f.json["scenes"] = json!([{ "nodes": [0, 1, 2] }]);
    f.json["nodes"] = json!([
        { "mesh": 0 },
        { "translation": [0.5, 0.5, 4.0], "camera": 0 },
        { "translation": [0.5, 0.5, 3.0], "camera": 1 }
    ]);
    let m = load_gltf(&f.write_gltf(&dir, "wide", BufferAt::DataUri), &ImportOptions::default()).unwrap();
    assert_eq!(m.cameras.len(), 1, "the wide one skipped");
    let said = m.warnings.iter().find(|w| w.problem.contains("camera skipped")).expect("said");
    assert!(said.problem.starts_with("yfov 3.13 (cameras[0].perspective.yfov) is outside"), "{}", said.problem);
}

#[test]
fn an_aspect_ratio_that_is_not_positive_is_left_out_with_a_warning() {
    let dir = TempDir::new("gltf-aspect");
    for (aspect, written) in [(0.0, "aspectRatio 0 "), (-1.0, "aspectRatio -1 ")] {
        let mut f = Fixture::quad();
        f.json["cameras"] =
            json!([{ "type": "perspective", "perspective": { "yfov": 0.5, "aspectRatio": aspect, "znear": 0.1 } }]);
        f.json["scenes"] = json!([{ "nodes": [0, 1] }]);
        f.json["nodes"] = json!([{ "mesh": 0 }, { "translation": [0.5, 0.5, 4.0], "camera": 0 }]);
        let m = load(&f.write_gltf(&dir, "aspect", BufferAt::DataUri));
        assert_eq!((m.cameras.len(), m.cameras[0].aspect), (1, None), "aspectRatio {aspect}");
        let said = m.warnings.iter().find(|w| w.problem.contains("aspectRatio")).expect("a warning");
        assert!(said.problem.starts_with(written) && said.problem.contains("not a positive number"), "{said:?}");
    }
}

#[test]
fn an_orthographic_camera_without_a_usable_ymag_is_skipped_and_a_negative_xmag_left_out() {
    let dir = TempDir::new("gltf-orthographic");
    for (xmag, ymag, kept, said) in [
        (1.0, 0.0, false, "ymag 0 (cameras[0].orthographic.ymag) gives no view height in [1e-9, 1e9]"),
        (1.0, -2.0, false, "ymag -2 "),
        (1.0, 1e30, false, "ymag 1e30 "),
        (-3.0, 1.5, true, "xmag -3 (cameras[0].orthographic.xmag) is not a positive number"),
    ] {
        let mut f = Fixture::quad();
        f.json["cameras"] = json!([{ "type": "orthographic", "orthographic": { "xmag": xmag, "ymag": ymag, "znear": 0.1, "zfar": 10.0 } }]);
        f.json["scenes"] = json!([{ "nodes": [0, 1] }]);
        f.json["nodes"] = json!([{ "mesh": 0 }, { "translation": [0.5, 0.5, 4.0], "camera": 0 }]);
        let m = load(&f.write_gltf(&dir, "orthographic", BufferAt::DataUri));
        assert_eq!(m.cameras.len(), usize::from(kept), "xmag {xmag}, ymag {ymag}");
        if kept {
            assert_eq!((m.cameras[0].camera.view_height, m.cameras[0].aspect), (Some(3.0), None));
        }
        let warning = m.warnings.iter().find(|w| w.field.contains("cameras[0]")).expect("a warning");
        assert!(warning.problem.starts_with(said), "{warning:?}");
    }
}

#[test]
fn cameras_come_from_their_nodes_and_the_scene_uses_the_chosen_one() {
    let dir = TempDir::new("gltf-cameras");
    let mut f = Fixture::quad();
    f.json["cameras"] = json!([
        { "type": "perspective", "perspective": { "yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1 } },
        { "type": "orthographic", "orthographic": { "xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0 } },
        { "type": "perspective", "name": "close", "perspective": { "yfov": 0.25, "znear": 0.1 } }
    ]);
    f.json["scenes"] = json!([{ "nodes": [0, 1, 2, 3] }]);
    f.json["nodes"] = json!([
        { "mesh": 0 },
        { "translation": [0.5, 0.5, 4.0], "camera": 0 },
        { "translation": [0.5, 0.5, 4.0], "camera": 1 },
        { "translation": [0.5, 0.5, 2.0], "camera": 2 }
    ]);
    let path = f.write_gltf(&dir, "cams", BufferAt::DataUri);
    let m = load(&path);
    assert_eq!(m.cameras.len(), 3);
    assert!(m.warnings.iter().all(|w| !w.field.contains("camera")), "{:?}", m.warnings);
    // xmag and ymag are the half-width and half-height.
    let o = &m.cameras[1];
    assert_eq!((o.camera.projection, o.camera.view_height, o.aspect), (Projection::Orthographic, Some(2.0), Some(1.0)));
    let c = &m.cameras[0].camera;
    assert_eq!(c.position, [0.5, 0.5, 4.0]);
    assert_eq!(c.look_at, [0.5, 0.5, 3.0], "down the node's −Z");
    assert!(close(c.fov_y, 0.5f32.to_degrees().into()) || close(c.fov_y, f64::from(0.5f32).to_degrees()));
    let arg = path.to_str().unwrap();
    let first = load_scene_with(arg, &LoadOptions::default()).unwrap();
    assert_eq!(first.desc.camera.position, [0.5, 0.5, 4.0]);
    assert_eq!(first.desc.render.width, 2 * first.desc.render.height, "the camera's aspect ratio");
    assert!(first.warnings.iter().any(|w| w.field == "lights"), "the default rig is said: {:?}", first.warnings);
    let chosen =
        LoadOptions { import: ImportOptions { camera: Some(1), ..ImportOptions::default() }, ..LoadOptions::default() };
    let orthographic = load_scene_with(arg, &chosen).unwrap().desc.camera;
    assert_eq!((orthographic.position, orthographic.projection), ([0.5, 0.5, 4.0], Projection::Orthographic));
    let chosen =
        LoadOptions { import: ImportOptions { camera: Some(2), ..ImportOptions::default() }, ..LoadOptions::default() };
    assert_eq!(load_scene_with(arg, &chosen).unwrap().desc.camera.position, [0.5, 0.5, 2.0]);
    let missing =
        LoadOptions { import: ImportOptions { camera: Some(5), ..ImportOptions::default() }, ..LoadOptions::default() };
    let message = load_scene_with(arg, &missing).unwrap_err().to_string();
    assert!(message.contains("--camera") && message.contains("has 3"), "{message}");
    let scene = LoadOptions {
        import: ImportOptions { scene_index: Some(3), ..ImportOptions::default() },
        ..LoadOptions::default()
    };
    let message = load_scene_with(arg, &scene).unwrap_err().to_string();
    assert!(message.contains("scenes[3]") && message.contains("has 1"), "{message}");
    let not_a_model = load_scene_with("whitted", &missing).unwrap_err().to_string();
    assert!(not_a_model.contains("not a model file"), "{not_a_model}");
    // A scene file that is not there is said to be missing, whatever flags came with it.
    let gone = load_scene_with(dir.join("example.toml"), &missing).unwrap_err().to_string();
    assert!(gone.contains("no such file") && !gone.contains("not a model"), "{gone}");
    // A camera under a mirroring parent is looked through unmirrored, and said so.
    f.json["nodes"][3] = json!({ "scale": [-1.0, 1.0, 1.0], "children": [4] });
    f.json["nodes"].as_array_mut().unwrap().push(json!({ "translation": [-0.5, 0.5, 2.0], "camera": 2 }));
    let m = load(&f.write_gltf(&dir, "mirrored", BufferAt::DataUri));
    assert_eq!(m.cameras[2].camera.position, [0.5, 0.5, 2.0]);
    let said = m.warnings.iter().find(|w| w.problem.contains("mirrors")).expect("the mirror is said");
    assert!(said.field.contains("nodes[4].camera"), "{said:?}");
    assert_eq!(m.warnings.iter().filter(|w| w.problem.contains("mirrors")).count(), 1, "{:?}", m.warnings);
}

#[test]
fn the_camera_made_for_a_model_sees_all_of_a_tall_one() {
    // A column 0.2 × 2 × 0.2 (a tester's file): the framing camera stood 2.6 bounding radii
    // away, where its 40° view holds only 22.6° of the 20° it needs, and the column's top was
    // cut off. Every corner of the box lies within the view's half-height of its axis.
    let dir = TempDir::new("gltf-tall");
    let mut f = Fixture::quad();
    f.json["nodes"][0]["scale"] = json!([0.2, 2.0, 0.2]);
    let path = f.write_gltf(&dir, "tall", BufferAt::DataUri);
    let loaded = glint_io::load_scene(path.display().to_string()).expect("the model opens");
    let camera = &loaded.desc.camera;
    let (eye, at) = (glam::DVec3::from(camera.position), glam::DVec3::from(camera.look_at));
    let axis = (at - eye).normalize();
    for corner in [[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.0, 2.0, 0.0], [0.2, 2.0, 0.0]] {
        let to = (glam::DVec3::from(corner) - eye).normalize();
        let angle = axis.dot(to).clamp(-1.0, 1.0).acos().to_degrees();
        assert!(
            angle < 0.5 * camera.fov_y,
            "corner {corner:?} is {angle:.2}° off the axis of a {}° view",
            camera.fov_y
        );
    }
}

#[test]
fn a_camera_index_beyond_those_kept_names_the_ones_skipped() {
    // A file with two camera nodes, the first with yfov 0 (a tester's file): `--camera 1` said
    // "it has one camera on a node" and the warning that explains it was not printed.
    let dir = TempDir::new("gltf-camera-skipped");
    let mut f = Fixture::quad();
    f.json["cameras"] = json!([
        { "type": "perspective", "perspective": { "yfov": 0.0, "znear": 0.1 } },
        { "type": "perspective", "perspective": { "yfov": 0.7, "znear": 0.1 } }
    ]);
    f.json["scenes"] = json!([{ "nodes": [0, 1, 2] }]);
    f.json["nodes"] = json!([{ "mesh": 0 }, { "translation": [0.5, 0.5, 4.0], "camera": 0 }, { "translation": [0.5, 0.5, 5.0], "camera": 1 }]);
    let path = f.write_gltf(&dir, "cameras", BufferAt::DataUri);
    let options =
        LoadOptions { import: ImportOptions { camera: Some(1), ..ImportOptions::default() }, ..LoadOptions::default() };
    let err = load_scene_with(path.display().to_string(), &options).unwrap_err().to_string();
    assert!(err.contains("--camera: 1 is not a camera of the file; it has one camera on a node, camera 0"), "{err}");
    assert!(err.contains("(skipped: nodes[1].camera (cameras[0]): yfov 0 "), "{err}");
}
