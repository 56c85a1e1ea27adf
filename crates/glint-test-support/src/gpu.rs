//! The GPU the tests share (with the fail/skip policy), GPU renders checked for NaN/Inf, and
//! rendering one scene on both backends.
//!
//! Policy: without an adapter a GPU test fails with a clear message; `GLINT_SKIP_GPU=1` skips
//! the GPU part on purpose (a test that renders on both backends then checks the CPU only).
//! `WGPU_ADAPTER_NAME` picks the adapter by name; `GLINT_REQUIRE_HARDWARE_GPU=1` (the device
//! suite's) makes a software adapter such as lavapipe a failure, never a silent stand-in.

use std::sync::OnceLock;

pub use glint_core::Backend;
use glint_core::{Accel, CpuRender, FlatScene, HdrImage};
use glint_gpu::{AdapterRequest, GpuContext, GpuOptions, GpuRender, GpuTracer};

use crate::render::{artefact_dir, nonfinite_pixels, render_cpu_checked, write_failure_images};

/// The tracer every test shares, or `None` when `GLINT_SKIP_GPU=1`. Without an adapter this
/// panics: a GPU test never passes silently.
pub fn gpu() -> Option<&'static GpuTracer> {
    static TRACER: OnceLock<Option<GpuTracer>> = OnceLock::new();
    TRACER
        .get_or_init(|| {
            if crate::skip_requested("GLINT_SKIP_GPU") {
                eprintln!("GLINT_SKIP_GPU=1: skipping GPU tests");
                return None;
            }
            // A CPU adapter (lavapipe) when there is one: its arithmetic is the same everywhere.
            let request = AdapterRequest { name: None, prefer_cpu: true };
            match GpuContext::new(&request) {
                Ok(ctx) => {
                    eprintln!("GPU tests run on {}", ctx.adapter);
                    let hardware_only = std::env::var("GLINT_REQUIRE_HARDWARE_GPU").is_ok_and(|v| v == "1");
                    assert!(
                        !(hardware_only && ctx.adapter.is_software()),
                        "GLINT_REQUIRE_HARDWARE_GPU=1, but the adapter is {}, a software one: install the GPU's \
                         Vulkan driver (and the Vulkan loader), or name the adapter with WGPU_ADAPTER_NAME",
                        ctx.adapter
                    );
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
#[macro_export]
macro_rules! gpu_or_skip {
    () => {
        match $crate::gpu::gpu() {
            Some(g) => g,
            None => return,
        }
    };
}
pub use crate::gpu_or_skip;

/// Renders on the GPU and asserts that no read-back pixel is NaN or infinite.
pub fn gpu_render(tracer: &GpuTracer, flat: &FlatScene, specialise: bool) -> GpuRender {
    gpu_render_with(tracer, flat, &GpuOptions { specialise, ..GpuOptions::default() })
}

/// `gpu_render` with every option.
pub fn gpu_render_with(tracer: &GpuTracer, flat: &FlatScene, options: &GpuOptions) -> GpuRender {
    let r = tracer.render(flat, options).expect("GPU render");
    let nonfinite = nonfinite_pixels(&r.image).len();
    assert_eq!(nonfinite, 0, "{nonfinite} GPU pixels are NaN or infinite");
    r
}

/// How `render_both` runs the GPU.
#[derive(Clone, Copy, Debug)]
pub struct BothOptions {
    /// The shader specialised to the scene (default), or the full one. The images are
    /// bit-identical either way (tests/gpu/specialisation.rs); sweeps over the depth use the
    /// full shader so that they share one compiled variant instead of one per stack size.
    pub specialise: bool,
    /// The status word the GPU must raise (`STATUS_*` bits): 0 unless a case provokes a bound
    /// (a driver-dependent one, such as lavapipe's loop budget, chosen by the case).
    pub expect_status: u32,
    /// How the GPU finds primitives (the CPU reference always uses its default, the BVH, whose
    /// images are bit-identical to brute force).
    pub accel: Accel,
}

impl Default for BothOptions {
    fn default() -> Self {
        Self { specialise: true, expect_status: 0, accel: Accel::default() }
    }
}

/// One scene rendered on the CPU reference and, unless skipped, on the GPU. Both images have
/// been scanned: no pixel is NaN or infinite.
#[derive(Debug)]
pub struct Both {
    /// `GROUP/NAME`, where failure images go (under target/tmp).
    pub group: String,
    pub name: String,
    pub cpu: CpuRender,
    pub gpu: Option<GpuRender>,
}

/// Renders `flat` on both backends (the GPU with the specialised shader, status 0 expected).
pub fn render_both(group: &str, name: &str, flat: &FlatScene) -> Both {
    render_both_with(group, name, flat, BothOptions::default())
}

pub fn render_both_with(group: &str, name: &str, flat: &FlatScene, options: BothOptions) -> Both {
    let cpu = render_cpu_checked(flat, 0, true);
    let gpu = gpu().map(|tracer| {
        tracer
            .render(flat, &GpuOptions { specialise: options.specialise, accel: options.accel, ..GpuOptions::default() })
            .expect("GPU render")
    });
    let both = Both { group: group.to_string(), name: name.to_string(), cpu, gpu };
    if let Some(g) = &both.gpu {
        let bad = nonfinite_pixels(&g.image);
        both.ensure(bad.is_empty(), || {
            format!("{} GPU pixels are NaN or infinite (first: {:?})", bad.len(), bad.first())
        });
        both.ensure(g.status == options.expect_status, || {
            format!("GPU status word {:#x}, expected {:#x}", g.status, options.expect_status)
        });
    }
    both
}

impl Both {
    /// The images of the backends that ran, CPU first.
    pub fn images(&self) -> Vec<(Backend, &HdrImage)> {
        let mut v = vec![(Backend::Cpu, &self.cpu.image)];
        if let Some(g) = &self.gpu {
            v.push((Backend::Gpu, &g.image));
        }
        v
    }

    /// Panics with `message` (prefixed with the scene's name) unless `ok`, after writing the
    /// CPU, GPU and difference images to target/tmp/GROUP/NAME-*.png.
    pub fn ensure(&self, ok: bool, message: impl FnOnce() -> String) {
        if ok {
            return;
        }
        let base = artefact_dir(&self.group).join(&self.name);
        write_failure_images(&base, &self.cpu.image, self.gpu.as_ref().map(|g| &g.image));
        panic!("{}/{}: {}", self.group, self.name, message());
    }

    /// Pixels whose first-hit object differs between the backends (none without a GPU).
    pub fn first_hit_mismatches(&self) -> Vec<usize> {
        let Some(g) = &self.gpu else { return Vec::new() };
        let (a, b) = (&self.cpu.image.first_hit, &g.image.first_hit);
        (0..a.len()).filter(|&i| a[i] != b[i]).collect()
    }
}
