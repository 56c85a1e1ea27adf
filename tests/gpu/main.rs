//! GPU tests on a real adapter (lavapipe in CI): parity of the WGSL tracer with the CPU
//! reference, specialisation, stiff cases, adapter selection. With no adapter they fail with
//! a clear message; `GLINT_SKIP_GPU=1` skips them on purpose.

mod adapter;
mod parity;
mod specialisation;
mod stiff;
mod support;
