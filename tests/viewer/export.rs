//! "Save image" (Ctrl+S) writes a valid PNG whose embedded settings match the scene's.

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use glint_io::image_file::read_png_text;

use crate::support::{HEIGHT, WIDTH, temp_dir, viewer};

/// Saves through the dialog (Ctrl+S), choosing the view `choice` where given, to `path`.
fn save_through_the_dialog(
    h: &mut egui_kittest::Harness<'static, glint_viewer::ViewerApp>,
    choice: Option<&str>,
    path: &std::path::Path,
) {
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(2);
    if let Some(label) = choice {
        h.get_by_label(label).click();
        h.run_steps(1);
    }
    let field = h.get_by_role_and_label(Role::TextInput, "File");
    field.focus();
    field.set_text_value_accesskit(&path.display().to_string());
    h.run_steps(2);
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert!(path.is_file(), "no image written; message: {:?}", h.state().message);
}

/// The value of the PNG text chunk `key` of `path` ("" where it has none).
fn png_text(path: &std::path::Path, key: &str) -> String {
    let text = read_png_text(path).expect("text chunks");
    text.into_iter().find(|(k, _)| k == key).map(|(_, v)| v).unwrap_or_default()
}

#[test]
fn save_image_writes_a_png_with_the_render_settings() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("export");
    let path = dir.join("all three.png");
    save_through_the_dialog(&mut h, Some("All three side by side"), &path);

    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).expect("open")));
    let mut reader = decoder.read_info().expect("a valid PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("decodes");
    // CPU | GPU | difference, each at the render size.
    assert_eq!((info.width, info.height), (3 * WIDTH, HEIGHT));

    let get = |k: &str| png_text(&path, k);
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

/// The Whitted vs GI view's images can be saved (they could not: a lecturer built the side by
/// side and the signed difference in numpy): Whitted's image, the paths, Whitted − GI and the
/// three side by side, the EXR's difference signed and equal to Whitted − paths.
#[test]
fn the_whitted_vs_gi_views_are_saved_with_a_signed_difference() {
    let Some(mut h) = crate::support::viewer_with("cornell-gi", (800.0, 500.0), |o| o.paused = true) else { return };
    let dir = temp_dir("export-gi");
    // Before the view has rendered anything, it says so.
    let early = h.state_mut().save_image(&dir.join("early.png"), glint_viewer::ExportView::WhittedMinusGi);
    assert!(early.is_err_and(|e| e.to_string().contains("Whitted vs GI view")), "saved before Whitted's image");
    h.get_by_label("Whitted vs GI").click();
    h.run_steps(2);
    crate::support::settle(&mut h);
    let rev = h.state().doc.revision;
    let whitted = h.state().renders.gi.whitted_of(rev).expect("Whitted's image").clone();
    let paths = crate::support::gpu_image(&h);
    for (name, view) in [
        ("whitted", glint_viewer::ExportView::Whitted),
        ("paths", glint_viewer::ExportView::Paths),
        ("minus", glint_viewer::ExportView::WhittedMinusGi),
        ("three", glint_viewer::ExportView::WhittedVsGi),
    ] {
        for ext in ["png", "exr"] {
            let path = dir.join(format!("{name}.{ext}"));
            h.state_mut().save_image(&path, view).unwrap_or_else(|e| panic!("{name}.{ext}: {e}"));
        }
        let png = image::open(dir.join(format!("{name}.png"))).expect("decodes").into_rgb8();
        let across = if name == "three" { 3 } else { 1 };
        assert_eq!(png.dimensions(), (across * whitted.width, whitted.height), "{name}");
    }
    let exr = |name: &str| glint_io::exr_file::read_exr(&dir.join(format!("{name}.exr"))).expect("reads").rgb;
    let f32s = |v: glam::DVec3| [v.x as f32, v.y as f32, v.z as f32];
    assert_eq!(exr("whitted"), whitted.pixels.iter().map(|p| f32s(*p)).collect::<Vec<_>>());
    assert_eq!(exr("paths"), paths.pixels.iter().map(|p| f32s(*p)).collect::<Vec<_>>());
    let minus = exr("minus");
    for (i, m) in minus.iter().enumerate() {
        assert_eq!(*m, f32s(whitted.pixels[i] - paths.pixels[i]), "pixel {i}");
    }
    assert!(minus.iter().any(|m| m[0] < 0.0), "the difference is signed: Whitted is darker");
    let minus = dir.join("minus.png");
    assert_eq!(png_text(&minus, "glint:view"), "Whitted vs GI: Whitted − GI, signed");
    let scale = png_text(&minus, "glint:diff_scale");
    assert!(scale.starts_with("Whitted - GI, mean of R, G, B: blue below, white 0, red above"), "{scale}");
    assert_eq!(png_text(&dir.join("paths.png"), "glint:integrator"), "path");
    // Ctrl+S from this view offers its own images: saved as opened, the three side by side (it
    // offered the GPU−CPU "All three", and a tester saved the magma map from the signed view).
    let path = dir.join("from the dialog.png");
    save_through_the_dialog(&mut h, None, &path);
    assert_eq!(png_text(&path, "glint:view"), "Whitted vs GI: the three side by side");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_image_named_other_than_png_or_exr_is_refused() {
    // `cpu.jpg` was written as a PNG under that name (a viewer tester).
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    crate::support::settle(&mut h);
    let dir = temp_dir("export-jpg");
    for name in ["cpu.jpg", "cpu.pn", "cpu"] {
        let e = h.state_mut().save_image(&dir.join(name), glint_viewer::ExportView::Cpu).expect_err(name);
        assert!(
            e.to_string()
                .ends_with("an image is saved as .png (sRGB, the settings embedded) or .exr (linear); name it so"),
            "{e}"
        );
        assert!(!dir.join(name).exists(), "{name} was written");
    }
    h.state_mut().save_image(&dir.join("cpu.PNG"), glint_viewer::ExportView::Cpu).expect("a PNG in capitals");
    let _ = std::fs::remove_dir_all(dir);
}
