//! Background jobs of the UI thread (CPU render, comparison, GPU probe, GPU submission): each
//! job runs on a named thread of its own and hands back one result, tagged with the document
//! revision it was started for. The UI thread polls without blocking. Starting the next job, or
//! dropping the worker, cancels the running one and discards its result, so a stale result can
//! never arrive as the current one.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};

#[derive(Debug, thiserror::Error)]
pub enum WorkerError {
    #[error("cannot start the {what} thread: {error}")]
    Spawn { what: &'static str, error: std::io::Error },
    #[error("the {what} thread stopped without a result")]
    Stopped { what: &'static str },
}

/// What a running job may use: its cancel flag, and a way to wake the UI for partial results.
#[derive(Debug)]
pub struct JobHandle {
    cancel: Arc<AtomicBool>,
    repaint: Option<egui::Context>,
}

impl JobHandle {
    /// Set when the job was replaced or its worker dropped; a long job polls it and stops early.
    pub fn cancel_flag(&self) -> &AtomicBool {
        &self.cancel
    }

    /// Asks the UI for a frame (e.g. to show a partial result).
    pub fn repaint(&self) {
        if let Some(ctx) = &self.repaint {
            ctx.request_repaint();
        }
    }

    /// Asks the UI for a frame within `delay`: partial results that arrive faster than the UI
    /// shows them (tiles) then cost one frame per `delay`, not one each.
    pub fn repaint_within(&self, delay: std::time::Duration) {
        if let Some(ctx) = &self.repaint {
            ctx.request_repaint_after(delay);
        }
    }
}

#[derive(Debug)]
struct Running<T> {
    revision: u64,
    cancel: Arc<AtomicBool>,
    result: Receiver<T>,
}

/// One job at a time, producing a `T`.
#[derive(Debug)]
pub struct Worker<T> {
    /// The thread's name (seen in debuggers and panics).
    thread: &'static str,
    /// What the job is, for messages: "cannot start the {what} thread".
    what: &'static str,
    /// Woken when a result is ready; `None` for a worker the UI polls every frame anyway.
    repaint: Option<egui::Context>,
    running: Option<Running<T>>,
    /// The threads it started that may still run (a cancelled job finishes its step first).
    threads: Vec<std::thread::JoinHandle<()>>,
}

impl<T> Worker<T> {
    pub fn new(thread: &'static str, what: &'static str, repaint: Option<egui::Context>) -> Self {
        Self { thread, what, repaint, running: None, threads: Vec::new() }
    }

    /// Cancels the running job and waits, at most until `deadline`, for every thread this worker
    /// started to end: for an owner that goes away with the device its jobs use (a process that
    /// exits while a GPU job still runs in the driver crashed in the driver's teardown). Whether
    /// they all ended.
    pub fn cancel_and_wait(&mut self, deadline: std::time::Instant) -> bool {
        self.cancel();
        while self.threads.iter().any(|t| !t.is_finished()) && std::time::Instant::now() < deadline {
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        self.threads.retain(|t| !t.is_finished());
        self.threads.is_empty()
    }

    /// Cancels the running job: its flag is set and its result will be discarded. The thread is
    /// not waited for (a job that cannot stop early, a GPU submission, would stall the UI).
    pub fn cancel(&mut self) {
        if let Some(r) = self.running.take() {
            r.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// The revision of the running job, if any.
    pub fn running_revision(&self) -> Option<u64> {
        self.running.as_ref().map(|r| r.revision)
    }

    pub fn is_running(&self) -> bool {
        self.running.is_some()
    }

    /// The running job's result once it is there, with the revision the job was started for.
    /// A job that ended without one (it panicked) gives `WorkerError::Stopped`.
    pub fn poll(&mut self) -> Option<(u64, Result<T, WorkerError>)> {
        let running = self.running.as_ref()?;
        let result = match running.result.try_recv() {
            Ok(value) => Ok(value),
            Err(TryRecvError::Empty) => return None,
            Err(TryRecvError::Disconnected) => Err(WorkerError::Stopped { what: self.what }),
        };
        let revision = running.revision;
        self.running = None;
        Some((revision, result))
    }
}

impl<T: Send + 'static> Worker<T> {
    /// Runs `job` for `revision` on a new thread, cancelling the running job first.
    pub fn start(
        &mut self,
        revision: u64,
        job: impl FnOnce(&JobHandle) -> T + Send + 'static,
    ) -> Result<(), WorkerError> {
        self.cancel();
        let (tx, rx) = channel();
        let handle = JobHandle { cancel: Arc::default(), repaint: self.repaint.clone() };
        let cancel = handle.cancel.clone();
        let thread = std::thread::Builder::new()
            .name(self.thread.into())
            .spawn(move || {
                let value = job(&handle);
                // The receiver is gone when the job was cancelled: the result is not wanted then.
                if tx.send(value).is_ok() {
                    // After the send, so that the frame this wakes finds the result.
                    handle.repaint();
                }
            })
            .map_err(|error| WorkerError::Spawn { what: self.what, error })?;
        self.threads.retain(|t| !t.is_finished());
        self.threads.push(thread);
        self.running = Some(Running { revision, cancel, result: rx });
        Ok(())
    }
}

impl<T> Drop for Worker<T> {
    fn drop(&mut self) {
        self.cancel();
    }
}

#[cfg(test)]
mod tests {
    use std::sync::mpsc::sync_channel;
    use std::time::{Duration, Instant};

    use super::*;

    fn wait<T>(worker: &mut Worker<T>) -> (u64, Result<T, WorkerError>) {
        let deadline = Instant::now() + Duration::from_secs(10);
        loop {
            if let Some(r) = worker.poll() {
                return r;
            }
            assert!(Instant::now() < deadline, "no result within 10 s");
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn a_result_carries_its_revision_and_a_replaced_job_is_cancelled_and_never_delivered() {
        let mut worker = Worker::new("glint-test", "test", None);
        // The first job holds until released, then reports whether it saw its cancel flag.
        let (release, hold) = sync_channel::<()>(0);
        worker
            .start(1, move |job| {
                let _ = hold.recv();
                job.cancel_flag().load(Ordering::Relaxed)
            })
            .expect("spawn");
        assert_eq!((worker.running_revision(), worker.poll().is_none()), (Some(1), true));
        worker.start(2, |job| job.cancel_flag().load(Ordering::Relaxed)).expect("spawn");
        release.send(()).expect("the first job waits");
        let (revision, cancelled) = wait(&mut worker);
        assert_eq!((revision, cancelled.expect("a result")), (2, false), "only the current job's result");
        assert!(!worker.is_running() && worker.poll().is_none());
    }

    #[test]
    fn a_job_that_panics_reports_that_it_stopped() {
        let mut worker: Worker<()> = Worker::new("glint-test-panic", "test", None);
        worker.start(7, |_| panic!("on purpose")).expect("spawn");
        let (revision, result) = wait(&mut worker);
        assert_eq!(revision, 7);
        assert!(matches!(result, Err(WorkerError::Stopped { what: "test" })), "{result:?}");
    }

    #[test]
    fn dropping_the_worker_cancels_its_job() {
        let mut worker = Worker::new("glint-test-drop", "test", None);
        let (seen_tx, seen) = channel();
        let (release, hold) = sync_channel::<()>(0);
        worker
            .start(1, move |job| {
                let _ = hold.recv();
                let _ = seen_tx.send(job.cancel_flag().load(Ordering::Relaxed));
            })
            .expect("spawn");
        drop(worker);
        release.send(()).expect("the job waits");
        assert_eq!(seen.recv_timeout(Duration::from_secs(10)), Ok(true));
    }

    #[test]
    fn waiting_cancels_and_covers_replaced_jobs_still_running_but_only_until_the_deadline() {
        let mut worker = Worker::new("glint-test-wait", "test", None);
        // Two jobs that run until cancelled: the first replaced by the second, both still running.
        for revision in [1, 2] {
            worker
                .start(revision, |job| {
                    while !job.cancel_flag().load(Ordering::Relaxed) {
                        std::thread::sleep(Duration::from_millis(1));
                    }
                })
                .expect("spawn");
        }
        assert!(worker.cancel_and_wait(Instant::now() + Duration::from_secs(10)), "both ended");
        // A job that ignores its flag is waited for only until the deadline.
        let (release, hold) = sync_channel::<()>(0);
        worker.start(3, move |_| hold.recv().unwrap_or_default()).expect("spawn");
        assert!(!worker.cancel_and_wait(Instant::now() + Duration::from_millis(20)), "still held");
        release.send(()).expect("the job waits");
        assert!(worker.cancel_and_wait(Instant::now() + Duration::from_secs(10)));
    }
}
