//! The worker thread: a [`Worker`] sends the app's requests over a channel to a thread that
//! drives an [`Engine`] (its scheduler is the `schedule` module); every reply goes to a sink.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Sender};

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

/// The worker thread. Dropping it cancels the running solve and lets the thread end.
pub struct Worker {
    tx: Sender<Request>,
    latest: Arc<AtomicU64>,
}

impl Worker {
    /// Start the thread; every response goes to `sink`, which returns false once nobody listens.
    pub fn spawn(scenario: Scenario, sink: impl Fn(Response) -> bool + Send + Sync + 'static) -> Self {
        let (tx, rx) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let shared = latest.clone();
        let sink: Sink = Arc::new(sink);
        std::thread::Builder::new()
            .name("riplab-worker".into())
            .spawn(move || run(Engine::new(scenario), &rx, &shared, &sink))
            .expect("spawn the worker thread");
        Worker { tx, latest }
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
        // A dead worker shows as requests that never finish; the app keeps running.
        let _ = self.tx.send(request);
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.latest.store(u64::MAX, Ordering::SeqCst);
    }
}
