//! The scene being edited: its description, where it came from, and a revision number that
//! every edit bumps (renders are keyed by it, so a stale result is never shown as current).

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};

use glint_core::FlatScene;
use glint_io::ModelFormat;
use glint_io::atomic::{AtomicWriteError, write_file_atomically};
use glint_io::{LoadOptions, LoadedScene, load_scene_with, to_toml};
use glint_scene::{
    CameraDesc, FieldIssue, ObjectDesc, Report, SceneDesc, validate, validate_objects, validate_with_objects,
};

use crate::error::ViewerError;
use crate::light_kind::SetAside;
use crate::render_inputs::{FitInputs, RenderInputs};

#[derive(Clone, Debug)]
pub struct Document {
    pub desc: SceneDesc,
    /// Short name (file stem or built-in name), used in image metadata and file names.
    pub name: String,
    /// The scene file it was loaded from or last saved to, where "Save scene" writes; `None`
    /// for a built-in scene or a model (saving over a model file would destroy it).
    pub path: Option<PathBuf>,
    /// The file it was opened from (a scene or a model), for the recent files.
    pub source: Option<PathBuf>,
    /// Edited since it was loaded or saved.
    pub dirty: bool,
    pub revision: u64,
    /// The revision it was opened at: renders older than it are another scene's.
    pub opened: u64,
    /// The revision of the last edit that could move a first hit (the objects, the camera or
    /// the image's size), and those as it left them: the outline traced through pixel centres
    /// is found again only then, not on every edit of a value dragged.
    pub hits_revision: u64,
    hits_of: Option<(CameraDesc, u32, u32)>,
    /// The revision of the last edit that changed what the render under the scene's own
    /// integrator reads (`RenderInputs`), and that: the renders of the view are keyed by it. In
    /// path mode an ambient edit leaves the paths as they are, and the GPU's mean goes on.
    pub render_revision: u64,
    render_inputs: Option<RenderInputs>,
    /// The revision of the last edit that changed what the ambient fit reads (`FitInputs`):
    /// the world's I_a, applied or typed, leaves a fit current.
    pub fit_revision: u64,
    fit_inputs: Option<FitInputs>,
    /// The camera as loaded, for "Reset camera".
    pub initial_camera: CameraDesc,
    /// Validation problems of the current description; while there are any, the last valid
    /// scene stays on screen.
    pub issues: Vec<FieldIssue>,
    /// Validation's warnings of the current description (an ε as large as the scene, a ray
    /// tree past its bound, what the integrator leaves out): rendered anyway, and said.
    pub warnings: Vec<FieldIssue>,
    /// What the load warned of that validation does not (a model file's import): kept while
    /// the scene is edited.
    pub load_warnings: Vec<FieldIssue>,
    /// Per light, the fields its type lacks that an earlier type had (`light_kind::switch_kind`).
    pub light_set_aside: Vec<SetAside>,
    /// The kinds of path-traced light the view leaves out (`SceneHeader::omit_kinds`): a way of
    /// looking at the scene, not part of it, so never saved.
    pub omit_kinds: u32,
    /// The last flat scene built, with the objects it was built from: while those and the
    /// material names stay the same (a camera, light or material-value edit) its primitives and BVH
    /// are reused instead of rebuilt (`FlatScene::rebuild`).
    geometry: RefCell<Option<BuiltGeometry>>,
    /// The revision `geometry` was last found to be built from the description at (`edited`
    /// compares the objects once per edit; `flat` then need not compare them again).
    geometry_checked: Cell<Option<u64>>,
}

#[derive(Clone, Debug)]
struct BuiltGeometry {
    objects: Vec<ObjectDesc>,
    /// Validation's verdict on those objects (`validate_objects`), and the ε it was judged at:
    /// its coplanar-overlap and stored-contact warnings read ε, so an ε edit judges the objects
    /// again.
    objects_report: Report,
    report_epsilon: f64,
    flat: FlatScene,
}

impl BuiltGeometry {
    /// Whether `desc` has the objects and material names this was built from.
    fn built_from(&self, desc: &SceneDesc) -> bool {
        self.objects == desc.objects && self.flat.material_names.iter().eq(desc.materials.keys())
    }
}

