//! Wakes the window when a signal raises the stop flag: the handler only sets the flag, and an
//! idle window paints no frame to see it (Ctrl+C in the terminal was ignored until the mouse
//! moved).

use std::time::Duration;

/// How often the flag is looked at: a quit within a tenth of a second, at no cost worth naming.
const LOOK_EVERY: Duration = Duration::from_millis(100);

/// Starts the thread that repaints `ctx` each time the flag goes up; it ends with the process.
pub fn start(ctx: &egui::Context) {
    let ctx = ctx.clone();
    let spawned = std::thread::Builder::new().name("glint-signal-watch".into()).spawn(move || {
        let mut was = false;
        loop {
            std::thread::sleep(LOOK_EVERY);
            let raised = glint_io::interrupt::requested();
            if raised && !was {
                ctx.request_repaint();
            }
            was = raised;
        }
    });
    if let Err(e) = spawned {
        log::warn!("no thread to watch for Ctrl+C ({e}): the window sees it at its next frame");
    }
}
