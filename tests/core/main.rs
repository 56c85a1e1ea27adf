//! Integration tests of the core: closed-form checks of the model, determinism, and scene
//! validation. One test binary, several modules. (The stiff and extreme cases, on both
//! backends, are the `stiff` test binary.)

mod ambient_fit;
mod architecture;
mod bit_identity;
mod builtin_scenes;
mod bvh;
mod closed_form;
mod determinism;
mod fuzz_replay;
mod global_attenuation;
mod gltf;
mod gltf_cameras;
mod gltf_lights;
mod gltf_refused;
mod module_cycles;
mod path;
mod ray_tree;
mod sampling;
mod skip_convex;
mod support;
mod tour;
mod validation;
mod vertex_colours;

use glint_test_support::{reference, render, scene};
