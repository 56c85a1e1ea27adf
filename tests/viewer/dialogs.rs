//! Where no system file dialog can open: the reason shown in the UI and a typed path (with
//! completion of the folder's scene and model files) for Open scene, Save scene as and
//! "Save image" → Browse…; and "unsaved changes" before another scene replaces an edited one.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glint_viewer::ViewerApp;

use crate::support::{NO_DIALOGS, menu, temp_dir, viewer};

const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";

/// Types `text` into the text field labelled `label`.
fn type_path(h: &mut Harness<'static, ViewerApp>, label: &str, text: &str) {
    let field = h.get_by_role_and_label(Role::TextInput, label);
    field.focus();
    field.set_text_value_accesskit(text);
    h.run_steps(2);
}

#[test]
fn open_scene_without_a_dialog_says_why_and_opens_a_typed_model_which_recent_files_open_again() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("typed-open");
    std::fs::write(dir.join("model.obj"), OBJ).unwrap();
    std::fs::write(dir.join("notes.txt"), "").unwrap();
    std::fs::create_dir(dir.join("more")).unwrap();
    menu(&mut h, &["File", "Open scene…"]);
    assert!(h.query_all_by_label_contains(NO_DIALOGS).count() > 0, "the reason is shown");
    assert_eq!(h.state().message.as_deref(), Some(NO_DIALOGS), "and in the messages panel");

    let sep = std::path::MAIN_SEPARATOR;
    let folder = format!("{}{sep}", dir.display());
    type_path(&mut h, "Path", &folder);
    let model = format!("{folder}model.obj");
    assert!(h.query_by_label(&format!("{folder}more{sep}")).is_some(), "folders are completed");
    assert!(h.query_by_label(&format!("{folder}notes.txt")).is_none(), "only scenes and models");
    h.get_by_label(&model).click();
    h.run_steps(2);
    h.get_by_label("Open").click();
    h.run_steps(2);
    let doc = &h.state().doc;
    assert_eq!(doc.name, "model", "message: {:?}", h.state().message);
    assert_eq!(doc.path, None, "Save scene must not write over the model file");
    let canonical = dir.join("model.obj").canonicalize().unwrap();
    assert_eq!(h.state().recent.files.first(), Some(&canonical));

    menu(&mut h, &["File", "Built-in scenes", "cornell"]);
    assert_eq!(h.state().doc.name, "cornell");
    menu(&mut h, &["File", "Recent files", &canonical.display().to_string()]);
    assert_eq!(h.state().doc.name, "model", "the recent model opens again");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn save_scene_as_and_browse_without_a_dialog_take_a_typed_path() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("typed-save");
    std::fs::write(dir.join("old.png"), "").unwrap();
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();
    menu(&mut h, &["File", "Save scene as…"]);
    let path = dir.join("saved.toml");
    type_path(&mut h, "Path", &path.display().to_string());
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert!(path.is_file(), "message: {:?}", h.state().message);
    assert_eq!(h.state().doc.path.as_deref(), Some(path.as_path()));
    assert!(!h.state().doc.dirty);

    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    h.run_steps(2);
    h.get_by_label("Browse…").click();
    h.run_steps(2);
    assert!(h.query_by_label(&format!("{NO_DIALOGS}: type the path above.")).is_some(), "said in the window");
    assert_eq!(h.state().message.as_deref(), Some(NO_DIALOGS));
    let folder = format!("{}{}", dir.display(), std::path::MAIN_SEPARATOR);
    type_path(&mut h, "File", &folder);
    assert!(h.query_by_label(&format!("{folder}old.png")).is_some(), "images in the folder are completed");
    assert!(h.query_by_label(&format!("{folder}saved.toml")).is_none());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn another_scene_over_unsaved_edits_asks_first_save_discard_or_cancel() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("unsaved");
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();
    let edited = h.state().doc.desc.clone();

    // Cancel keeps the edits; so does Escape.
    menu(&mut h, &["File", "Built-in scenes", "cornell"]);
    assert!(h.query_by_label("Unsaved changes").is_some(), "asked first");
    assert_eq!(h.state().doc.desc, edited, "nothing replaced while asking");
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    assert!(h.query_by_label("Unsaved changes").is_none());
    assert_eq!((h.state().doc.name.as_str(), &h.state().doc.desc), ("whitted", &edited));

    // Save, for a built-in scene, asks where (here: a typed path), saves, then opens.
    h.state_mut().request_open("cornell");
    h.run_steps(2);
    h.get_by_label("Save").click();
    // The typed-path window opens the frame after the answer, and shows one frame later.
    h.run_steps(3);
    let path = dir.join("whitted-edited.toml");
    type_path(&mut h, "Path", &path.display().to_string());
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert!(path.is_file(), "message: {:?}", h.state().message);
    assert_eq!(h.state().doc.name, "cornell", "opened after saving");

    // Reopened and edited: Save writes to its own file, then opens the next scene.
    h.state_mut().open(&path.display().to_string());
    h.state_mut().doc.desc.render.max_depth = 3;
    h.state_mut().doc.edited();
    menu(&mut h, &["File", "Built-in scenes", "cornell"]);
    h.get_by_label("Save").click();
    h.run_steps(2);
    assert_eq!(h.state().doc.name, "cornell");
    let (saved, _) = glint_io::parse_scene(&std::fs::read_to_string(&path).unwrap(), &path).unwrap();
    assert_eq!(saved.render.max_depth, 3, "the edit was saved");

    // Discard opens without saving.
    h.state_mut().doc.desc.render.max_depth = 1;
    h.state_mut().doc.edited();
    h.state_mut().request_open("whitted");
    h.run_steps(2);
    h.get_by_label("Discard").click();
    h.run_steps(2);
    assert_eq!(h.state().doc.name, "whitted");
    assert!(!h.state().doc.dirty);
    let _ = std::fs::remove_dir_all(dir);
}

