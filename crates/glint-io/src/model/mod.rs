//! Model files (glTF 2.0, OBJ/MTL): their import into glint-scene's `Model`, and the lab
//! scene a model opens in.

pub mod gltf;
mod ground;
pub mod obj;

use std::path::Path;

pub use self::gltf::{GltfError, load_gltf};
pub use ground::{FLOOR_COVER, GROUND_GAP, Ground};
pub use obj::{ObjError, load_obj};

use glint_scene::{
    CameraDesc, EPSILON_SHARE, FieldIssue, LightDesc, LightKind, LoadedModel, MAX_COORD, MAX_IMAGE_SIDE, MaterialDesc,
    Model, ModelCamera, ModelDesc, ObjectDesc, PlaneDesc, RenderSettings, Rgb, SceneDesc, TransformDesc, WorldDesc,
};

/// Choices made when a model file is opened (`--scene-index`, `--camera`, `--exposure`,
/// `--ground`), and the image sides given (`--width`, `--height`).
#[derive(Clone, Debug, PartialEq)]
pub struct ImportOptions {
    /// The glTF scene to load; the file's default scene (else its first) when `None`.
    pub scene_index: Option<u32>,
    /// The file's camera to look through; its first camera when `None`, or the lab camera
    /// framing the model when the file has none.
    pub camera: Option<usize>,
    /// Scales the file's light intensities (candela, lux) into the model's I_d and I_s.
    pub exposure: f64,
    /// Whether the lab scene puts a ground under the model.
    pub ground: Ground,
    /// Whether the file's lights are read: a scene's model object uses them only with
    /// `lights = true`, and a light it does not use must not fail its load.
    pub lights: bool,
    /// Image sides given by the user: a side given alone sizes the other by the file camera's
    /// aspect ratio (exact, not the default image's rounded one).
    pub width: Option<u32>,
    pub height: Option<u32>,
}

impl Default for ImportOptions {
    fn default() -> Self {
        Self {
            scene_index: None,
            camera: None,
            exposure: 1.0,
            ground: Ground::Auto,
            lights: true,
            width: None,
            height: None,
        }
    }
}

impl ImportOptions {
    /// Whether no import choice was made; the image sides are not one (every scene takes them).
    pub fn is_default(&self) -> bool {
        Self { width: None, height: None, ..self.clone() } == Self::default()
    }
}

/// A number a model file stored as f32, as the file wrote it: the shortest decimal of that f32
/// (to 7 digits), so `Kd 0.1` or `"roughnessFactor": 0.1` is 0.1 as in a scene file, not
/// 0.10000000149.
pub(crate) fn widen(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// The warning naming what a model's materials hold that Glint does not read, each with how many
/// materials hold it (`Tf (1 material), map_Bump (2 materials)`); `None` when nothing is left out.
pub(crate) fn left_out(
    field: &str,
    what: &str,
    counts: &std::collections::BTreeMap<&str, usize>,
) -> Option<FieldIssue> {
    let each = |(k, n): (&&str, &usize)| format!("{k} ({n} material{})", if *n == 1 { "" } else { "s" });
    (!counts.is_empty()).then(|| FieldIssue {
        field: field.into(),
        problem: format!("{what}, left out: {}", counts.iter().map(each).collect::<Vec<_>>().join(", ")),
    })
}

/// Which importer reads a file, by its extension (case-insensitive).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    Gltf,
    Obj,
}

/// Extensions of 3D formats glint does not import (Assimp's commonest, Blender's, USD's): such a
/// file was read as a TOML scene, and refused for its first line ("key with no value").
pub const OTHER_MODEL_FORMATS: [&str; 29] = [
    "3ds", "3mf", "abc", "ac", "amf", "ase", "b3d", "blend", "bvh", "dae", "dxf", "fbx", "ifc", "lwo", "lws", "md2",
    "md3", "ms3d", "off", "ply", "smd", "stl", "usd", "usda", "usdc", "usdz", "wrl", "x", "x3d",
];

/// The extension of `path` in lower case, if it has one in UTF-8.
fn extension(path: &Path) -> Option<String> {
    Some(path.extension()?.to_str()?.to_ascii_lowercase())
}

