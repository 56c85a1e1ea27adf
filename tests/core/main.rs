//! Integration tests of the core: closed-form checks of the model, determinism, and scene
//! validation. One test binary, several modules. (The stiff and extreme cases, on both
//! backends, are the `stiff` test binary.)

mod bit_identity;
mod closed_form;
mod determinism;
mod support;
mod validation;

#[path = "../common/image_hash.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod image_hash;
#[path = "../common/reference.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod reference;
#[path = "../common/render.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod render;
#[path = "../common/scene.rs"]
#[allow(dead_code, reason = "shared with the other test binaries, which use other parts of it")]
mod scene;
