//! SIGINT and SIGTERM: the first raises `glint_io::interrupt`'s flag, which the CPU render
//! loop and the atomic writer check (the render stops at the next pixel, a write in progress
//! stops and its temporary is removed); `main` then says "interrupted" and exits with
//! 128 + the signal's number (130, 143), as shells report a process killed by it. A second
//! signal ends the process at once, with the same code, as does the first while a scene loads.
//! The viewer answers the flag as File → Quit (`glint_viewer`'s `signal_watch` wakes it). SIGXFSZ (a file size limit) is caught
//! so that the write fails and is reported instead of ending the process.

use std::sync::Arc;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use anyhow::Context;
use signal_hook::consts::{SIGINT, SIGTERM, SIGXFSZ};

/// The number of the signal that raised the flag (0: none).
static SIGNAL: OnceLock<Arc<AtomicUsize>> = OnceLock::new();

/// Set while a scene loads: the first signal then ends the process at once. Loading writes
/// nothing, and a read that waits (a named pipe's writer that never comes) would not see the
/// flag: the first Ctrl+C was swallowed until a second.
static LOADING: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// Installs the handlers; call once, before any work.
pub fn install() -> anyhow::Result<()> {
    let flag = glint_io::interrupt::flag();
    let signal = SIGNAL.get_or_init(Arc::default);
    let loading = LOADING.get_or_init(Arc::default);
    for number in [SIGINT, SIGTERM] {
        let code = 128 + number;
        // Registered before the flag is set, so it sees the flag of an earlier signal only.
        signal_hook::flag::register_conditional_shutdown(number, code, flag.clone())
            .and_then(|_| signal_hook::flag::register_conditional_shutdown(number, code, loading.clone()))
            .and_then(|_| signal_hook::flag::register_usize(number, signal.clone(), number as usize))
            .and_then(|_| signal_hook::flag::register(number, flag.clone()))
            .with_context(|| format!("cannot install the handler of signal {number}"))?;
    }
    // A file size limit (`ulimit -f`) ends a process that writes past it, by SIGXFSZ's default
    // action, with no message and its temporary file left behind. Handled, the write fails
    // with EFBIG instead, which the writer reports, naming the output, after removing it.
    signal_hook::flag::register(SIGXFSZ, Arc::default()).context("cannot install the handler of SIGXFSZ")?;
    Ok(())
}

/// Runs `load` with the first signal ending the process at once (see `LOADING`).
pub fn while_loading<T>(load: impl FnOnce() -> T) -> T {
    /// Lowers the flag however `load` ends, an unwinding panic included.
    struct Loading(Option<&'static Arc<AtomicBool>>);
    impl Drop for Loading {
        fn drop(&mut self) {
            self.0.inspect(|l| l.store(false, Ordering::SeqCst));
        }
    }
    let guard = Loading(LOADING.get());
    guard.0.inspect(|l| l.store(true, Ordering::SeqCst));
    load()
}

/// The exit code of an interrupted run (128 + the signal), if a signal interrupted it.
pub fn exit_code() -> Option<u8> {
    if !glint_io::interrupt::requested() {
        return None;
    }
    let number = SIGNAL.get().map_or(0, |s| s.load(Ordering::Relaxed));
    u8::try_from(128 + number).ok().filter(|_| number != 0).or(Some(130))
}

/// An error if a stop was requested: checked between the steps that do not check it themselves
/// (loading, building, a GPU render, which cannot be stopped once dispatched).
pub fn check() -> anyhow::Result<()> {
    if glint_io::interrupt::requested() {
        return Err(glint_io::interrupt::Interrupted.into());
    }
    Ok(())
}
