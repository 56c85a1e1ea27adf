//! The ray tree inspector: the probed pixel's whole Whitted tree in the Probe panel (CPU beside
//! GPU, the first differing node pointed out) and drawn over the images.

use egui::Modifiers;
use egui_kittest::kittest::Queryable;
use glint_core::cpu::ray_tree::RayTree;
use glint_types::RayKind;

use crate::support::{click, menu, settle, viewer};

/// The glass sphere of whitted at the tests' 160×120 (as the probe snapshot).
const GLASS: (u32, u32) = (100, 70);

fn probe_glass(h: &mut egui_kittest::Harness<'static, glint_viewer::ViewerApp>) {
    let pos = h.state().screen_pos_of_pixel(GLASS.0, GLASS.1).expect("the view is drawn");
    click(h, pos, Modifiers::COMMAND);
    settle(h);
}

fn trees(h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>) -> (RayTree, RayTree) {
    let probe = h.state().renders.probe.as_ref().expect("a probe");
    (probe.cpu_tree.clone(), probe.gpu_tree.clone().expect("the GPU tree arrived"))
}

#[test]
fn the_probe_panel_lists_the_glass_sphere_tree_on_both_tracers() {
    let Some(mut h) = viewer("whitted", (1000.0, 700.0)) else { return };
    probe_glass(&mut h);
    let (cpu, gpu) = trees(&h);
    // A camera ray into the glass, refracted through it and reflected off it, shadow rays to
    // the lights, and branches the bailout cut.
    assert_eq!(cpu.nodes[0].kind, RayKind::Camera);
    assert!(cpu.nodes.len() >= 10, "{} nodes", cpu.nodes.len());
    assert!(
        cpu.count(RayKind::Refraction) >= 2 && cpu.count(RayKind::Reflection) >= 2 && cpu.count(RayKind::Shadow) >= 1
    );
    assert!(cpu.nodes.iter().any(|n| n.cut.is_some()));
    assert_eq!(gpu.nodes.len(), cpu.nodes.len(), "the GPU recorded the same rays");
    // Each ray's weight is the product of the k along its path, formed in f32 as the bailout
    // judges it on both tracers: within f32's rounding of a step a level.
    for n in cpu.nodes.iter().filter(|n| n.kind != RayKind::Shadow) {
        let mut product = n.factor;
        let mut at = n.parent;
        while let Some(p) = at {
            product *= cpu.nodes[p].factor * cpu.nodes[p].attenuation;
            at = cpu.nodes[p].parent;
        }
        let steps = f64::from(n.depth + 1);
        assert!((product - n.weight).abs().max_element() <= steps * 1.2e-7 * product.max_element(), "{n:?}");
    }
    assert!(h.query_by_label("CPU and GPU trees agree node by node within tolerance.").is_some());
    // The root is open: its own rows and its children's titles are listed.
    assert!(h.query_by_label_contains("#0 camera: glass sphere").is_some(), "the root node is listed");
    for child in cpu.children(0) {
        let title = format!("#{child} {}", cpu.nodes[child].kind.name());
        assert!(h.query_by_label_contains(&title).is_some(), "child {title} is listed");
    }
    assert!(h.query_by_label("weight (path product of k)").is_some());
    let summary = format!("{} rays: ", cpu.nodes.len());
    assert!(h.query_by_label_contains(&summary).is_some(), "the summary line");
}

#[test]
fn a_perturbed_gpu_node_is_highlighted_and_its_path_opened() {
    let Some(mut h) = viewer("whitted", (1000.0, 700.0)) else { return };
    probe_glass(&mut h);
    let (cpu, _) = trees(&h);
    let deep = cpu
        .nodes
        .iter()
        .position(|n| n.depth == 2 && n.kind == RayKind::Refraction)
        .expect("a refraction ray at depth 2");
    let probe = h.state_mut().renders.probe.as_mut().expect("a probe");
    probe.gpu_tree.as_mut().expect("GPU tree").nodes[deep].weight *= 1.01;
    h.run_steps(3);
    let pointer = format!("First differing node: #{deep} (refraction): weight");
    assert!(h.query_by_label(&pointer).is_some(), "the differing node is not pointed out");
    // Its header is shown (the path to it opened) and its rows are listed.
    assert!(h.query_by_label_contains(&format!("#{deep} refraction")).is_some(), "node {deep} is not shown");
}

