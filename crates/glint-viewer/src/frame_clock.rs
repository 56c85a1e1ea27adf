//! The time of each frame: the app's own share (shown in the status bar) and the interval
//! between frames (for the drag benchmark).

use std::time::{Duration, Instant};

#[derive(Debug, Default)]
pub struct FrameClock {
    /// Milliseconds the app itself took in the last frame.
    pub ui_ms: f64,
    last_frame: Option<Instant>,
}

impl FrameClock {
    /// Ends the frame that began at `start`; returns the interval since the previous frame.
    pub fn end_frame(&mut self, start: Instant) -> Option<Duration> {
        let now = Instant::now();
        self.ui_ms = now.duration_since(start).as_secs_f64() * 1e3;
        let interval = self.last_frame.map(|last| now.duration_since(last));
        self.last_frame = Some(now);
        interval
    }
}