impl ModelFormat {
    /// The extension of `path` (lower case) when it is a 3D format glint does not import.
    pub fn other(path: &Path) -> Option<String> {
        extension(path).filter(|ext| OTHER_MODEL_FORMATS.contains(&ext.as_str()))
    }

    pub fn of(path: &Path) -> Option<Self> {
        let ext = extension(path)?;
        match ext.as_str() {
            "gltf" | "glb" => Some(Self::Gltf),
            "obj" => Some(Self::Obj),
            _ => None,
        }
    }
}

/// Why a model file did not import; each names the file and what is wrong.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error(transparent)]
    Gltf(#[from] GltfError),
    #[error(transparent)]
    Obj(#[from] ObjError),
    #[error(
        "{}: an OBJ file has no scenes to choose from: a scene index (--scene-index, an object's scene_index) is \
         for glTF files",
        file.display()
    )]
    ObjHasNoScenes { file: std::path::PathBuf },
    #[error(
        "{}: an OBJ file has no cameras to choose from: --camera is for glTF files (without it Glint frames the \
         model)",
        file.display()
    )]
    ObjHasNoCameras { file: std::path::PathBuf },
    #[error("{}: not a model file (.gltf, .glb or .obj)", file.display())]
    NotAModel { file: std::path::PathBuf },
}

/// The model file at `path`, read by the importer of its format.
pub fn load_model_file(path: &Path, options: &ImportOptions) -> Result<Model, ModelError> {
    match ModelFormat::of(path) {
        Some(ModelFormat::Gltf) => Ok(load_gltf(path, options)?),
        Some(ModelFormat::Obj) if options.scene_index.is_some() => {
            Err(ModelError::ObjHasNoScenes { file: path.to_owned() })
        }
        Some(ModelFormat::Obj) if options.camera.is_some() => {
            Err(ModelError::ObjHasNoCameras { file: path.to_owned() })
        }
        Some(ModelFormat::Obj) => Ok(load_obj(path)?),
        None => Err(ModelError::NotAModel { file: path.to_owned() }),
    }
}

/// Where the camera framing a model stands: a direction from the model's centre and how many
/// of its radii along it. Its 40° view holds the bounding sphere from 1/sin 20° = 2.92 radii:
/// at 2.6 a tall model (a skinned figure, a column) lost its top.
/// The least largest side of a model Glint frames: its coordinates' products (a triangle's
/// normal, side², and determinant, side³) stay far above f32's least normal number, 1.2e-38.
pub const MIN_MODEL_SIDE: f64 = 1e-9;

const FRAMING_CAMERA: ([f64; 3], f64) = ([0.45, 0.35, 0.82], 3.0);
/// Where the default rig's point key light stands, as `FRAMING_CAMERA`.
const KEY_LIGHT: ([f64; 3], f64) = ([-0.8, 1.6, 1.2], 3.0);

/// The image sides for a camera of aspect ratio `aspect` (width / height): a side the user gave
/// alone sizes the other (the height is the default's when neither is given), both given are
/// kept. A side beyond the image limits is held to them, and said.
fn size_by_aspect(
    render: &mut RenderSettings,
    aspect: f64,
    width: Option<u32>,
    height: Option<u32>,
    camera: &str,
    warnings: &mut Vec<FieldIssue>,
) {
    // A side no image can have is left to the settings' validation, which names its flag.
    let valid = |side: Option<u32>| side.filter(|s| (1..=MAX_IMAGE_SIDE).contains(s));
    // The image the ratio asks (width, height), one side of it given.
    let wanted = match (valid(width), valid(height)) {
        (Some(w), Some(h)) => (f64::from(w), f64::from(h)),
        (Some(w), None) => (f64::from(w), (f64::from(w) / aspect).round()),
        (None, h) => {
            let h = f64::from(h.unwrap_or(render.height));
            ((h * aspect).round(), h)
        }
    };
    let held = |side: f64| side.clamp(1.0, f64::from(MAX_IMAGE_SIDE));
    let (w, h) = (held(wanted.0), held(wanted.1));
    (render.width, render.height) = (w as u32, h as u32);
    let clamped = if w != wanted.0 { Some(("width", w)) } else { (h != wanted.1).then_some(("height", h)) };
    if let Some((side, now)) = clamped {
        warnings.push(FieldIssue {
            field: format!("camera `{camera}`"),
            problem: format!(
                "its aspect ratio {} would make the image {}x{} pixels; the {side} is held to {now} \
                 (sides in [1, {MAX_IMAGE_SIDE}]): set --width and --height",
                // To 7 digits: the lab scene's 4:3 is 1.3333333333333333 in full.
                glint_scene::format_rounded(aspect, 7),
                glint_scene::format_number(wanted.0),
                glint_scene::format_number(wanted.1),
            ),
        });
    }
}

