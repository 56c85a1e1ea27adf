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
