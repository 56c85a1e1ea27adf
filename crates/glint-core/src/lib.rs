//! Glint core: the flat GPU-ready layout built from a scene description, the BVH, and the
//! exact f64 CPU reference tracer of the Phong/Whitted model (with its ray trees, rebasing,
//! rendering and image comparison). It reads no file and holds no GPU code.

pub mod ambient_fit;
pub mod backend;
pub mod bvh;
pub mod compare;
pub mod cpu;
pub mod flat;
pub mod huge_pages;
pub mod image;
pub mod memory;
pub mod path_kinds;
pub mod probe_terms;
pub mod rays;
pub mod rebase;
pub mod render;
mod texture_table;
pub mod tiles;

pub use backend::Backend;
pub use flat::{FlatScene, WorldCamera, camera_eye};
pub use image::HdrImage;
pub use render::{
    Accel, CpuOptions, CpuRender, Picked, RenderControl, centre_hits, pick, probe_pixel, probe_tree, render_cpu,
};
pub use tiles::{PixelRect, TileGrid};

/// Re-exported so that the GPU tracer and the viewer use the same vector types.
pub use glam;
