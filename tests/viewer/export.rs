//! "Save image" (Ctrl+S) writes a valid PNG whose embedded settings match the scene's.

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use glint_io::image_file::read_png_text;

use crate::support::{HEIGHT, WIDTH, temp_dir, viewer};

#[test]
fn save_image_writes_a_png_with_the_render_settings() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("export");
    let path = dir.join("all three.png");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(2);
    h.get_by_label("All three side by side").click();
    h.run_steps(1);
    let field = h.get_by_role_and_label(Role::TextInput, "File");
    field.focus();
    field.set_text_value_accesskit(&path.display().to_string());
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert!(path.is_file(), "no image written; message: {:?}", h.state().message);

    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).expect("open")));
    let mut reader = decoder.read_info().expect("a valid PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("decodes");
    // CPU | GPU | difference, each at the render size.
    assert_eq!((info.width, info.height), (3 * WIDTH, HEIGHT));

    let text = read_png_text(&path).expect("tEXt chunks");
    let get = |k: &str| text.iter().find(|(key, _)| key == k).map(|(_, v)| v.clone()).unwrap_or_default();
    let s = &h.state().doc.desc.render;
    assert_eq!(get("glint:scene"), "whitted");
    assert_eq!(get("glint:size"), format!("{}x{}", s.width, s.height));
    assert_eq!(get("glint:depth"), s.max_depth.to_string());
    assert_eq!(get("glint:spp"), s.spp.to_string());
    assert_eq!(get("glint:epsilon"), s.epsilon.to_string());
    assert_eq!(get("glint:epsilon_mode"), s.epsilon_mode.name());
    assert_eq!(get("glint:view"), "All three side by side");
    let adapter = h.state().renders.gpu.as_ref().map(|g| g.adapter_name()).expect("a GPU in this test");
    assert_eq!(get("glint:device"), adapter);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn saving_before_the_cpu_has_finished_is_reported_not_crashed() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("early");
    let path = dir.join("cpu.png");
    // An edit restarts the CPU reference; saving its view right away must give a message.
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();
    let result = h.state_mut().save_image(&path, glint_viewer::ExportView::Cpu);
    assert!(result.is_err(), "the CPU view of the new revision cannot exist yet");
    assert!(!path.exists());
    let _ = std::fs::remove_dir_all(dir);
}
