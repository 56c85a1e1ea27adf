//! Validation's messages stand at the side panel's foot, seen at the viewer's own window size,
//! name the control that edits each field beside the file's name for it, and "Show" opens that
//! tab with the light, material or object selected; one that goes moves no control.

use egui_kittest::kittest::Queryable;
use glint_scene::ObjectDesc;
use glint_viewer::Tab;

use crate::support::{settle, viewer};

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
    h.get_all_by_label("Show").nth(k).expect("a Show per warning").click();
    h.run_steps(3);
    assert_eq!(h.state().layout.tab, Tab::Lights);
    assert_eq!(h.state().selection.light, 0);
    assert!(h.query_by_label("Position").is_some(), "the light's position is edited there");

    let k = index("materials.floor.kd");
    h.get_all_by_label("Show").nth(k).expect("a Show per warning").click();
    h.run_steps(3);
    assert_eq!(h.state().layout.tab, Tab::Materials);
    assert_eq!(h.state().selection.material.as_deref(), Some("floor"));
    assert!(h.query_by_label("k_d").is_some(), "the floor's k_d is edited there");

    let k = index("render.epsilon");
    h.get_all_by_label("Show").nth(k).expect("a Show per warning").click();
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
