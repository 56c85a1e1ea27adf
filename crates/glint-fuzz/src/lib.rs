//! What every fuzz target checks, as plain functions: `cargo fuzz` (nightly, `fuzz/`) calls
//! them on generated inputs, and the stable test suite replays the kept corpus and every input
//! that once failed through the same functions (`replay`), so CI keeps them fixed.
//!
//! Each check panics when Glint breaks a promise on its input: a panic inside the loaders, a
//! scene that validation accepts but the flat layout or the tracer cannot take, a NaN pixel, or
//! a non-finite pixel in a scene whose materials cannot gain energy. An input Glint refuses with
//! an error is fine: that is what bad input should get.

mod checks;
mod replay;

pub use checks::{Target, gltf_model, obj_model, scene_pixels, scene_text};
pub use replay::{ReplayReport, replay_folder};
