//! Undo and redo of the scene's edits (Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y, and the Edit menu).
//!
//! An edit is committed as one step once the scene has stood still for a moment with no button
//! held and no field being typed into: a drag of a value or of the camera, a scroll of the
//! zoom or a value typed and entered is one step, not one per frame. The steps hold what the
//! viewer edits (the render settings, camera, world, materials and lights); the objects are
//! never edited in the viewer, so an undo leaves them, and a million triangles are not copied
//! per step.

use glint_scene::{CameraDesc, LightDesc, MaterialDesc, RenderSettings, WorldDesc};
use std::collections::BTreeMap;

use crate::document::{Document, light_label};
use crate::light_kind::SetAside;

/// Seconds a scene stands still before its edit is a step of its own (a scroll of the zoom
/// moves it a notch at a time).
const STILL_SECONDS: f64 = 0.4;

/// The most steps kept each way; the oldest go first.
const MAX_STEPS: usize = 200;

/// What an undo gives back: every part of the scene the viewer edits.
#[derive(Clone, Debug, PartialEq)]
struct SceneState {
    render: RenderSettings,
    camera: CameraDesc,
    world: WorldDesc,
    materials: BTreeMap<String, MaterialDesc>,
    lights: Vec<LightDesc>,
    light_set_aside: Vec<SetAside>,
}

impl SceneState {
    fn of(doc: &Document) -> Self {
        let d = &doc.desc;
        // One entry per light, as the Lights panel pads it when drawn (no edit): a list not yet
        // padded is the same state.
        let mut light_set_aside = doc.light_set_aside.clone();
        light_set_aside.resize_with(d.lights.len(), SetAside::default);
        Self {
            render: d.render.clone(),
            camera: d.camera.clone(),
            world: d.world.clone(),
            materials: d.materials.clone(),
            lights: d.lights.clone(),
            light_set_aside,
        }
    }

    fn apply(&self, doc: &mut Document) {
        let d = &mut doc.desc;
        d.render = self.render.clone();
        d.camera = self.camera.clone();
        d.world = self.world.clone();
        d.materials = self.materials.clone();
        d.lights = self.lights.clone();
        doc.light_set_aside = self.light_set_aside.clone();
    }

    /// What tells `self` from `other`, as the side panel names it with `self` on screen:
    /// "Camera", "Materials › red", "Lights › point 0" (the first that differs, "and N more" for
    /// the rest).
    fn changed_from(&self, other: &Self) -> String {
        let mut parts = Vec::new();
        if self.render != other.render {
            parts.push("Render settings".to_string());
        }
        if self.camera != other.camera {
            parts.push("Camera".to_string());
        }
        if self.world != other.world {
            parts.push("World".to_string());
        }
        let names: std::collections::BTreeSet<&String> = self.materials.keys().chain(other.materials.keys()).collect();
        for name in names {
            if self.materials.get(name) != other.materials.get(name) {
                parts.push(format!("Materials › {name}"));
            }
        }
        if self.lights.len() == other.lights.len() {
            for i in 0..self.lights.len() {
                if self.lights[i] != other.lights[i] {
                    parts.push(format!("Lights › {}", light_label(&self.lights, i)));
                }
            }
        } else {
            parts.push("Lights".to_string());
        }
        match parts.len() {
            0 => "a light's set-aside fields".to_string(),
            1 => parts.remove(0),
            n => format!("{} and {} more", parts[0], n - 1),
        }
    }
}

/// The viewer's undo and redo steps of one opened scene.
#[derive(Debug)]
pub struct EditHistory {
    /// The states before each step, the latest last.
    undo: Vec<SceneState>,
    /// The states undone, the latest undone last.
    redo: Vec<SceneState>,
    /// The scene as the last step left it (as opened before any).
    base: SceneState,
    /// The document's revision `base` was taken at: a later one is an edit not yet a step.
    base_revision: u64,
    /// The document's revision when it last moved, and the time then (egui's input time).
    moved: (u64, f64),
    /// The state last saved, or as opened: after an undo or redo the document has unsaved
    /// edits unless it is back there.
    saved: Option<SceneState>,
}

impl EditHistory {
    /// The history of `doc` as it is now (opened or saved: nothing to undo).
    pub fn new(doc: &Document) -> Self {
        let base = SceneState::of(doc);
        let saved = (!doc.dirty).then(|| base.clone());
        Self {
            undo: Vec::new(),
            redo: Vec::new(),
            base,
            base_revision: doc.revision,
            moved: (doc.revision, 0.0),
            saved,
        }
    }

    /// Called once a frame, after the frame's edits: commits an edit as a step once the scene
    /// has stood still for `STILL_SECONDS` at `now` while `settled` (no button held, no field
    /// being typed into).
    pub fn track(&mut self, doc: &Document, now: f64, settled: bool) {
        if doc.revision != self.moved.0 {
            self.moved = (doc.revision, now);
        }
        if doc.revision != self.base_revision && settled && now - self.moved.1 >= STILL_SECONDS {
            self.commit(doc);
        }
    }

