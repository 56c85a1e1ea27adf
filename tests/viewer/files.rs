//! Scene files and failures: save and reload, an unreadable scene, no GPU at all.

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_io::{load_scene, parse_scene};
use glint_viewer::{ViewMode, ViewerApp, ViewerOptions};

use crate::support::{choose, settle, temp_dir, viewer};

#[test]
fn a_saved_scene_reads_back_as_the_edited_scene() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("save");
    let path = dir.join("edited.toml");
    h.state_mut().doc.desc.lights[0].diffuse.0 = [0.25, 0.5, 0.75];
    h.state_mut().doc.edited();
    h.state_mut().save_scene(&path);
    assert!(!h.state().doc.dirty, "saving clears the edited mark");
    let text = std::fs::read_to_string(&path).expect("the scene was written");
    let (desc, _) = parse_scene(&text, &path).expect("glint render reads it");
    assert_eq!(desc, h.state().doc.desc);
    // And the viewer opens it again as a file, remembered among the recent scenes.
    h.state_mut().open(&path.display().to_string());
    assert_eq!(h.state().doc.desc, desc);
    assert_eq!(h.state().recent.files.first(), Some(&path.canonicalize().expect("exists")));
    let _ = std::fs::remove_dir_all(dir);
}

/// A file dropped on the window, as eframe's winit integration hands it over.
#[derive(Debug)]
struct DroppedPath(std::path::PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &std::path::Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

#[test]
fn a_scene_file_dropped_on_the_window_is_opened() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("drop");
    let path = dir.join("dropped.toml");
    h.state_mut().doc.desc.lights[0].diffuse.0 = [0.1, 0.2, 0.3];
    h.state_mut().doc.edited();
    h.state_mut().save_scene(&path);
    let dropped = h.state().doc.desc.clone();
    h.state_mut().open("whitted");
    assert_ne!(h.state().doc.desc, dropped, "the built-in scene is open again");

    h.input_mut().dropped_files.push(std::sync::Arc::new(DroppedPath(path.clone())));
    h.run_steps(2);
    assert_eq!(h.state().doc.desc, dropped, "the dropped file is the open scene");
    assert_eq!(h.state().recent.files.first(), Some(&path.canonicalize().expect("exists")));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_obj_model_dropped_on_the_window_is_opened_with_its_materials() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("drop-obj");
    std::fs::write(dir.join("m.mtl"), "newmtl red\nKd 0.8 0.1 0.1\nKs 0.5 0.5 0.5\nNs 40\nillum 2\n").unwrap();
    let path = dir.join("model.obj");
    std::fs::write(&path, "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\n").unwrap();
    h.input_mut().dropped_files.push(std::sync::Arc::new(DroppedPath(path.clone())));
    h.run_steps(2);
    let doc = &h.state().doc;
    assert_eq!(doc.name, "model", "the dropped model is the open document");
    assert_eq!(doc.desc.materials["model/red"].kd.0, [0.8, 0.1, 0.1]);
    assert!(doc.desc.objects.iter().any(|o| matches!(o, glint_scene::ObjectDesc::Model(_))), "the model");
    // Saving keeps the reference: the model's path, never its vertices or unchanged materials.
    let saved = glint_io::to_toml(&doc.desc).unwrap();
    assert!(saved.contains("type = \"model\"") && saved.contains("model.obj"), "{saved}");
    assert!(!saved.contains("vertices") && !saved.contains("model/red"), "{saved}");
    assert!(h.state().message.is_none(), "no error: {:?}", h.state().message);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_unreadable_scene_is_a_message_not_a_crash() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let before = h.state().doc.desc.clone();
    h.state_mut().open("/nonexistent/scene.toml");
    h.run_steps(2);
    let message = h.state().message.clone().unwrap_or_default();
    assert!(message.contains("/nonexistent/scene.toml"), "{message}");
    assert!(h.query_by_label_contains("cannot read the scene file").is_some(), "the message is shown");
    assert_eq!(h.state().doc.desc, before, "the open scene stays");
    // It stays through later edits until dismissed.
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();
    h.run_steps(2);
    assert!(h.query_by_label_contains("cannot read the scene file").is_some(), "the message stays");
    h.get_by_label("Dismiss").click();
    h.run_steps(2);
    assert!(h.state().message.is_none() && h.query_by_label_contains("cannot read the scene file").is_none());
}

