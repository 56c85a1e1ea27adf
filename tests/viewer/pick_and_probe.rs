//! Picking an object by clicking it, and the pixel probe's breakdown on both tracers.

use egui::Modifiers;
use egui_kittest::kittest::Queryable;
use glint_core::glam::DVec3;
use glint_types::layout::NO_HIT;
use glint_viewer::{GpuProbe, Tab};

use crate::support::{click, gpu_image, settle, viewer};

/// A pixel whose first hit (on the CPU) is object `object`, near the middle of its area.
fn pixel_of(h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>, object: u32) -> (u32, u32) {
    let (_, cpu) = h.state().renders.cpu.finished.as_ref().expect("a CPU render");
    let img = &cpu.image;
    let hits: Vec<(u32, u32)> = (0..img.height)
        .flat_map(|y| (0..img.width).map(move |x| (x, y)))
        .filter(|&(x, y)| img.first_hit[(y * img.width + x) as usize] == object)
        .collect();
    assert!(!hits.is_empty(), "object {object} is not visible");
    hits[hits.len() / 2]
}

fn object_named(h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>, name: &str) -> u32 {
    let doc = &h.state().doc;
    (0..doc.desc.objects.len()).find(|&i| doc.object_label(i) == name).unwrap_or_else(|| panic!("no object {name}"))
        as u32
}

#[test]
fn clicking_an_object_selects_it_and_shows_its_material() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::NONE);
    h.run_steps(2);
    assert_eq!(h.state().selection.object, Some(glass as usize));
    assert_eq!(h.state().layout.tab, Tab::Materials);
    assert_eq!(h.state().selection.material.as_deref(), Some("glass"));
    // Clicking the sky selects nothing.
    let pos = h.state().screen_pos_of_pixel(2, 2).expect("the view is drawn");
    click(&mut h, pos, Modifiers::NONE);
    assert_eq!(h.state().selection.object, None);
}

#[test]
fn ctrl_clicking_an_object_probes_the_pixel_and_selects_the_object() {
    // A lecturer's find: Ctrl+click probed but left the selection as it was.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    h.run_steps(2);
    assert_eq!(h.state().selection.object, Some(glass as usize), "the object under the probe is selected");
    assert_eq!(h.state().selection.material.as_deref(), Some("glass"));
    assert_eq!(h.state().layout.tab, Tab::Probe, "the probe's panel shows, not the material's");
    let probe = h.state().renders.probe.as_ref().expect("a probe");
    assert_eq!((probe.x, probe.y), (x, y));
    // Ctrl+click on the sky probes it and selects nothing, as a plain click there does.
    let pos = h.state().screen_pos_of_pixel(2, 2).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    assert_eq!(h.state().selection.object, None);
    assert_eq!(h.state().renders.probe.as_ref().map(|p| (p.x, p.y)), Some((2, 2)));
}