    /// The scene was saved as it is now: its edits so far are a step, and that state is the
    /// one an undo or redo finds nothing unsaved in. Said by the save, not read from
    /// `doc.dirty` (a save between two quick edits, merged into one step, left the state as
    /// opened marked saved).
    pub fn saved(&mut self, doc: &Document) {
        self.commit(doc);
        self.saved = Some(self.base.clone());
    }

    /// Makes the edits since the last step a step of their own (none when they changed nothing
    /// an undo gives back: a value dragged away and back, or a view change that left the scene
    /// as it was).
    fn commit(&mut self, doc: &Document) {
        if doc.revision == self.base_revision {
            return;
        }
        self.base_revision = doc.revision;
        let state = SceneState::of(doc);
        if state == self.base {
            return;
        }
        let before = std::mem::replace(&mut self.base, state);
        push_bounded(&mut self.undo, before);
        self.redo.clear();
    }

    /// What an undo would take back ("Camera", "Materials › red"), if anything; an edit not
    /// yet a step counts.
    pub fn undo_label(&self, doc: &Document) -> Option<String> {
        if doc.revision != self.base_revision {
            let now = SceneState::of(doc);
            if now != self.base {
                return Some(now.changed_from(&self.base));
            }
        }
        self.undo.last().map(|before| self.base.changed_from(before))
    }

    /// What a redo would give back, if anything.
    pub fn redo_label(&self, doc: &Document) -> Option<String> {
        if doc.revision != self.base_revision && SceneState::of(doc) != self.base {
            return None;
        }
        self.redo.last().map(|after| self.base.changed_from(after))
    }

    /// Takes the last step back; false when there is none. `view` holds what the view
    /// forces on the scene (Whitted vs GI's paths): applied to the state given back, it is no
    /// edit of its own, which would end the redo steps and undo the same step again.
    pub fn undo(&mut self, doc: &mut Document, view: impl Fn(&mut Document)) -> bool {
        self.commit(doc);
        let Some(before) = self.undo.pop() else { return false };
        let after = std::mem::replace(&mut self.base, before);
        push_bounded(&mut self.redo, after);
        self.restore(doc, view);
        true
    }

    /// Gives back the last step undone; false when there is none (or an edit since).
    pub fn redo(&mut self, doc: &mut Document, view: impl Fn(&mut Document)) -> bool {
        self.commit(doc);
        let Some(after) = self.redo.pop() else { return false };
        let before = std::mem::replace(&mut self.base, after);
        push_bounded(&mut self.undo, before);
        self.restore(doc, view);
        true
    }

    fn restore(&mut self, doc: &mut Document, view: impl Fn(&mut Document)) {
        self.base.apply(doc);
        view(doc);
        self.base = SceneState::of(doc);
        doc.edited();
        doc.dirty = self.saved.as_ref() != Some(&self.base);
        self.base_revision = doc.revision;
        self.moved.0 = doc.revision;
    }
}

