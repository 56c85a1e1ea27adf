//! Helpers of the core tests. The scene builder, the independent re-derivation of the geometry
//! and the NaN/Inf-checked render live in glint-test-support (shared with the other test
//! binaries); this module re-exports them under the names the core tests use.

use glint_core::{CpuRender, FlatScene};

pub use crate::reference::{
    FresnelForm, assert_rel, blinn, cook_torrance, dv, phong, plane_hit, pow0, primary_ray, probe, sphere_hit,
};
pub use crate::scene::{SceneText, num, w3};

/// Renders with `threads` threads and asserts that no pixel is NaN or infinite.
pub fn render_with(flat: &FlatScene, threads: usize, specialise: bool) -> CpuRender {
    crate::render::render_cpu_checked(flat, threads, specialise)
}

/// Single-threaded, specialised render; every pixel finite.
pub fn render(flat: &FlatScene) -> CpuRender {
    render_with(flat, 1, true)
}
