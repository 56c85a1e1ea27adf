//! Glint's GPU tracer: the WGSL twin of the CPU reference (`shaders/*.wgsl`), composed with
//! naga_oil and specialised per scene, run with wgpu.

pub mod binding;
pub mod buffers;
pub mod context;
pub mod dispatch;
pub mod error;
pub mod job;
pub mod pipeline;
pub mod present;
pub mod probe;
pub mod raycast;
pub mod readback;
pub mod shaders;
pub mod status;
pub mod tracer;

pub use context::{AdapterRequest, AdapterSummary, GpuContext, list_adapters};
pub use dispatch::{DispatchControl, SampleProgress};
pub use error::GpuError;
pub use job::GpuJob;
pub use present::{PendingPixels, Presenter};
pub use readback::JobReadback;
pub use shaders::{GPU_STACK_LIMIT, LAVAPIPE_LOOP_BUDGET, ShaderKey};
pub use tracer::{GpuOptions, GpuRender, GpuTracer, PixelProbe};

#[cfg(test)]
#[path = "../../glint-types/src/layout_check.rs"]
#[allow(
    dead_code,
    unused_macros,
    reason = "glint-types' reflection harness, of which these tests read only literal values"
)]
mod layout_check;
#[cfg(test)]
mod reflection_tests;
#[cfg(test)]
mod shader_tests;
#[cfg(test)]
mod twin_tests;
