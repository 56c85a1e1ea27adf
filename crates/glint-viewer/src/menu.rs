//! The menu bar: files (open, recent, built-in, save, save as, save image, quit), undo and redo,
//! view and help.

use std::path::PathBuf;

use egui::Ui;
use glint_io::BUILTIN_SCENES;

use crate::document::Document;
use crate::layout::Layout;
use crate::recent::Recent;
use crate::undo::EditHistory;
use crate::view::ViewMode;

/// What a menu item asks the app to do (the view settings the menu changes itself).
#[derive(Clone, Debug, PartialEq)]
pub enum MenuAction {
    /// The system's "open" dialog (or a typed path).
    OpenDialog,
    /// Open this scene or model file.
    Open(PathBuf),
    OpenBuiltin(&'static str),
    Save(PathBuf),
    SaveAs,
    SaveImage,
    /// Quit, asking first while the scene has unsaved edits.
    Quit,
    Undo,
    Redo,
}

pub fn bar(
    ui: &mut Ui,
    doc: &Document,
    recent: &Recent,
    edits: &EditHistory,
    layout: &mut Layout,
) -> Option<MenuAction> {
    let mut action = None;
    egui::MenuBar::new().ui(ui, |ui| {
        ui.menu_button("File", |ui| {
            if ui.button("Open scene…").clicked() {
                action = Some(MenuAction::OpenDialog);
            }
            ui.menu_button("Recent files", |ui| {
                if recent.files.is_empty() {
                    ui.weak("none yet");
                }
                for f in &recent.files {
                    if ui.button(f.display().to_string()).clicked() {
                        action = Some(MenuAction::Open(f.clone()));
                    }
                }
            });
            ui.menu_button("Built-in scenes", |ui| {
                for b in BUILTIN_SCENES {
                    if ui.button(b.name).clicked() {
                        action = Some(MenuAction::OpenBuiltin(b.name));
                    }
                }
            });
            ui.separator();
            if ui.add_enabled(doc.path.is_some(), egui::Button::new("Save scene")).clicked()
                && let Some(p) = doc.path.clone()
            {
                action = Some(MenuAction::Save(p));
            }
            if ui.button("Save scene as…").clicked() {
                action = Some(MenuAction::SaveAs);
            }
            if ui.button("Save image…  (Ctrl+S)").clicked() {
                action = Some(MenuAction::SaveImage);
            }
            ui.separator();
            if ui.button("Quit").clicked() {
                action = Some(MenuAction::Quit);
            }
        });
        ui.menu_button("Edit", |ui| {
            // Named by what they take back, as the side panel names it ("Undo Materials › red").
            let undo = edits.undo_label(doc);
            let text = undo.as_ref().map_or("Undo".into(), |what| format!("Undo {what}"));
            if ui.add_enabled(undo.is_some(), egui::Button::new(text).shortcut_text("Ctrl+Z")).clicked() {
                action = Some(MenuAction::Undo);
            }
            let redo = edits.redo_label(doc);
            let text = redo.as_ref().map_or("Redo".into(), |what| format!("Redo {what}"));
            if ui.add_enabled(redo.is_some(), egui::Button::new(text).shortcut_text("Ctrl+Shift+Z")).clicked() {
                action = Some(MenuAction::Redo);
            }
        });
        ui.menu_button("View", |ui| {
            for m in ViewMode::ALL {
                ui.radio_value(&mut layout.mode, m, m.label());
            }
            ui.checkbox(&mut layout.show_gizmos, "Light gizmos");
            ui.checkbox(&mut layout.show_ray_tree, "Ray tree overlay");
            ui.checkbox(&mut layout.show_side_panel, "Side panel (F9)");
        });
        if let Some(window) = crate::help::menu(ui) {
            layout.help = window;
        }
        ui.separator();
        let dirty = if doc.dirty { " (edited)" } else { "" };
        ui.label(format!("{}{dirty}", doc.name));
    });
    action
}
