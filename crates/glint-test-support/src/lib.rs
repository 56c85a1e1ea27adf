//! What the integration test binaries of the `glint` package (`core`, `cli`, `gpu`, `stiff`,
//! `viewer`) share, as one crate instead of `#[path]` includes: each binary uses the parts it
//! needs, and nothing is compiled once per binary with `dead_code` allowed.
//!
//! A binary names the modules at its root (`use glint_test_support::{gpu, render, scene};`),
//! so its tests refer to them as `crate::gpu::…` and so on.

pub mod chi2;
pub mod gltf;
pub mod gpu;
pub mod image_hash;
pub mod reference;
pub mod render;
pub mod scene;
pub mod temp;
pub mod texture;

pub use temp::TempDir;

/// Whether the user skips a group of tests on purpose with its `GLINT_SKIP_*` variable set to
/// 1 (README's table). Without it, a test that lacks what it needs fails saying what to install.
pub fn skip_requested(variable: &str) -> bool {
    std::env::var(variable).is_ok_and(|v| v == "1")
}
