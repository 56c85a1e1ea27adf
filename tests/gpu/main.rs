//! GPU tests on a real adapter (lavapipe in CI): parity of the WGSL tracer with the CPU
//! reference, specialisation, adapter selection. With no adapter they fail with a clear
//! message; `GLINT_SKIP_GPU=1` skips them on purpose. (The stiff and extreme cases, on both
//! backends, are the `stiff` test binary.)

mod adapter;
mod bvh;
mod cook_torrance;
mod geometry_cache;
mod gltf_lights;
mod ground;
mod parity;
mod path;
mod present;
mod probe;
mod properties;
mod ray_tree;
mod raycast;
mod specialisation;
mod support;
mod textures;
mod vertex_colours;

use glint_test_support::{gpu, render};
