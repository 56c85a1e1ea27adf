//! GPU tests on a real adapter (lavapipe in CI): parity of the WGSL tracer with the CPU
//! reference, specialisation, adapter selection. With no adapter they fail with a clear
//! message; `GLINT_SKIP_GPU=1` skips them on purpose. (The stiff and extreme cases, on both
//! backends, are the `stiff` test binary.)

mod adapter;
mod parity;
mod probe;
mod specialisation;
mod support;

#[path = "../common/gpu.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod gpu;
#[path = "../common/image_hash.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod image_hash;
#[path = "../common/render.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod render;
