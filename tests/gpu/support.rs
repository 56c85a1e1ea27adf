//! The shared GPU, scene helpers and failure artefacts.

use std::path::PathBuf;
use std::sync::OnceLock;

use glint_core::compare::{ImageErrors, compare_images, diff_heatmap};
use glint_core::image::{write_png, write_png_rgb8};
use glint_core::scene::{load_scene, parse_scene};
use glint_core::{CpuOptions, CpuRender, FlatScene, RenderControl, render_cpu};
use glint_gpu::{AdapterRequest, GpuContext, GpuOptions, GpuRender, GpuTracer};

/// The tracer every test shares, or `None` when `GLINT_SKIP_GPU=1`. Without an adapter this
/// panics: a GPU test never passes silently.
pub fn gpu() -> Option<&'static GpuTracer> {
    static TRACER: OnceLock<Option<GpuTracer>> = OnceLock::new();
    TRACER
        .get_or_init(|| {
            if std::env::var("GLINT_SKIP_GPU").is_ok_and(|v| v == "1") {
                eprintln!("GLINT_SKIP_GPU=1: skipping GPU tests");
                return None;
            }
            // A CPU adapter (lavapipe) when there is one: its arithmetic is the same everywhere.
            let request = AdapterRequest { name: None, prefer_cpu: true };
            match GpuContext::new(&request) {
                Ok(ctx) => {
                    eprintln!("GPU tests run on {}", ctx.adapter);
                    Some(GpuTracer::new(ctx))
                }
                Err(e) => panic!(
                    "GPU tests need an adapter and found none: {e}\n\
                     Install Mesa's lavapipe (apt-get install mesa-vulkan-drivers), or set GLINT_SKIP_GPU=1 \
                     to skip the GPU tests on purpose."
                ),
            }
        })
        .as_ref()
}

/// Returns early from a test when GPU tests are skipped on purpose.
macro_rules! gpu_or_skip {
    () => {
        match crate::support::gpu() {
            Some(g) => g,
            None => return,
        }
    };
}
pub(crate) use gpu_or_skip;

pub fn flat_from_toml(text: &str) -> FlatScene {
    let (desc, _) = parse_scene(text, std::path::Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}\n{text}"));
    FlatScene::build(&desc, &desc.render)
}

/// A built-in scene at the given size, spp and depth.
pub fn builtin(name: &str, width: u32, height: u32, spp: u32, depth: u32) -> FlatScene {
    let loaded = load_scene(name).expect("built-in scene");
    let mut s = loaded.desc.render.clone();
    (s.width, s.height, s.spp, s.max_depth) = (width, height, spp, depth);
    FlatScene::build(&loaded.desc, &s)
}

pub fn cpu(flat: &FlatScene) -> CpuRender {
    render_cpu(flat, &CpuOptions::default(), RenderControl::default()).expect("CPU render")
}

pub fn gpu_render(tracer: &GpuTracer, flat: &FlatScene, specialise: bool) -> GpuRender {
    let r = tracer.render(flat, &GpuOptions { specialise, ..GpuOptions::default() }).expect("GPU render");
    let nonfinite = r.image.pixels.iter().filter(|p| !p.is_finite()).count();
    assert_eq!(nonfinite, 0, "{nonfinite} GPU pixels are NaN or infinite");
    r
}

/// Where failing tests leave their images.
pub fn artefact_dir(group: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-tests").join(group);
    std::fs::create_dir_all(&dir).expect("artefact folder");
    dir
}

/// Compares the images; on `failed`, writes NAME-cpu.png, NAME-gpu.png and NAME-diff.png.
pub fn compare_and_keep(group: &str, name: &str, cpu: &CpuRender, gpu: &GpuRender) -> (ImageErrors, PathBuf) {
    let errors = compare_images(&cpu.image, &gpu.image);
    (errors, artefact_dir(group).join(name))
}

pub fn write_failure_images(base: &std::path::Path, cpu: &CpuRender, gpu: &GpuRender) {
    let with =
        |suffix: &str| base.with_file_name(format!("{}-{suffix}.png", base.file_name().unwrap().to_string_lossy()));
    let _ = write_png(&with("cpu"), &cpu.image, &[]);
    let _ = write_png(&with("gpu"), &gpu.image, &[]);
    let heat = diff_heatmap(&cpu.image, &gpu.image);
    let _ = write_png_rgb8(&with("diff"), cpu.image.width, cpu.image.height, &heat, &[]);
    eprintln!("wrote {}-{{cpu,gpu,diff}}.png", base.display());
}
