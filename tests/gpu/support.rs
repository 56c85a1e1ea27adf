//! Helpers of the GPU tests. The shared GPU (with the fail/skip policy), the NaN/Inf-checked
//! renders and the failure images live in glint-test-support (shared with the other test
//! binaries); this module re-exports them under the names the GPU tests use.

use std::path::PathBuf;

use glint_core::compare::{ImageErrors, compare_images};
use glint_core::{CpuRender, FlatScene};
use glint_gpu::GpuRender;
use glint_io::load_scene;

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

/// The parity thresholds, measured and justified in parity.rs's header.
pub const FLIP_MEAN_MAX: f64 = 0.005;
pub const P99_MAX: f64 = 1.0 / 255.0;
pub const MISMATCH_MAX: f64 = 0.005;

/// Whether a GPU image is within parity of the CPU reference and raised no status flag.
pub fn within_parity(e: &ImageErrors, status: u32) -> bool {
    e.flip_mean <= FLIP_MEAN_MAX
        && e.p99_abs_same_hit <= P99_MAX
        && e.first_hit_mismatch <= MISMATCH_MAX
        && status == 0
        && e.nonfinite == 0
}

/// One line of a GPU-against-CPU comparison on stderr.
pub fn log_errors(name: &str, e: &ImageErrors, status: u32) {
    eprintln!(
        "{name:<20} FLIP {:.5}  p99 {:.2e}  max {:.2e}  mismatch {:.3} %  PSNR {:.1} dB  status {status}",
        e.flip_mean,
        e.p99_abs_same_hit,
        e.max_abs,
        100.0 * e.first_hit_mismatch,
        e.psnr,
    );
}

/// Writes NAME-cpu.png, NAME-gpu.png and NAME-diff.png.
pub fn write_failure_images(base: &std::path::Path, cpu: &CpuRender, gpu: &GpuRender) {
    crate::render::write_failure_images(base, &cpu.image, Some(&gpu.image));
}
