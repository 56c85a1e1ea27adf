//! The File menu's flow on the app: open, save, save as and quit, each through "unsaved
//! changes" while the scene has edits, and a signal's quit (Ctrl+C, SIGTERM) as File → Quit.

use std::path::Path;

use super::ViewerApp;
use crate::dialogs::{PathPurpose, Picked, Then, Unsaved};
use crate::menu::MenuAction;
use crate::view::ViewMode;

impl ViewerApp {
    pub(super) fn apply_menu_action(&mut self, action: MenuAction) {
        match action {
            MenuAction::OpenDialog => self.open_dialog(),
            MenuAction::Open(p) => self.request_open(&p.display().to_string()),
            MenuAction::OpenBuiltin(name) => self.request_open(name),
            MenuAction::Save(p) => self.save_scene(&p),
            MenuAction::SaveAs => self.save_as(None),
            MenuAction::SaveImage => self.dialogs.open_export(self.layout.mode == ViewMode::WhittedVsGi),
            MenuAction::Quit => self.request_quit(),
            MenuAction::Undo => self.step_history(false),
            MenuAction::Redo => self.step_history(true),
        }
    }

    /// "Open scene…": the system dialog, or a typed path (starting in the document's folder)
    /// where it cannot open.
    fn open_dialog(&mut self) {
        match self.dialogs.pick_scene() {
            Picked::File(p) => self.request_open(&p.display().to_string()),
            Picked::Cancelled => {}
            Picked::Failed(why) => {
                let folder = self.doc.source.as_deref().and_then(Path::parent).filter(|p| !p.as_os_str().is_empty());
                let start =
                    folder.map_or_else(String::new, |f| format!("{}{}", f.display(), std::path::MAIN_SEPARATOR));
                self.message = Some(why.clone());
                self.dialogs.prompt_path(PathPurpose::OpenScene, start, why, None);
            }
        }
    }

    /// "Save scene as…": the system dialog, or a typed path where it cannot open; then opens
    /// `then_open` if the scene was saved.
    fn save_as(&mut self, then_open: Option<Then>) {
        match self.dialogs.pick_scene_to_save(&self.doc.name) {
            Picked::File(p) => self.save_then_open(&p, then_open),
            Picked::Cancelled => {}
            Picked::Failed(why) => {
                let suggestion = match &self.doc.path {
                    Some(p) => p.display().to_string(),
                    None => format!("{}.toml", self.doc.name),
                };
                self.message = Some(why.clone());
                self.dialogs.prompt_path(PathPurpose::SaveSceneAs, suggestion, why, then_open);
            }
        }
    }

    pub(super) fn save_then_open(&mut self, path: &Path, then: Option<Then>) {
        self.save_scene(path);
        if !self.doc.dirty
            && let Some(t) = then
        {
            self.then(t);
        }
    }

    /// Opens the scene or quits, once "unsaved changes" was answered.
    pub(super) fn then(&mut self, then: Then) {
        match then {
            Then::Open(t) => self.open(&t),
            Then::Quit => self.quit(),
        }
    }

    /// Closes the window, without asking again.
    fn quit(&mut self) {
        self.quitting = true;
        self.close_pending = true;
    }

    /// File → Quit: asks "unsaved changes" first while the scene has edits.
    pub fn request_quit(&mut self) {
        if self.doc.dirty {
            self.dialogs.confirm_unsaved(Then::Quit);
        } else {
            self.quit();
        }
    }

    /// A SIGINT or SIGTERM (Ctrl+C in the terminal, `kill`) quits as File → Quit does, asking
    /// first while the scene has edits; a second signal then ends the process at once, as the
    /// CLI's does. Woken by `crate::signal_watch`.
    pub(super) fn answer_signal(&mut self) {
        let raised = glint_io::interrupt::requested();
        if raised && !self.signal_answered {
            log::info!("a signal asked the viewer to quit");
            self.request_quit();
        }
        self.signal_answered = raised;
    }

    /// The answer to "unsaved changes" before `target`.
    pub(super) fn apply_unsaved(&mut self, answer: Unsaved, target: Then) {
        if matches!(answer, Unsaved::Save | Unsaved::Cancel) {
            // The user took over from a signal's quit: go on (a save must not be stopped by it).
            glint_io::interrupt::withdraw();
        }
        match answer {
            Unsaved::Save => match self.doc.path.clone() {
                Some(p) => self.save_then_open(&p, Some(target)),
                None => self.save_as(Some(target)),
            },
            Unsaved::Discard => self.then(target),
            Unsaved::Cancel => {}
        }
    }

    /// A request to close the window (File → Quit, the window's close button, the window
    /// manager): held back to ask "unsaved changes" while the scene has edits, unless a
    /// scripted run (`--screenshot`, the drag benchmark) closes it.
    pub(super) fn hold_close_for_unsaved_edits(&mut self, ctx: &egui::Context) {
        let requested = ctx.input(|i| i.viewport().close_requested());
        if requested && self.doc.dirty && !self.quitting && !self.automation.active() {
            ctx.send_viewport_cmd(egui::ViewportCommand::CancelClose);
            if !self.dialogs.asking_unsaved() {
                self.dialogs.confirm_unsaved(Then::Quit);
            }
        }
    }
}
