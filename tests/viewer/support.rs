//! Building the app in a test harness and waiting for its background renders.

use std::time::{Duration, Instant};

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_io::load_scene;
use glint_scene::RenderSettings;
use glint_viewer::{ViewerApp, ViewerOptions};

/// Small renders keep the CPU reference and lavapipe quick (a whole test under seconds).
pub const WIDTH: u32 = 160;
pub const HEIGHT: u32 = 120;

/// Why the tests' viewers use no system file dialog (shown where a dialog would fail).
pub const NO_DIALOGS: &str = "no file dialog in this test";

/// The viewer on `scene` at WIDTH×HEIGHT in a `window`-sized harness, rendered with wgpu;
/// `None` when `GLINT_SKIP_GPU=1`. Panics with a clear message when there is no adapter.
pub fn viewer(scene: &str, window: (f32, f32)) -> Option<Harness<'static, ViewerApp>> {
    viewer_with(scene, window, |_| {})
}

/// `viewer` with its options changed by `change` (a start view, paused path batches).
pub fn viewer_with(
    scene: &str,
    window: (f32, f32),
    change: impl FnOnce(&mut ViewerOptions),
) -> Option<Harness<'static, ViewerApp>> {
    if glint_test_support::skip_requested("GLINT_SKIP_GPU") {
        eprintln!("GLINT_SKIP_GPU=1: skipping the viewer UI tests");
        return None;
    }
    if let Err(e) = glint_gpu::GpuContext::new(&glint_gpu::AdapterRequest { name: None, prefer_cpu: true }) {
        panic!(
            "the viewer tests need a wgpu adapter and found none: {e}\n\
             Install Mesa's lavapipe (apt-get install mesa-vulkan-drivers), or set GLINT_SKIP_GPU=1 to skip them."
        );
    }
    let base = load_scene(scene).expect("built-in scene").desc.render;
    let settings = RenderSettings { width: WIDTH, height: HEIGHT, ..base };
    // Never a real file dialog in a test: it would wait for a person.
    let mut options = ViewerOptions {
        scene: scene.into(),
        settings: Some(settings),
        no_recent: true,
        no_file_dialogs: Some(NO_DIALOGS.into()),
        ..ViewerOptions::default()
    };
    change(&mut options);
    let mut harness = Harness::builder()
        .with_size(egui::vec2(window.0, window.1))
        .wgpu_setup(glint_viewer::with_tracer_limits(egui_kittest::wgpu::default_wgpu_setup()))
        .build_eframe(move |cc| ViewerApp::new(cc, options));
    settle(&mut harness);
    Some(harness)
}

/// A fresh folder for one test's files, removed when dropped.
pub fn temp_dir(name: &str) -> glint_test_support::TempDir {
    glint_test_support::TempDir::new(&format!("viewer-{name}"))
}

/// Steps the UI until every render of the current scene is done (GPU, CPU, comparison).
pub fn settle(harness: &mut Harness<'static, ViewerApp>) {
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        harness.step();
        // A few more frames after settling, so the UI shows the final state.
        if harness.state().is_settled() {
            for _ in 0..3 {
                harness.step();
            }
            if harness.state().is_settled() {
                return;
            }
        }
        assert!(Instant::now() < deadline, "the viewer did not finish rendering within 120 s");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// Clicks through to entry `item` of the combo box `combo` on the side panel's `tab`
/// (e.g. Lights, Type, spot), letting the UI answer each click.
pub fn choose(harness: &mut Harness<'static, ViewerApp>, tab: &str, combo: &str, item: &str) {
    for label in [tab, combo, item] {
        harness.get_by_label(label).click();
        harness.run_steps(2);
    }
}

/// A primary click at `pos` with `modifiers`.
pub fn click(harness: &mut Harness<'static, ViewerApp>, pos: egui::Pos2, modifiers: egui::Modifiers) {
    harness.hover_at(pos);
    harness.step();
    for pressed in [true, false] {
        harness.event_modifiers(
            egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed, modifiers },
            modifiers,
        );
        harness.step();
    }
}

/// The current GPU image (read back for the comparison) of the current revision.
pub fn gpu_image(harness: &Harness<'static, ViewerApp>) -> glint_core::HdrImage {
    let app = harness.state();
    let latest = app.renders.gpu.as_ref().and_then(|g| g.latest.as_ref()).expect("a GPU render");
    assert_eq!(latest.revision, app.doc.revision, "the GPU image is of an older revision");
    latest.image.clone()
}

/// The mean absolute difference of two images of the same size.
pub fn mean_abs_diff(a: &glint_core::HdrImage, b: &glint_core::HdrImage) -> f64 {
    a.pixels.iter().zip(&b.pixels).map(|(x, y)| (*x - *y).abs().element_sum()).sum::<f64>()
        / (3 * a.pixels.len()) as f64
}

/// Clicks through the menu bar: `path` is the menu, any submenus and the item.
pub fn menu(harness: &mut Harness<'static, ViewerApp>, path: &[&str]) {
    for label in path {
        harness.get_by_label(label).click();
        harness.run_steps(2);
    }
}
