//! The dialogs: "Save image" (a window of the app), the system's file pickers with a typed
//! path (with completion) where those cannot open, "unsaved changes" before another scene
//! replaces an edited one, and a scene file dropped on the window.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::export::ExportView;

/// The files the path field completes: scenes and the models that open as scenes.
pub const SCENE_EXTENSIONS: [&str; 4] = ["toml", "glb", "gltf", "obj"];
const SCENE_FILE_EXTENSIONS: [&str; 1] = ["toml"];
const IMAGE_EXTENSIONS: [&str; 2] = ["png", "exr"];

/// At most this many completions are listed (a folder of thousands would fill the window).
const MAX_COMPLETIONS: usize = 40;
/// The height of the list of completions (about eight of them).
const COMPLETIONS_HEIGHT: f32 = 160.0;

/// A system dialog that gives nothing back sooner than this never showed: rfd returns `None`
/// both for a cancel and for a portal that is missing (after logging the error), and no person
/// cancels within a fifth of a second.
const NOT_SHOWN: Duration = Duration::from_millis(200);

/// What a system file dialog gave.
#[derive(Clone, Debug, PartialEq)]
pub enum Picked {
    File(PathBuf),
    Cancelled,
    /// The dialog could not open: why.
    Failed(String),
}

/// What a typed path is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathPurpose {
    OpenScene,
    SaveSceneAs,
}

impl PathPurpose {
    fn title(self) -> &'static str {
        match self {
            Self::OpenScene => "Open scene",
            Self::SaveSceneAs => "Save scene as",
        }
    }

    fn button(self) -> &'static str {
        match self {
            Self::OpenScene => "Open",
            Self::SaveSceneAs => "Save",
        }
    }

    fn extensions(self) -> &'static [&'static str] {
        match self {
            Self::OpenScene => &SCENE_EXTENSIONS,
            Self::SaveSceneAs => &SCENE_FILE_EXTENSIONS,
        }
    }
}

/// The window asking for a typed path.
#[derive(Debug)]
struct PathPrompt {
    purpose: PathPurpose,
    field: PathField,
    /// Why the system dialog is not used.
    why: String,
    /// What to do once the scene is saved (Save of "unsaved changes").
    then_open: Option<Then>,
}

/// What waits for the answer to "unsaved changes": another scene to open, or quitting.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Then {
    /// A file or a built-in scene.
    Open(String),
    Quit,
}

/// The answer to "unsaved changes".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unsaved {
    Save,
    Discard,
    Cancel,
}

/// A path typed by the user, with the files of its folder that match so far.
#[derive(Debug, Default)]
struct PathField {
    text: String,
    /// The completions of `completed_for` (recomputed when the text changes, not every frame).
    completions: Vec<String>,
    completed_for: Option<String>,
}

impl PathField {
    /// The text field labelled `label` and the completions under it; returns whether Enter was
    /// pressed in the field.
    fn ui(&mut self, ui: &mut egui::Ui, label: &str, hint: &str, extensions: &[&str]) -> bool {
        let mut entered = false;
        let row = ui.horizontal(|ui| {
            let l = ui.label(label);
            let r = ui.add(egui::TextEdit::singleline(&mut self.text).hint_text(hint).desired_width(320.0));
            let r = r.labelled_by(l.id);
            entered = r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        });
        if self.completed_for.as_deref() != Some(&self.text) {
            self.completions = completions(&self.text, extensions);
            self.completed_for = Some(self.text.clone());
        }
        // The list keeps one size, however many completions it holds (none included): a click
        // on one completes the text, which changes the list, and the list's height moved the
        // buttons below it under the pointer (a lecturer).
        let size = egui::vec2(row.response.rect.width(), COMPLETIONS_HEIGHT);
        ui.allocate_ui_with_layout(size, egui::Layout::top_down(egui::Align::Min), |ui| {
            ui.set_min_size(size);
            ui.set_max_width(size.x);
            egui::ScrollArea::vertical().max_height(size.y).auto_shrink([false; 2]).id_salt(label).show(ui, |ui| {
                if self.completions.is_empty() {
                    ui.weak("No folder or matching file here.");
                }
                for c in &self.completions {
                    if ui.selectable_label(false, c).clicked() {
                        self.text = c.clone();
                    }
                }
            });
        });
        entered
    }
}

