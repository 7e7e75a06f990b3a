//! The tour's two-body solver (docs/lab.md, "Two bodies"): a thread on one two-body scenario
//! that solves the newest request of its steps' scenes on the bodies it keeps
//! ([`BodiesCache`]), gives a solve up as soon as a newer request is made (a stale answer is
//! never sent), and sends each answer to the loop ([`Input::Bodies`]); idle, it builds the
//! upper bodies of the ratios `k` and `K` step to. Dropped, it gives up what it solves and
//! ends.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, mpsc};

use crate::scenario::Scenario;

use super::super::bodies::Request;
use super::super::bodies::cache::BodiesCache;
use super::super::event_loop::Input;

/// The way to the solver's thread.
pub(super) struct BodiesWorker {
    /// The two-body scenario it solves.
    pub(super) scenario: Scenario,
    requests: mpsc::Sender<Request>,
    /// The newest request's generation: the thread gives up a solve of any other.
    newest: Arc<AtomicU64>,
}

impl BodiesWorker {
    /// A solver's thread on `scenario`, its answers sent to `tx`.
    ///
    /// # Errors
    ///
    /// The thread could not be started.
    pub(super) fn spawn(scenario: Scenario, tx: mpsc::Sender<Input>) -> std::io::Result<BodiesWorker> {
        let (requests, rx) = mpsc::channel::<Request>();
        let newest = Arc::new(AtomicU64::new(0));
        let seen = newest.clone();
        let own = scenario.clone();
        std::thread::Builder::new()
            .name("riplab-tour-bodies".into())
            .spawn(move || {
                // Built on the thread: the bodies it keeps stay there.
                let mut cache = BodiesCache::new(own);
                while let Ok(mut job) = rx.recv() {
                    // Only the newest request matters: the others are already stale.
                    while let Ok(newer) = rx.try_recv() {
                        job = newer;
                    }
                    let (generation, settings) = job;
                    let stale = || seen.load(Ordering::Acquire) != generation;
                    let result = cache.solve(&settings, &stale);
                    if stale() {
                        continue;
                    }
                    if tx.send(Input::Bodies(generation, Box::new(result))).is_err() {
                        return;
                    }
                    cache.prefetch_ratios(&settings, &stale);
                }
            })?;
        Ok(BodiesWorker {
            scenario,
            requests,
            newest,
        })
    }

    /// Ask for `request` (every older one is stale from now on); false if the thread has
    /// stopped.
    pub(super) fn send(&self, request: Request) -> bool {
        self.newest.store(request.0, Ordering::Release);
        self.requests.send(request).is_ok()
    }
}

impl Drop for BodiesWorker {
    /// A solve under way is given up (no request has this generation); the thread ends once
    /// its channel is closed.
    fn drop(&mut self) {
        self.newest.store(u64::MAX, Ordering::Release);
    }
}