#[test]
fn the_probe_breakdown_sums_to_the_pixel_radiance_on_both_tracers() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    let app = h.state();
    assert_eq!(app.layout.tab, Tab::Probe);
    let probe = app.renders.probe.as_ref().expect("a probe");
    assert_eq!((probe.x, probe.y), (x, y));
    let cpu = &probe.cpu;
    assert_eq!(cpu.object_id, glass);
    assert!(!cpu.lights.is_empty());
    // CPU: the terms add up to the radiance, which is the pixel's value (1 spp: one sample).
    let cpu_pixel = app.renders.cpu.finished.as_ref().map(|(_, f)| f.image.get(x, y)).expect("CPU image");
    assert!((cpu.sum_of_terms() - cpu.total).abs().max_element() < 1e-12, "{cpu:?}");
    assert!((cpu.total - cpu_pixel).abs().max_element() < 1e-12, "probe {} vs pixel {cpu_pixel}", cpu.total);
    // GPU: the same in f32 (sums in another order: a few ULPs of the largest term).
    let GpuProbe::Done(Ok(gpu)) = &probe.gpu else { panic!("GPU probe: {:?}", probe.gpu) };
    let gpu_pixel = gpu_image(&h).get(x, y);
    assert_eq!(gpu.object_id, glass);
    assert!((gpu.sum_of_terms() - gpu.total).abs().max_element() < 1e-5, "{gpu:?}");
    assert!((gpu.total - gpu_pixel).abs().max_element() < 1e-6, "probe {} vs pixel {gpu_pixel}", gpu.total);
    // And the two agree on the hit; the table marks the first term beyond tolerance, if any.
    assert_ne!(gpu.object_id, NO_HIT);
    let rows = glint_viewer::terms(cpu, Some(gpu));
    assert!(rows.iter().all(|t| t.gpu.is_some()));
    if let Some(i) = glint_viewer::first_difference(&rows) {
        assert!(h.query_by_label(&rows[i].name).is_some(), "the differing term {} is listed", rows[i].name);
    }

    // The probe follows an edit: at depth 0 the glass has no k_r·I_r or k_t·I_t left.
    h.state_mut().doc.desc.render.max_depth = 0;
    h.state_mut().doc.edited();
    settle(&mut h);
    let app = h.state();
    let probe = app.renders.probe.as_ref().expect("the probe stays");
    assert_eq!(probe.revision, app.doc.revision, "the probe is of the edited scene");
    assert_eq!((probe.cpu.reflected, probe.cpu.transmitted), (DVec3::ZERO, DVec3::ZERO));
    let cpu_pixel = app.renders.cpu.finished.as_ref().map(|(_, f)| f.image.get(x, y)).expect("CPU image");
    assert!(
        (probe.cpu.total - cpu_pixel).abs().max_element() < 1e-12,
        "probe {} vs pixel {cpu_pixel}",
        probe.cpu.total
    );
    assert!(h.query_by_label("CPU and GPU agree on every term within tolerance.").is_some());

    // A GPU term off by 0.1 (as a shader bug would make it) is the one the panel points at.
    let mut wrong = match &h.state().renders.probe.as_ref().expect("probe").gpu {
        GpuProbe::Done(Ok(g)) => g.clone(),
        other => panic!("GPU probe: {other:?}"),
    };
    wrong.lights[0].diffuse += DVec3::splat(0.1);
    h.state_mut().renders.probe.as_mut().expect("probe").gpu = GpuProbe::Done(Ok(wrong));
    h.run_steps(2);
    assert!(
        h.query_by_label("First difference beyond tolerance: light 0: diffuse").is_some(),
        "the differing term is not pointed out"
    );
    // Each light's cosines are listed before the terms they give (whitted's lobes are
    // Blinn's), so a wrong N·L is named as the cause rather than the diffuse it feeds.
    for row in ["light 0: N·L", "light 0: N·H", "light 0: (N·H)^n"] {
        assert!(h.query_all_by_label(row).next().is_some(), "the probe lists no {row}");
    }
    let probe = h.state_mut().renders.probe.as_mut().expect("probe");
    let GpuProbe::Done(Ok(wrong)) = &mut probe.gpu else { panic!("GPU probe: {:?}", probe.gpu) };
    wrong.lights[0].angles.n_dot_l += 0.1;
    h.run_steps(2);
    assert!(
        h.query_by_label("First difference beyond tolerance: light 0: N·L").is_some(),
        "the differing cosine is not pointed out"
    );
    // Another lobe evaluated on the GPU is said as such, not only through its cosine.
    let probe = h.state_mut().renders.probe.as_mut().expect("probe");
    let GpuProbe::Done(Ok(wrong)) = &mut probe.gpu else { panic!("GPU probe: {:?}", probe.gpu) };
    wrong.lights[0].angles.lobe_model = glint_scene::SpecularModel::Phong;
    h.run_steps(2);
    let said = "Specular lobe differs: light 0: the CPU evaluated (N·H)^n, the GPU (R·V)^n";
    assert!(h.query_by_label(said).is_some(), "the other lobe is not said");
}

