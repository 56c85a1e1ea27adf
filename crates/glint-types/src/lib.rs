//! Glint's shared vocabulary, as `wgpu-types` is wgpu's: the tags both tracers switch on (with
//! their scene-file names), the `#[repr(C)]` flat layout both read (each struct the twin of one
//! in `shaders/layout.wgsl`), its sentinels and constants, and the probe's records. It depends
//! on nothing of Glint; the scene description, the CPU tracer, the GPU tracer and the viewer
//! all speak it.

pub mod layout;
pub mod tags;

pub use tags::{
    AttenuationModel, EpsilonMode, Filter, Fresnel, Integrator, LightKind, LightTags, MaterialTags, PathKind, RayKind,
    SpecularModel, SpotFalloff, Wrap,
};

#[cfg(test)]
#[macro_use]
mod layout_check;
#[cfg(test)]
mod reflection_tests;