/// The folders and the files with one of `extensions` in the folder of `text` whose names
/// begin with the rest of `text`, as `text` completed with them (folders end in a separator).
/// Hidden entries only when the name typed so far begins with a dot.
pub fn completions(text: &str, extensions: &[&str]) -> Vec<String> {
    let split = text.rfind(std::path::is_separator).map_or(0, |i| i + 1);
    let (dir, prefix) = text.split_at(split);
    let folder = if dir.is_empty() { Path::new(".") } else { Path::new(dir) };
    let Ok(entries) = std::fs::read_dir(folder) else { return Vec::new() };
    let mut found: Vec<String> = entries
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().into_string().ok()?;
            if !name.starts_with(prefix) || (name.starts_with('.') && !prefix.starts_with('.')) {
                return None;
            }
            let path = e.path();
            if path.is_dir() {
                return Some(format!("{dir}{name}{}", std::path::MAIN_SEPARATOR));
            }
            let ext = path.extension()?.to_str()?.to_ascii_lowercase();
            extensions.contains(&ext.as_str()).then(|| format!("{dir}{name}"))
        })
        .collect();
    found.sort();
    found.truncate(MAX_COMPLETIONS);
    found
}

/// Why no system file dialog can open here, if that can be told beforehand: rfd's Linux
/// backend needs the desktop portal (over the D-Bus session bus) or zenity on the PATH.
fn dialogs_unavailable(env: impl Fn(&str) -> Option<OsString>) -> Option<String> {
    if cfg!(any(target_os = "windows", target_os = "macos")) {
        return None;
    }
    let set = |name: &str| env(name).filter(|v| !v.is_empty());
    let session_bus = set("DBUS_SESSION_BUS_ADDRESS").is_some()
        || set("XDG_RUNTIME_DIR").is_some_and(|d| Path::new(&d).join("bus").exists());
    let zenity = set("PATH").is_some_and(|p| std::env::split_paths(&p).any(|d| d.join("zenity").is_file()));
    (!session_bus && !zenity)
        .then(|| "no file dialog here (no D-Bus session bus for the desktop portal, and no zenity)".to_string())
}

#[derive(Debug)]
pub struct Dialogs {
    export_open: bool,
    export_view: ExportView,
    export_path: PathField,
    /// Why "Browse…" of "Save image" gave nothing, shown in that window.
    export_error: Option<String>,
    /// A typed path instead of a system dialog.
    path_prompt: Option<PathPrompt>,
    /// What to do once the user answered "unsaved changes".
    unsaved: Option<Then>,
    /// Why the system's file dialogs cannot be used here (`None`: try them).
    system_unavailable: Option<String>,
    /// A scene or model file dropped on the window, opened next frame.
    pub pending_open: Option<PathBuf>,
}

impl Dialogs {
    /// `no_system_dialogs`: why the system's file dialogs must not be used (tests); otherwise
    /// whether they can open is found out here and at each use.
    pub fn new(no_system_dialogs: Option<String>) -> Self {
        Self {
            export_open: false,
            export_view: ExportView::All,
            export_path: PathField::default(),
            export_error: None,
            path_prompt: None,
            unsaved: None,
            system_unavailable: no_system_dialogs.or_else(|| dialogs_unavailable(|v| std::env::var_os(v))),
            pending_open: None,
        }
    }

    /// Runs a system file dialog, telling a failure from a cancel.
    fn pick(&self, dialog: impl FnOnce() -> Option<PathBuf>) -> Picked {
        if let Some(why) = &self.system_unavailable {
            return Picked::Failed(why.clone());
        }
        let start = Instant::now();
        match dialog() {
            Some(p) => Picked::File(p),
            None if start.elapsed() < NOT_SHOWN => {
                Picked::Failed("the system file dialog did not open (no desktop portal or zenity?)".into())
            }
            None => Picked::Cancelled,
        }
    }

    /// The system's "open" dialog for a scene file or a model (opened like a scene, see
    /// `scene::load_scene`).
    pub fn pick_scene(&self) -> Picked {
        self.pick(|| {
            rfd::FileDialog::new()
                .add_filter("Scenes and models", &SCENE_EXTENSIONS)
                .add_filter("Glint scene", &["toml"])
                .add_filter("glTF 2.0 model", &["gltf", "glb"])
                .add_filter("Wavefront OBJ model", &["obj"])
                .pick_file()
        })
    }

    /// The system's "save" dialog for a scene file, suggesting one named after `scene`.
    pub fn pick_scene_to_save(&self, scene: &str) -> Picked {
        self.pick(|| {
            rfd::FileDialog::new()
                .add_filter("Glint scene", &["toml"])
                .set_file_name(format!("{scene}.toml"))
                .save_file()
        })
    }

