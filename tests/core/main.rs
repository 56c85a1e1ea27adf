//! Integration tests of the core: closed-form checks of the model, stiff numerical cases,
//! determinism, and scene validation. One test binary, several modules.

mod closed_form;
mod determinism;
mod stiff;
mod support;
mod validation;