#[test]
fn the_tree_is_drawn_over_the_image_and_can_be_hidden() {
    let Some(mut h) = viewer("whitted", (1000.0, 700.0)) else { return };
    h.get_by_role_and_label(egui::accesskit::Role::Button, "GPU").click();
    h.run_steps(2);
    probe_glass(&mut h);
    assert!(h.query_by_label_contains("Ray tree: ").is_some(), "the tree is not drawn");
    for (name, ..) in glint_viewer::RAY_TREE_LEGEND {
        assert!(h.query_by_label(name).is_some(), "the legend does not say what {name} looks like");
    }
    // The legend stays within the image (it ran onto the difference view's colour bar below).
    let image = *h.state().layout.view_rects.last().expect("an image");
    let last = h.get_by_label("width: the ray's path weight").rect();
    assert!(
        last.bottom() <= image.bottom(),
        "the legend ends at {} below the image's {}",
        last.bottom(),
        image.bottom()
    );
    menu(&mut h, &["View", "Ray tree overlay"]);
    h.key_press(egui::Key::Escape);
    h.run_steps(2);
    assert!(!h.state().layout.show_ray_tree);
    assert!(h.query_by_label_contains("Ray tree: ").is_none(), "the tree is still drawn");
    assert!(h.query_by_label("cut by bailout or depth").is_none(), "the legend stays without the tree");
}

/// Whitted moved to a map coordinate (UTM zone 32N), which f32 cannot store (its step is 1/2
/// there): stored relative to its geometry, the probe reports the same tree as at the origin,
/// moved, on both tracers, in world coordinates, and the two trees agree.
#[test]
fn a_scene_at_a_map_coordinate_is_probed_in_world_coordinates_on_both_tracers() {
    const AT: [f64; 3] = [452_331.127, 81.5, 5_411_876.883];
    let Some(mut origin) = viewer("whitted", (1000.0, 700.0)) else { return };
    probe_glass(&mut origin);
    let (near, _) = trees(&origin);
    drop(origin);

    let mut desc = glint_io::load_scene("whitted").expect("built-in").desc;
    glint_test_support::scene::translate(&mut desc, AT);
    let dir = crate::support::temp_dir("map-coordinate");
    let file = dir.join("whitted-utm.toml");
    std::fs::write(&file, glint_io::to_toml(&desc).expect("TOML")).expect("scene written");
    let Some(mut far) = viewer(file.to_str().expect("UTF-8 path"), (1000.0, 700.0)) else { return };
    probe_glass(&mut far);
    let (cpu, gpu) = trees(&far);
    assert!(far.query_by_label("CPU and GPU trees agree node by node within tolerance.").is_some());
    assert_eq!(cpu.nodes.len(), near.nodes.len(), "the same rays as at the origin");
    let at = glam::DVec3::from(AT);
    for (i, ((c, g), n)) in cpu.nodes.iter().zip(&gpu.nodes).zip(&near.nodes).enumerate() {
        assert_eq!(c.kind, n.kind, "node {i}");
        // World coordinates: the node at the origin, moved (to the f32 rounding of the scene's size).
        assert!((c.origin - at - n.origin).abs().max_element() < 1e-5, "CPU node {i}: {} vs {}", c.origin, n.origin);
        assert!((g.origin - c.origin).abs().max_element() < 1e-3, "GPU node {i}: {} vs {}", g.origin, c.origin);
    }
}

#[test]
fn the_delta_row_and_the_radiance_brought_back_say_on_hover_what_they_are() {
    // A lecturer found neither explained where it stands.
    for (label, hint) in
        [("Δ", glint_viewer::DELTA_HINT), ("I brought back (CPU only)", glint_viewer::BROUGHT_BACK_HINT)]
    {
        let Some(mut h) = viewer("whitted", (1000.0, 700.0)) else { return };
        probe_glass(&mut h);
        assert!(h.query_by_label(hint).is_none(), "{hint:?} shown before hovering");
        let node = h.query_all_by_label(label).next().unwrap_or_else(|| panic!("no {label:?} in the probe panel"));
        node.scroll_to_me();
        // Until the scroll has brought it into the panel.
        let side = h.state().layout.side_rect;
        for _ in 0..120 {
            h.step();
            if side.contains_rect(h.query_all_by_label(label).next().expect("still listed").rect()) {
                break;
            }
        }
        h.query_all_by_label(label).next().expect("still listed").hover();
        // A tooltip shows once the pointer has rested (egui's delay).
        for _ in 0..120 {
            h.step();
            if h.query_by_label(hint).is_some() {
                break;
            }
        }
        assert!(h.query_by_label(hint).is_some(), "hovering {label:?} does not say what it is");
    }
}