impl Document {
    pub fn from_loaded(loaded: LoadedScene) -> Self {
        let source = loaded.source.to_str().filter(|s| !s.starts_with("builtin:")).map(PathBuf::from);
        let path = source.clone().filter(|p| ModelFormat::of(p).is_none());
        // The loader validated the scene: `warnings` ends with validation's, kept apart too.
        let warnings = loaded.scene_warnings;
        let mut load_warnings = loaded.warnings;
        load_warnings.truncate(load_warnings.len().saturating_sub(warnings.len()));
        // What the renders and a fit of the scene as loaded read: without them the first edit
        // of a scene opened from the menu counted as a change of everything, so applying a
        // fitted I_a started the paths over and called the fit an earlier edit's (a lecturer).
        let render_inputs = Some(RenderInputs::of(&loaded.desc, 0));
        let fit_inputs = Some(FitInputs::of(&loaded.desc));
        Self {
            source,
            initial_camera: loaded.desc.camera.clone(),
            desc: loaded.desc,
            name: loaded.name,
            path,
            dirty: false,
            revision: 0,
            opened: 0,
            hits_revision: 0,
            hits_of: None,
            render_revision: 0,
            render_inputs,
            fit_revision: 0,
            fit_inputs,
            issues: Vec::new(),
            warnings,
            load_warnings,
            light_set_aside: Vec::new(),
            geometry: RefCell::new(None),
            geometry_checked: Cell::new(None),
            omit_kinds: 0,
        }
    }

    /// An empty scene: the last resort if even the built-in scene cannot be loaded.
    pub fn empty() -> Self {
        let desc = SceneDesc {
            description: String::new(),
            provenance: String::new(),
            render: Default::default(),
            camera: CameraDesc::perspective([0.0, 0.0, -5.0], [0.0; 3], [0.0, 1.0, 0.0], 45.0),
            world: Default::default(),
            materials: Default::default(),
            lights: Vec::new(),
            objects: Vec::new(),
        };
        // As a loaded scene with nothing to warn of: one constructor for every field.
        let source = PathBuf::from("builtin:empty");
        Self::from_loaded(LoadedScene { desc, source, name: "empty".into(), warnings: vec![], scene_warnings: vec![] })
    }

    /// Loads a scene file or a built-in scene by name.
    pub fn load(arg: impl AsRef<std::ffi::OsStr>) -> Result<Self, ViewerError> {
        Self::load_with(arg, &LoadOptions::default())
    }

    /// `load` with a generated scene's resolution or a model file's import options.
    pub fn load_with(arg: impl AsRef<std::ffi::OsStr>, options: &LoadOptions) -> Result<Self, ViewerError> {
        Ok(Self::from_loaded(load_scene_with(arg, options)?))
    }

    /// A change of how the scene is looked at (not of the scene): renders again; unsaved
    /// changes, and what was made of the scene as it is (an ambient fit), stay as they were.
    pub fn view_changed(&mut self) {
        let dirty = self.dirty;
        self.edited();
        self.dirty = dirty;
    }

    /// Records an edit: bumps the revision and re-validates.
    pub fn edited(&mut self) {
        self.revision += 1;
        self.dirty = true;
        let mut geometry = self.geometry.borrow_mut();
        // Objects and material names as last built: their part of validation stands (a camera
        // drag over a million triangles re-validated every vertex each frame before).
        let view = Some((self.desc.camera.clone(), self.desc.render.width, self.desc.render.height));
        let same_objects = geometry.as_ref().is_some_and(|g| g.built_from(&self.desc));
        if !same_objects || view != self.hits_of {
            (self.hits_revision, self.hits_of) = (self.revision, view);
        }
        let report = match geometry.as_mut().filter(|_| same_objects) {
            Some(g) => {
                self.geometry_checked.set(Some(self.revision));
                if g.report_epsilon.to_bits() != self.desc.render.epsilon.to_bits() {
                    g.objects_report = validate_objects(&self.desc);
                    g.report_epsilon = self.desc.render.epsilon;
                }
                validate_with_objects(&self.desc, &g.objects_report)
            }
            None => validate(&self.desc),
        };
        drop(geometry);
        self.issues = report.errors;
        self.warnings = report.warnings;
        // An invalid edit holds the whole view, the paths too, even when what it broke is an
        // ambient term they do not read: one state on screen, not undimmed paths beside a
        // "held" status (a reviewer).
        let inputs = RenderInputs::of(&self.desc, self.omit_kinds);
        if !same_objects || !self.is_valid() || self.render_inputs.as_ref() != Some(&inputs) {
            (self.render_revision, self.render_inputs) = (self.revision, Some(inputs));
        }
        let fit = FitInputs::of(&self.desc);
        if !same_objects || self.fit_inputs.as_ref() != Some(&fit) {
            (self.fit_revision, self.fit_inputs) = (self.revision, Some(fit));
        }
    }

