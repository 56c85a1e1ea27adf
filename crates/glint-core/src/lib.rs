//! Glint core: the scene model and its validation, the flat GPU-ready layout, and the exact
//! f64 CPU reference tracer of the Phong/Whitted model. No GPU code lives here.

pub mod backend;
pub mod bvh;
pub mod compare;
pub mod cpu;
pub mod flat;
pub mod huge_pages;
pub mod image;
pub mod memory;
pub mod probe_terms;
pub mod ray_tree;
pub mod rays;
pub mod rebase;
pub mod render;
mod texture_table;

pub use backend::Backend;
pub use flat::FlatScene;
pub use image::HdrImage;
pub use render::{Accel, CpuOptions, CpuRender, RenderControl, pick_object, probe_pixel, probe_tree, render_cpu};

/// Re-exported so that the GPU tracer and the viewer use the same vector types.
pub use glam;
