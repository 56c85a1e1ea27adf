//! The side panels: each edits one part of the document and says whether it changed it.

pub mod lights;
pub mod materials;
pub mod probe;
pub mod scene;
pub mod status;