    /// Asks for a path in a window of the app, saying why (`why`: the system dialog failed);
    /// `then_open`: what to open after saving.
    pub fn prompt_path(&mut self, purpose: PathPurpose, suggestion: String, why: String, then_open: Option<Then>) {
        let field = PathField { text: suggestion, ..PathField::default() };
        self.path_prompt = Some(PathPrompt { purpose, field, why, then_open });
    }

    /// The typed-path window (when open); returns the path when the user confirmed it, with
    /// what to open after saving.
    pub fn path_window(&mut self, ctx: &egui::Context) -> Option<(PathPurpose, PathBuf, Option<Then>)> {
        let prompt = self.path_prompt.as_mut()?;
        let purpose = prompt.purpose;
        let mut open = true;
        let mut confirmed = false;
        let mut cancelled = false;
        egui::Window::new(purpose.title()).open(&mut open).collapsible(false).show(ctx, |ui| {
            ui.colored_label(ui.visuals().warn_fg_color, format!("{}: type the path instead.", prompt.why));
            let hint = if purpose == PathPurpose::OpenScene { "scene.toml, model.glb, …" } else { "scene.toml" };
            confirmed = prompt.field.ui(ui, "Path", hint, purpose.extensions());
            ui.horizontal(|ui| {
                let ready = !prompt.field.text.trim().is_empty();
                confirmed |= ui.add_enabled(ready, egui::Button::new(purpose.button())).clicked();
                cancelled = ui.button("Cancel").clicked();
            });
        });
        let path = prompt.field.text.trim().to_string();
        if !open || cancelled {
            self.path_prompt = None;
            return None;
        }
        if confirmed && !path.is_empty() {
            let then_open = self.path_prompt.take().and_then(|p| p.then_open);
            return Some((purpose, PathBuf::from(path), then_open));
        }
        None
    }

    /// Asks "unsaved changes" before `target` (another scene, or quitting).
    pub fn confirm_unsaved(&mut self, target: Then) {
        self.unsaved = Some(target);
    }

    /// Whether "unsaved changes" is being asked.
    pub fn asking_unsaved(&self) -> bool {
        self.unsaved.is_some()
    }

    /// Escape: closes the typed-path window, else "Save image", as their Cancel or close button
    /// would (nothing typed there is applied); whether one was open. "Unsaved changes" answers
    /// Escape itself, as Cancel.
    pub fn close_on_escape(&mut self) -> bool {
        if self.path_prompt.take().is_some() {
            return true;
        }
        std::mem::take(&mut self.export_open)
    }

    /// The "unsaved changes" window (when asked) over the document `name`; returns the answer
    /// with what waited for it.
    pub fn unsaved_window(&mut self, ctx: &egui::Context, name: &str) -> Option<(Unsaved, Then)> {
        let target = self.unsaved.as_ref()?;
        let mut answer = None;
        let modal = egui::Modal::new(egui::Id::unique("unsaved changes")).show(ctx, |ui| {
            ui.heading("Unsaved changes");
            let before = match target {
                Then::Open(t) => format!("opening {t}"),
                Then::Quit => "quitting".to_string(),
            };
            ui.label(format!("“{name}” has edits that are not saved. Save them before {before}?"));
            ui.horizontal(|ui| {
                for (text, a) in [("Save", Unsaved::Save), ("Discard", Unsaved::Discard), ("Cancel", Unsaved::Cancel)] {
                    if ui.button(text).clicked() {
                        answer = Some(a);
                    }
                }
            });
        });
        // Escape or a click beside the window keeps the edits, as Cancel does.
        let answer = answer.or_else(|| modal.should_close().then_some(Unsaved::Cancel))?;
        self.unsaved.take().map(|t| (answer, t))
    }

    /// Opens "Save image", with a view of the mode on screen chosen: from Whitted vs GI its
    /// three side by side (it offered the GPU−CPU views' "All three" there, and a tester saved
    /// the magma GPU−CPU map from the signed Whitted − GI view), else the last choice of the
    /// other views.
    pub fn open_export(&mut self, gi_view: bool) {
        self.export_open = true;
        if gi_view && !self.export_view.is_gi() {
            self.export_view = ExportView::WhittedVsGi;
        } else if !gi_view && self.export_view.is_gi() {
            self.export_view = ExportView::All;
        }
    }

