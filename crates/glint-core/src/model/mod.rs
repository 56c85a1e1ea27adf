//! Model files (glTF 2.0, OBJ/MTL): what the importers share.

pub mod uri;

pub use uri::{MAX_RESOURCE_BYTES, UriError, resolve_uri};
