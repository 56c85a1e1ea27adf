//! Validation's messages stand at the side panel's foot, seen at the viewer's own window size,
//! name the control that edits each field beside the file's name for it, and "Show" opens that
//! tab with the light, material or object selected; one that goes moves no control.

use egui_kittest::kittest::{NodeT, Queryable};
use glint_scene::ObjectDesc;
use glint_viewer::Tab;

use crate::support::{settle, viewer};

/// Clicks the `k`th message's Show, the strip scrolled (by the wheel, as a user would) until it
/// is in view: wrapped to the panel's width, the messages may be taller than the strip.
fn show(h: &mut egui_kittest::Harness<'static, glint_viewer::ViewerApp>, k: usize) {
    let button = |h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>| {
        h.get_all_by_label("Show").nth(k).expect("a Show per warning").rect()
    };
    for _ in 0..40 {
        let side = h.state().layout.side_rect;
        if button(h).bottom() <= side.bottom() - 2.0 {
            break;
        }
        h.hover_at(egui::pos2(button(h).center().x, side.bottom() - 30.0));
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: egui::vec2(0.0, -40.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(3);
    }
    h.get_all_by_label("Show").nth(k).expect("a Show per warning").click();
}

#[test]
fn warnings_stand_at_the_panels_foot_name_their_control_and_show_it_and_move_nothing_as_they_go() {
    let [width, height] = glint_viewer::WINDOW_SIZE;
    let Some(mut h) = viewer("whitted", (width, height)) else { return };
    let mirror = h.state().doc.desc.objects.iter().position(|o| o.name() == "mirror sphere").expect("whitted's mirror");
    let ObjectDesc::Sphere(sphere) = &h.state().doc.desc.objects[mirror] else { panic!("a sphere") };
    let centre = sphere.center;
    let light = h.state().doc.light_label(0);
    {
        let doc = &mut h.state_mut().doc;
        // A light shut inside the opaque mirror, a floor k_d of 8-bit values, an ε the size of the scene.
        doc.desc.lights[0].position = Some(centre);
        doc.desc.materials.get_mut("floor").expect("whitted's floor").kd = [200.0, 200.0, 200.0].into();
        doc.desc.render.epsilon = 1.0;
        doc.edited();
    }
    settle(&mut h);
    // The list's order: the importer's warnings, then validation's; a Show button each.
    let doc = &h.state().doc;
    let fields: Vec<String> = doc.load_warnings.iter().chain(&doc.warnings).map(|w| w.field.clone()).collect();
    for field in ["lights[0].position", "materials.floor.kd", "render.epsilon"] {
        assert!(fields.iter().any(|f| f == field), "{field} among {fields:?}");
    }

    // On the Scene tab, seen without scrolling in the window the viewer opens with (below the
    // tab they went unseen), in a strip of their own at the panel's foot.
    assert_eq!(h.state().layout.tab, Tab::Scene);
    let header = h.get_by_label_contains("Warnings (").rect();
    let camera = h.get_by_label("Camera").rect();
    assert!(header.bottom() < height - 40.0, "seen without scrolling: {header:?} in a window {height} high");
    assert!(camera.bottom() < header.top(), "the tab's first section ({camera:?}) above the strip ({header:?})");

    // Each names its control: the trail for the light, the material and the render setting.
    let trails =
        [format!("Lights › {light} › Position"), "Materials › floor › k_d".into(), "Scene › Render › Epsilon".into()];
    for trail in &trails {
        assert!(h.query_by_label(trail).is_some(), "{trail} shown");
    }

    // Show goes there: the light's tab with the light selected and its control on screen.
    let index = |field: &str| fields.iter().position(|f| f == field).expect("listed");
    let k = index("lights[0].position");
    h.state_mut().selection.light = usize::MAX;
    show(&mut h, k);
    h.run_steps(3);
    assert_eq!(h.state().layout.tab, Tab::Lights);
    assert_eq!(h.state().selection.light, 0);
    assert!(h.query_by_label("Position").is_some(), "the light's position is edited there");

    let k = index("materials.floor.kd");
    show(&mut h, k);
    h.run_steps(3);
    assert_eq!(h.state().layout.tab, Tab::Materials);
    assert_eq!(h.state().selection.material.as_deref(), Some("floor"));
    assert!(h.query_by_label("k_d").is_some(), "the floor's k_d is edited there");

    let k = index("render.epsilon");
    show(&mut h, k);
    h.run_steps(3);
    assert_eq!(h.state().layout.tab, Tab::Scene);
    assert!(h.query_all_by_label("Epsilon").next().is_some(), "ε is edited there");

    // A value fixed takes its warning away and moves none of the tab's controls (at the top,
    // the controls jumped under the pointer as a lecturer typed).
    let depth = |h: &egui_kittest::Harness<'static, glint_viewer::ViewerApp>| {
        h.query_all_by_label("Max depth").map(|n| n.rect()).collect::<Vec<_>>()
    };
    let before = depth(&h);
    assert!(!before.is_empty(), "the Scene tab shows Max depth");
    h.state_mut().doc.desc.render.epsilon = 1e-6;
    h.state_mut().doc.edited();
    h.run_steps(3);
    assert!(h.state().doc.warnings.iter().all(|w| w.field != "render.epsilon"), "{:?}", h.state().doc.warnings);
    assert_eq!(depth(&h), before, "a control moved as a warning went");
}

/// At the least window, 760×480, the messages wrap inside the side panel: a long header title
/// widened the strip, and the messages wrapped to that width were cut at the panel's edge
/// ("world.ambient: is not used by the path trace…"; a viewer tester).
#[test]
fn the_messages_wrap_inside_a_narrow_side_panel() {
    let Some(mut h) = viewer("whitted", (760.0, 480.0)) else { return };
    {
        let doc = &mut h.state_mut().doc;
        doc.desc.render.integrator = glint_scene::Integrator::Path;
        doc.desc.render.epsilon = 1.0;
        doc.edited();
    }
    settle(&mut h);
    let side = h.state().layout.side_rect;
    let header = h.get_by_label_contains("Warnings (").rect();
    let strip: Vec<(String, egui::Rect)> = h
        .query_all_by_label_contains("")
        .filter(|n| n.rect().top() >= header.top() && n.rect().top() < side.bottom() && n.rect().left() < side.right())
        .map(|n| (n.accesskit_node().label().unwrap_or_default(), n.rect()))
        .collect();
    assert!(strip.iter().any(|(l, _)| l == "Show"), "the messages are in the strip: {strip:?}");
    for (label, rect) in &strip {
        assert!(
            rect.right() <= side.right() + 1.0,
            "{label:?} ends at {} beyond the panel's {}",
            rect.right(),
            side.right()
        );
    }
}
