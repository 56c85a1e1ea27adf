//! Helpers of the GPU tests. The shared GPU (with the fail/skip policy), the NaN/Inf-checked
//! renders and the failure images live in glint-test-support (shared with the other test
//! binaries); this module re-exports them under the names the GPU tests use.

use std::path::PathBuf;

use glint_core::compare::{ImageErrors, compare_images};
use glint_core::scene::load_scene;
use glint_core::{CpuRender, FlatScene};
use glint_gpu::GpuRender;

pub use crate::gpu::gpu_or_skip;
pub use crate::gpu::gpu_render;

/// A built-in scene at the given size, spp and depth.
pub fn builtin(name: &str, width: u32, height: u32, spp: u32, depth: u32) -> FlatScene {
    let loaded = load_scene(name).expect("built-in scene");
    let mut s = loaded.desc.render.clone();
    (s.width, s.height, s.spp, s.max_depth) = (width, height, spp, depth);
    FlatScene::build(&loaded.desc, &s)
}

/// The CPU reference render (all cores), every pixel finite.
pub fn cpu(flat: &FlatScene) -> CpuRender {
    crate::render::render_cpu_checked(flat, 0, true)
}

/// Where failing tests leave their images: target/tmp/gpu-tests/GROUP.
pub fn artefact_dir(group: &str) -> PathBuf {
    crate::render::artefact_dir(&format!("gpu-tests/{group}"))
}

/// Compares the images and returns where their failure images would go.
pub fn compare_and_keep(group: &str, name: &str, cpu: &CpuRender, gpu: &GpuRender) -> (ImageErrors, PathBuf) {
    let errors = compare_images(&cpu.image, &gpu.image);
    (errors, artefact_dir(group).join(name))
}

/// Writes NAME-cpu.png, NAME-gpu.png and NAME-diff.png.
pub fn write_failure_images(base: &std::path::Path, cpu: &CpuRender, gpu: &GpuRender) {
    crate::render::write_failure_images(base, &cpu.image, Some(&gpu.image));
}