#[test]
fn the_probe_table_fits_the_default_side_panel() {
    let Some(mut h) = viewer("whitted", (1024.0, 768.0)) else { return };
    let before = h.state().layout.side_rect;
    // A sphere's normal has three non-zero components: the widest row of the table.
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    let normal = h.state().renders.probe.as_ref().expect("a probe").cpu.normal;
    assert!(normal.to_array().iter().all(|c| c.abs() > 1e-3), "pick a pixel with a slanted normal: {normal}");
    let side = h.state().layout.side_rect;
    // The table fits the panel as it was, rather than widening it.
    assert_eq!(side, before, "the probe widened the side panel");
    // The N row's values (CPU and GPU), as the table writes them.
    let first = glint_viewer::probe_cell(normal.x);
    let values: Vec<egui::Rect> = h.query_all_by_label(&first).map(|n| n.rect()).collect();
    assert!(!values.is_empty(), "the N row is not shown");
    for r in values {
        assert!(r.right() <= side.right(), "a value of N ends at x = {} beyond the panel's {side:?}", r.right());
    }
}

/// Paths switched on (their warnings shown in the strip) and a pixel probed leave the side
/// panel as wide as it was: it widened from 300 to about 340 points in a tester's 1280×800
/// window, the strip's one-line header "Warnings (2): rendered anyway, as glint render does"
/// being wider than the panel.
#[test]
fn paths_and_a_probe_leave_the_side_panel_its_width() {
    let Some(mut h) = viewer("whitted", (1280.0, 800.0)) else { return };
    let before = h.state().layout.side_rect.width();
    h.state_mut().doc.desc.render.integrator = glint_scene::Integrator::Path;
    h.state_mut().doc.edited();
    settle(&mut h);
    assert!(!h.state().doc.warnings.is_empty(), "whitted under paths has warnings to show");
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::COMMAND);
    settle(&mut h);
    let after = h.state().layout.side_rect.width();
    assert!((after - before).abs() < 0.5, "the side panel went from {before} to {after} points wide");
}

#[test]
fn the_selected_object_is_outlined_on_both_images() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let glass = object_named(&h, "glass sphere");
    let (x, y) = pixel_of(&h, glass);
    assert!(h.query_by_label("Selected: glass sphere").is_none(), "nothing is selected yet");
    let pos = h.state().screen_pos_of_pixel(x, y).expect("the view is drawn");
    click(&mut h, pos, Modifiers::NONE);
    h.run_steps(2);
    // The sphere's pixels (CPU first hits; the GPU's may differ at the rim by a pixel).
    let (_, cpu) = h.state().renders.cpu.finished.as_ref().expect("a CPU render");
    let img = &cpu.image;
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    for (i, _) in img.first_hit.iter().enumerate().filter(|(_, id)| **id == glass) {
        let (px, py) = (i as u32 % img.width, i as u32 / img.width);
        (lo, hi) = ((lo.0.min(px), lo.1.min(py)), (hi.0.max(px + 1), hi.1.max(py + 1)));
    }
    let (w, hgt) = (img.width as f32, img.height as f32);
    let outlines: Vec<egui::Rect> = h.query_all_by_label("Selected: glass sphere").map(|n| n.rect()).collect();
    let images = h.state().layout.view_rects.clone();
    assert_eq!(outlines.len(), images.len(), "side by side: one outline on each image: {outlines:?}");
    for image in &images {
        let at = |(px, py): (u32, u32)| {
            image.min + egui::vec2(px as f32 / w * image.width(), py as f32 / hgt * image.height())
        };
        let expected = egui::Rect::from_min_max(at(lo), at(hi));
        let pixel = image.width() / w;
        let outline = outlines.iter().find(|o| image.contains_rect(**o)).expect("an outline on this image");
        for (a, b) in [(outline.min, expected.min), (outline.max, expected.max)] {
            assert!((a - b).length() <= 1.5 * pixel, "outline {outline:?} vs the sphere's pixels {expected:?}");
        }
    }
    // Clicking the sky selects nothing, and nothing is outlined.
    let pos = h.state().screen_pos_of_pixel(2, 2).expect("the view is drawn");
    click(&mut h, pos, Modifiers::NONE);
    assert!(h.query_by_label("Selected: glass sphere").is_none(), "the outline stays after deselecting");
}