fn push_bounded(steps: &mut Vec<SceneState>, state: SceneState) {
    if steps.len() == MAX_STEPS {
        steps.remove(0);
    }
    steps.push(state);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn whitted() -> Document {
        Document::load("whitted").expect("built-in scene")
    }

    /// Sets the first material's red k_d and records the edit, as a panel does.
    fn set_kd(doc: &mut Document, value: f64) {
        doc.desc.materials.values_mut().next().unwrap().kd.0[0] = value;
        doc.edited();
    }

    fn kd(doc: &Document) -> f64 {
        doc.desc.materials.values().next().unwrap().kd.0[0]
    }

    #[test]
    fn a_drag_is_one_step_and_undo_and_redo_walk_the_steps() {
        let mut doc = whitted();
        let first = kd(&doc);
        let mut history = EditHistory::new(&doc);
        assert_eq!(history.undo_label(&doc), None);
        // A drag: an edit every frame with the button held, then still.
        for (frame, value) in [0.1, 0.2, 0.3].into_iter().enumerate() {
            set_kd(&mut doc, value);
            history.track(&doc, frame as f64 * 0.016, false);
        }
        history.track(&doc, 1.0, true);
        doc.desc.camera.fov_y += 5.0;
        doc.edited();
        history.track(&doc, 2.0, true);
        history.track(&doc, 3.0, true);
        let material = doc.desc.materials.keys().next().unwrap().clone();
        assert_eq!(history.undo_label(&doc).as_deref(), Some("Camera"));

        assert!(history.undo(&mut doc, |_| {}));
        assert_eq!(kd(&doc), 0.3, "the camera step alone goes");
        assert_eq!(history.undo_label(&doc), Some(format!("Materials › {material}")));
        assert_eq!(history.redo_label(&doc).as_deref(), Some("Camera"));
        assert!(history.undo(&mut doc, |_| {}));
        assert_eq!(kd(&doc), first, "the whole drag goes at once");
        assert!(!doc.dirty, "back as opened: nothing unsaved");
        assert!(!history.undo(&mut doc, |_| {}), "nothing before the scene as opened");

        assert!(history.redo(&mut doc, |_| {}));
        assert!(history.redo(&mut doc, |_| {}));
        assert_eq!((kd(&doc), doc.dirty), (0.3, true));
        assert!(!history.redo(&mut doc, |_| {}));
    }

    #[test]
    fn an_edit_not_yet_still_is_undone_at_once_and_ends_the_redo_steps() {
        let mut doc = whitted();
        let first = kd(&doc);
        let mut history = EditHistory::new(&doc);
        set_kd(&mut doc, 0.5);
        history.track(&doc, 0.0, true);
        assert!(history.undo_label(&doc).is_some(), "an edit not yet a step can be undone");
        assert!(history.undo(&mut doc, |_| {}));
        assert_eq!(kd(&doc), first);
        set_kd(&mut doc, 0.7);
        assert_eq!(history.redo_label(&doc), None, "an edit after an undo ends what it undid");
        assert!(!history.redo(&mut doc, |_| {}));
        assert_eq!(kd(&doc), 0.7);
    }

    #[test]
    fn undoing_to_the_saved_state_leaves_nothing_unsaved() {
        let mut doc = whitted();
        let mut history = EditHistory::new(&doc);
        set_kd(&mut doc, 0.5);
        history.track(&doc, 1.0, true);
        // Saved here (as `Document::save` does, without an edit).
        doc.dirty = false;
        history.saved(&doc);
        set_kd(&mut doc, 0.6);
        history.track(&doc, 3.0, true);
        assert!(history.undo(&mut doc, |_| {}));
        assert_eq!((kd(&doc), doc.dirty), (0.5, false), "back at the saved scene");
        assert!(history.undo(&mut doc, |_| {}));
        assert!(doc.dirty, "the scene as opened is not the one saved");
    }

    #[test]
    fn steps_are_bounded_and_name_what_they_change() {
        let mut doc = whitted();
        let mut history = EditHistory::new(&doc);
        for i in 0..MAX_STEPS + 10 {
            set_kd(&mut doc, i as f64 / 1000.0);
            history.track(&doc, 10.0 * i as f64, true);
            history.track(&doc, 10.0 * i as f64 + 2.0 * STILL_SECONDS, true);
        }
        let mut undone = 0;
        while history.undo(&mut doc, |_| {}) {
            undone += 1;
        }
        assert_eq!(undone, MAX_STEPS);
        assert_eq!(kd(&doc), 9.0 / 1000.0, "the oldest steps went first");

        doc.desc.lights[0].diffuse.0[0] *= 0.5;
        doc.desc.camera.fov_y += 1.0;
        doc.edited();
        let label = history.undo_label(&doc).unwrap();
        assert_eq!(label, "Camera and 1 more");
        doc.desc.camera.fov_y -= 1.0;
        doc.edited();
        assert_eq!(history.undo_label(&doc), Some(format!("Lights › {}", doc.light_label(0))));
    }

    #[test]
    fn what_the_view_forces_is_no_step_and_keeps_the_redo_steps() {
        use glint_scene::Integrator;
        let mut doc = whitted();
        let mut history = EditHistory::new(&doc);
        // Whitted vs GI switches the scene to paths: a step, as any edit of the integrator.
        doc.desc.render.integrator = Integrator::Path;
        doc.edited();
        history.track(&doc, 1.0, true);
        history.track(&doc, 1.5, true);
        set_kd(&mut doc, 0.5);
        history.track(&doc, 2.0, true);
        history.track(&doc, 3.0, true);
        let paths = |d: &mut Document| d.desc.render.integrator = Integrator::Path;
        assert!(history.undo(&mut doc, paths));
        assert!(history.undo(&mut doc, paths));
        assert_eq!(doc.desc.render.integrator, Integrator::Path, "the view's paths stay");
        history.track(&doc, 4.0, true);
        history.track(&doc, 5.0, true);
        assert!(history.undo_label(&doc).is_none(), "nothing before the scene as opened");
        assert!(history.redo(&mut doc, paths) && history.redo(&mut doc, paths), "both redo steps kept");
        assert_eq!(kd(&doc), 0.5);
    }

    #[test]
    fn a_save_between_two_quick_edits_is_the_saved_state() {
        let mut doc = whitted();
        let mut history = EditHistory::new(&doc);
        set_kd(&mut doc, 0.5);
        history.track(&doc, 0.0, true);
        doc.dirty = false;
        history.saved(&doc);
        set_kd(&mut doc, 0.6);
        history.track(&doc, 0.1, true);
        history.track(&doc, 1.0, true);
        assert!(history.undo(&mut doc, |_| {}));
        assert_eq!((kd(&doc), doc.dirty), (0.5, false), "the file on disk holds 0.5");
        assert!(history.undo(&mut doc, |_| {}));
        assert!(doc.dirty, "the scene as opened is not the one saved");
    }
}
