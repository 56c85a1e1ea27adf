//! The four checks: scene text → validated scene → flat layout; the same through a few CPU
//! pixels; a glTF file (JSON or GLB) → scene; an OBJ file with its MTL → scene.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use glint_core::render::{CpuOptions, CpuRenderError, RenderControl, render_cpu};
use glint_core::{Accel, FlatScene};
use glint_io::{LoadOptions, load_scene_with, parse_scene};
use glint_scene::SceneDesc;

/// The fuzz targets, by the name of their corpus folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    SceneText,
    ScenePixels,
    Gltf,
    Obj,
}

impl Target {
    pub const ALL: [Self; 4] = [Self::SceneText, Self::ScenePixels, Self::Gltf, Self::Obj];

    /// The name of the fuzz target and of its corpus folder.
    pub fn name(self) -> &'static str {
        match self {
            Self::SceneText => "scene_text",
            Self::ScenePixels => "scene_pixels",
            Self::Gltf => "gltf_model",
            Self::Obj => "obj_model",
        }
    }

    /// Runs the check on one input.
    pub fn check(self, data: &[u8]) {
        match self {
            Self::SceneText => scene_text(data),
            Self::ScenePixels => scene_pixels(data),
            Self::Gltf => gltf_model(data),
            Self::Obj => obj_model(data),
        }
    }
}

/// Rendered pixels stay few and trees short, so that one input takes milliseconds: what is
/// checked is that every accepted scene renders, not how fast.
const SIDE: u32 = 3;
const RAY_CAP: u64 = 20_000;

/// An empty folder of this process where model inputs are written (the loaders read files),
/// and that scene text names as its own folder: paths in the input resolve inside it.
fn folder() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| tempfile::Builder::new().prefix("glint-fuzz").tempdir().expect("a temporary folder")).path()
}

/// Scene text is parsed and validated; an accepted scene builds its flat layout.
pub fn scene_text(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok((desc, _)) = parse_scene(text, &folder().join("scene.toml")) else { return };
    let _ = FlatScene::build(&desc, &desc.render);
}

/// As `scene_text`, then a few pixels of the accepted scene on the CPU (both traversals).
pub fn scene_pixels(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let Ok((desc, _)) = parse_scene(text, &folder().join("scene.toml")) else { return };
    render_few_pixels(&desc);
}

/// A glTF file, JSON or binary (told by its magic), opened as `glint render model.glb` does.
pub fn gltf_model(data: &[u8]) {
    let name = if data.starts_with(b"glTF") { "model.glb" } else { "model.gltf" };
    open_model(&[(name, data)], name);
}

/// An OBJ file; the part after a line `#MTL` is written as its `m.mtl` (`mtllib m.mtl`).
pub fn obj_model(data: &[u8]) {
    let marker = b"\n#MTL\n";
    let (obj, mtl) = match data.windows(marker.len()).position(|w| w == marker) {
        Some(at) => (&data[..at], &data[at + marker.len()..]),
        None => (data, &[][..]),
    };
    open_model(&[("model.obj", obj), ("m.mtl", mtl)], "model.obj");
}

fn open_model(files: &[(&str, &[u8])], open: &str) {
    let dir = folder();
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).expect("write a fuzz input");
    }
    let path: PathBuf = dir.join(open);
    let loaded = load_scene_with(path, &LoadOptions::default());
    for (name, _) in files {
        let _ = std::fs::remove_file(dir.join(name));
    }
    if let Ok(loaded) = loaded {
        render_few_pixels(&loaded.desc);
    }
}

/// Renders `desc` at `SIDE`² pixels, one sample, through the BVH and by brute force: both
/// succeed or stop at the ray cap, agree bit for bit, hold no NaN, and hold only finite
/// values unless a material returns more light than it receives (`MaterialDesc::gain` > 1),
/// which the CLI reports as the cause of an overflow.
fn render_few_pixels(desc: &SceneDesc) {
    let mut settings = desc.render.clone();
    settings.width = settings.width.min(SIDE);
    settings.height = settings.height.min(SIDE);
    settings.spp = 1;
    let flat = FlatScene::build(desc, &settings);
    let render = |accel| {
        let options = CpuOptions { threads: 1, accel, max_rays_per_sample: RAY_CAP, ..CpuOptions::default() };
        match render_cpu(&flat, &options, RenderControl::default()) {
            Ok(r) => Some(r.image),
            Err(CpuRenderError::RayCap { .. }) => None,
            Err(e) => panic!("an accepted scene failed to render: {e}"),
        }
    };
    let (Some(bvh), Some(brute)) = (render(Accel::Bvh), render(Accel::None)) else { return };
    assert!(bvh.pixels.iter().all(|p| !p.is_nan()), "a NaN pixel: {:?}", bvh.pixels);
    let bits = |p: &glint_core::glam::DVec3| p.to_array().map(f64::to_bits);
    assert!(
        bvh.pixels.iter().map(bits).eq(brute.pixels.iter().map(bits)),
        "the BVH and brute force differ: {:?} vs {:?}",
        bvh.pixels,
        brute.pixels
    );
    let gains = desc.materials.values().any(|m| m.gain(settings.integrator) > 1.0);
    if !gains && let Some(found) = bvh.unrepresentable() {
        panic!("no material gains energy, yet {found}");
    }
}