/// Whether the app asked the window to close in its last frame.
fn asked_to_close(h: &Harness<'static, ViewerApp>) -> bool {
    h.output().viewport_output.values().any(|v| v.commands.contains(&egui::ViewportCommand::Close))
}

#[test]
fn quitting_or_closing_the_window_over_unsaved_edits_asks_first() {
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();

    // File → Quit asks; Cancel keeps the window and the edits.
    menu(&mut h, &["File", "Quit"]);
    assert!(h.query_by_label_contains("before quitting").is_some(), "asked first");
    assert!(!h.state().quitting && !asked_to_close(&h));
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    assert!(h.query_by_label("Unsaved changes").is_none());
    assert!(!h.state().quitting && h.state().doc.dirty);

    // The window's close button (or the window manager) asks the same; Discard quits.
    h.input_mut().viewports.entry(egui::ViewportId::ROOT).or_default().events.push(egui::ViewportEvent::Close);
    h.run_steps(2);
    assert!(h.query_by_label_contains("before quitting").is_some(), "a close request asks first");
    h.get_by_label("Discard").click();
    h.run_steps(1);
    assert!(h.state().quitting && asked_to_close(&h), "Discard quits");

    // Without edits, Quit closes at once.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.get_by_label("File").click();
    h.run_steps(2);
    h.get_by_label("Quit").click();
    h.run_steps(1);
    assert!(h.query_by_label("Unsaved changes").is_none());
    assert!(h.state().quitting && asked_to_close(&h));
}

/// Set in the child process `a_signal_quits_as_file_quit_does…` runs itself in.
const SIGNAL_CHILD: &str = "GLINT_VIEWER_SIGNAL_CHILD";

#[test]
fn a_signal_quits_as_file_quit_does_and_save_or_cancel_take_over_from_it() {
    // The stop flag a signal raises is one for the process (other tests' saves would stop):
    // the test runs again, alone, in a child process.
    let name = "dialogs::a_signal_quits_as_file_quit_does_and_save_or_cancel_take_over_from_it";
    if std::env::var_os(SIGNAL_CHILD).is_none() {
        let exe = std::env::current_exe().expect("the test binary");
        let out = std::process::Command::new(exe)
            .args(["--exact", name, "--test-threads=1"])
            .env(SIGNAL_CHILD, "1")
            .output()
            .expect("the test binary runs");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
        assert!(stdout.contains("1 passed"), "the child ran no test: {stdout}");
        return;
    }
    let raise = || glint_io::interrupt::flag().store(true, std::sync::atomic::Ordering::Relaxed);

    // Without edits, a signal closes the window at once.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    raise();
    h.run_steps(1);
    assert!(h.state().quitting && asked_to_close(&h), "a signal quits");
    glint_io::interrupt::withdraw();

    // Over edits it asks first, the flag still raised (a second signal ends the process).
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    h.state_mut().doc.desc.render.max_depth = 2;
    h.state_mut().doc.edited();
    raise();
    h.run_steps(2);
    assert!(h.query_by_label_contains("before quitting").is_some(), "asked first");
    assert!(!h.state().quitting && glint_io::interrupt::requested());
    // Cancel takes over: the flag is lowered, the window stays and a later save is not stopped.
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    assert!(!h.state().quitting && !glint_io::interrupt::requested());
    let dir = temp_dir("signal-save");
    h.state_mut().doc.save(&dir.join("after.toml")).expect("a save after Cancel is not interrupted");
    // The next signal is answered again: the edits saved, it quits.
    raise();
    h.run_steps(1);
    assert!(h.state().quitting && asked_to_close(&h), "the next signal quits");
}

#[test]
fn clicking_a_completion_leaves_the_buttons_where_they_were() {
    // A lecturer's find: the list of completions took the height of its entries, and a click
    // on one (which completes the path, and so changes the list) moved Open under the pointer.
    let Some(mut h) = viewer("whitted", (1000.0, 640.0)) else { return };
    let dir = temp_dir("typed-stable");
    std::fs::write(dir.join("model.obj"), OBJ).unwrap();
    std::fs::write(dir.join("other.obj"), OBJ).unwrap();
    std::fs::create_dir(dir.join("empty")).unwrap();
    menu(&mut h, &["File", "Open scene…"]);
    let sep = std::path::MAIN_SEPARATOR;
    let folder = format!("{}{sep}", dir.display());
    let buttons = |h: &Harness<'static, ViewerApp>| {
        (h.get_by_role_and_label(Role::Button, "Open").rect(), h.get_by_role_and_label(Role::Button, "Cancel").rect())
    };
    // Three completions; then one (the file's own), then none (an empty folder).
    for completion in [format!("{folder}model.obj"), format!("{folder}empty{sep}")] {
        type_path(&mut h, "Path", &folder);
        let before = buttons(&h);
        h.get_by_label(&completion).click();
        h.run_steps(3);
        assert_eq!(h.get_by_role_and_label(Role::TextInput, "Path").value().as_deref(), Some(completion.as_str()));
        assert_eq!(buttons(&h), before, "the buttons moved when {completion:?} was clicked");
    }
    let _ = std::fs::remove_dir_all(dir);
}
