//! CPU renders checked for NaN/Inf, and the images a failing comparison leaves behind.

use std::path::{Path, PathBuf};

use glint_core::compare::diff_heatmap;
use glint_core::{CpuOptions, CpuRender, FlatScene, HdrImage, RenderControl, render_cpu};
use glint_io::image_file::{write_png, write_png_rgb8};

/// Indices of the pixels with a NaN or infinite channel.
pub fn nonfinite_pixels(image: &HdrImage) -> Vec<usize> {
    image.pixels.iter().enumerate().filter(|(_, p)| !p.is_finite()).map(|(i, _)| i).collect()
}

/// Panics, naming the first few, if any pixel of `image` is NaN or infinite.
pub fn assert_all_finite(image: &HdrImage, what: &str) {
    let bad = nonfinite_pixels(image);
    if let Some(&first) = bad.first() {
        let (x, y) = (first as u32 % image.width, first as u32 / image.width);
        panic!("{what}: {} pixels are NaN or infinite, the first at ({x}, {y}): {}", bad.len(), image.pixels[first]);
    }
}

/// Renders with `threads` threads (0 = one per core) and asserts that no pixel is NaN or
/// infinite.
pub fn render_cpu_checked(flat: &FlatScene, threads: usize, specialise: bool) -> CpuRender {
    let r = render_cpu(flat, &CpuOptions { threads, specialise, ..CpuOptions::default() }, RenderControl::default())
        .expect("CPU render");
    assert_eq!(r.image.pixels.len(), flat.pixel_count());
    assert_all_finite(&r.image, "CPU render");
    crate::image_hash::check_render_hash(&r);
    r
}

/// Where failing tests leave their images: `target/tmp/<group>` (created). Cargo tells test
/// binaries that folder (`CARGO_TARGET_TMPDIR`) but not this library, so it is found from the
/// running test binary, `target/<profile>/deps/<binary>`.
pub fn artefact_dir(group: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let target = exe.ancestors().nth(3).expect("the test binary lies in target/<profile>/deps");
    let dir = target.join("tmp").join(group);
    std::fs::create_dir_all(&dir).expect("artefact folder");
    dir
}

/// Writes BASE-cpu.png, BASE-gpu.png and BASE-diff.png (the |GPU − CPU| heat map).
pub fn write_failure_images(base: &Path, cpu: &HdrImage, gpu: Option<&HdrImage>) {
    let with =
        |suffix: &str| base.with_file_name(format!("{}-{suffix}.png", base.file_name().unwrap().to_string_lossy()));
    let _ = write_png(&with("cpu"), cpu, &[]);
    if let Some(gpu) = gpu {
        let _ = write_png(&with("gpu"), gpu, &[]);
        let heat = diff_heatmap(cpu, gpu);
        let _ = write_png_rgb8(&with("diff"), cpu.width, cpu.height, &heat, &[]);
    }
    eprintln!("wrote {}-{{cpu,gpu,diff}}.png", base.display());
}