    pub fn is_valid(&self) -> bool {
        self.issues.is_empty()
    }

    /// The flat scene at full resolution, or at half width and height for previews while a
    /// value is dragged. `None` while the description is invalid.
    pub fn flat(&self, preview: bool) -> Option<FlatScene> {
        let mut settings = self.desc.render.clone();
        if preview {
            settings.width = settings.width.div_ceil(2);
            settings.height = settings.height.div_ceil(2);
            // A preview shows the picture, not the noise: one sample is enough while dragging.
            settings.spp = 1;
        }
        let mut flat = self.flat_with(&settings)?;
        flat.header.omit_kinds = self.omit_kinds;
        Some(flat)
    }

    /// The scene with `settings` in place of its own (the Whitted image beside the paths').
    pub fn flat_with(&self, settings: &glint_scene::RenderSettings) -> Option<FlatScene> {
        if !self.is_valid() {
            return None;
        }
        let mut cache = self.geometry.borrow_mut();
        let checked = self.geometry_checked.get() == Some(self.revision);
        if let Some(g) = cache.as_ref().filter(|g| checked || g.built_from(&self.desc)) {
            self.geometry_checked.set(Some(self.revision));
            return Some(g.flat.rebuild(&self.desc, settings));
        }
        self.geometry_checked.set(Some(self.revision));
        let flat = FlatScene::build(&self.desc, settings);
        *cache = Some(BuiltGeometry {
            objects: self.desc.objects.clone(),
            objects_report: validate_objects(&self.desc),
            report_epsilon: self.desc.render.epsilon,
            flat: flat.clone(),
        });
        Some(flat)
    }

    /// Writes the scene in the format `glint render` reads.
    pub fn save(&mut self, path: &Path) -> Result<(), ViewerError> {
        let text = to_toml(&self.desc).map_err(|e| ViewerError::Serialise(e.to_string()))?;
        write_file_atomically(path, text.as_bytes())
            .map_err(|AtomicWriteError { path, error }| ViewerError::SaveScene { path, error })?;
        self.path = Some(path.to_owned());
        self.source = Some(path.to_owned());
        self.name = path.file_stem().map_or_else(|| self.name.clone(), |s| s.to_string_lossy().into_owned());
        self.dirty = false;
        Ok(())
    }

    /// Index into `desc.objects` of an object id from a render (ids are scene order).
    pub fn object_index(&self, id: u32) -> Option<usize> {
        let i = id as usize;
        (i < self.desc.objects.len()).then_some(i)
    }

    /// A light as the Lights panel lists it: its name, or its type and index.
    pub fn light_label(&self, index: usize) -> String {
        light_label(&self.desc.lights, index)
    }

    pub fn object_label(&self, index: usize) -> String {
        match self.desc.objects.get(index) {
            Some(o) if !o.name().is_empty() => o.name().to_string(),
            Some(o) => format!("{} #{index}", o.kind_name()),
            None => format!("object #{index}"),
        }
    }
}

