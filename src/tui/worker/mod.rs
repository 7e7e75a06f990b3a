//! The worker thread: a [`Worker`] sends the app's requests over a channel to a thread that
//! drives an [`Engine`] (its scheduler is the `schedule` module); every reply goes to a sink.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Sender};
use std::sync::{Arc, Condvar, Mutex, PoisonError};

use crate::scenario::Scenario;

use super::engine::Engine;
use super::job::Sink;
use super::protocol::{Command, InfSupRequest, Response, SolveRequest, Solved, StressRequest, StudyRequest};

mod schedule;

use schedule::run;

/// A request to the worker thread.
enum Request {
    Solve(SolveRequest),
    Stresses(StressRequest),
    Displace(Arc<Solved>),
    InfSup(InfSupRequest),
    Study(StudyRequest),
}

/// What the worker is at, for a caller that waits for it (the lab's tests wait on this, never
/// for a fixed time).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Activity {
    /// The requests sent to the worker.
    sent: u64,
    /// The requests it had taken when it last waited for the next one (each then answered,
    /// or under way on a thread of its own).
    waited_after: Option<u64>,
    /// Whether a build, an estimate or a study ran then on a thread of its own.
    background: bool,
}

#[cfg(test)]
impl Activity {
    /// Every request sent was taken, and the worker waits for the next.
    pub fn waits(&self) -> bool {
        self.waited_after == Some(self.sent)
    }

    /// The worker waits, and nothing runs in its background: it has built the neighbouring
    /// levels it could.
    pub fn idle(&self) -> bool {
        self.waits() && !self.background
    }
}

/// The worker's [`Activity`], each change signalled.
#[derive(Default)]
struct Watch {
    activity: Mutex<Activity>,
    changed: Condvar,
}

impl Watch {
    /// Change the activity with `change`, and signal it if it changed.
    fn update(&self, change: impl FnOnce(&mut Activity)) {
        let mut activity = self.activity.lock().unwrap_or_else(PoisonError::into_inner);
        let before = *activity;
        change(&mut activity);
        if *activity != before {
            self.changed.notify_all();
        }
    }

    /// The worker waits for a request, having taken `taken`, with work in the background or not.
    fn waits(&self, taken: u64, background: bool) {
        self.update(|a| {
            a.waited_after = Some(taken);
            a.background = background;
        });
    }
}

/// The worker thread. Dropping it cancels the running solve and lets the thread end.
pub struct Worker {
    tx: Sender<Request>,
    latest: Arc<AtomicU64>,
    watch: Arc<Watch>,
}

impl Worker {
    /// Start the thread; every response goes to `sink`, which returns false once nobody listens.
    pub fn spawn(scenario: Scenario, sink: impl Fn(Response) -> bool + Send + Sync + 'static) -> Self {
        let (tx, rx) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let shared = latest.clone();
        let sink: Sink = Arc::new(sink);
        let watch = Arc::new(Watch::default());
        let watched = watch.clone();
        std::thread::Builder::new()
            .name("riplab-worker".into())
            .spawn(move || run(Engine::new(scenario), &rx, &shared, &sink, &watched))
            .expect("spawn the worker thread");
        Worker { tx, latest, watch }
    }

    /// Wait until `until` holds of the worker's [`Activity`], at most `timeout`; whether it did.
    #[cfg(test)]
    pub fn wait_for(&self, timeout: std::time::Duration, until: impl Fn(&Activity) -> bool) -> bool {
        let activity = self.watch.activity.lock().unwrap_or_else(PoisonError::into_inner);
        let (activity, waited) = self
            .watch
            .changed
            .wait_timeout_while(activity, timeout, |a| !until(a))
            .unwrap_or_else(PoisonError::into_inner);
        drop(activity);
        !waited.timed_out()
    }

    /// Send a solve or an inf-sup request, or say which are superseded (anything else is
    /// not the worker's).
    pub fn send(&self, command: &Command) {
        let request = match command {
            Command::Supersede(generation) => {
                self.latest.fetch_max(*generation, Ordering::SeqCst);
                return;
            }
            Command::Solve(r) => Request::Solve(*r),
            Command::Stresses(r) => Request::Stresses(r.clone()),
            Command::Displace(r) => Request::Displace(r.solved.clone()),
            Command::InfSup(r) => Request::InfSup(*r),
            Command::Study(r) => Request::Study(r.clone()),
            Command::Export | Command::Suspend => return,
        };
        let generation = match &request {
            // Not ordered by generation: the stresses of a solution are wanted whenever shown.
            Request::Stresses(_) | Request::Displace(_) => 0,
            Request::Solve(r) => r.generation,
            Request::InfSup(r) => r.generation,
            Request::Study(r) => r.generation,
        };
        self.latest.fetch_max(generation, Ordering::SeqCst);
        // Counted before it is sent, so that the worker is never seen waiting with it unread.
        self.watch.update(|a| a.sent += 1);
        // A dead worker shows as requests that never finish; the app keeps running.
        let _ = self.tx.send(request);
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.latest.store(u64::MAX, Ordering::SeqCst);
    }
}
