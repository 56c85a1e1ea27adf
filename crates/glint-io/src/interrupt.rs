//! The process-wide request to stop that the CLI's SIGINT/SIGTERM handler raises: the CPU
//! render loop stops at the next pixel, and the atomic writer stops writing and removes its
//! temporary. One flag for the process because a signal is one for the process; nothing but
//! a signal handler (or a test in a child process) raises it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

static REQUESTED: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The flag, shared (signal handlers take an `Arc`).
pub fn flag() -> Arc<AtomicBool> {
    REQUESTED.get_or_init(Arc::default).clone()
}

/// Whether a stop was requested.
pub fn requested() -> bool {
    REQUESTED.get().is_some_and(|f| f.load(Ordering::Relaxed))
}

/// Lowers the flag: a stop asked of an interactive program that its user has taken over (the
/// viewer asks "unsaved changes" on a signal; Save or Cancel there means go on, and a save
/// must not be stopped by the signal that asked).
pub fn withdraw() {
    if let Some(f) = REQUESTED.get() {
        f.store(false, Ordering::Relaxed);
    }
}

/// The error of work stopped by the request.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("interrupted")]
pub struct Interrupted;

/// Whether `error` is, or wraps, `Interrupted`.
pub fn is_interrupted(error: &std::io::Error) -> bool {
    error.get_ref().is_some_and(|e| e.is::<Interrupted>())
}