/// Light `index` of `lights` as the Lights panel lists it: its name, or its type and index
/// (also of a state an undo would give back, `undo.rs`).
pub fn light_label(lights: &[glint_scene::LightDesc], index: usize) -> String {
    match lights.get(index) {
        Some(l) if !l.name.is_empty() => l.name.clone(),
        Some(l) => format!("{} {index}", l.kind.name()),
        None => format!("light {index}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_hits_move_with_the_objects_the_camera_and_the_size_alone() {
        let mut doc = Document::load("whitted").expect("built-in scene");
        doc.flat(false).expect("valid");
        doc.edited();
        let at = doc.hits_revision;
        doc.desc.materials.values_mut().for_each(|m| m.kd.0[0] *= 0.5);
        doc.desc.lights[0].diffuse.0[0] *= 0.5;
        doc.edited();
        assert_eq!(doc.hits_revision, at, "a material or light edit moves no first hit");
        for edit in [
            (|d: &mut Document| d.desc.camera.fov_y += 1.0) as fn(&mut Document),
            |d| d.desc.render.width += 2,
            |d| d.desc.objects.truncate(1),
        ] {
            let before = doc.hits_revision;
            edit(&mut doc);
            doc.edited();
            assert!(doc.hits_revision > before && doc.hits_revision == doc.revision);
            doc.flat(false).expect("valid");
        }
    }

    #[test]
    fn the_ambient_terms_leave_a_path_render_as_it_is_and_start_a_whitted_one_over() {
        let mut doc = Document::load("cornell-gi").expect("built-in scene");
        doc.desc.render.integrator = glint_scene::Integrator::Path;
        doc.edited();
        doc.flat(false).expect("valid");
        let at = doc.render_revision;
        doc.desc.world.ambient.0[1] += 0.25;
        doc.desc.materials.values_mut().for_each(|m| m.ka.0[0] += 0.5);
        doc.desc.lights.iter_mut().for_each(|l| l.ambient.0[2] += 0.5);
        doc.edited();
        assert!(doc.revision > at && doc.render_revision == at, "paths read no ambient term");
        for edit in [
            (|d: &mut Document| d.desc.world.background.0[0] += 0.5) as fn(&mut Document),
            |d| d.desc.materials.values_mut().for_each(|m| m.kd.0[0] *= 0.5),
            |d| d.desc.render.spp += 1,
            |d| d.omit_kinds ^= 1,
            |d| d.desc.render.integrator = glint_scene::Integrator::Whitted,
            |d| d.desc.world.ambient.0[1] += 0.25,
            // Back to paths, then an invalid ambient term: the view is held, paths and all.
            |d| d.desc.render.integrator = glint_scene::Integrator::Path,
            |d| d.desc.world.ambient.0[1] = -1.0,
        ] {
            let before = doc.render_revision;
            edit(&mut doc);
            doc.edited();
            assert!(doc.render_revision > before && doc.render_revision == doc.revision);
        }
    }

    #[test]
    fn the_first_edit_of_a_scene_as_loaded_is_judged_by_what_it_changes() {
        // Opened from the menu, a scene has had no edit: applying a fitted I_a, its first, was
        // taken for a change of everything (the paths started over, the fit an earlier edit's).
        let mut doc = Document::load("cornell-gi").expect("built-in scene");
        doc.flat(false).expect("valid");
        let (render, fit) = (doc.render_revision, doc.fit_revision);
        doc.desc.world.ambient = glint_scene::Rgb([0.2, 0.2, 0.1]);
        doc.edited();
        assert!(doc.revision > render);
        assert_eq!((doc.render_revision, doc.fit_revision), (render, fit), "paths and the fit read no I_a");
    }

    #[test]
    fn previews_are_half_size_with_one_sample_and_invalid_scenes_render_nothing() {
        let mut doc = Document::load("whitted").expect("built-in scene");
        doc.desc.render.spp = 4;
        doc.edited();
        let full = doc.flat(false).expect("valid");
        let preview = doc.flat(true).expect("valid");
        assert_eq!((full.header.width, full.header.height, full.header.spp), (640, 480, 4));
        assert_eq!((preview.header.width, preview.header.height, preview.header.spp), (320, 240, 1));
        let revision = doc.revision;
        doc.desc.camera.fov_y = 0.0;
        doc.edited();
        assert!(doc.revision > revision && doc.dirty);
        assert!(doc.issues.iter().any(|i| i.field.contains("fov_y")), "{:?}", doc.issues);
        assert!(doc.flat(false).is_none());
    }

    #[test]
    fn an_edit_that_validation_warns_of_is_warned_of_and_still_rendered() {
        // A tester's lecture: ε = 2000 (held at 1000) in cornell took every shadow and reflection away with no
        // word, where `glint render --epsilon 1000` warns.
        let mut doc = Document::load("cornell").expect("built-in scene");
        assert!(doc.warnings.is_empty() && doc.load_warnings.is_empty(), "{:?}", doc.warnings);
        doc.desc.render.epsilon = 1000.0;
        doc.edited();
        assert!(doc.warnings.iter().any(|w| w.field == "render.epsilon"), "{:?}", doc.warnings);
        assert!(doc.is_valid() && doc.flat(false).is_some(), "a warning does not stop the render");
        doc.desc.render.epsilon = 1e-6;
        doc.edited();
        assert!(doc.warnings.is_empty(), "{:?}", doc.warnings);
    }
}