/// How many of the model's radii the placements `made` (`FRAMING_CAMERA`, `KEY_LIGHT`) lie from
/// its centre, at most, on any axis.
fn made_around(made: &[([f64; 3], f64)]) -> f64 {
    made.iter().flat_map(|(d, s)| d.map(|c| c.abs() * s)).fold(0.0, f64::max)
}

/// The material of the ground under an opened model.
pub const GROUND_MATERIAL: &str = "glint-ground";

/// A lab scene around an imported model, with the importer's warnings: the file's camera
/// (`options.camera`, else its first) or one that frames the model's bounding box from the
/// front, above and to the right; the file's lights, or a key and a fill light (said in a
/// warning); and a grey ground just below the model so that its shadows show (`options.ground`:
/// never coplanar with the model's faces, and left out in `auto` where the model has a floor).
pub fn scene_around(
    mut model: Model,
    path: &Path,
    options: &ImportOptions,
) -> Result<(SceneDesc, Vec<FieldIssue>), FieldIssue> {
    let description = format!("the model {}", path.display());
    // A model given alone whose every triangle has no area renders only the ground: refused,
    // as one without triangles is (it rendered, exit 0, with a warning; a tester).
    let triangles = model.meshes.iter().map(|m| m.triangles.len()).sum::<usize>();
    if triangles > 0 && !model.meshes.iter().any(has_area) {
        let all = if triangles == 1 {
            "its one triangle has".to_string()
        } else {
            format!("all {triangles} of its triangles have")
        };
        return Err(FieldIssue {
            field: "triangles".into(),
            problem: format!("{all} zero area (the corners on one line or at one point): there is nothing to trace"),
        });
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in model.meshes.iter().flat_map(|m| &m.vertices) {
        for k in 0..3 {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    let center: [f64; 3] = std::array::from_fn(|k| 0.5 * (lo[k] + hi[k]));
    let side = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    // Framed by its own size however small (a floor of 1e-6 once framed a 1e-8 model as a dot,
    // and a 1e-10 one not at all, without a word), down to where the GPU's f32 products of its
    // coordinates would underflow; a model of one point has no size and gets 1e-6.
    if side > 0.0 && side < MIN_MODEL_SIDE {
        return Err(FieldIssue {
            field: "vertices".into(),
            problem: format!(
                "the model's largest side is {side:.3e}, below {MIN_MODEL_SIDE:e}, the least Glint frames and traces \
                 (the GPU's f32 products of such coordinates underflow); scale it up (a node's scale, or a file in \
                 other units?)"
            ),
        });
    }
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let radius = if diagonal > 0.0 { 0.5 * diagonal } else { 0.5e-6 };
    // Beyond the coordinates a scene may hold, the camera and lights Glint makes around the model
    // (where the file has none) would be refused, each under Glint's own names: say once what
    // is wrong. The ground lies within the model's box.
    let reach = lo.iter().chain(&hi).fold(0.0_f64, |r, c| r.max(c.abs()));
    if reach > MAX_COORD {
        return Err(FieldIssue {
            field: "vertices".into(),
            problem: format!(
                "the model reaches {reach:.3e} from the origin; coordinates must lie in [-{MAX_COORD:e}, {MAX_COORD:e}] \
                 (a node's scale, or a file in other units?)"
            ),
        });
    }
    let makes_camera = options.camera.is_none() && model.cameras.is_empty();
    let makes_lights = model.lights.is_empty();
    let made: Vec<_> =
        [makes_camera.then_some(FRAMING_CAMERA), makes_lights.then_some(KEY_LIGHT)].into_iter().flatten().collect();
    let around = center.iter().fold(0.0_f64, |r, c| r.max(c.abs())) + made_around(&made) * radius;
    if !made.is_empty() && around > MAX_COORD {
        let what = match (makes_camera, makes_lights) {
            (true, true) => "the camera and lights",
            (true, false) => "the camera",
            (false, _) => "the lights",
        };
        return Err(FieldIssue {
            field: "model".into(),
            problem: format!(
                "{what} Glint makes around a model without its own would reach {around:.3e} from the origin \
                 (the model's box reaches {reach:.3e}); coordinates must lie in [-{MAX_COORD:e}, {MAX_COORD:e}]: \
                 give the file its own, or scale it down (a node's scale)"
            ),
        });
    }
    let at = |d: [f64; 3], s: f64| std::array::from_fn(|k| center[k] + d[k] * s * radius);
    let mut render = RenderSettings::default();
    // The default ε is 1e-6 of a model 1 wide; a smaller model (a file in other units, or a
    // node's scale) gets the same share of its own size, so that it renders as it would at 1.
    if side > 0.0 {
        render.epsilon = render.epsilon.min(EPSILON_SHARE * side);
    }
    let camera = match (options.camera, model.cameras.first()) {
        (Some(i), _) => {
            let count = model.cameras.len();
            // The cameras skipped (with the warnings that say why) explain a count lower than the
            // file's: the error is all that is printed, so it says them.
            let skipped: Vec<String> = model
                .warnings
                .iter()
                .filter(|w| w.problem.ends_with(gltf::CAMERA_SKIPPED))
                .map(|w| format!("{}: {}", w.field, w.problem))
                .collect();
            let skipped =
                if skipped.is_empty() { String::new() } else { format!(" (skipped: {})", skipped.join("; ")) };
            let chosen = model.cameras.get(i).ok_or_else(|| FieldIssue {
                field: "--camera".into(),
                // Counted as `--camera` counts them: the nodes with a camera Glint looks through, in
                // the order the scene's nodes are walked (not the file's `cameras` indices).
                problem: match count {
                    0 => format!("{i} is not a camera of the file; it has no camera on a node{skipped}"),
                    1 => format!("{i} is not a camera of the file; it has one camera on a node, camera 0{skipped}"),
                    _ => format!(
                        "{i} is not a camera of the file; it has {count} cameras on nodes, cameras 0 to {}{skipped}",
                        count - 1
                    ),
                },
            })?;
            chosen.clone()
        }
        (None, Some(first)) => first.clone(),
        (None, None) => ModelCamera {
            name: "framing the model".into(),
            camera: CameraDesc::perspective(at(FRAMING_CAMERA.0, FRAMING_CAMERA.1), center, [0.0, 1.0, 0.0], 40.0),
            aspect: None,
        },
    };
    let mut warnings = std::mem::take(&mut model.warnings);
    // A camera without its own aspect ratio keeps the default image's.
    let aspect = camera.aspect.unwrap_or(f64::from(render.width) / f64::from(render.height));
    size_by_aspect(&mut render, aspect, options.width, options.height, &camera.name, &mut warnings);
    let lights = std::mem::take(&mut model.lights);
    // The scene refers to the file (saved as a reference, never as vertices): an absolute
    // path, since the scene may be saved anywhere.
    let file = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_owned());
    let reference = ModelDesc {
        path: file.to_string_lossy().into_owned(),
        transform: TransformDesc::default(),
        scene_index: options.scene_index,
        name: String::new(),
        // The file's lights (scaled by the exposure already) are the lab scene's own
        // `[[lights]]`, editable and saved as such; the reference does not add them again.
        lights: false,
        exposure: None,
        loaded: None,
    };
    let (ground, note) = ground::ground_height(&model.meshes, lo, hi, options.ground);
    warnings.extend(note);
    let loaded = LoadedModel::place(file, model, &reference.transform, &reference.prefix());
    let mut materials = loaded.materials.clone();
    let mut objects =
        vec![ObjectDesc::Model(Box::new(ModelDesc { loaded: Some(std::sync::Arc::new(loaded)), ..reference }))];
    if let Some(y) = ground {
        materials.insert(
            GROUND_MATERIAL.into(),
            MaterialDesc { ka: Rgb::splat(0.5), kd: Rgb::splat(0.5), ..MaterialDesc::default() },
        );
        objects.push(ObjectDesc::Plane(PlaneDesc {
            point: [center[0], y, center[2]],
            normal: [0.0, 1.0, 0.0],
            material: GROUND_MATERIAL.into(),
            name: "ground".into(),
        }));
    }
    let lights = if lights.is_empty() {
        // --exposure scales a file's lights: with none it would change nothing without a word.
        let exposure = if options.exposure == ImportOptions::default().exposure {
            ""
        } else {
            "; --exposure scales a file's lights and changes nothing here"
        };
        warnings.push(FieldIssue {
            field: "lights".into(),
            problem: format!(
                "the model has none: lit by Glint's default rig (a point key light, a directional fill, \
                 and an ambient 0.1 that only Whitted's model uses){exposure}"
            ),
        });
        let light = |kind, position, direction, intensity| LightDesc {
            diffuse: Rgb::splat(intensity),
            specular: Rgb::splat(intensity),
            ..LightDesc::new(kind, position, direction)
        };
        vec![
            light(LightKind::Point, at(KEY_LIGHT.0, KEY_LIGHT.1), [0.0; 3], 0.8),
            light(LightKind::Directional, [0.0; 3], [0.4, -1.0, -0.3], 0.3),
        ]
    } else {
        lights
    };
    let desc = SceneDesc {
        description,
        provenance: String::new(),
        render,
        camera: camera.camera,
        world: WorldDesc { ambient: Rgb::splat(0.1), background: Rgb([0.2, 0.25, 0.3]), ..WorldDesc::default() },
        materials,
        lights,
        objects,
    };
    Ok((desc, warnings))
}

/// Whether some triangle of `mesh` has area (as validation judges a degenerate one).
fn has_area(mesh: &glint_scene::MeshDesc) -> bool {
    let corner = |k: u32| mesh.vertices.get(k as usize).copied();
    mesh.triangles.iter().filter_map(|t| Some([corner(t[0])?, corner(t[1])?, corner(t[2])?])).any(glint_scene::has_area)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_scene::MeshDesc;

    #[test]
    fn a_model_whose_triangles_all_lack_area_is_refused() {
        let line = MeshDesc::new(vec![[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], vec![[0, 1, 2]], "m", "line");
        let point = MeshDesc::new(vec![[1.0; 3]; 3], vec![[0, 1, 2], [2, 1, 0]], "m", "point");
        let e = scene_around(
            Model { meshes: vec![line.clone(), point], ..Model::default() },
            Path::new("m.obj"),
            &ImportOptions::default(),
        )
        .unwrap_err();
        assert_eq!(e.field, "triangles");
        assert_eq!(
            e.problem,
            "all 3 of its triangles have zero area (the corners on one line or at one point): there is nothing to trace"
        );
        // One triangle with area beside them is a model (the rest are warned of as degenerate).
        let model = Model { meshes: vec![line, quad(1.0)], ..Model::default() };
        assert!(scene_around(model, Path::new("m.obj"), &ImportOptions::default()).is_ok());
    }

    fn quad(s: f64) -> MeshDesc {
        MeshDesc::new(vec![[-s, -s, 0.0], [s, -s, 0.0], [s, s, 0.0]], vec![[0, 1, 2]], "m", "node0")
    }

    #[test]
    fn a_model_beyond_the_coordinate_range_is_one_error_not_one_per_object_made_around_it() {
        let model = |s| Model { meshes: vec![quad(s)], ..Model::default() };
        let path = Path::new("huge.gltf");
        let e = scene_around(model(1e15), path, &ImportOptions::default()).unwrap_err();
        assert_eq!(e.field, "vertices");
        assert!(e.problem.contains("reaches 1.000e15") && e.problem.contains("[-1e9, 1e9]"), "{}", e.problem);
        assert!(scene_around(model(1e6), path, &ImportOptions::default()).is_ok());
        // Within the range itself, but not the key light made 4.8 radii (here 3.4e8) above it.
        let e = scene_around(model(5e8), path, &ImportOptions::default()).unwrap_err();
        assert_eq!(e.field, "model");
        assert!(e.problem.starts_with("the camera and lights Glint makes"), "{}", e.problem);
        assert!(e.problem.contains("reach 3.394e9") && e.problem.contains("box reaches 5.000e8"), "{}", e.problem);
        // A file with its own camera and light is judged by what it uses: its vertices.
        let light = LightDesc::new(LightKind::Directional, [0.0; 3], [0.0, -1.0, 0.0]);
        let camera = ModelCamera {
            name: "own".into(),
            camera: CameraDesc::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0),
            aspect: None,
        };
        let own = Model { lights: vec![light.clone()], cameras: vec![camera.clone()], ..model(5e8) };
        assert!(scene_around(own, path, &ImportOptions::default()).is_ok());
        let e = scene_around(Model { lights: vec![light], ..model(5e8) }, path, &ImportOptions::default()).unwrap_err();
        assert!(e.problem.starts_with("the camera Glint makes"), "{}", e.problem);
        let e =
            scene_around(Model { cameras: vec![camera], ..model(5e8) }, path, &ImportOptions::default()).unwrap_err();
        assert!(e.problem.starts_with("the lights Glint makes"), "{}", e.problem);
    }

    #[test]
    fn a_model_smaller_than_1_gets_the_default_epsilons_share_of_its_size() {
        let epsilon = |s: f64| {
            let model = Model { meshes: vec![quad(s)], ..Model::default() };
            let (desc, _) = scene_around(model, Path::new("m.gltf"), &ImportOptions::default()).expect("in range");
            assert!(glint_scene::validate(&desc).warnings.iter().all(|w| w.field != "render.epsilon"), "at {s}");
            desc.render.epsilon
        };
        assert_eq!(epsilon(10.0), RenderSettings::default().epsilon);
        assert_eq!(epsilon(0.5), RenderSettings::default().epsilon, "1 wide");
        assert_eq!(epsilon(1e-3), 1e-6 * 2e-3);
    }

    #[test]
    fn an_aspect_ratio_no_image_can_have_is_said_with_the_width_held() {
        let camera = |aspect: f64| ModelCamera {
            name: "c".into(),
            camera: CameraDesc::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0),
            aspect: Some(aspect),
        };
        let said = |aspect: f64| {
            let model = Model { meshes: vec![quad(1.0)], cameras: vec![camera(aspect)], ..Model::default() };
            let (desc, warnings) = scene_around(model, Path::new("m.gltf"), &ImportOptions::default()).unwrap();
            (desc.render.width, warnings.into_iter().find(|w| w.problem.contains("aspect ratio")))
        };
        let (width, warning) = said(1e-9);
        assert_eq!(width, 1);
        assert!(warning.expect("said").problem.starts_with("its aspect ratio 1e-9 would make the image 0x"));
        assert_eq!(said(2.0).1, None);
        // Written short, not as 39 digits.
        let said = said(1e38).1.expect("said").problem;
        assert!(said.starts_with("its aspect ratio 1e38 would make the image 4.8e40x480 pixels"), "{said}");
    }

    #[test]
    fn an_exposure_for_a_model_without_lights_is_said_to_change_nothing() {
        let said = |exposure: f64| {
            let model = Model { meshes: vec![quad(1.0)], ..Model::default() };
            let options = ImportOptions { exposure, ..ImportOptions::default() };
            let (_, warnings) = scene_around(model, Path::new("m.gltf"), &options).unwrap();
            warnings.into_iter().find(|w| w.field == "lights").expect("the default rig is said").problem
        };
        assert!(said(2.0).ends_with("; --exposure scales a file's lights and changes nothing here"), "{}", said(2.0));
        assert!(!said(1.0).contains("--exposure"));
    }

    #[test]
    fn a_camera_index_beyond_the_files_names_the_ones_it_has() {
        let camera = ModelCamera {
            name: "c".into(),
            camera: CameraDesc::perspective([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0),
            aspect: None,
        };
        for (count, says) in [
            (0, "it has no camera on a node"),
            (1, "it has one camera on a node, camera 0"),
            (3, "it has 3 cameras on nodes, cameras 0 to 2"),
        ] {
            let mut model = Model { meshes: vec![quad(1.0)], ..Model::default() };
            model.cameras = vec![camera.clone(); count];
            let options = ImportOptions { camera: Some(5), ..ImportOptions::default() };
            let e = scene_around(model, Path::new("m.gltf"), &options).unwrap_err();
            assert_eq!(
                (e.field.as_str(), e.problem.as_str()),
                ("--camera", format!("5 is not a camera of the file; {says}").as_str())
            );
        }
    }
}