#[test]
fn clicking_a_models_face_shows_that_faces_material_and_the_list_can_choose_another() {
    // A tester's find: a model's own materials could not be chosen (the panel set the object's
    // first material every frame), and a click on a face showed that first material.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = crate::support::temp_dir("two-materials");
    std::fs::write(dir.join("m.mtl"), "newmtl a\nKd 0.9 0.1 0.1\nnewmtl b\nKd 0.1 0.1 0.9\n").unwrap();
    let obj = "mtllib m.mtl\nv -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 1 0 0\nv 1 1 0\n\
               usemtl a\nf 1 2 3 4\nusemtl b\nf 2 5 6 3\n";
    std::fs::write(dir.join("model.obj"), obj).unwrap();
    h.state_mut().open(&dir.join("model.obj").display().to_string());
    settle(&mut h);
    let (w, ht) = (h.state().doc.desc.render.width, h.state().doc.desc.render.height);
    let mut seen = std::collections::BTreeSet::new();
    for x in (0..w).step_by(4) {
        h.state_mut().pick(x, ht / 2);
        if h.state().selection.object.is_some() {
            seen.extend(h.state().selection.material.clone());
        }
    }
    assert!(seen.contains("model/a") && seen.contains("model/b"), "materials picked along the middle row: {seen:?}");
    // With the model selected, the list chooses its other material, and the choice stays.
    crate::support::choose(&mut h, "Materials", "Material", "model/a");
    h.run_steps(3);
    assert_eq!(h.state().selection.material.as_deref(), Some("model/a"));
    crate::support::choose(&mut h, "Materials", "Material", "model/b");
    h.run_steps(3);
    assert_eq!(h.state().selection.material.as_deref(), Some("model/b"));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_path_views_outline_follows_each_pixels_centre_not_its_jittered_first_sample() {
    // A lecturer's find: in a path view the outline was drawn from the first sample's hits,
    // which fall anywhere in the pixel: a ragged rim, a pixel beyond the sphere here and there.
    // It is now traced through each pixel's centre: the sphere's pixels as a one-sample
    // Whitted render (and `glint_core::centre_hits`) finds them.
    let Some(mut h) = viewer("cornell-gi", (1000.0, 640.0)) else { return };
    let glass = object_named(&h, "glass sphere");
    h.state_mut().selection.object = Some(glass as usize);
    h.run_steps(3);
    let flat = h.state().doc.flat(false).expect("a valid scene");
    let (w, hgt) = (flat.header.width, flat.header.height);
    let hits = glint_core::centre_hits(&flat).expect("valid tags");
    let (mut lo, mut hi) = ((u32::MAX, u32::MAX), (0, 0));
    for (i, _) in hits.iter().enumerate().filter(|(_, id)| **id == glass) {
        let (px, py) = (i as u32 % w, i as u32 / w);
        (lo, hi) = ((lo.0.min(px), lo.1.min(py)), (hi.0.max(px + 1), hi.1.max(py + 1)));
    }
    // The first sample's hits do reach beyond the centres' (else this test tells nothing).
    let (_, cpu) = h.state().renders.cpu.finished.as_ref().expect("a CPU render");
    let beyond = cpu.image.first_hit.iter().zip(&hits).any(|(first, centre)| *first == glass && *centre != glass);
    assert!(beyond, "the jittered first hits are the centres' here");
    let outlines: Vec<egui::Rect> = h.query_all_by_label("Selected: glass sphere").map(|n| n.rect()).collect();
    assert!(!outlines.is_empty(), "outlined");
    let images = h.state().layout.view_rects.clone();
    for image in &images {
        let at = |(px, py): (u32, u32)| {
            image.min + egui::vec2(px as f32 / w as f32 * image.width(), py as f32 / hgt as f32 * image.height())
        };
        let expected = egui::Rect::from_min_max(at(lo), at(hi));
        let Some(outline) = outlines.iter().find(|o| image.contains_rect(**o)) else { continue };
        for (a, b) in [(outline.min, expected.min), (outline.max, expected.max)] {
            assert!((a - b).length() <= 0.5, "outline {outline:?} vs the centres' pixels {expected:?}");
        }
    }
}
