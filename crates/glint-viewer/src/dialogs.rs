//! The dialogs: "Save image" (a window of the app), the system's file pickers, and a scene
//! file dropped on the window.

use std::path::PathBuf;

use crate::export::ExportView;

#[derive(Debug)]
pub struct Dialogs {
    export_open: bool,
    export_view: ExportView,
    export_path: String,
    /// A scene file dropped on the window or chosen in a dialog, loaded next frame.
    pub pending_open: Option<PathBuf>,
}

impl Default for Dialogs {
    fn default() -> Self {
        Self { export_open: false, export_view: ExportView::All, export_path: String::new(), pending_open: None }
    }
}

impl Dialogs {
    /// Opens "Save image".
    pub fn open_export(&mut self) {
        self.export_open = true;
    }

    /// Opens "Save image" from the keyboard (Ctrl+S), suggesting a file named after `scene`.
    pub fn export_shortcut(&mut self, ctx: &egui::Context, scene: &str) {
        if ctx.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, egui::Key::S)) {
            self.export_open = true;
            if self.export_path.is_empty() {
                self.export_path = format!("{scene}.png");
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
    /// pressed Save.
    pub fn export_window(&mut self, ctx: &egui::Context, scene: &str) -> Option<(PathBuf, ExportView)> {
        if !self.export_open {
            return None;
        }
        let mut open = true;
        let mut save = false;
        egui::Window::new("Save image").open(&mut open).collapsible(false).resizable(false).show(ctx, |ui| {
            for v in ExportView::ALL {
                ui.radio_value(&mut self.export_view, v, v.label());
            }
            ui.horizontal(|ui| {
                let label = ui.label("File");
                ui.add(egui::TextEdit::singleline(&mut self.export_path).hint_text("image.png or image.exr"))
                    .labelled_by(label.id);
                if ui.button("Browse…").clicked()
                    && let Some(p) = rfd::FileDialog::new()
                        .add_filter("PNG (settings embedded)", &["png"])
                        .add_filter("OpenEXR (linear)", &["exr"])
                        .set_file_name(format!("{scene}.png"))
                        .save_file()
                {
                    self.export_path = p.display().to_string();
                }
            });
            ui.weak("PNG: sRGB with the render settings as metadata. EXR: linear radiance.");
            save = ui.add_enabled(!self.export_path.trim().is_empty(), egui::Button::new("Save")).clicked();
        });
        self.export_open = open;
        save.then(|| (PathBuf::from(self.export_path.trim()), self.export_view))
    }
}

/// The system's "open" dialog for a scene file or a model (opened like a scene, see
/// `scene::load_scene`).
pub fn pick_scene() -> Option<PathBuf> {
    rfd::FileDialog::new()
        .add_filter("Scenes and models", &["toml", "gltf", "glb", "obj"])
        .add_filter("Glint scene", &["toml"])
        .add_filter("glTF 2.0 model", &["gltf", "glb"])
        .add_filter("Wavefront OBJ model", &["obj"])
        .pick_file()
}

/// The system's "save" dialog for a scene file, suggesting one named after `scene`.
pub fn pick_scene_to_save(scene: &str) -> Option<PathBuf> {
    rfd::FileDialog::new().add_filter("Glint scene", &["toml"]).set_file_name(format!("{scene}.toml")).save_file()
}
