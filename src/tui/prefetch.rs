//! Building the discretisation of a neighbouring level while the lab is idle (issue 13,
//! item 4), so that `]` and `[` find the next finer or coarser mesh assembled and factorised.
//!
//! A build runs on a thread of its own, one at a time, and hands its result back through a
//! channel; the worker adopts it into its cache ([`super::worker::Engine::adopt`]) or drops it
//! when the user has moved on to another element. A factorisation cannot be interrupted, so
//! "cancelling" a build means dropping its result; the memory it may use is bounded before it
//! starts ([`super::worker::Engine::next_prefetch`]).

use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::time::{Duration, Instant};

use crate::error::SolveError;
use crate::mesh::Element;
use crate::scenario::Scenario;
use crate::solve::Discretization;

/// A background build of the discretisation of `level` with `element`.
pub struct Prefetch {
    /// The level being built.
    pub level: u32,
    /// The element being built.
    pub element: Element,
    /// Its number of unknowns (for the time estimate).
    pub unknowns: usize,
    /// When the build began.
    pub started: Instant,
    /// What the build is expected to take ([`super::eta`]).
    pub estimate_ms: f64,
    done: Receiver<Built>,
}

/// A finished build and its wall time in ms, or why there is none.
pub type Built = Result<(Discretization, f64), SolveError>;

impl Prefetch {
    /// Start building `level` with `element` of `scenario`; None if no thread can be started
    /// (the lab then simply builds on demand).
    pub fn start(
        scenario: &Scenario,
        level: u32,
        element: Element,
        unknowns: usize,
        estimate_ms: f64,
    ) -> Option<Self> {
        let (tx, done) = mpsc::channel();
        let scenario = scenario.clone();
        std::thread::Builder::new()
            .name("riplab-prefetch".into())
            .spawn(move || {
                let t = Instant::now();
                let built = Discretization::of(&scenario, level, element)
                    .map(|d| (d, t.elapsed().as_secs_f64() * 1e3));
                // Nobody listens any more when the worker has ended: nothing to do then.
                let _ = tx.send(built);
            })
            .ok()?;
        Some(Prefetch {
            level,
            element,
            unknowns,
            started: Instant::now(),
            estimate_ms,
            done,
        })
    }

    /// The build's result if it finished within `wait` (a thread that ended without one
    /// counts as cancelled: the level is then built on demand); `Err(self)` while it runs.
    pub fn finished(self, wait: Duration) -> Result<Built, Self> {
        let got = if wait.is_zero() {
            self.done.try_recv().map_err(|e| match e {
                mpsc::TryRecvError::Empty => RecvTimeoutError::Timeout,
                mpsc::TryRecvError::Disconnected => RecvTimeoutError::Disconnected,
            })
        } else {
            self.done.recv_timeout(wait)
        };
        match got {
            Ok(built) => Ok(built),
            Err(RecvTimeoutError::Timeout) => Err(self),
            Err(RecvTimeoutError::Disconnected) => Ok(Err(SolveError::Cancelled)),
        }
    }

    /// Whether this build is of `level` with `element`.
    pub fn is_for(&self, level: u32, element: Element) -> bool {
        (self.level, self.element) == (level, element)
    }
}