/// Without a wgpu renderer (no adapter) the viewer runs with the CPU view alone and says why.
/// No GPU is needed for this test, so it also runs under GLINT_SKIP_GPU=1.
#[test]
fn without_a_gpu_the_viewer_shows_the_cpu_reference_and_says_why() {
    let base = load_scene("whitted").expect("built-in").desc.render;
    let settings = glint_scene::RenderSettings { width: 64, height: 48, ..base };
    let options = ViewerOptions {
        scene: "whitted".into(),
        settings: Some(settings),
        no_gpu_reason: Some("no adapter in this test".into()),
        no_recent: true,
        ..ViewerOptions::default()
    };
    let mut h = Harness::builder().with_size(egui::vec2(1000.0, 640.0)).build_eframe(|cc| ViewerApp::new(cc, options));
    let deadline = Instant::now() + Duration::from_secs(60);
    while !h.state().is_settled() {
        assert!(Instant::now() < deadline, "the CPU reference did not finish");
        h.step();
        std::thread::sleep(Duration::from_millis(5));
    }
    h.run_steps(2);
    let app = h.state();
    assert!(app.renders.gpu.is_none());
    assert_eq!(app.layout.mode, ViewMode::Cpu);
    assert!(app.renders.cpu.finished.is_some(), "the CPU reference rendered");
    assert!(h.query_by_label_contains("No GPU: no adapter in this test").is_some());
}

#[test]
fn the_cameras_of_a_gltf_file_can_be_looked_through_from_the_scene_panel() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("model-cameras");
    let mut f = glint_test_support::gltf::Fixture::quad();
    // Two cameras: in front of the quad, and above it looking down (−90° about x).
    f.json["cameras"] = serde_json::json!([
        { "type": "perspective", "name": "front", "perspective": { "yfov": 0.8, "znear": 0.1 } },
        { "type": "perspective", "name": "top", "perspective": { "yfov": 0.6, "znear": 0.1 } }
    ]);
    let half = std::f64::consts::FRAC_1_SQRT_2;
    f.json["nodes"] = serde_json::json!([
        { "mesh": 0, "name": "quad" },
        { "camera": 0, "translation": [0.5, 0.5, 3.0] },
        { "camera": 1, "translation": [0.5, 3.0, 0.0], "rotation": [-half, 0.0, 0.0, half] }
    ]);
    f.json["scenes"] = serde_json::json!([{ "nodes": [0, 1, 2] }]);
    let path = f.write_glb(&dir, "cams");
    h.state_mut().open(path.to_str().unwrap());
    settle(&mut h);
    let front = h.state().doc.desc.camera.clone();
    assert_eq!(front.position, [0.5, 0.5, 3.0], "the file's first camera, as --camera 0");
    choose(&mut h, "Scene", "Model camera", "1: top");
    settle(&mut h);
    let top = &h.state().doc.desc.camera;
    assert!((top.position[1] - 3.0).abs() < 1e-9 && top.look_at[1] < top.position[1], "{top:?}");
    assert!((top.fov_y - 0.6f64.to_degrees()).abs() < 1e-5, "the file stores yfov as f32: {top:?}");
    assert!(h.state().message.is_none(), "no error: {:?}", h.state().message);
    // Back to the first, and the panel names it.
    choose(&mut h, "Scene", "Model camera", "0: front");
    settle(&mut h);
    assert_eq!(h.state().doc.desc.camera, front);
}