    /// Opens "Save image" from the keyboard (Ctrl+S), suggesting a file named after `scene`.
    pub fn export_shortcut(&mut self, ctx: &egui::Context, scene: &str, gi_view: bool) {
        if ctx.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, egui::Key::S)) {
            self.open_export(gi_view);
            if self.export_path.text.is_empty() {
                self.export_path.text = format!("{scene}.png");
            }
        }
    }

    /// Closes "Save image" (after its image was saved).
    pub fn close_export(&mut self) {
        self.export_open = false;
    }

    /// Remembers a scene or model file dropped on the window, to be opened.
    pub fn take_dropped_file(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| {
            i.raw.dropped_files.iter().find_map(|f| {
                let p = f.path();
                (!p.as_os_str().is_empty()).then(|| p.to_path_buf())
            })
        });
        if let Some(p) = dropped {
            self.pending_open = Some(p);
        }
    }

    /// The "Save image" window (when open); returns the file and view to save when the user
    /// pressed Save, and why "Browse…" failed when it did (for the messages panel too).
    pub fn export_window(
        &mut self,
        ctx: &egui::Context,
        scene: &str,
    ) -> (Option<(PathBuf, ExportView)>, Option<String>) {
        if !self.export_open {
            return (None, None);
        }
        let mut open = true;
        let mut save = false;
        let mut browse = false;
        egui::Window::new("Save image").open(&mut open).collapsible(false).resizable(false).show(ctx, |ui| {
            for v in ExportView::ALL {
                ui.radio_value(&mut self.export_view, v, v.label());
            }
            save = self.export_path.ui(ui, "File", "image.png or image.exr", &IMAGE_EXTENSIONS);
            browse = ui.button("Browse…").clicked();
            if let Some(e) = &self.export_error {
                ui.colored_label(ui.visuals().error_fg_color, format!("{e}: type the path above."));
            }
            ui.weak("PNG: sRGB with the render settings as metadata. EXR: linear radiance.");
            let ready = !self.export_path.text.trim().is_empty();
            save |= ui.add_enabled(ready, egui::Button::new("Save")).clicked();
        });
        let mut failed = None;
        if browse {
            let picked = self.pick(|| {
                rfd::FileDialog::new()
                    .add_filter("PNG (settings embedded)", &["png"])
                    .add_filter("OpenEXR (linear)", &["exr"])
                    .set_file_name(format!("{scene}.png"))
                    .save_file()
            });
            match picked {
                Picked::File(p) => self.export_path.text = p.display().to_string(),
                Picked::Cancelled => {}
                Picked::Failed(why) => {
                    self.export_error = Some(why.clone());
                    failed = Some(why);
                }
            }
        }
        self.export_open = open;
        let path = self.export_path.text.trim();
        let chosen = (save && !path.is_empty()).then(|| (PathBuf::from(path), self.export_view));
        (chosen, failed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn completions_list_the_folders_and_the_matching_files_of_the_typed_folder() {
        let dir = std::env::temp_dir().join(format!("glint-completions-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        for f in ["a.toml", "b.GLB", "c.gltf", "d.obj", "notes.txt", ".hidden.toml"] {
            std::fs::write(dir.join(f), "").unwrap();
        }
        let base = format!("{}{}", dir.display(), std::path::MAIN_SEPARATOR);
        let names = |text: &str, ext: &[&str]| -> Vec<String> {
            completions(text, ext).into_iter().map(|c| c[base.len()..].to_string()).collect()
        };
        let sep = std::path::MAIN_SEPARATOR;
        assert_eq!(names(&base, &SCENE_EXTENSIONS), ["a.toml", "b.GLB", "c.gltf", "d.obj", &format!("sub{sep}")]);
        assert_eq!(names(&format!("{base}c"), &SCENE_EXTENSIONS), ["c.gltf"]);
        assert_eq!(names(&format!("{base}."), &SCENE_FILE_EXTENSIONS), [".hidden.toml"]);
        assert!(completions(&format!("{base}missing{sep}"), &SCENE_EXTENSIONS).is_empty());
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn without_a_session_bus_or_zenity_the_dialogs_are_known_to_fail() {
        if cfg!(any(target_os = "windows", target_os = "macos")) {
            return;
        }
        let none = |_: &str| None;
        assert!(dialogs_unavailable(none).is_some());
        let bus = |v: &str| (v == "DBUS_SESSION_BUS_ADDRESS").then(|| OsString::from("unix:path=/run/bus"));
        assert!(dialogs_unavailable(bus).is_none());
        let dir = std::env::temp_dir().join(format!("glint-zenity-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("zenity"), "").unwrap();
        let path = |v: &str| (v == "PATH").then(|| dir.clone().into_os_string());
        assert!(dialogs_unavailable(path).is_none());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
