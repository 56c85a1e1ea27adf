//! UI tests of the real viewer app (egui_kittest, rendered with wgpu on lavapipe): edits made
//! through the widgets by their labels, picking, the pixel probe, "Save image", the editors'
//! ranges against validation's, and snapshots of the main layouts. Without an adapter they fail
//! with a clear message; `GLINT_SKIP_GPU=1` skips them on purpose.

mod camera;
mod dialogs;
mod differences;
mod edits;
mod export;
mod files;
mod fit;
mod gi;
mod glyphs;
mod help;
mod lights;
mod materials;
mod pick_and_probe;
mod ranges;
mod ray_tree;
mod snapshots;
mod status;
mod support;
mod view;
mod warnings;
mod world;
